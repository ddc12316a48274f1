//! Compound eye: spherical lenslets on spherical elements on a base sphere, the "multiple-compound
//! eye" of paper 000 (section "Experimental validation", Figure 10: seven single-compound eye
//! elements in a hexagonal layout on the largest spherical surface, each carrying 17 lenses in a
//! hexagonal layout on a smaller spherical surface) and the compound eye of paper 001 (section 3,
//! Figure 5: "many small spherical patches on a big sphere").
//!
//! Construction, three levels of spheres, every count, radius, height and pitch a parameter:
//! - the **base**: a sphere of signed radius R_b through the origin (vertex at z = 0, centre at
//!   (0, 0, R_b): R_b < 0 is a dome standing towards the tool, R_b > 0 a bowl, the sign
//!   convention of the even asphere), or the plane z = 0;
//! - **elements**: layout points `(x_e, y_e)` on a hexagonal grid of pitch p_e in XY (rows along
//!   X) within `element_rings` rings of the axis (0 → 1 element, 1 → 7, 2 → 19); each element is
//!   the upper cap of a sphere of radius R_e standing on the base point over its layout point,
//!   along the base's normal there: its pole (the point on its axis) lies h_e out of the base;
//! - **lenslets**: on every element the same pattern of layout points, offsets in XY from the
//!   element's pole: rows `p_l·√3/2` apart holding `lenslet_rows[k]` lenslets a pitch p_l apart,
//!   each row centred; each lenslet is the upper cap of a sphere of radius R_l standing on the
//!   element's sphere over its layout point, along the element's normal, its pole h_l out of the
//!   element.
//!
//! Standing along the normal (rather than straight up along Z) puts a child's centre on its
//! spherical parent's radius, so every lenslet meets its element, and every element a spherical
//! base, along a circle about its own axis, the same wherever it sits, as the patches of a
//! compound eye do. (Straight up along Z, a child on a sloping parent is lopsided: on the
//! paper-000 preset an outer element would reach 2.2 mm down the base's slope and 0.9 mm up it.)
//!
//! Elements and lenslets are convex: they stand towards +Z, the tool (their centres of curvature
//! lie on −Z, a negative radius in the asphere's convention; their radii are given as positive
//! lengths, like the lens array's). The surface is the **upper envelope** of the pieces,
//! `z = max(base, every element cap, every lenslet cap defined there)`, with sharp intersections
//! and no fillet: where two convex pieces meet, the section has a concave slope kink (a valley).
//! No nose of radius r > 0 reaches into such a valley; the tool leaves its own fillet there,
//! which the planner's concave-zone report ([`crate::tool::reach`]) measures.
//!
//! Rooting. Every sphere must sit in its parent: its equator, the horizontal circle of its own
//! radius through its centre, lies strictly on the material side of the parent (inside a dome
//! parent's sphere, under a bowl, under the plane). Then the cap rises out of the parent along
//! one circle (where the two spheres meet), is on the envelope only inside the XY projection of
//! that circle (an ellipse, its footprint), and is back under the parent well before its sides
//! turn vertical: the envelope is continuous, has no overhang (which a lathe could not cut
//! anyway), and its slope jumps only where two spheres meet. The heights for which this holds
//! have a closed form (`compound_eye/rooting.rs`); [`CompoundEye::new`] checks them and names
//! the parameter and the range otherwise.
//!
//! Evaluation. Each piece's footprint ellipse lies in the disc of its circle's radius about the
//! circle's centre; a uniform grid of cells lists the footprints meeting each cell, so a point
//! looks at its cell's few pieces and the base: O(1) in the element and lenslet counts. The sag
//! is the largest of those, its derivatives those of the piece that wins (a piece outside its
//! footprint lies under its parent, which lies under the base outside its own footprint, so the
//! pieces left out are never above the envelope).
//!
//! Slope kinks. Along a line, the slope jumps where the line crosses a seam, the circle where
//! two spheres meet, at a point where those two pieces are the top two of the envelope (such a
//! point lies in both pieces' footprints). Seams are listed once (each cap with its parent,
//! caps with overlapping footprints, and the base with any lenslet whose footprint leaves its
//! element's) and indexed by the smaller of their two footprints; their crossings with the
//! line's vertical plane are solved in closed form (`Circle::crossings` in
//! `compound_eye/sphere.rs`), polished by Newton steps on the difference of the two caps'
//! sags, and kept when the two sags agree within 0.1 nm and nothing lies above them. The rims of
//! the pieces are never on the envelope (rooting), so they add no kinks.
//!
//! Paper 000's figures and dimensions were lost in the text; [`CompoundEyeSpec::paper000`]
//! documents the values chosen instead.

mod index;
mod layout;
mod rooting;
mod sphere;

use super::asphere::Asphere;
use super::{Line, Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, length};
use index::DiscIndex;
use rooting::Parent;
use serde::{Deserialize, Serialize};
use sphere::{Circle, Sphere};

/// Most rings of elements: 30 rings are 2791 elements.
pub const MAX_ELEMENT_RINGS: u32 = 30;
/// Most rows of lenslets on an element.
pub const MAX_LENSLET_ROWS: usize = 64;
/// Most lenslets in one row.
pub const MAX_LENSLETS_PER_ROW: u32 = 64;
/// Most spheres in all (elements and lenslets).
pub const MAX_PIECES: u64 = 200_000;

/// Two pieces whose sags agree within this are tied at a seam crossing, mm (0.1 nm).
const TIE_MM: f64 = 1e-10;
/// Largest Newton step that polishes a seam crossing, mm: the closed form is good to rounding
/// except at a tangent crossing, where it is good to about √ε times the seam's radius.
const POLISH_STEP_MM: f64 = 1e-6;
/// Crossings closer than this are one kink, mm.
const SAME_KINK_MM: f64 = 1e-12;

/// Job entry of a compound eye (see the module documentation for the construction). Counts
/// default to paper 000's 7 elements × 17 lenslets; every length must be given.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CompoundEyeSpec {
    /// Signed radius of the base sphere R_b, mm, finite and non-zero; negative for a dome
    /// (centre of curvature on −Z, standing towards the tool), positive for a bowl. Leave it out
    /// for a flat base z = 0 (the default).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub base_radius_mm: Option<f64>,
    /// Rings of elements about the axis on a hexagonal grid, 0 … 30: 0 → 1 element, 1 → 7,
    /// 2 → 19, n → 1 + 3n(n + 1); default 1.
    #[serde(default = "default_element_rings")]
    pub element_rings: u32,
    /// Distance p_e between neighbouring element layout points in XY, mm, > 0; every layout
    /// point must lie within the base sphere's rim.
    pub element_pitch_mm: f64,
    /// Radius of each element's sphere R_e, mm, > 0 (convex).
    pub element_radius_mm: f64,
    /// Height h_e of each element's pole out of the base, along the base's normal, mm, > 0 and
    /// small enough that every element's equator lies under the base (the error message gives
    /// the range).
    pub element_height_mm: f64,
    /// Lenslets per row, rows `p_l·√3/2` apart along Y and centred on the element's pole,
    /// each 1 … 64, at most 64 rows; rows differing by one interleave hexagonally; empty for
    /// bare elements. Default `[3, 4, 3, 4, 3]` (paper 000's 17 lenses).
    #[serde(default = "default_lenslet_rows")]
    pub lenslet_rows: Vec<u32>,
    /// Distance p_l between neighbouring lenslet layout points in XY, mm, > 0; every layout
    /// point must lie within its element's rim.
    pub lenslet_pitch_mm: f64,
    /// Radius of each lenslet's sphere R_l, mm, > 0 (convex); it must be small enough for some
    /// lenslet height to root every lenslet in its element.
    pub lenslet_radius_mm: f64,
    /// Height h_l of each lenslet's pole out of its element, along the element's normal, mm,
    /// positive and small enough that every lenslet's equator lies inside its element's sphere
    /// (the error message gives the range).
    pub lenslet_height_mm: f64,
}

fn default_element_rings() -> u32 {
    1
}

fn default_lenslet_rows() -> Vec<u32> {
    vec![3, 4, 3, 4, 3]
}

impl CompoundEyeSpec {
    /// Paper 000's multiple-compound eye (Figure 10, diamond turned with hybrid FTS/SSS to a PV
    /// tolerance of 1 µm): 7 elements × 17 lenslets (rows 3, 4, 3, 4, 3). The paper's figures
    /// and dimensions were lost in the text, so the sizes are chosen here, for a Ø10 mm part, to
    /// agree with what the text does give:
    /// - its HCAA transition radii, 3.9865 mm and 0.2782 mm, bound the zone where the section's
    ///   curvature changes (outside it the section is one sphere): here the outermost valley,
    ///   where the outer elements meet the base, lies at 4.003 mm (element pitch 2.6 mm,
    ///   footprints about 1.4 mm in radius, so neighbouring elements meet in a valley), and the
    ///   first valley around the central lenslet at 0.225 mm (lenslet pitch 0.45 mm; a pitch of
    ///   0.556 mm would put it at 0.278 mm but would make the lenslet clusters of neighbouring
    ///   elements collide);
    /// - its critical half included angles of 65°–70° with 5° clearance mean radial slopes of
    ///   about 15°–20°: base R_b = −40 mm (a dome), elements R_e = 8 mm standing h_e = 0.1 mm
    ///   out of it, lenslets R_l = 2 mm standing h_l = 16 µm out of their element (footprints
    ///   0.29 mm in radius, which cover each cluster without gaps) give at most 18.6°;
    /// - its two frequencies of the geometry splitting (6.098 Hz and 47.03 Hz) say the surface
    ///   has two scales: base and elements (0.43 mm of sag over the part, for the slide) and
    ///   lenslets (16 µm, for the FTS).
    pub fn paper000() -> Self {
        Self {
            base_radius_mm: Some(-40.0),
            element_rings: 1,
            element_pitch_mm: 2.6,
            element_radius_mm: 8.0,
            element_height_mm: 0.1,
            lenslet_rows: vec![3, 4, 3, 4, 3],
            lenslet_pitch_mm: 0.45,
            lenslet_radius_mm: 2.0,
            lenslet_height_mm: 0.016,
        }
    }
}

/// One of the pieces whose envelope is the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Piece {
    /// The base sphere or plane.
    Base,
    /// An element or lenslet cap: an index into `CompoundEye::caps`.
    Cap(u32),
}

/// The circle where two pieces meet, where the envelope may have a slope kink.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Seam {
    a: Piece,
    b: Piece,
    circle: Circle,
}

/// A compound eye, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct CompoundEye {
    spec: CompoundEyeSpec,
    /// The base as a surface (sphere or plane).
    base: Asphere,
    /// The base sphere in space, `None` for a plane.
    base_sphere: Option<Sphere>,
    /// Element caps, then each element's lenslets in turn.
    caps: Vec<Sphere>,
    elements: usize,
    lenslets_per_element: usize,
    /// Footprint discs of the caps.
    pieces: DiscIndex,
    seams: Vec<Seam>,
    /// XY extents of the seams.
    seam_index: DiscIndex,
    feature: f64,
}

impl CompoundEye {
    /// Checks a spec and builds the surface. The layout is fixed by the spec, centred on the
    /// surface's axis and not clipped to the part (place it with a composite's decentre), so
    /// `part` is not used.
    pub fn new(spec: &CompoundEyeSpec, part: PartDisc) -> Result<Self, FieldError> {
        let _ = part;
        let base_sphere = check_base(spec.base_radius_mm)?;
        let dims = Dimensions::check(spec)?;
        let (base, parent) = match spec.base_radius_mm {
            Some(r) => (
                Asphere::sphere(r).map_err(|e| FieldError::new("base_radius_mm", r, e.allowed))?,
                if r < 0.0 {
                    Parent::Dome(-r)
                } else {
                    Parent::Bowl(r)
                },
            ),
            None => (Asphere::plane(), Parent::Plane),
        };
        let offsets = layout::lenslet_offsets(&spec.lenslet_rows, dims.lenslet_pitch);
        let pieces = layout::hexagon_count(spec.element_rings) * (1 + offsets.len() as u64);
        if pieces > MAX_PIECES {
            return Err(FieldError::new(
                "lenslet_rows",
                format!(
                    "{} elements × {} lenslets",
                    layout::hexagon_count(spec.element_rings),
                    offsets.len()
                ),
                format!("at most {MAX_PIECES} elements and lenslets in all"),
            ));
        }
        let centres = layout::element_centres(spec.element_rings, dims.element_pitch);
        let (mut caps, poles) = place_elements(&base, parent, &centres, &dims)?;
        let elements = caps.len();
        for e in 0..elements {
            caps.extend(place_lenslets(&caps[e], poles[e], &offsets, &dims)?);
        }
        check_lenslet_heights(&caps[..elements], &poles, &offsets, &dims)?;
        let mut eye = Self {
            spec: spec.clone(),
            base,
            base_sphere,
            caps,
            elements,
            lenslets_per_element: offsets.len(),
            pieces: DiscIndex::new(&[], 1.0),
            seams: Vec::new(),
            seam_index: DiscIndex::new(&[], 1.0),
            feature: f64::INFINITY,
        };
        eye.assemble();
        Ok(eye)
    }

    /// Indexes the caps and their seams and measures the narrowest feature (the pieces are
    /// placed; `pieces`, `seams`, `seam_index` and `feature` are filled in).
    fn assemble(&mut self) {
        let rooted = self.rooted_seams();
        let footprints: Vec<[f64; 3]> = rooted.iter().map(|s| disc(&s.circle)).collect();
        let cell = footprints
            .iter()
            .map(|d| d[2])
            .fold(f64::INFINITY, f64::min);
        self.pieces = DiscIndex::new(&footprints, cell);
        let pairs = self.overlapping_pairs(&footprints);
        self.feature = rooted
            .iter()
            .map(|s| s.circle.projected_half_width())
            .chain(
                pairs
                    .iter()
                    .filter(|&&(i, j)| self.same_level(i, j))
                    .map(|&(i, j)| {
                        let (f, g) = (footprints[i as usize], footprints[j as usize]);
                        0.5 * (f[0] - g[0]).hypot(f[1] - g[1])
                    }),
            )
            .fold(f64::INFINITY, f64::min);
        let mut seams = self.base_seams(&rooted);
        seams.extend(pairs.iter().filter_map(|&(i, j)| {
            let circle = self.caps[i as usize].meet(&self.caps[j as usize])?;
            Some(Seam {
                a: Piece::Cap(i),
                b: Piece::Cap(j),
                circle,
            })
        }));
        seams.extend(rooted);
        self.seam_index = DiscIndex::new(&seam_extents(&seams, &footprints), cell);
        self.seams = seams;
    }

    /// Each cap against its parent: the seam whose projection is the cap's footprint.
    fn rooted_seams(&self) -> Vec<Seam> {
        (0..self.caps.len() as u32)
            .map(|k| {
                let parent = self.parent(k);
                let circle = self.meet(Piece::Cap(k), parent).unwrap_or_else(|| {
                    // Rooting guarantees a circle; fall back to the whole sphere's disc.
                    let s = self.caps[k as usize];
                    Circle {
                        centre: s.centre,
                        normal: [0.0, 0.0, 1.0],
                        radius: s.radius,
                    }
                });
                Seam {
                    a: Piece::Cap(k),
                    b: parent,
                    circle,
                }
            })
            .collect()
    }

    /// The base against every lenslet whose footprint leaves its element's inscribed footprint
    /// disc: elsewhere the lenslet, where it is on top, stands on an element above the base.
    fn base_seams(&self, rooted: &[Seam]) -> Vec<Seam> {
        (self.elements as u32..self.caps.len() as u32)
            .filter_map(|k| {
                let Piece::Cap(p) = self.parent(k) else {
                    return None;
                };
                let (own, parent) = (&rooted[k as usize].circle, &rooted[p as usize].circle);
                let gap =
                    (own.centre[0] - parent.centre[0]).hypot(own.centre[1] - parent.centre[1]);
                if gap + own.radius < parent.projected_half_width() {
                    return None;
                }
                let circle = self.meet(Piece::Cap(k), Piece::Base)?;
                Some(Seam {
                    a: Piece::Cap(k),
                    b: Piece::Base,
                    circle,
                })
            })
            .collect()
    }

    /// The pairs of caps (i < j, not parent and child) whose footprint discs overlap.
    fn overlapping_pairs(&self, footprints: &[[f64; 3]]) -> Vec<(u32, u32)> {
        let mut pairs = Vec::new();
        for (k, f) in footprints.iter().enumerate() {
            let mut near = Vec::new();
            self.pieces.in_box(
                [f[0] - f[2], f[0] + f[2], f[1] - f[2], f[1] + f[2]],
                &mut near,
            );
            for j in near {
                let g = footprints[j as usize];
                let apart = (f[0] - g[0]).hypot(f[1] - g[1]);
                let k = k as u32;
                let related = self.parent(j) == Piece::Cap(k) || self.parent(k) == Piece::Cap(j);
                if j > k && apart < f[2] + g[2] && !related {
                    pairs.push((k, j));
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    /// The piece a cap is rooted in.
    fn parent(&self, k: u32) -> Piece {
        let k = k as usize;
        if k < self.elements {
            Piece::Base
        } else {
            Piece::Cap(((k - self.elements) / self.lenslets_per_element) as u32)
        }
    }

    /// Whether two caps are both elements or both lenslets.
    fn same_level(&self, i: u32, j: u32) -> bool {
        ((i as usize) < self.elements) == ((j as usize) < self.elements)
    }

    /// The circle where two pieces meet (at most one of them the base).
    fn meet(&self, a: Piece, b: Piece) -> Option<Circle> {
        match (a, b) {
            (Piece::Cap(i), Piece::Cap(j)) => self.caps[i as usize].meet(&self.caps[j as usize]),
            (Piece::Cap(k), Piece::Base) | (Piece::Base, Piece::Cap(k)) => {
                let cap = &self.caps[k as usize];
                match &self.base_sphere {
                    Some(base) => cap.meet(base),
                    None => cap.meet_plane(),
                }
            }
            (Piece::Base, Piece::Base) => None,
        }
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.elements
    }

    /// Number of lenslets on all elements.
    pub fn lenslet_count(&self) -> usize {
        self.elements * self.lenslets_per_element
    }

    /// The error for a point beyond the base sphere's rim.
    fn undefined(&self, x: f64, y: f64) -> UndefinedError {
        let rim = self.base.rim_radius_mm().unwrap_or(f64::INFINITY);
        UndefinedError {
            surface: "compound eye",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason: format!("beyond the base sphere's rim at radius {rim} mm"),
        }
    }

    /// The envelope's sag, or `None` beyond the base's rim.
    fn envelope_sag(&self, x: f64, y: f64) -> Option<f64> {
        let mut z = self.base.sag(x, y).ok()?;
        for &k in self.pieces.at(x, y) {
            if let Some(zk) = self.caps[k as usize].cap_sag(x, y) {
                z = z.max(zk);
            }
        }
        Some(z)
    }

    /// Sag of one piece at `line.at(t)` and its slope along the line.
    fn along(&self, piece: Piece, line: Line, t: f64) -> Option<(f64, f64)> {
        let (x, y) = line.at(t);
        let l = match piece {
            Piece::Base => self.base.local(x, y).ok()?,
            Piece::Cap(k) => self.caps[k as usize].cap_local(x, y)?,
        };
        Some((l.z, l.zx * line.c + l.zy * line.s))
    }

    /// Whether the point X of a seam lies on the side of a piece's sphere that the piece uses
    /// (the upper half of a cap, the lower half of a bowl base, the upper half of a dome base).
    fn on_used_half(&self, piece: Piece, z: f64) -> bool {
        let tolerance = 1e-9;
        match piece {
            Piece::Cap(k) => z >= self.caps[k as usize].centre[2] - tolerance,
            Piece::Base => match (&self.base_sphere, self.spec.base_radius_mm) {
                (Some(s), Some(r)) if r > 0.0 => z <= s.centre[2] + tolerance,
                (Some(s), _) => z >= s.centre[2] - tolerance,
                (None, _) => true,
            },
        }
    }

    /// The line parameter of a slope kink where `line` crosses `seam` near `t` at the point
    /// `x`, or `None` if the crossing is not on the envelope.
    fn kink_at(&self, seam: &Seam, line: Line, t: f64, x: [f64; 3]) -> Option<f64> {
        if !(self.on_used_half(seam.a, x[2]) && self.on_used_half(seam.b, x[2])) {
            return None;
        }
        let mut t = t;
        for _ in 0..3 {
            let (za, sa) = self.along(seam.a, line, t)?;
            let (zb, sb) = self.along(seam.b, line, t)?;
            let step = (za - zb) / (sa - sb);
            if step.is_nan() || step.abs() > POLISH_STEP_MM || step == 0.0 {
                break;
            }
            t -= step;
        }
        let (za, _) = self.along(seam.a, line, t)?;
        let (zb, _) = self.along(seam.b, line, t)?;
        let (px, py) = line.at(t);
        let top = self.envelope_sag(px, py)?;
        ((za - zb).abs() <= TIE_MM && top <= za.min(zb) + TIE_MM).then_some(t)
    }
}

/// The footprint disc of a circle's XY projection: centre and radius.
fn disc(c: &Circle) -> [f64; 3] {
    [c.centre[0], c.centre[1], c.radius]
}

/// The disc each seam is indexed by. A crossing on the envelope lies in both pieces'
/// footprints: the smaller of the two bounds it (a seam circle itself can be far wider than
/// where it matters, as where two lenslet spheres of 2 mm meet along a circle of almost 2 mm).
fn seam_extents(seams: &[Seam], footprints: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let within = |p: Piece| match p {
        Piece::Cap(k) => footprints[k as usize],
        Piece::Base => [0.0, 0.0, f64::INFINITY],
    };
    seams
        .iter()
        .map(|s| {
            let (a, b) = (within(s.a), within(s.b));
            if a[2] <= b[2] { a } else { b }
        })
        .collect()
}

/// The base sphere in space, or `None` for a plane.
fn check_base(radius: Option<f64>) -> Result<Option<Sphere>, FieldError> {
    match radius {
        None => Ok(None),
        Some(r) if r.is_finite() && r != 0.0 => Ok(Some(Sphere {
            centre: [0.0, 0.0, r],
            radius: r.abs(),
        })),
        Some(r) => Err(FieldError::new(
            "base_radius_mm",
            r,
            "must be finite and non-zero (leave it out for a flat base)",
        )),
    }
}

/// The checked lengths of a spec.
struct Dimensions {
    element_pitch: f64,
    element_radius: f64,
    element_height: f64,
    lenslet_pitch: f64,
    lenslet_radius: f64,
    lenslet_height: f64,
}

impl Dimensions {
    /// Checks the counts and that every length is a positive number.
    fn check(spec: &CompoundEyeSpec) -> Result<Self, FieldError> {
        if spec.element_rings > MAX_ELEMENT_RINGS {
            return Err(FieldError::new(
                "element_rings",
                spec.element_rings,
                format!("must lie in [0, {MAX_ELEMENT_RINGS}]"),
            ));
        }
        if spec.lenslet_rows.len() > MAX_LENSLET_ROWS {
            return Err(FieldError::new(
                "lenslet_rows",
                format!("{} rows", spec.lenslet_rows.len()),
                format!("at most {MAX_LENSLET_ROWS} rows"),
            ));
        }
        for (k, &n) in spec.lenslet_rows.iter().enumerate() {
            if !(1..=MAX_LENSLETS_PER_ROW).contains(&n) {
                return Err(FieldError::new(
                    format!("lenslet_rows[{k}]"),
                    n,
                    format!("must lie in [1, {MAX_LENSLETS_PER_ROW}]"),
                ));
            }
        }
        Ok(Self {
            element_pitch: length("element_pitch_mm", spec.element_pitch_mm)?,
            element_radius: length("element_radius_mm", spec.element_radius_mm)?,
            element_height: length("element_height_mm", spec.element_height_mm)?,
            lenslet_pitch: length("lenslet_pitch_mm", spec.lenslet_pitch_mm)?,
            lenslet_radius: length("lenslet_radius_mm", spec.lenslet_radius_mm)?,
            lenslet_height: length("lenslet_height_mm", spec.lenslet_height_mm)?,
        })
    }
}

/// The element spheres, each rooted in the base at its layout point, and their poles; checks
/// that every element's layout point lies on the base and that the element height keeps every
/// element rooted.
fn place_elements(
    base: &Asphere,
    parent: Parent,
    centres: &[(f64, f64)],
    dims: &Dimensions,
) -> Result<(Vec<Sphere>, Vec<[f64; 3]>), FieldError> {
    let (re, h) = (dims.element_radius, dims.element_height);
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    let (mut caps, mut poles) = (Vec::new(), Vec::new());
    for &(x, y) in centres {
        let at = base.local(x, y).map_err(|_| {
            FieldError::new(
                "element_pitch_mm",
                dims.element_pitch,
                format!(
                    "puts an element at ({x}, {y}) mm, beyond the base sphere's rim at radius {} mm",
                    base.rim_radius_mm().unwrap_or(f64::INFINITY)
                ),
            )
        })?;
        let (l, u) = rooting::height_limits(parent, re, x.hypot(y));
        (lo, hi) = (lo.max(l), hi.min(u));
        let (sphere, pole) = rooting::rooted_sphere(&at, x, y, h, re);
        caps.push(sphere);
        poles.push(pole);
    }
    if h > lo && h < hi {
        Ok((caps, poles))
    } else {
        Err(FieldError::new(
            "element_height_mm",
            h,
            format!(
                "must lie in ({lo}, {hi}) mm for this base, element radius and layout: every element sphere must rise out of the base and dip back under it before its equator{}",
                if lo < hi {
                    ""
                } else {
                    " (no height fits: make element_radius_mm smaller or the base larger)"
                }
            ),
        ))
    }
}

/// The lenslet spheres of one element, rooted in it at its pole's XY plus each offset; checks
/// that every layout point lies on the element's sphere.
fn place_lenslets(
    element: &Sphere,
    pole: [f64; 3],
    offsets: &[(f64, f64)],
    dims: &Dimensions,
) -> Result<Vec<Sphere>, FieldError> {
    offsets
        .iter()
        .map(|&(ox, oy)| {
            let (x, y) = (pole[0] + ox, pole[1] + oy);
            let at = element.cap_local(x, y).ok_or_else(|| {
                FieldError::new(
                    "lenslet_pitch_mm",
                    dims.lenslet_pitch,
                    format!(
                        "puts a lenslet {} mm from its element's axis, beyond element_radius_mm ({} mm)",
                        (x - element.centre[0]).hypot(y - element.centre[1]),
                        element.radius
                    ),
                )
            })?;
            Ok(rooting::rooted_sphere(&at, x, y, dims.lenslet_height, dims.lenslet_radius).0)
        })
        .collect()
}

/// Checks that the lenslet height keeps every lenslet rooted in its element.
fn check_lenslet_heights(
    elements: &[Sphere],
    poles: &[[f64; 3]],
    offsets: &[(f64, f64)],
    dims: &Dimensions,
) -> Result<(), FieldError> {
    let (re, rl, h) = (
        dims.element_radius,
        dims.lenslet_radius,
        dims.lenslet_height,
    );
    let (mut lo, mut hi) = (0.0f64, f64::INFINITY);
    for (element, pole) in elements.iter().zip(poles) {
        for &(ox, oy) in offsets {
            let d = (pole[0] + ox - element.centre[0]).hypot(pole[1] + oy - element.centre[1]);
            let (l, u) = rooting::height_limits(Parent::Dome(re), rl, d);
            (lo, hi) = (lo.max(l), hi.min(u));
        }
    }
    if offsets.is_empty() || (h > lo && h < hi) {
        Ok(())
    } else {
        Err(FieldError::new(
            "lenslet_height_mm",
            h,
            format!(
                "must lie in ({lo}, {hi}) mm for these radii and this layout: every lenslet sphere must rise out of its element and dip back under it before its equator{}",
                if lo < hi {
                    ""
                } else {
                    " (no height fits: make lenslet_radius_mm smaller or element_radius_mm larger)"
                }
            ),
        ))
    }
}

impl Surface for CompoundEye {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let base = self.base.local(x, y).map_err(|_| self.undefined(x, y))?;
        let mut best = (base.z, None);
        for &k in self.pieces.at(x, y) {
            if let Some(z) = self.caps[k as usize].cap_sag(x, y)
                && z > best.0
            {
                best = (z, Some(k));
            }
        }
        Ok(match best.1 {
            Some(k) => self.caps[k as usize].cap_local(x, y).unwrap_or(base),
            None => base,
        })
    }

    fn sag(&self, x: f64, y: f64) -> Result<f64, UndefinedError> {
        self.envelope_sag(x, y).ok_or_else(|| self.undefined(x, y))
    }

    /// The smallest half-width of a piece's footprint (the semi-minor axis of the ellipse where
    /// it rises out of its parent), or half the XY distance between two elements or two
    /// lenslets whose footprints overlap, if smaller. Slivers of a parent left between
    /// footprints that almost touch can be narrower; they do not hide a maximum from the nose
    /// compensation, because every stretch of a section between two reported kinks is one
    /// spherical cap's section, concave, on which the nose's height has a single maximum.
    fn feature_length_mm(&self) -> f64 {
        self.feature
    }

    /// Its bounds on every line ([`Surface::disc_bounds`]).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.disc_bounds(radius_mm)
    }

    /// The base's bounds and every cap's whose footprint disc meets the disc: a cap is on top
    /// only inside the disc of its rooted seam (centre c, radius ρ), where its horizontal
    /// distance from its centre is at most `d = |c − C| + ρ` (< R by the rooting); there a
    /// sphere's gradient is at most `d/w` and its Hessian's eigenvalues (−1/w and −R²/w³,
    /// w = √(R² − d²)) lie in `[−R²/w³, −1/R]`. The envelope of convex caps meets itself and the
    /// base in valleys only (the upper envelope's slope rises across each seam).
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let mut b = self.base.disc_bounds(t)?;
        for seam in self.rooted_seams() {
            let Piece::Cap(k) = seam.a else {
                continue;
            };
            let [x, y, r] = disc(&seam.circle);
            if x.hypot(y) - r > t {
                continue;
            }
            let cap = &self.caps[k as usize];
            let (big, d) = (cap.radius, (x - cap.centre[0]).hypot(y - cap.centre[1]) + r);
            if d >= big {
                return None;
            }
            let w = ((big - d) * (big + d)).sqrt();
            b = b.or(SectionBounds {
                max_slope: d / w,
                max_curvature: -1.0 / big,
                min_curvature: -big * big / (w * w * w),
                has_ridges: false,
                has_valleys: true,
            });
        }
        // The sum with a flat section adds the margins every bound carries.
        SectionBounds::FLAT.and(b)
    }

    /// Not said: the seams are found where the top piece changes (0).
    fn kink_free_radius(&self, _x: f64, _y: f64) -> f64 {
        0.0
    }

    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let ((xa, ya), (xb, yb)) = (line.at(t0), line.at(t1));
        let mut near = Vec::new();
        self.seam_index
            .in_box([xa.min(xb), xa.max(xb), ya.min(yb), ya.max(yb)], &mut near);
        near.sort_unstable();
        near.dedup();
        let mut kinks = Vec::new();
        for k in near {
            let seam = &self.seams[k as usize];
            for (t, x) in seam.circle.crossings(line) {
                // Crossings well outside the interval cannot polish into it.
                if t < t0 - POLISH_STEP_MM || t > t1 + POLISH_STEP_MM {
                    continue;
                }
                if let Some(t) = self.kink_at(seam, line, t, x)
                    && t > t0
                    && t < t1
                {
                    kinks.push(t);
                }
            }
        }
        kinks.sort_by(f64::total_cmp);
        kinks.dedup_by(|later, kept| *later - *kept <= SAME_KINK_MM);
        out.extend(kinks);
    }

    fn describe(&self) -> String {
        let s = &self.spec;
        let base = match s.base_radius_mm {
            None => "a flat base".to_string(),
            Some(r) if r < 0.0 => format!("a convex base sphere R {r} mm"),
            Some(r) => format!("a concave base sphere R {r} mm"),
        };
        format!(
            "compound eye: {} elements × {} lenslets on {base}; elements R {} mm, {} mm high, pitch {} mm; lenslets R {} mm, {} mm high, pitch {} mm, rows {:?}; sharp intersections",
            self.elements,
            self.lenslets_per_element,
            s.element_radius_mm,
            s.element_height_mm,
            s.element_pitch_mm,
            s.lenslet_radius_mm,
            s.lenslet_height_mm,
            s.lenslet_pitch_mm,
            s.lenslet_rows
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn preset() -> CompoundEye {
        CompoundEye::new(&CompoundEyeSpec::paper000(), PartDisc::centred(5.0)).unwrap()
    }

    #[test]
    fn bounds_hold_on_dense_sections_with_valleys() {
        // The preset (dome base, 7 elements of 17 lenslets), and a lone element on a dome, a
        // bowl and a plane: the caps' and base's bounds hold at every section sample.
        use crate::surface::section_bounds::assert_bounds_hold;
        let eyes = [
            preset(),
            lone_element(Some(-20.0), 3.0, 0.5),
            lone_element(Some(30.0), 3.0, 0.5),
            lone_element(None, 3.0, 0.5),
        ];
        for eye in eyes {
            let (b, slope, _) = assert_bounds_hold(&eye, 5.0, 72, 20_000);
            assert!(b.has_valleys && !b.has_ridges, "{b:?}");
            assert_eq!(eye.disc_bounds(5.0), Some(b));
            // The rims' slope is reached to within the footprint discs' looseness.
            assert!(b.max_slope < 1.5 * slope, "{b:?} {slope}");
        }
    }

    /// A single bare element (no lenslets) on the given base.
    fn lone_element(base_radius_mm: Option<f64>, radius: f64, height: f64) -> CompoundEye {
        let spec = CompoundEyeSpec {
            base_radius_mm,
            element_rings: 0,
            element_radius_mm: radius,
            element_height_mm: height,
            lenslet_rows: vec![],
            ..CompoundEyeSpec::paper000()
        };
        CompoundEye::new(&spec, PartDisc::centred(5.0)).unwrap()
    }

    #[test]
    fn paper000_has_seven_elements_of_seventeen_lenslets() {
        let eye = preset();
        assert_eq!(eye.element_count(), 7);
        assert_eq!(eye.lenslet_count(), 7 * 17);
        assert_eq!(eye.caps.len(), 7 + 7 * 17);
        assert!(eye.describe().contains("7 elements × 17 lenslets"));
    }

    #[test]
    fn the_sag_at_a_lenslet_pole_is_the_pole() {
        let eye = preset();
        // On the axis everything is coaxial: the central lenslet's pole is h_e + h_l up, level.
        let l = eye.local(0.0, 0.0).unwrap();
        assert!((l.z - 0.116).abs() < 1e-15, "{}", l.z);
        assert!(l.zx.abs() < 1e-15 && l.zy.abs() < 1e-15);
        // The element at (2.6, 0) stands on the dome R −40 (centre (0, 0, −40)) along its
        // normal n; its central lenslet's pole is (h_e + h_l)·n out of the base point, and the
        // lenslet's normal there is n itself.
        let w = (1600.0f64 - 2.6 * 2.6).sqrt();
        let base = [2.6, 0.0, w - 40.0];
        let n = [2.6 / 40.0, 0.0, w / 40.0];
        let pole = [base[0] + 0.116 * n[0], 0.0, base[2] + 0.116 * n[2]];
        let l = eye.local(pole[0], pole[1]).unwrap();
        assert!((l.z - pole[2]).abs() < 1e-14, "{} vs {}", l.z, pole[2]);
        assert!((l.zx + n[0] / n[2]).abs() < 1e-14 && l.zy.abs() < 1e-15);
    }

    #[test]
    fn the_feature_length_is_half_the_distance_between_lenslet_footprints() {
        // The footprints' centres are the seam circles' centres C_e + a·n, with n the element's
        // normal at the lenslet's layout point and a = (D² + R_e² − R_l²)/(2D), D the distance
        // between the spheres' centres (R_e + h_l − R_l): so neighbouring footprints lie
        // a/R_e·p_l apart in XY on every element. That is below every footprint's half-width.
        let (re, rl, hl, p) = (8.0, 2.0, 0.016, 0.45);
        let d = re + hl - rl;
        let a = (d * d + re * re - rl * rl) / (2.0 * d);
        let eye = preset();
        assert!(
            (eye.feature_length_mm() - 0.5 * p * a / re).abs() < 1e-12,
            "{}",
            eye.feature_length_mm()
        );
    }

    #[test]
    fn a_lone_element_on_a_plane_is_a_spherical_cap_with_rim_kinks() {
        // Centre (0, 0, h − R): the cap meets the plane at ρ = √(R² − (R − h)²).
        let (big, h) = (3.0, 0.2);
        let eye = lone_element(None, big, h);
        let rim = (big * big - (big - h) * (big - h)).sqrt();
        for &(x, y) in &[(0.0, 0.0), (0.3, -0.4), (0.9, 0.5), (1.2, 0.0), (-2.0, 1.0)] {
            let rho2: f64 = x * x + y * y;
            let cap = h - big + (big * big - rho2).sqrt();
            assert!(
                (eye.sag(x, y).unwrap() - cap.max(0.0)).abs() < 1e-15,
                "({x}, {y})"
            );
        }
        let mut kinks = Vec::new();
        eye.slope_kinks(Line::radial(0.6, 0.8), -2.0, 2.0, &mut kinks);
        kinks.sort_by(f64::total_cmp);
        assert_eq!(kinks.len(), 2, "{kinks:?}");
        assert!((kinks[0] + rim).abs() < 1e-14 && (kinks[1] - rim).abs() < 1e-14);
        // A line off the axis crosses the rim circle where x² + 0.5² = rim².
        let mut kinks = Vec::new();
        let line = Line {
            x0: -2.0,
            y0: 0.5,
            c: 1.0,
            s: 0.0,
        };
        eye.slope_kinks(line, 0.0, 4.0, &mut kinks);
        kinks.sort_by(f64::total_cmp);
        let half = (rim * rim - 0.25).sqrt();
        assert_eq!(kinks.len(), 2, "{kinks:?}");
        assert!((kinks[0] - (2.0 - half)).abs() < 1e-14 && (kinks[1] - (2.0 + half)).abs() < 1e-14);
    }

    #[test]
    fn a_lone_element_in_a_bowl_meets_it_where_the_spheres_meet() {
        // Element centre (0, 0, h − R_e), bowl centre (0, 0, R_b): the seam is the horizontal
        // circle at the radical plane's height z, radius √(R_b² − (z − R_b)²).
        let (rb, re, h) = (20.0f64, 4.0f64, 0.3f64);
        let eye = lone_element(Some(rb), re, h);
        let ce = h - re;
        let z = (re * re - rb * rb + rb * rb - ce * ce) / (2.0 * (rb - ce));
        let rim = (rb * rb - (z - rb) * (z - rb)).sqrt();
        let mut kinks = Vec::new();
        eye.slope_kinks(Line::radial(1.0, 0.0), 0.0, 3.0, &mut kinks);
        assert_eq!(kinks.len(), 1, "{kinks:?}");
        assert!((kinks[0] - rim).abs() < 1e-13, "{} vs {rim}", kinks[0]);
        // Either side, the sag is the element's, then the bowl's.
        let bowl = |r: f64| r * r / (rb + (rb * rb - r * r).sqrt());
        let cap = |r: f64| ce + (re * re - r * r).sqrt();
        assert!((eye.sag(rim - 0.01, 0.0).unwrap() - cap(rim - 0.01)).abs() < 1e-15);
        assert!((eye.sag(rim + 0.01, 0.0).unwrap() - bowl(rim + 0.01)).abs() < 1e-15);
    }

    /// The piece on top at (x, y) by looking at every cap, not only those the index lists.
    fn top_piece(eye: &CompoundEye, x: f64, y: f64) -> Option<u32> {
        let mut best = (eye.base.sag(x, y).unwrap(), None);
        for (k, cap) in eye.caps.iter().enumerate() {
            if let Some(z) = cap.cap_sag(x, y)
                && z > best.0
            {
                best = (z, Some(k as u32));
            }
        }
        best.1
    }

    #[test]
    fn slope_kinks_are_where_the_top_piece_changes() {
        // Brute force along radial lines of the preset: every change of the top piece between
        // two scan samples holds a reported kink, and every reported kink lies in such a change
        // (a grazing pair of kinks may fall between two samples: then both sides agree).
        let eye = preset();
        let n = 40_000;
        for theta in [0.0f64, 0.35, 1.2, 2.9] {
            let (s, c) = theta.sin_cos();
            let (t0, t1) = (-4.7, 4.7);
            let mut kinks = Vec::new();
            eye.slope_kinks(Line::radial(c, s), t0, t1, &mut kinks);
            let step = (t1 - t0) / n as f64;
            let mut changes = Vec::new();
            let mut prev = top_piece(&eye, t0 * c, t0 * s);
            for k in 1..=n {
                let t = t0 + step * k as f64;
                let top = top_piece(&eye, t * c, t * s);
                if top != prev {
                    changes.push((t - step, t));
                }
                prev = top;
            }
            assert!(changes.len() > 6, "θ {theta}: {changes:?}");
            for (a, b) in &changes {
                assert!(
                    kinks.iter().any(|t| *t >= a - 1e-12 && *t <= b + 1e-12),
                    "θ {theta}: no kink in [{a}, {b}]: {kinks:?}"
                );
            }
            for t in &kinks {
                let (a, b) = (t - 1e-9, t + 1e-9);
                assert_ne!(
                    top_piece(&eye, a * c, a * s),
                    top_piece(&eye, b * c, b * s),
                    "θ {theta}: kink {t} changes nothing"
                );
            }
        }
    }

    #[test]
    fn beyond_the_base_rim_is_an_error_naming_the_radius() {
        let eye = lone_element(Some(-6.0), 2.0, 0.1);
        let e = eye.local(0.0, 6.5).unwrap_err();
        assert_eq!(e.radius_mm, 6.5);
        assert_eq!(e.surface, "compound eye");
        assert!(e.reason.contains("rim at radius 6 mm"), "{e}");
        assert_eq!(eye.sag(6.5, 0.0).unwrap_err().radius_mm, 6.5);
        assert!(eye.local(5.9, 0.0).is_ok());
    }

    fn error(spec: CompoundEyeSpec) -> FieldError {
        CompoundEye::new(&spec, PartDisc::centred(5.0)).unwrap_err()
    }

    #[test]
    fn parameters_that_make_no_eye_are_rejected_by_name() {
        let p = CompoundEyeSpec::paper000;
        let cases = [
            (
                CompoundEyeSpec {
                    base_radius_mm: Some(0.0),
                    ..p()
                },
                "base_radius_mm",
            ),
            (
                CompoundEyeSpec {
                    element_rings: 31,
                    ..p()
                },
                "element_rings",
            ),
            (
                CompoundEyeSpec {
                    element_pitch_mm: -1.0,
                    ..p()
                },
                "element_pitch_mm",
            ),
            (
                CompoundEyeSpec {
                    lenslet_radius_mm: f64::NAN,
                    ..p()
                },
                "lenslet_radius_mm",
            ),
            (
                CompoundEyeSpec {
                    lenslet_rows: vec![3, 0, 3],
                    ..p()
                },
                "lenslet_rows[1]",
            ),
            (
                CompoundEyeSpec {
                    element_rings: 30,
                    lenslet_rows: vec![64; 64],
                    ..p()
                },
                "lenslet_rows",
            ),
            // The outer elements' layout points beyond the base sphere's rim.
            (
                CompoundEyeSpec {
                    base_radius_mm: Some(-2.0),
                    element_radius_mm: 1.0,
                    ..p()
                },
                "element_pitch_mm",
            ),
            // Lenslet layout points beyond the element's rim.
            (
                CompoundEyeSpec {
                    lenslet_pitch_mm: 5.0,
                    ..p()
                },
                "lenslet_pitch_mm",
            ),
            // Standing on their equators.
            (
                CompoundEyeSpec {
                    element_height_mm: 7.0,
                    ..p()
                },
                "element_height_mm",
            ),
            (
                CompoundEyeSpec {
                    lenslet_height_mm: 1.9,
                    ..p()
                },
                "lenslet_height_mm",
            ),
        ];
        for (spec, field) in cases {
            let e = error(spec);
            assert_eq!(e.field, field, "{e}");
        }
        let e = error(CompoundEyeSpec {
            lenslet_height_mm: 1.9,
            ..p()
        });
        assert!(e.allowed.starts_with("must lie in (0, "), "{e}");
        // A lenslet as wide as its element fits at no height.
        let e = error(CompoundEyeSpec {
            lenslet_radius_mm: 8.0,
            ..p()
        });
        assert!(e.allowed.contains("no height fits"), "{e}");
    }

    #[test]
    fn the_height_range_in_the_message_is_the_one_that_builds() {
        // The message's upper limit for the element height: just below it builds, above fails.
        let e = error(CompoundEyeSpec {
            element_height_mm: 7.0,
            ..CompoundEyeSpec::paper000()
        });
        let hi: f64 = e.allowed["must lie in (0, ".len()..]
            .split(')')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(hi > 0.1 && hi < 7.0, "{hi}");
        for (h, ok) in [(hi * (1.0 - 1e-9), true), (hi * (1.0 + 1e-9), false)] {
            let spec = CompoundEyeSpec {
                element_height_mm: h,
                lenslet_rows: vec![],
                ..CompoundEyeSpec::paper000()
            };
            assert_eq!(
                CompoundEye::new(&spec, PartDisc::centred(5.0)).is_ok(),
                ok,
                "{h}"
            );
        }
    }

    #[test]
    fn json_defaults_to_seven_by_seventeen_and_rejects_unknown_fields() {
        let json = r#"{"type":"compound_eye","base_radius_mm":-40,"element_pitch_mm":2.6,
            "element_radius_mm":8,"element_height_mm":0.1,"lenslet_pitch_mm":0.45,
            "lenslet_radius_mm":2,"lenslet_height_mm":0.016}"#;
        let spec: super::super::SurfaceSpec = serde_json::from_str(json).unwrap();
        assert_eq!(
            spec,
            super::super::SurfaceSpec::CompoundEye(CompoundEyeSpec::paper000())
        );
        let text = serde_json::to_string(&spec).unwrap();
        assert_eq!(
            serde_json::from_str::<super::super::SurfaceSpec>(&text).unwrap(),
            spec
        );
        let bad = json.replace("\"lenslet_pitch_mm\"", "\"lens_pitch_mm\"");
        let e = serde_json::from_str::<super::super::SurfaceSpec>(&bad)
            .unwrap_err()
            .to_string();
        assert!(e.contains("lens_pitch_mm"), "{e}");
        // No base radius: a flat base.
        let flat = json.replace("\"base_radius_mm\":-40,", "");
        let spec: super::super::SurfaceSpec = serde_json::from_str(&flat).unwrap();
        let eye = spec.build(5.0).unwrap();
        assert_eq!(eye.sag(4.9, 0.0).unwrap(), 0.0);
    }
}

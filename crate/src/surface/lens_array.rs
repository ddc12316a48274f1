//! Microlens array: spherical lenslets of radius R and clear aperture a on a rectangular or
//! hexagonal grid of pitch p, convex or concave, on a flat land at z = 0 (paper 004, section 3.2
//! and Table 1: Ø10 mm, a = 1 mm, p = 1 mm, R = 2.84 mm, lenslet sag −44.4 µm).
//!
//! A lenslet centred at c has, for ρ = |(x, y) − c| ≤ a/2, the sag
//! `z = ±(√(R² − (a/2)²) − √(R² − ρ²))` (− convex, + concave), so its rim meets the land at
//! z = 0 and its vertex lies at ∓(R − √(R² − a²/4)). Only lenslets whose whole aperture lies
//! inside the part (|c| + a/2 ≤ part radius) are cut; the rest of the part is land. Because
//! a ≤ p, a point can only lie in the lenslet of its nearest grid node, found in O(1).
//! A lenslet sits on the spindle axis; grid rows run along X.

use super::{Line, Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, length};
use crate::rounding::nearest;
use serde::{Deserialize, Serialize};

/// The most lenslets on a part.
pub const MAX_LENSLETS: f64 = 1e7;

/// Lattice of the lenslet centres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Grid {
    /// Centres at `p·(i, j)`.
    Rectangular,
    /// Centres at `p·(i + j/2, j·√3/2)`.
    Hexagonal,
}

/// Whether the lenslets stand out of the land or are dug into it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Form {
    /// Bumps: vertex at +sag.
    Convex,
    /// Dimples: vertex at −sag (paper 004's −44.4 µm).
    Concave,
}

/// Job entry of a lens array.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LensArraySpec {
    /// Radius of curvature of each lenslet, mm, ≥ aperture/2.
    pub lens_radius_mm: f64,
    /// Clear aperture (diameter) of each lenslet, mm, ≤ pitch.
    pub aperture_mm: f64,
    /// Distance between neighbouring lenslet centres, mm.
    pub pitch_mm: f64,
    /// `rectangular` or `hexagonal`.
    pub grid: Grid,
    /// `convex` or `concave`.
    pub form: Form,
}

impl LensArraySpec {
    /// Paper 004, Table 1: R 2.84 mm, aperture 1 mm, pitch 1 mm, concave (sag −44.4 µm) on a
    /// rectangular grid; the part is Ø10 mm.
    pub fn paper004() -> Self {
        Self {
            lens_radius_mm: 2.84,
            aperture_mm: 1.0,
            pitch_mm: 1.0,
            grid: Grid::Rectangular,
            form: Form::Concave,
        }
    }
}

/// A lens array, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct LensArray {
    spec: LensArraySpec,
    half_aperture: f64,
    /// √(R² − (a/2)²): the rim height offset.
    rim_w: f64,
    /// +1 concave, −1 convex.
    sign: f64,
    /// The part disc: only lenslets whose centre lies within `max_centre_radius` of its
    /// centre are cut.
    part: PartDisc,
    /// Part radius less half the aperture.
    max_centre_radius: f64,
    /// Its square.
    max_centre_radius2: f64,
    /// 1/pitch and 1/(row spacing), for the grid lookups.
    per_pitch: f64,
    per_row: f64,
}

impl LensArray {
    /// Checks a spec and builds the surface for the part disc `part`.
    pub fn new(spec: &LensArraySpec, part: PartDisc) -> Result<Self, FieldError> {
        let part_radius_mm = part.radius_mm;
        let r = length("lens_radius_mm", spec.lens_radius_mm)?;
        let a = length("aperture_mm", spec.aperture_mm)?;
        let p = length("pitch_mm", spec.pitch_mm)?;
        if a > p {
            return Err(FieldError::new(
                "aperture_mm",
                a,
                format!("must not exceed pitch_mm ({p} mm)"),
            ));
        }
        if a > 2.0 * r {
            return Err(FieldError::new(
                "aperture_mm",
                a,
                format!("must not exceed twice lens_radius_mm ({} mm)", 2.0 * r),
            ));
        }
        // Grid cells over the part: a guard against a pitch that is a typo.
        let cells = (part_radius_mm / p).powi(2) * std::f64::consts::PI;
        if cells > MAX_LENSLETS {
            return Err(FieldError::new(
                "pitch_mm",
                p,
                format!("gives about {cells:.2e} lenslets on the part; at most {MAX_LENSLETS:.0e}"),
            ));
        }
        let half_aperture = a / 2.0;
        let max_centre_radius = part_radius_mm - half_aperture + 1e-9;
        let sign = match spec.form {
            Form::Concave => 1.0,
            Form::Convex => -1.0,
        };
        Ok(Self {
            spec: spec.clone(),
            half_aperture,
            rim_w: (r * r - half_aperture * half_aperture).sqrt(),
            sign,
            part,
            max_centre_radius,
            // None is cut when a lenslet is wider than the part (the radius is negative).
            max_centre_radius2: if max_centre_radius >= 0.0 {
                max_centre_radius * max_centre_radius
            } else {
                -1.0
            },
            per_pitch: 1.0 / p,
            per_row: 1.0 / row_spacing(spec.grid, p),
        })
    }

    /// Signed sag of each lenslet's vertex below (concave, negative) or above the land, mm.
    pub fn lenslet_sag_mm(&self) -> f64 {
        -self.sign * (self.spec.lens_radius_mm - self.rim_w)
    }

    /// The grid node nearest to (x, y).
    fn nearest_centre(&self, x: f64, y: f64) -> (f64, f64) {
        let p = self.spec.pitch_mm;
        let columns = |x: f64, shift: f64| nearest_of_ratio(x, p, self.per_pitch, shift);
        match self.spec.grid {
            Grid::Rectangular => (columns(x, 0.0) * p, columns(y, 0.0) * p),
            Grid::Hexagonal => {
                let row = row_spacing(Grid::Hexagonal, p);
                let j0 = nearest_of_ratio(y, row, self.per_row, 0.0);
                let mut best = (f64::INFINITY, 0.0, 0.0);
                for j in [j0 - 1.0, j0, j0 + 1.0] {
                    let cx = (columns(x, j / 2.0) + j / 2.0) * p;
                    let cy = j * row;
                    let d = (x - cx).powi(2) + (y - cy).powi(2);
                    if d < best.0 {
                        best = (d, cx, cy);
                    }
                }
                (best.1, best.2)
            }
        }
    }

    /// Calls `visit` with every grid node in the box `[x0, x1] × [y0, y1]` whose lenslet is cut.
    fn centres_in(&self, [x0, x1, y0, y1]: [f64; 4], mut visit: impl FnMut(f64, f64)) {
        // Only centres within the part's bounds are cut: the box cut to them bounds the loops
        // by the lenslets on the part, wherever the box lies (a composite term decentred by
        // 1e308 mm once asked for 2⁶⁴ rows).
        let (r, part) = (self.max_centre_radius, &self.part);
        let (x0, x1) = (x0.max(part.x_mm - r), x1.min(part.x_mm + r));
        let (y0, y1) = (y0.max(part.y_mm - r), y1.min(part.y_mm + r));
        if !(x0 <= x1 && y0 <= y1) {
            return;
        }
        let p = self.spec.pitch_mm;
        let row = row_spacing(self.spec.grid, p);
        for j in ceiling(y0 / row)..=floor(y1 / row) {
            let shift = match self.spec.grid {
                Grid::Rectangular => 0.0,
                Grid::Hexagonal => j as f64 / 2.0,
            };
            for i in ceiling(x0 / p - shift)..=floor(x1 / p - shift) {
                let (cx, cy) = ((i as f64 + shift) * p, j as f64 * row);
                if self.is_cut(cx, cy) {
                    visit(cx, cy);
                }
            }
        }
    }

    /// Whether the lenslet centred at (cx, cy) lies wholly inside the part.
    fn is_cut(&self, cx: f64, cy: f64) -> bool {
        let (dx, dy) = (cx - self.part.x_mm, cy - self.part.y_mm);
        dx * dx + dy * dy <= self.max_centre_radius2
    }

    /// Number of lenslets cut on the part.
    pub fn lenslet_count(&self) -> usize {
        let (r, x, y) = (self.max_centre_radius, self.part.x_mm, self.part.y_mm);
        let mut count = 0;
        self.centres_in([x - r, x + r, y - r, y + r], |_, _| count += 1);
        count
    }
}

/// `nearest(x / d − shift)`, by a multiplication with `per_d` = 1/d where that rounds to the
/// same integer: the product differs from the quotient by a few ulps (less than 10⁻¹⁵·|t| + one
/// ulp of the shift's subtraction), so the two can disagree only where t lies within that of a
/// half, and there the quotient decides. A division per coordinate was a fifth of a lens
/// array's evaluation.
fn nearest_of_ratio(x: f64, d: f64, per_d: f64, shift: f64) -> f64 {
    let t = x * per_d - shift;
    let n = nearest(t);
    let from_half = (t - n).abs() - 0.5;
    if from_half.abs() < 1e-12 + 1e-15 * t.abs() {
        nearest(x / d - shift)
    } else {
        n
    }
}

/// The distance between the grid's rows: the pitch, or √3/2 of it on a hexagonal grid.
fn row_spacing(grid: Grid, p: f64) -> f64 {
    match grid {
        Grid::Rectangular => p,
        Grid::Hexagonal => p * 3f64.sqrt() / 2.0,
    }
}

/// ⌊x⌋ for |x| < 2⁶³ by truncation, saturated beyond (`f64::floor` is a library call on
/// baseline x86-64, and the kinks of a section are asked for at every Newton step of the
/// compensation).
fn floor(x: f64) -> i64 {
    let t = x as i64;
    if t as f64 > x { t.saturating_sub(1) } else { t }
}

/// ⌈x⌉ for |x| < 2⁶³ by truncation (saturated beyond).
fn ceiling(x: f64) -> i64 {
    let t = x as i64;
    if (t as f64) < x {
        t.saturating_add(1)
    } else {
        t
    }
}

impl Surface for LensArray {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let (cx, cy) = self.nearest_centre(x, y);
        let (dx, dy) = (x - cx, y - cy);
        let rho2 = dx * dx + dy * dy;
        let h = self.half_aperture;
        if rho2 > h * h || !self.is_cut(cx, cy) {
            return Ok(Local::default());
        }
        let r2 = self.spec.lens_radius_mm * self.spec.lens_radius_mm;
        let w = (r2 - rho2).sqrt();
        let s = self.sign;
        // One division: the slopes and curvatures scale with s/w and s/w³ = (s/w)³ (s = ±1).
        let k = s / w;
        let k3 = k * k * k;
        Ok(Local {
            z: s * (self.rim_w - w),
            zx: dx * k,
            zy: dy * k,
            zxx: (r2 - dy * dy) * k3,
            zxy: dx * dy * k3,
            zyy: (r2 - dx * dx) * k3,
        })
    }

    /// The crossings of the line with the rims of the lenslets near it: the roots of
    /// `|p(t) − centre|² = (a/2)²`, `t = along ± √((a/2 − across)(a/2 + across))` with the
    /// centre's offsets along and across the line (the product, not `b² − c`, keeps a line
    /// that grazes a rim from losing its digits to cancellation).
    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let h = self.half_aperture;
        let ((xa, ya), (xb, yb)) = (line.at(t0), line.at(t1));
        let bounds = [
            xa.min(xb) - h,
            xa.max(xb) + h,
            ya.min(yb) - h,
            ya.max(yb) + h,
        ];
        self.centres_in(bounds, |cx, cy| {
            let (dx, dy) = (cx - line.x0, cy - line.y0);
            let along = line.c * dx + line.s * dy;
            let across = line.c * dy - line.s * dx;
            let disc = (h - across) * (h + across);
            if disc > 0.0 {
                let w = disc.sqrt();
                out.extend(
                    [along - w, along + w]
                        .into_iter()
                        .filter(|t| *t > t0 && *t < t1),
                );
            }
        });
    }

    /// The distance to the nearest lenslet's rim, `|d − a/2|` (d the distance to the nearest
    /// grid node, cut or not): from outside every rim the nearest rim is the nearest node's (the
    /// rims are equal circles); from inside a rim that is its own node's, and any other rim lies
    /// at least `p − d − a/2 ≥ a/2 − d` away, the nodes being at least a pitch apart and a ≤ p.
    /// Rims that are not cut only add distance.
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        let (cx, cy) = self.nearest_centre(x, y);
        let (dx, dy) = (x - cx, y - cy);
        ((dx * dx + dy * dy).sqrt() - self.half_aperture).abs()
    }

    /// On a sphere of radius R, |∇z| = ρ/w and every second directional derivative is at most
    /// R²/w³ in size (w = √(R² − ρ²)), both largest at the rim (ρ = a/2); the land is flat.
    /// Concave lenslets are bowls (f″ ≥ 0) whose rims are ridges (the slope drops from the
    /// land's 0 into the bowl and from the bowl's wall back to 0); convex ones are bumps
    /// (f″ ≤ 0) whose rims are valleys.
    fn section_bounds(&self, _radius_mm: f64) -> Option<SectionBounds> {
        let (big, w) = (self.spec.lens_radius_mm, self.rim_w);
        let curvature = big * big / (w * w * w) * (1.0 + 1e-9);
        let convex = self.spec.form == Form::Convex;
        Some(SectionBounds {
            max_slope: self.half_aperture / w * (1.0 + 1e-9),
            max_curvature: if convex { 0.0 } else { curvature },
            min_curvature: if convex { -curvature } else { 0.0 },
            has_ridges: !convex,
            has_valleys: convex,
        })
    }

    /// The section bounds, which hold on any line: |∇z| = ρ/w and the sphere's Hessian has the
    /// eigenvalues ±R²/w³ and ±1/w (R²/w³ the larger), and a concave rim is a ridge, a convex
    /// one a valley, along any line that crosses it.
    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.section_bounds(radius_mm)
    }

    fn feature_length_mm(&self) -> f64 {
        let land = self.spec.pitch_mm - self.spec.aperture_mm;
        if land > 0.0 {
            self.half_aperture.min(land)
        } else {
            self.half_aperture
        }
    }

    fn describe(&self) -> String {
        let s = &self.spec;
        let form = match s.form {
            Form::Convex => "convex",
            Form::Concave => "concave",
        };
        let grid = match s.grid {
            Grid::Rectangular => "rectangular",
            Grid::Hexagonal => "hexagonal",
        };
        format!(
            "lens array: {} {form} lenslets, R {} mm, aperture {} mm, pitch {} mm, {grid} grid, lenslet sag {:.4} µm",
            self.lenslet_count(),
            s.lens_radius_mm,
            s.aperture_mm,
            s.pitch_mm,
            self.lenslet_sag_mm() * 1e3
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn section_bounds_hold_over_the_part_and_convex_arrays_have_valleys() {
        let l = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        let b = l.section_bounds(5.0).unwrap();
        let (mut slope, mut curv) = (0.0f64, 0.0f64);
        for i in 0..200_000 {
            let (t, theta) = (-5.0 + 10.0 * i as f64 / 200_000.0, 0.37 + 1e-4 * i as f64);
            let (s, c) = f64::sin_cos(theta);
            let r = l.local(t * c, t * s).unwrap().radial(c, s);
            slope = slope.max(r.slope.abs());
            curv = curv.max(r.curvature_term);
        }
        assert!(
            slope <= b.max_slope && slope > 0.99 * b.max_slope,
            "{slope} {b:?}"
        );
        assert!(
            curv <= b.max_curvature && curv > 0.95 * b.max_curvature,
            "{curv} {b:?}"
        );
        let convex = LensArraySpec {
            form: Form::Convex,
            ..LensArraySpec::paper004()
        };
        let convex = LensArray::new(&convex, PartDisc::centred(5.0)).unwrap();
        // Convex lenslets: the same slope, the curvature's size as the least, valleys.
        let v = convex.section_bounds(5.0).unwrap();
        assert_eq!((v.max_slope, v.max_curvature), (b.max_slope, 0.0));
        assert_eq!(v.min_curvature, -b.max_curvature);
        assert!(v.has_valleys && !v.has_ridges && b.has_ridges && !b.has_valleys);
        let (mut least, mut most) = (0.0f64, f64::NEG_INFINITY);
        for i in 0..200_000 {
            let (t, theta) = (-5.0 + 10.0 * i as f64 / 200_000.0, 0.37 + 1e-4 * i as f64);
            let (s, c) = f64::sin_cos(theta);
            let r = convex.local(t * c, t * s).unwrap().radial(c, s);
            least = least.min(r.curvature_term);
            most = most.max(r.curvature_term);
        }
        assert!(least >= v.min_curvature && least < 0.95 * v.min_curvature);
        assert!(most <= v.max_curvature, "{most}");
    }

    #[test]
    fn paper004_lenslet_sag_is_minus_44_4_um() {
        let l = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        // Table 1 gives −44.4 µm; the exact value is 2.84 − √(2.84² − 0.25) mm.
        assert!((l.lenslet_sag_mm() * 1e3 - -44.4).abs() < 0.05);
        assert!((l.local(0.0, 0.0).unwrap().z - l.lenslet_sag_mm()).abs() < 1e-15);
        assert!((l.local(2.0, -3.0).unwrap().z - l.lenslet_sag_mm()).abs() < 1e-15);
        // Corner of a cell: land.
        assert_eq!(l.local(0.5, 0.5).unwrap(), Local::default());
        // Centres with |c| ≤ 4.5 mm on the unit grid.
        let brute = (-5i32..=5)
            .flat_map(|i| (-5i32..=5).map(move |j| (i, j)))
            .filter(|&(i, j)| ((i * i + j * j) as f64).sqrt() <= 4.5)
            .count();
        assert_eq!(l.lenslet_count(), brute);
        // A lenslet at (5, 0) would cross the part edge: land there.
        assert_eq!(l.local(4.9, 0.0).unwrap().z, 0.0);
    }

    #[test]
    fn slope_kinks_are_the_rim_crossings_found_by_scanning() {
        for grid in [Grid::Rectangular, Grid::Hexagonal] {
            let spec = LensArraySpec {
                grid,
                aperture_mm: 0.8,
                ..LensArraySpec::paper004()
            };
            let l = LensArray::new(&spec, PartDisc::centred(5.0)).unwrap();
            for theta in [0.0f64, 0.3, 1.1, 2.5, 4.0] {
                let (s, c) = theta.sin_cos();
                let (t0, t1) = (-1.3, 4.7);
                let mut kinks = Vec::new();
                l.slope_kinks(Line::radial(c, s), t0, t1, &mut kinks);
                kinks.sort_by(f64::total_cmp);
                // Brute force: where the point moves in or out of a lenslet (non-zero sag).
                let inside = |t: f64| l.local(t * c, t * s).unwrap().z != 0.0;
                let n = 600_000;
                let step = (t1 - t0) / n as f64;
                let mut crossings = Vec::new();
                for k in 0..n {
                    let (a, b) = (t0 + step * k as f64, t0 + step * (k + 1) as f64);
                    if inside(a) != inside(b) {
                        crossings.push((a, b));
                    }
                }
                assert_eq!(kinks.len(), crossings.len(), "θ {theta}: {kinks:?}");
                for (t, (a, b)) in kinks.iter().zip(&crossings) {
                    assert!(
                        *t >= a - 1e-12 && *t <= b + 1e-12,
                        "θ {theta}: {t} not in [{a}, {b}]"
                    );
                }
            }
        }
    }

    #[test]
    fn nearest_rounds_like_round_off_the_halves() {
        for &x in &[
            0.0,
            0.49,
            0.51,
            -0.49,
            -0.51,
            3.2,
            -3.2,
            7.7,
            -7.7,
            1e9 + 0.3,
            -1e9 - 0.7,
            // x + 0.5 just below 2⁵¹ (rounded by the 1.5·2⁵² sum) and just above it (by the
            // conversion).
            (1u64 << 51) as f64 - 1.25,
            1.25 - (1u64 << 51) as f64,
            2251799813685247.7,
            -2251799813685247.7,
            2251799813685249.0,
            -2251799813685249.0,
        ] {
            assert_eq!(nearest(x), f64::round(x), "{x}");
        }
        // Halves go up (f64::round goes away from zero); both neighbours are equally near.
        assert_eq!(nearest(-2.5), -2.0);
        assert_eq!(nearest(2.5), 3.0);
    }

    #[test]
    fn grid_lookups_by_reciprocal_pick_the_quotients_node() {
        // Pitches whose reciprocal is inexact, abscissae on, a few ulps either side of and
        // between the halves of the grid (where product and quotient may round apart), and the
        // hexagonal rows' half shifts: the node is the quotient's, always.
        for d in [
            0.3,
            0.7,
            1.0 / 3.0,
            0.123_456_789,
            3f64.sqrt() / 2.0,
            1.0,
            2.5e-3,
        ] {
            let per_d = 1.0 / d;
            for k in -2000..=2000 {
                for shift in [0.0, 0.5, -1.5] {
                    let half = (k as f64 + 0.5 + shift) * d;
                    let mut xs = vec![half, (k as f64 + 0.2) * d, k as f64 * d];
                    let (mut up, mut down) = (half, half);
                    for _ in 0..3 {
                        (up, down) = (up.next_up(), down.next_down());
                        xs.extend([up, down]);
                    }
                    for x in xs {
                        assert_eq!(
                            nearest_of_ratio(x, d, per_d, shift),
                            nearest(x / d - shift),
                            "x {x} d {d} shift {shift}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn floor_and_ceiling_match_std() {
        let mut xs = vec![
            0.0,
            -0.0,
            1e-300,
            -1e-300,
            1e15 + 0.5,
            -1e15 - 0.5,
            4503599627370497.0,
        ];
        for k in -40..=40 {
            let x = k as f64 * 0.25;
            xs.extend([x, x + 1e-12, x - 1e-12, f64::from_bits(x.to_bits() + 1)]);
        }
        for x in xs {
            assert_eq!(floor(x) as f64, x.floor(), "{x}");
            assert_eq!(ceiling(x) as f64, x.ceil(), "{x}");
        }
        // Beyond i64 both saturate (a wrapped floor of −1e308 once made a range of 2⁶⁴ rows).
        for (x, low) in [(-1e308, i64::MIN), (1e308, i64::MAX), (-1e19, i64::MIN)] {
            assert_eq!((floor(x), ceiling(x)), (low, low), "{x}");
        }
    }

    #[test]
    fn kinks_of_a_line_far_from_the_part_are_none_and_found_at_once() {
        let l = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        let (s, c) = 0.26f64.sin_cos();
        for (x0, y0) in [
            (0.0, -f64::MAX),
            (f64::MAX, 3.0),
            (-1e300, 1e300),
            (40.0, 0.0),
        ] {
            let mut kinks = Vec::new();
            l.slope_kinks(Line { x0, y0, c, s }, 0.0, 10.0, &mut kinks);
            assert!(kinks.is_empty(), "({x0}, {y0}): {kinks:?}");
        }
        // A part narrower than a lenslet cuts none, by the kinks and by the surface alike.
        let tiny = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(0.1)).unwrap();
        assert_eq!(tiny.lenslet_count(), 0);
        assert_eq!(tiny.local(0.0, 0.0).unwrap().z, 0.0);
    }

    #[test]
    fn hexagonal_lenslets_sit_on_the_lattice() {
        let spec = LensArraySpec {
            grid: Grid::Hexagonal,
            form: Form::Convex,
            ..LensArraySpec::paper004()
        };
        let l = LensArray::new(&spec, PartDisc::centred(5.0)).unwrap();
        let row = 3f64.sqrt() / 2.0;
        for &(cx, cy) in &[(0.5, row), (-1.5, -row), (1.0, 2.0 * row), (2.0, 0.0)] {
            let v = l.local(cx + 0.1, cy - 0.05).unwrap();
            let rho2: f64 = 0.01 + 0.0025;
            let z = (2.84f64 * 2.84 - rho2).sqrt() - (2.84f64 * 2.84 - 0.25).sqrt();
            assert!((v.z - z).abs() < 1e-15, "{cx} {cy}");
        }
    }

    #[test]
    fn parameters_that_make_no_array_are_rejected() {
        let s = LensArraySpec {
            aperture_mm: 1.5,
            ..LensArraySpec::paper004()
        };
        assert_eq!(
            LensArray::new(&s, PartDisc::centred(5.0))
                .unwrap_err()
                .field,
            "aperture_mm"
        );
        let s = LensArraySpec {
            lens_radius_mm: 0.4,
            ..LensArraySpec::paper004()
        };
        assert!(
            LensArray::new(&s, PartDisc::centred(5.0))
                .unwrap_err()
                .allowed
                .contains("twice lens_radius_mm")
        );
        let s = LensArraySpec {
            pitch_mm: -1.0,
            ..LensArraySpec::paper004()
        };
        assert_eq!(
            LensArray::new(&s, PartDisc::centred(5.0))
                .unwrap_err()
                .field,
            "pitch_mm"
        );
        let s = LensArraySpec {
            pitch_mm: 1e-3,
            aperture_mm: 1e-3,
            lens_radius_mm: 1.0,
            ..LensArraySpec::paper004()
        };
        let e = LensArray::new(&s, PartDisc::centred(50.0)).unwrap_err();
        assert_eq!(e.field, "pitch_mm");
        assert!(e.allowed.contains("lenslets on the part"), "{e}");
    }
}

//! One-way tool nose radius compensation (paper 003, section 3.3, eqs 17–24): X stays on the
//! spiral and only Z is lifted until the round nose touches the surface.
//!
//! A nose of radius r whose centre sits above the spiral point ρ_s cuts with the arc
//! `u = r·sin a`, `a ∈ [−β/2, β/2]` (β the included angle) in the radial plane at θ. Paper 003
//! writes the centre height as `z_s = f(ρ_s + r·sin a) + r·cos a` with a from the local condition
//! `tan a = f′(ρ_s + r·sin a)` (eqs 19–20). That condition has several roots on a wavy or
//! concave section, and the wrong one gouges. Here the centre height is the maximum over the
//! whole arc (DESIGN.md):
//!
//! `z_c(ρ_s) = max_{|a| ≤ β/2} F(a)`, `F(a) = f(ρ_s + r·sin a, θ) + r·cos a`,
//!
//! so the arc touches the surface at the maximiser and lies on or above it everywhere else:
//! gouge-free by construction. The maximum is found by sampling F on a grid fine enough not to
//! step over a surface feature ([`crate::surface::Surface::feature_length_mm`]), then refining
//! every sampled bracket where `F′(a) = r·cos a·(f′ − tan a)` changes sign from + to − with a
//! safeguarded Newton iteration on `F′ = 0` (eq 20), which falls back to bisection at slope
//! kinks. Where the surface reports a slope kink under the arc ([`Surface::slope_kinks`], a
//! lenslet's rim) samples are added just either side of it, so that F is smooth between any two
//! samples: a kink between samples could otherwise let F rise, fall and rise again unseen. The
//! sample grid has an odd number of intervals, so that a = 0 (where F′ = 0 over flat land) falls
//! inside a bracket, not on a sample. The NC commands the tool tip `z_c − r`. With r = 0 the tip
//! follows the sag.
//!
//! **Concave shortcut.** Where the surface bounds its radial sections
//! ([`crate::surface::Surface::section_bounds`]: slope ≤ S, curvature ≤ K, slope kinks only
//! ridges) and `r·K⁺ + S·tan(β/2) < 0.9`, F″ < 0 on the whole arc and F′ only drops at kinks
//! ([`crate::surface::SectionBounds::nose_height_concavity`]): F has one local maximum, the
//! global one. It is then found without the grid: Newton on F′ = 0 from a = 0, the kinks'
//! sides probed where a step would cross one, the maximum bracketed and refined as above, about
//! 4 evaluations a point instead of 20 or more. The bounds are the certificate; a surface
//! without them, or a nose too wide for them, gets the full search (the families that give
//! them: [`crate::surface::section_bounds`]).
//!
//! **Valleys.** Where the sections may have kinks that are not ridges (convex lenslets' rims,
//! a zone boundary whose slope rises or whose value steps, a ridged design turned over), the
//! same bounds make F concave between them only ([`Concavity::valleys`]): the arc is cut at
//! each kink under it ([`Surface::slope_kinks`], each side sampled as by the search) and each
//! stretch's one maximum is its left end where F′ ≤ 0 there, its right end where F′ ≥ 0 there,
//! else the refined bracket between them; the largest of them is the contact. About two
//! evaluations a stretch and a few Newton steps in the one or two that hold a maximum, instead
//! of the whole grid.
//!
//! **Warm start.** Along a path the certificate does not depend on where Newton starts: with
//! one maximum on the arc, any start converges to it (kinks probed as before). A path therefore
//! starts each point's iteration from its predecessors' contacts ([`ContactTrail`],
//! [`NoseCompensator::compensate_from`]; [`super::tool_path::WARM_RUN`] says how a path keeps
//! that independent of its batches): the cubic through the last four contact angles, each
//! refined by the Newton step its last sample gives ([`Contact::refined_angle`]), or the line
//! through the last two where the cubic strays from it (the contact jumped), its sine and
//! cosine by rotation from the last contact's (no library call). On a smooth section the
//! cubic's error is fourth order in the step, so the first sample is usually already within
//! the 10⁻¹⁰ rad tolerance: about 1.07 evaluations a point on the asphere of the benchmarks
//! (the line does as well there: its contact angle barely changes along a turn; 2.03 from the
//! predecessor's angle alone, 4–5 cold), about 1.5 on the paper 004 lens array at 5 680 points
//! a turn (2.0 from the line, whose error, κ·Δθ² as the section turns with the lenslets, is
//! above the tolerance; most of the rest are contacts on rims). A contact on a rim predicted
//! within 10⁻⁹ rad serves as the kink's near side, its far side is sampled next and the
//! bracket's end tangents meet over the kink (`Section::refine_from`): three evaluations,
//! the height the rim's own to rounding. The slope kinks are listed only when a
//! Newton step is taken, and only those between the step's start and its target (those of the
//! stretch asked for before serve while the next step lands inside it), and not at all where the
//! surface shows none within the step's reach ([`Surface::kink_free_radius`]: a lenslet's rim
//! farther than the step moves the contact). The contact found is the cold start's to the tolerance
//! (tests/tests/compensation.rs).
//!
//! **Kept sections.** A surface that keeps the section of the line it was last asked for
//! kinks on ([`Surface::kept_radial`]: the L1 RBF of scattered data, a cubic between its kinks)
//! answers the samples on the arc's line from it; the contact's height and jet are then the
//! surface's own, evaluated once at the angle found. Such a surface also bounds its section
//! over any stretch of the line ([`Surface::kept_ranges`]: each cubic's extremes), so the
//! search bounds F on each group of 8 grid intervals by the section's highest value
//! there plus `r·max cos a`, samples the middle of the group with the highest bound, and leaves
//! out every group whose bound falls below that sample: no sample, kink side or bracket in it
//! could be the answer, so the search finds the same sample as over the whole grid, to the bit
//! (on the scattered example, most groups of most points).
//!
//! The arc is cut at the part's edge: beyond `limit_radius_mm` there is no material.
//!
//! **Measured edge** (`tool.waviness`, [`super::waviness`]): the edge has the radius
//! `R(a) = r + δ(a)`, so `F(a) = f(ρ_s + R(a)·sin a) + R(a)·cos a`, with
//! `F′ = f′·u′ + v′` and `F″ = f″·u′² + f′·u″ + v″` for `u = R·sin a`, `v = R·cos a`; the
//! maximum over the arc stays the rule, so the path is gouge-free for the measured edge. The
//! table's angles inside the arc are sampled besides the grid (δ is a cubic between them, its
//! extrema at them), and the tip the NC commands is `R(0)` below the centre. A constant δ is
//! exactly a nose of radius r + δ. Without a table every computation is the circle's, unchanged.

use super::waviness::Waviness;
use crate::field::{FieldError, in_range, non_negative};
use crate::job::ToolSpec;
use crate::surface::{Line, Local, Radial, Surface, UndefinedError};

/// Where the nose touches the surface for one spiral point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Height of the nose centre z_c, mm.
    pub z_center: f64,
    /// Height of the tool tip `z_c − r`, the Z the NC commands, mm.
    pub z_tip: f64,
    /// Nose angle a of the contact point, radians (positive: outward of ρ_s).
    pub angle: f64,
    /// Signed radial coordinate of the contact point `ρ_s + r·sin a`, mm.
    pub rho: f64,
    /// Sag at the contact point, mm.
    pub z: f64,
    /// The contact lies at an end of the arc: the section is steeper there than β/2, and the
    /// tool's flank may cut.
    pub at_arc_end: bool,
    /// sin a and cos a of the contact's nose angle (a warm start's rotation starts from them).
    pub sin_cos: (f64, f64),
    /// The contact angle one Newton step on from `angle` (within 10⁻⁸ rad of it), or `angle`:
    /// what a path's warm start extrapolates from ([`ContactTrail`]).
    pub refined_angle: f64,
}

/// Where the contact search of a point starts ([`NoseCompensator::compensate_from`]): an angle,
/// and a nearby contact angle whose sine and cosine are known, from which the start's are found
/// by rotation. Along a path, extrapolated from the contacts of the points before
/// ([`ContactTrail`]); between two points, an angle between their contacts
/// ([`WarmStart::toward`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WarmStart {
    last: f64,
    sin_cos: (f64, f64),
    angle: f64,
}

impl WarmStart {
    /// A start at `angle`, near the contact angle `from` whose sine and cosine are `sin_cos`.
    pub fn toward(from: f64, sin_cos: (f64, f64), angle: f64) -> Self {
        Self {
            last: from,
            sin_cos,
            angle,
        }
    }

    /// The angle to start from.
    pub fn angle(&self) -> f64 {
        self.angle
    }
}

/// The contacts of a path's last points and the warm start they give the next. The start
/// extrapolates their refined angles ([`Contact::refined_angle`]): from the last four by the
/// cubic through them, `4·(a₁ + a₃) − 6·a₂ − a₄`, where it lies within 10⁻⁵ rad of the line
/// through the last two, `2·a₁ − a₂` (else that line: the contact jumped, a rim passed under
/// the nose), from fewer by that line or the last alone. The cubic's error is fourth order in
/// the step: on a section that turns as the path goes round (a lenslet), the line misses by
/// about `κ·Δθ²` (some 10⁻⁶ rad on the paper 004 array at 5 680 points a turn), more than the
/// shortcut's tolerance, so each point took a Newton step; the cubic misses by about 5·10⁻¹¹
/// rad there (the refined angle's step), and the first sample is usually the answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactTrail {
    /// The next point's start.
    pub start: WarmStart,
    /// The refined contact angles of the last three points, the latest first.
    history: [f64; 3],
    /// How many points the trail follows (saturated).
    known: u8,
}

impl ContactTrail {
    /// The trail of a walk that starts at `contact`: the next start is its angle.
    pub fn new(contact: &Contact) -> Self {
        let h0 = contact.refined_angle;
        Self {
            start: WarmStart::toward(contact.angle, contact.sin_cos, h0),
            history: [h0; 3],
            known: 1,
        }
    }

    /// Follows the trail on to `contact`, the contact of the next point.
    pub fn push(&mut self, contact: &Contact) {
        let h0 = contact.refined_angle;
        let [h1, h2, h3] = self.history;
        self.history = [h0, h1, h2];
        self.known = (self.known + 1).min(4);
        let linear = 2.0 * h0 - h1;
        let cubic = 4.0 * (h0 + h2) - 6.0 * h1 - h3;
        let angle = if self.known >= 4 && (cubic - linear).abs() < 1e-5 {
            cubic
        } else {
            linear
        };
        self.start = WarmStart::toward(contact.angle, contact.sin_cos, angle);
    }
}

/// One-way compensation for a given tool and part.
#[derive(Debug, Clone, PartialEq)]
pub struct NoseCompensator {
    r: f64,
    half_angle: f64,
    samples: usize,
    limit_radius: f64,
    /// How far the arc reaches either side of its centre, `r·sin(β/2)`, widened by 10⁻⁹ of
    /// itself: a part edge at least this far leaves the whole arc.
    reach: f64,
    /// (a, sin a, cos a) of the sample grid over the whole arc, the usual case away from the
    /// part edge: tabulated once rather than per point.
    grid: Vec<[f64; 3]>,
    /// The measured edge, if the job gives one.
    waviness: Option<Waviness>,
}

/// Bounds on the grid of nose angles sampled before refinement.
const MIN_SAMPLES: usize = 16;
const MAX_SAMPLES: usize = 4096;
/// Grid steps per feature length along the arc.
const STEPS_PER_FEATURE: f64 = 8.0;

impl NoseCompensator {
    /// Checks the tool and prepares the compensator for a surface with features no shorter than
    /// `feature_length_mm` on a part that ends at `limit_radius_mm`.
    pub fn new(
        tool: &ToolSpec,
        feature_length_mm: f64,
        limit_radius_mm: f64,
    ) -> Result<Self, FieldError> {
        let r = non_negative("nose_radius_mm", tool.nose_radius_mm)?;
        tool.angles()?;
        let beta = in_range("included_angle_deg", tool.included_angle_deg, 0.0, 180.0)?;
        if beta == 0.0 {
            return Err(FieldError::new(
                "included_angle_deg",
                beta,
                "must lie in (0, 180]",
            ));
        }
        let half_angle = (beta / 2.0).to_radians();
        let waviness = tool
            .waviness
            .as_ref()
            .map(|w| Waviness::new(w, r, half_angle))
            .transpose()?;
        let chord = 2.0 * r * half_angle.sin();
        let wanted = (chord / feature_length_mm * STEPS_PER_FEATURE).ceil();
        // An odd number of intervals keeps a = 0 off the grid: over flat land F′(0) = 0, and a
        // sample there would leave a bracket that only bisection can close.
        let samples = if wanted.is_finite() {
            (wanted as usize).clamp(MIN_SAMPLES, MAX_SAMPLES)
        } else {
            MIN_SAMPLES
        } | 1;
        let grid = (0..=samples)
            .map(|i| {
                let a = grid_angle(-half_angle, half_angle, samples, i);
                let (sa, ca) = a.sin_cos();
                [a, sa, ca]
            })
            .collect();
        Ok(Self {
            r,
            half_angle,
            samples,
            limit_radius: limit_radius_mm,
            reach: r * half_angle.sin() * (1.0 + 1e-9),
            grid,
            waviness,
        })
    }

    /// The measured edge, if any.
    pub fn waviness(&self) -> Option<&Waviness> {
        self.waviness.as_ref()
    }

    /// The edge's radius at nose angle `a`, mm: r, or `r + δ(a)` for a measured edge.
    pub fn edge_radius(&self, a: f64) -> f64 {
        self.waviness.as_ref().map_or(self.r, |w| w.radius(a)[0])
    }

    /// The distance from the nose centre down to the tip (a = 0), mm: what the NC's tip lies
    /// below the centre.
    pub fn tip_offset(&self) -> f64 {
        self.edge_radius(0.0)
    }

    /// The depth of the edge below the nose centre at the horizontal offset `d` (|d| within the
    /// reach), mm: `√(r² − d²)` for the circle, [`Waviness::depth`] for a measured edge.
    pub fn edge_depth(&self, d: f64) -> f64 {
        match &self.waviness {
            None => (self.r * self.r - d * d).max(0.0).sqrt(),
            Some(w) => w.depth(d),
        }
    }

    /// How far the edge reaches either side of the centre, mm: `r·sin(β/2)`, or the larger of
    /// the measured edge's two ends.
    pub fn reach(&self) -> f64 {
        let h = self.half_angle;
        match &self.waviness {
            None => self.r * h.sin(),
            Some(w) => w.radius(h)[0].max(w.radius(-h)[0]) * h.sin(),
        }
    }

    /// Nose radius, mm.
    pub fn nose_radius(&self) -> f64 {
        self.r
    }

    /// Half the included angle, radians.
    pub fn half_angle(&self) -> f64 {
        self.half_angle
    }

    /// The nose arc's angle range at ρ_s, cut at the part edge.
    pub fn arc_range(&self, rho_s: f64) -> (f64, f64) {
        let r = self.r;
        let clamp_asin = |s: f64| s.clamp(-1.0, 1.0).asin();
        let (to_rim, to_far_rim) = (self.limit_radius - rho_s, -self.limit_radius - rho_s);
        if self.waviness.is_none() && to_rim >= self.reach && to_far_rim <= -self.reach {
            // The part reaches beyond the whole arc: the included angle alone limits (the
            // arcsines below would be at least ±β/2).
            return (-self.half_angle, self.half_angle);
        }
        let (hi, lo) = match &self.waviness {
            None => (clamp_asin(to_rim / r), clamp_asin(to_far_rim / r)),
            Some(w) => (w.angle_at_offset(to_rim), w.angle_at_offset(to_far_rim)),
        };
        let hi = self.half_angle.min(hi);
        let lo = (-self.half_angle).max(lo);
        (lo, hi.max(lo))
    }

    /// The one-way tip height `z_c − r` over the point (ρ, θ) of `surface`: the height HCAA
    /// samples ([`crate::path::hcaa::TipHeight`]); `concavity` the path's certificate
    /// ([`NoseCompensator::concavity`]).
    pub fn tip_height(
        &self,
        surface: &dyn Surface,
        concavity: Option<Concavity>,
        rho: f64,
        theta: f64,
    ) -> Result<f64, UndefinedError> {
        let (s, c) = theta.sin_cos();
        Ok(self
            .compensate_from(surface, concavity, rho, c, s, None)?
            .z_tip)
    }

    /// The contact for the spiral point at radius `rho_s` and angle with cosine/sine `(c, s)`.
    /// It proves the certificate afresh ([`NoseCompensator::concavity`]: a few thousand
    /// evaluations of a polynomial for the Q surfaces); a path computes it once and calls
    /// [`NoseCompensator::compensate_from`].
    pub fn compensate(
        &self,
        surface: &dyn Surface,
        rho_s: f64,
        c: f64,
        s: f64,
    ) -> Result<Contact, UndefinedError> {
        self.compensate_from(surface, self.concavity(surface), rho_s, c, s, None)
    }

    /// The concavity bound (−F″ ≥ m on every arc over the part, between valleys where the
    /// sections have any) where `surface` proves one for this nose
    /// ([`crate::surface::SectionBounds::nose_height_concavity`]): the certificate of the
    /// concave shortcut. A path computes it once and hands it to
    /// [`NoseCompensator::compensate_from`].
    pub fn concavity(&self, surface: &dyn Surface) -> Option<Concavity> {
        match self.waviness {
            None => {
                let b = surface.section_bounds(self.limit_radius)?;
                Some(Concavity {
                    m: b.nose_height_concavity(self.r, self.half_angle)?,
                    valleys: b.has_valleys,
                })
            }
            Some(_) => None,
        }
    }

    /// [`NoseCompensator::compensate`] with the surface's [`NoseCompensator::concavity`] given,
    /// and a warm start: where the concave shortcut applies, its Newton iteration starts from
    /// the nose angle [`WarmStart::angle`] (extrapolated from the contacts of the points before)
    /// instead of 0. The certificate is the same either way (one maximum on the arc), so the
    /// contact found is the same to the shortcut's tolerance; only the evaluations spent differ.
    /// Ignored by the whole-arc search.
    pub fn compensate_from(
        &self,
        surface: &dyn Surface,
        concavity: Option<Concavity>,
        rho_s: f64,
        c: f64,
        s: f64,
        start: Option<WarmStart>,
    ) -> Result<Contact, UndefinedError> {
        if self.r == 0.0 {
            let z = surface.sag(rho_s * c, rho_s * s)?;
            return Ok(Self::sharp(rho_s, z));
        }
        let (contact, _) = self.round(surface, concavity, rho_s, c, s, start)?;
        Ok(contact)
    }

    /// [`NoseCompensator::compensate_from`] with the surface's jet at the contact point (from
    /// the search's own evaluation there).
    pub fn compensate_with_local(
        &self,
        surface: &dyn Surface,
        concavity: Option<Concavity>,
        rho_s: f64,
        c: f64,
        s: f64,
        start: Option<WarmStart>,
    ) -> Result<(Contact, Local), UndefinedError> {
        if self.r == 0.0 {
            let z = surface.sag(rho_s * c, rho_s * s)?;
            return Ok((Self::sharp(rho_s, z), surface.local(rho_s * c, rho_s * s)?));
        }
        self.round(surface, concavity, rho_s, c, s, start)
    }

    /// The contact of a sharp tool over ρ_s, where the sag is `z`.
    fn sharp(rho_s: f64, z: f64) -> Contact {
        Contact {
            z_center: z,
            z_tip: z,
            angle: 0.0,
            rho: rho_s,
            z,
            at_arc_end: false,
            sin_cos: (0.0, 1.0),
            refined_angle: 0.0,
        }
    }

    /// The contact of a round nose (r > 0) and the surface's jet there.
    fn round(
        &self,
        surface: &dyn Surface,
        concavity: Option<Concavity>,
        rho_s: f64,
        c: f64,
        s: f64,
        start: Option<WarmStart>,
    ) -> Result<(Contact, Local), UndefinedError> {
        let r = self.r;
        let section = Section {
            surface,
            rho_s,
            c,
            s,
            r,
            edge: self.waviness.as_ref(),
            kept: true,
        };
        let (lo, hi) = self.arc_range(rho_s);
        let kinks = |from, to, sine| self.kinks_near(&section, lo, hi, [from, to], sine);
        let best = match concavity {
            Some(Concavity { m, valleys: false }) => {
                section.concave_peak(&kinks, lo, hi, m, start)?
            }
            Some(Concavity { m, valleys: true }) => {
                let mut centres = self.kink_centres(&section, lo, hi);
                centres.sort_by(f64::total_cmp);
                section.piecewise_peak(&centres, lo, hi, m, start)?
            }
            None => self.search(&section, lo, hi)?,
        };
        let (best, local) = section.with_jet(best)?;
        let at_arc_end =
            (best.a - self.half_angle).abs() < 1e-12 || (best.a + self.half_angle).abs() < 1e-12;
        let (tip, reach) = match &self.waviness {
            None => (r, r),
            Some(_) => (self.tip_offset(), self.edge_radius(best.a)),
        };
        let contact = Contact {
            z_center: best.f,
            z_tip: best.f - tip,
            angle: best.a,
            rho: rho_s + reach * best.sa,
            z: local.z,
            at_arc_end: at_arc_end && best.g.abs() > 1e-12 * r,
            sin_cos: (best.sa, best.ca),
            refined_angle: refined(&best),
        };
        Ok((contact, local))
    }

    /// The largest F over `[lo, hi]` by the sampled search of the whole arc (module docs),
    /// skipping the groups of samples that cannot hold it ([`Self::live_groups`]).
    fn search(&self, section: &Section, lo: f64, hi: f64) -> Result<Sample, UndefinedError> {
        let offsets = self.kink_offsets(section, lo, hi);
        let ends = self.group_ends(lo, hi);
        let live = self.live_groups(section, [lo, hi], &ends)?;
        let centres = self.live_kinks(section, offsets, &ends, &live);
        let kinks = self.kink_sides(centres, [lo, hi], [lo, hi]);
        self.scan(section, lo, hi, &kinks, &live)
    }

    /// The grid points (angle, sine, cosine) that bound the search's groups of [`GROUP`]
    /// intervals over `[lo, hi]`, the first and the last the arc's ends.
    fn group_ends(&self, lo: f64, hi: f64) -> Vec<[f64; 3]> {
        let n = self.samples;
        (0..=n.div_ceil(GROUP))
            .map(|g| self.grid_point(lo, hi, (g * GROUP).min(n)))
            .collect()
    }

    /// Where the grid point `p` (angle, sine, cosine) reaches the section's line.
    fn offset_of(&self, section: &Section, p: [f64; 3]) -> f64 {
        section.rho_s + self.r * p[1]
    }

    /// The angles of the kinks at `offsets` (ascending along the line) that lie in a `live`
    /// group's stretch of the line (between its `ends`), widened by 10⁻⁹ mm (the sides of
    /// every other kink lie in groups the scan leaves out): the others' angles are not
    /// needed. All of them where the offsets are not ascending.
    fn live_kinks(
        &self,
        section: &Section,
        mut offsets: Vec<f64>,
        ends: &[[f64; 3]],
        live: &[bool],
    ) -> Vec<f64> {
        let ascending = offsets.is_sorted_by(|a, b| a <= b);
        if live.iter().all(|&l| l) || !ascending {
            offsets
                .iter_mut()
                .for_each(|t| *t = self.kink_angle(section, *t));
            return offsets;
        }
        let t = |g: usize| self.offset_of(section, ends[g]);
        let mut ranges = (0..live.len())
            .filter(|&g| live[g])
            .map(|g| [t(g) - 1e-9, t(g + 1) + 1e-9])
            .peekable();
        offsets.retain(|&k| {
            while ranges.next_if(|r| r[1] < k).is_some() {}
            ranges.peek().is_some_and(|r| r[0] <= k)
        });
        offsets
            .iter_mut()
            .for_each(|t| *t = self.kink_angle(section, *t));
        offsets
    }

    /// The search's i-th grid angle over `[lo, hi]`, with its sine and cosine.
    fn grid_point(&self, lo: f64, hi: f64, i: usize) -> [f64; 3] {
        if lo == -self.half_angle && hi == self.half_angle {
            self.grid[i]
        } else {
            let a = grid_angle(lo, hi, self.samples, i);
            let (sa, ca) = a.sin_cos();
            [a, sa, ca]
        }
    }

    /// Which of the groups between `ends` ([`Self::group_ends`] over `[lo, hi]`) may hold the
    /// search's maximum. Where the surface bounds its kept section ([`Surface::kept_ranges`]:
    /// the L1 RBF's cubics between the kinks just listed), F on a group's stretch of the arc
    /// is at most the section's highest there plus r times the largest cos a, plus
    /// [`BOUND_MARGIN`]; a group whose bound is below F at a grid sample (the middle of the
    /// group with the highest bound) holds neither a sample nor a refined peak that could be
    /// the search's answer, and is skipped. Every group is live otherwise.
    fn live_groups(
        &self,
        section: &Section,
        [lo, hi]: [f64; 2],
        ends: &[[f64; 3]],
    ) -> Result<Vec<bool>, UndefinedError> {
        let all = vec![true; ends.len() - 1];
        if self.waviness.is_some() {
            return Ok(all);
        }
        let ts: Vec<f64> = ends.iter().map(|&e| self.offset_of(section, e)).collect();
        let Some(ranges) = section.surface.kept_ranges(section.c, section.s, &ts) else {
            return Ok(all);
        };
        let bounds: Vec<f64> = ranges
            .iter()
            .zip(ends.windows(2))
            .map(|([_, high], e)| {
                let ([a0, _, c0], [a1, _, c1]) = (e[0], e[1]);
                let cos = if a0 <= 0.0 && a1 >= 0.0 {
                    1.0
                } else {
                    c0.max(c1)
                };
                high + self.r * cos + BOUND_MARGIN
            })
            .collect();
        let (best, bound) = bounds
            .iter()
            .enumerate()
            .fold(
                (0, f64::NEG_INFINITY),
                |m, (g, &u)| if u > m.1 { (g, u) } else { m },
            );
        let middle = (best * GROUP + ((best + 1) * GROUP).min(self.samples)) / 2;
        let [a, sa, ca] = self.grid_point(lo, hi, middle);
        let floor = section.at_sin_cos(a, sa, ca)?.f;
        if !(bound.is_finite() && floor.is_finite() && floor <= bound) {
            return Ok(all);
        }
        Ok(bounds.iter().map(|&u| u >= floor).collect())
    }

    /// The sampled search over the grid of `[lo, hi]` and the `kinks`' sides (module docs), in
    /// the groups marked `live`: the samples, kinks and brackets inside the others are left
    /// out (every group is scanned where none is live).
    fn scan(
        &self,
        section: &Section,
        lo: f64,
        hi: f64,
        kinks: &[f64],
        live: &[bool],
    ) -> Result<Sample, UndefinedError> {
        let n = self.samples;
        let mut sides = kinks.iter().peekable();
        let mut scan: Option<Scan> = None;
        for i in 0..=n {
            let [a, sa, ca] = self.grid_point(lo, hi, i);
            let before = i > 0 && live[(i - 1) / GROUP];
            let after = i < n && live[i / GROUP];
            while let Some(&k) = sides.next_if(|&&k| k < a) {
                if let (true, Some(scan)) = (before, &mut scan) {
                    scan.visit(section, section.at(k)?)?;
                }
            }
            if !(before || after) {
                continue;
            }
            let next = section.at_sin_cos(a, sa, ca)?;
            match &mut scan {
                Some(scan) if before => scan.visit(section, next)?,
                Some(scan) => scan.restart(next),
                None => scan = Some(Scan::new(next)),
            }
        }
        match scan {
            Some(scan) => Ok(scan.best),
            None => self.scan(section, lo, hi, kinks, &vec![true; live.len()]),
        }
    }
}

/// Grid intervals of the search bounded together ([`NoseCompensator::live_groups`]).
const GROUP: usize = 8;
/// What a group's bound on F allows, mm, above the rounding of F's samples and the kept
/// section's (about 10⁻¹⁶ mm): a group is skipped only where its bound falls below F
/// elsewhere by more.
const BOUND_MARGIN: f64 = 1e-12;

/// The certificate of the concave shortcut for a path (module docs): −F″ ≥ `m` on every arc,
/// between the sections' valleys and steps where `valleys`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Concavity {
    /// The lower bound of −F″, mm per rad².
    pub m: f64,
    /// Whether the sections may have valleys or steps ([`SectionBounds::has_valleys`]): each
    /// stretch of the arc between them is then searched apart.
    ///
    /// [`SectionBounds::has_valleys`]: crate::surface::SectionBounds::has_valleys
    pub valleys: bool,
}

/// Offset, radians of nose angle, of the samples either side of a slope kink: each sees the
/// slope of its own side.
const KINK_OFFSET: f64 = 1e-12;

impl NoseCompensator {
    /// How far the edge point at nose angle `a` lies beside the centre, `R(a)·sin a`; at the
    /// whole arc's ends (where almost every point's arc ends) from the tabulated grid.
    fn lateral(&self, a: f64) -> f64 {
        let sin = if a == self.half_angle {
            self.grid[self.samples][1]
        } else if a == -self.half_angle {
            self.grid[0][1]
        } else {
            a.sin()
        };
        self.edge_radius(a) * sin
    }

    /// [`Self::kink_angles`] in `[from, to]`, one end of which has the sine `sine`, or none
    /// without asking where the surface has no kink within reach of that end
    /// ([`Surface::kink_free_radius`]): every angle in the stretch, widened by the sides' margin,
    /// lies within `r·(to − from + margin)` of that end's point on the line, since the lateral
    /// offset `r·sin a` moves by at most r per radian (not with a measured edge, whose table
    /// angles are kinks too).
    fn kinks_near(
        &self,
        section: &Section,
        lo: f64,
        hi: f64,
        [from, to]: [f64; 2],
        sine: f64,
    ) -> Vec<f64> {
        if self.waviness.is_none() {
            let t = section.rho_s + self.r * sine;
            let reach = self.r * (to - from + KINK_OFFSET + 1e-9) + 1e-9;
            let free = section
                .surface
                .kink_free_radius(t * section.c, t * section.s);
            if reach < free {
                return Vec::new();
            }
        }
        self.kink_angles(section, lo, hi, from, to)
    }

    /// Nose angles just before and after each slope kink of the section under the arc `[lo,
    /// hi]` ([`Surface::slope_kinks`]), and the measured edge's table angles inside the arc,
    /// ascending: those of them in `[from, to]` (within the arc). The surface is asked only for
    /// the kinks under that stretch (with a margin of [`KINK_OFFSET`] and 10⁻⁹ rad), so a
    /// Newton step pays for the lenslets it crosses rather than for all under the nose; each
    /// kink's angle is computed as for the whole arc (it does not depend on the interval asked).
    fn kink_angles(&self, section: &Section, lo: f64, hi: f64, from: f64, to: f64) -> Vec<f64> {
        let margin = KINK_OFFSET + 1e-9;
        let centres = self.kink_centres(section, (from - margin).max(lo), (to + margin).min(hi));
        self.kink_sides(centres, [lo, hi], [from, to])
    }

    /// The angles just before and after each of the kinks at `centres` (ascending along the
    /// line) and the measured edge's table angles, ascending: those in `[from, to]` inside the
    /// arc `[lo, hi]` ([`Self::kink_angles`]).
    fn kink_sides(
        &self,
        mut angles: Vec<f64>,
        [lo, hi]: [f64; 2],
        [from, to]: [f64; 2],
    ) -> Vec<f64> {
        let table: &[f64] = self.waviness.as_ref().map_or(&[], |w| w.angles());
        if angles.is_empty() && table.is_empty() {
            return angles;
        }
        // In place, from the last: each kink's angle becomes the angles just before and just
        // after it, in order (ascending already unless two kinks lie within the offsets).
        let n = angles.len();
        angles.resize(2 * n, 0.0);
        for i in (0..n).rev() {
            let a = angles[i];
            angles[2 * i] = a - KINK_OFFSET;
            angles[2 * i + 1] = a + KINK_OFFSET;
        }
        angles.extend_from_slice(table);
        angles.retain(|a| *a > lo && *a < hi && *a >= from && *a <= to);
        if !angles.is_sorted_by(|a, b| a.total_cmp(b).is_le()) {
            angles.sort_unstable_by(f64::total_cmp);
        }
        angles
    }

    /// The nose angles of the slope kinks of the section under the arc
    /// ([`Surface::slope_kinks`]), in the order the surface lists them (ascending along the
    /// line).
    fn kink_centres(&self, section: &Section, lo: f64, hi: f64) -> Vec<f64> {
        let mut angles = self.kink_offsets(section, lo, hi);
        for t in &mut angles {
            *t = self.kink_angle(section, *t);
        }
        angles
    }

    /// Where the section's slope kinks under the arc lie on its line ([`Surface::slope_kinks`]).
    fn kink_offsets(&self, section: &Section, lo: f64, hi: f64) -> Vec<f64> {
        let mut offsets = Vec::new();
        section.surface.slope_kinks(
            Line::radial(section.c, section.s),
            section.rho_s + self.lateral(lo),
            section.rho_s + self.lateral(hi),
            &mut offsets,
        );
        offsets
    }

    /// The nose angle that reaches the point `t` of the section's line.
    fn kink_angle(&self, section: &Section, t: f64) -> f64 {
        let rho_s = section.rho_s;
        match &self.waviness {
            None => ((t - rho_s) / self.r).clamp(-1.0, 1.0).asin(),
            Some(w) => w.angle_at_offset(t - rho_s),
        }
    }
}

/// The running state of the scan along the arc: the previous sample and the best value.
struct Scan {
    prev: Sample,
    best: Sample,
}

impl Scan {
    fn new(first: Sample) -> Self {
        Self {
            prev: first,
            best: first,
        }
    }

    /// Takes the next sample after a stretch left out: no bracket with the one before.
    fn restart(&mut self, next: Sample) {
        if next.f > self.best.f {
            self.best = next;
        }
        self.prev = next;
    }

    /// Takes the next sample; where F′ goes from + to − (possibly through an exact 0 at a
    /// sample, as over flat land) a maximum lies between the two samples and is refined.
    fn visit(&mut self, section: &Section, next: Sample) -> Result<(), UndefinedError> {
        let prev = self.prev;
        if next.f > self.best.f {
            self.best = next;
        }
        if (prev.g > 0.0 && next.g <= 0.0) || (prev.g >= 0.0 && next.g < 0.0) {
            let peak = section.refine(prev, next)?;
            if peak.f > self.best.f {
                self.best = peak;
            }
        }
        self.prev = next;
        Ok(())
    }
}

/// Where the tangents of F at `lo` and `hi` meet (angle, height), for `lo.g > hi.g`.
fn tangents_meet(lo: &Sample, hi: &Sample) -> (f64, f64) {
    let a = lo.a + (hi.f - lo.f - hi.g * (hi.a - lo.a)) / (lo.g - hi.g);
    (a, lo.f + lo.g * (a - lo.a))
}

/// `x`'s angle one Newton step on (F′ = 0 of F's quadratic model there) where that step is
/// within 10⁻⁸ rad, else its own: at a smooth maximum the step is second order in `x`'s
/// distance from it, so a warm start extrapolated from refined angles is as good as the
/// points' exact maxima would give, whichever sample certified them.
fn refined(x: &Sample) -> f64 {
    let step = -x.g / x.gg;
    if x.gg < 0.0 && step.abs() <= 1e-8 {
        x.a + step
    } else {
        x.a
    }
}

/// The `i`-th of `n + 1` equally spaced angles from `lo` to `hi` (the last exactly `hi`).
fn grid_angle(lo: f64, hi: f64, n: usize, i: usize) -> f64 {
    if i == n {
        hi
    } else {
        lo + (hi - lo) / n as f64 * i as f64
    }
}

/// The radial section through one spiral point and the nose arc above it.
#[derive(Clone, Copy)]
struct Section<'a> {
    surface: &'a dyn Surface,
    rho_s: f64,
    c: f64,
    s: f64,
    r: f64,
    edge: Option<&'a Waviness>,
    /// Whether samples may be read from the surface's kept section of the line
    /// ([`Surface::kept_radial`]).
    kept: bool,
}

/// F(a), F′(a), F″(a) and the sag at the arc point.
#[derive(Debug, Clone, Copy)]
struct Sample {
    a: f64,
    /// sin a and cos a.
    sa: f64,
    ca: f64,
    f: f64,
    g: f64,
    gg: f64,
    /// The arc point's signed radius on the section's line.
    rho: f64,
    /// The surface's jet there, unless the sample was read from the surface's kept section
    /// ([`Surface::kept_radial`]).
    local: Option<Local>,
}

impl Section<'_> {
    fn at(&self, a: f64) -> Result<Sample, UndefinedError> {
        let (sa, ca) = a.sin_cos();
        self.at_sin_cos(a, sa, ca)
    }

    /// As [`Section::at`] for an angle `a` near the sample `from`: within 10⁻³ rad, sin a and
    /// cos a by rotating `from`'s by d = a − a_from, with sin d and cos d from their Taylor
    /// series (the first term left out is below 10⁻²¹ there), to the last bit or two of libm's
    /// and without its call; farther, by [`f64::sin_cos`].
    fn at_near(&self, from: &Sample, a: f64) -> Result<Sample, UndefinedError> {
        self.at_rotated(from.a, (from.sa, from.ca), a)
    }

    /// As [`Section::at_near`], from the angle `from` whose sine and cosine are `sin_cos`.
    fn at_rotated(&self, from: f64, sin_cos: (f64, f64), a: f64) -> Result<Sample, UndefinedError> {
        let d = a - from;
        if d.abs() > 1e-3 {
            return self.at(a);
        }
        let d2 = d * d;
        let sd = d * (1.0 - d2 / 6.0 * (1.0 - d2 / 20.0));
        let cd = 1.0 - d2 / 2.0 * (1.0 - d2 / 12.0 * (1.0 - d2 / 30.0));
        let (fs, fc) = sin_cos;
        self.at_sin_cos(a, fs * cd + fc * sd, fc * cd - fs * sd)
    }

    /// As [`Section::at`] with sin a and cos a given.
    fn at_sin_cos(&self, a: f64, sa: f64, ca: f64) -> Result<Sample, UndefinedError> {
        if let Some(edge) = self.edge {
            return self.at_measured(edge, a, sa, ca);
        }
        let r = self.r;
        let rho = self.rho_s + r * sa;
        let (l, local) = self.radial(rho)?;
        Ok(Sample {
            a,
            sa,
            ca,
            f: l.z + r * ca,
            g: r * ca * l.slope - r * sa,
            gg: r * r * ca * ca * l.curvature_term - r * sa * l.slope - r * ca,
            rho,
            local,
        })
    }

    /// The section at signed radius `rho`: from the surface's kept section of this line where
    /// it has one ([`Surface::kept_radial`]), else from its jet, which comes with it.
    fn radial(&self, rho: f64) -> Result<(Radial, Option<Local>), UndefinedError> {
        if self.kept
            && let Some(kept) = self.surface.kept_radial(self.c, self.s, rho)
        {
            return Ok((kept?, None));
        }
        let local = self.surface.local(rho * self.c, rho * self.s)?;
        Ok((local.radial(self.c, self.s), Some(local)))
    }

    /// `sample` as the surface's own jet gives it, with that jet: evaluated afresh where it was
    /// read from the kept section, so that the contact's height is the surface's to its last
    /// bit whichever way the search read it.
    fn with_jet(&self, sample: Sample) -> Result<(Sample, Local), UndefinedError> {
        let sample = match sample.local {
            Some(_) => sample,
            None => Section {
                kept: false,
                ..*self
            }
            .at_sin_cos(sample.a, sample.sa, sample.ca)?,
        };
        let local = match sample.local {
            Some(local) => local,
            None => self
                .surface
                .local(sample.rho * self.c, sample.rho * self.s)?,
        };
        Ok((sample, local))
    }

    /// [`Section::at_sin_cos`] for the measured edge R(a) (see the module docs).
    fn at_measured(
        &self,
        edge: &Waviness,
        a: f64,
        sa: f64,
        ca: f64,
    ) -> Result<Sample, UndefinedError> {
        let [rr, r1, r2] = edge.radius(a);
        let (u1, u2) = (r1 * sa + rr * ca, r2 * sa + 2.0 * r1 * ca - rr * sa);
        let (v1, v2) = (r1 * ca - rr * sa, r2 * ca - 2.0 * r1 * sa - rr * ca);
        let rho = self.rho_s + rr * sa;
        let (l, local) = self.radial(rho)?;
        Ok(Sample {
            a,
            sa,
            ca,
            f: l.z + rr * ca,
            g: l.slope * u1 + v1,
            gg: l.curvature_term * u1 * u1 + l.slope * u2 + v2,
            rho,
            local,
        })
    }

    /// The maximum of F over `[lo, hi]` where F is concave
    /// ([`crate::surface::SectionBounds::nose_height_concavity`]): F′ never rises, so the sign
    /// of F′ anywhere says on which side the one maximum lies. Newton from `start`'s angle (0
    /// without one; clamped to the arc, its sine and cosine by rotation) until a step would
    /// cross a slope kink (`kinks(from, to, sine)` gives the angles either side of each in
    /// `[from, to]`, ascending, `sine` the sine of the end where the step starts; each step asks
    /// for those between its start and its Newton target, or the arc's end where it has none,
    /// unless the stretch asked for last holds it, and a start that is already the answer asks
    /// for none), where the kink's sides are probed instead, or the arc's end. With −F″ ≥ `m`,
    /// the maximum lies within |F′(x)|/m of a sample x and exceeds F(x) by at most F′(x)²/(2m):
    /// a sample x with |F′(x)|/m ≤ 10⁻¹⁰ rad is the answer (its height then within 10⁻²⁰·m mm
    /// of the maximum, its contact within 10⁻¹⁰·r). Otherwise, once the maximum is bracketed,
    /// [`Section::refine_from`] closes the bracket.
    fn concave_peak(
        &self,
        kinks: &dyn Fn(f64, f64, f64) -> Vec<f64>,
        lo: f64,
        hi: f64,
        m: f64,
        start: Option<WarmStart>,
    ) -> Result<Sample, UndefinedError> {
        let mut x = match start {
            Some(w) => self.at_rotated(w.last, w.sin_cos, w.angle().clamp(lo, hi))?,
            None => self.at(0.0f64.clamp(lo, hi))?,
        };
        let (mut left, mut right) = (None::<Sample>, None::<Sample>);
        let mut asked: Option<(f64, f64, Vec<f64>)> = None;
        for _ in 0..100 {
            if x.g.abs() <= 1e-10 * m {
                return Ok(x);
            }
            if x.g > 0.0 {
                left = Some(x);
            } else if x.g < 0.0 {
                right = Some(x);
            } else {
                return Ok(x);
            }
            if let (Some(l), Some(r)) = (left, right) {
                return self.refine_from(l, r, x);
            }
            // Outwards from x towards the maximum: up to the next kink or the arc's end.
            let up = x.g > 0.0;
            let end = if up { hi } else { lo };
            if x.a == end {
                return Ok(x);
            }
            let step = if x.gg < 0.0 { -x.g / x.gg } else { f64::NAN };
            let target = x.a + step;
            // Only a kink between x and where the step lands can stop it (NaN: the arc's end).
            let (from, to) = match up {
                true if target < end => (x.a, target),
                true => (x.a, end),
                false if target > end => (target, x.a),
                false => (end, x.a),
            };
            // A Newton step lands within the one before it, whose kinks are then known.
            let known = asked.as_ref().filter(|(f, t, _)| *f <= from && to <= *t);
            let near = match known {
                Some((_, _, near)) => near,
                None => &asked.insert((from, to, kinks(from, to, x.sa))).2,
            };
            // The first kink side beyond x; where x already lies beside it (a contact on a
            // rim, predicted to within 10⁻⁹ rad), x serves as that side and the kink's far
            // side is next.
            let beyond = |from: f64| match up {
                true => near.iter().copied().find(|&k| k > from),
                false => near.iter().rev().copied().find(|&k| k < from),
            };
            let kink = beyond(x.a).map(|k| match beyond(k) {
                Some(far) if (k - x.a).abs() < 1e-9 && (far - k).abs() <= 3.0 * KINK_OFFSET => far,
                _ => k,
            });
            let stop = kink.unwrap_or(end);
            let a = if (up && target < stop) || (!up && target > stop) {
                target
            } else {
                stop
            };
            x = self.at_near(&x, a)?;
        }
        // Unreachable for a concave F (each step halves the distance or brackets); the best
        // seen stands.
        Ok([left, right, Some(x)]
            .into_iter()
            .flatten()
            .fold(x, |b, s| if s.f > b.f { s } else { b }))
    }

    /// The maximum of F over `[lo, hi]` where F is concave between the kinks (valleys and
    /// steps included: module docs), `kinks` their nose angles, ascending
    /// ([`NoseCompensator::kink_centres`]): the largest of the stretches' maxima, each stretch
    /// from just after a kink to just before the next ([`KINK_OFFSET`], clamped to the arc: a
    /// kink at an end leaves that end a stretch of its own), the one that holds the warm
    /// start's angle (all of the arc where no kink is under it) by [`Section::concave_peak`]
    /// from there, the others by [`Section::stretch_peak`].
    fn piecewise_peak(
        &self,
        kinks: &[f64],
        lo: f64,
        hi: f64,
        m: f64,
        start: Option<WarmStart>,
    ) -> Result<Sample, UndefinedError> {
        let from = start.map_or(0.0, |w| w.angle()).clamp(lo, hi);
        let mut best: Option<Sample> = None;
        let mut first = lo;
        for k in kinks.iter().map(Some).chain([None]) {
            let end = k.map_or(hi, |k| (k - KINK_OFFSET).clamp(lo, hi));
            if end >= first {
                let peak = if (first..=end).contains(&from) {
                    self.concave_peak(&|_, _, _| Vec::new(), first, end, m, start)?
                } else {
                    self.stretch_peak(first, end)?
                };
                if best.is_none_or(|b| peak.f > b.f) {
                    best = Some(peak);
                }
            }
            if let Some(k) = k {
                first = (k + KINK_OFFSET).clamp(lo, hi);
            }
        }
        best.map_or_else(|| self.at(lo), Ok)
    }

    /// The maximum of F over `[a, b]` where it is concave and smooth: `a` where F′(a) ≤ 0, `b`
    /// where F′(b) ≥ 0, else the refined bracket.
    fn stretch_peak(&self, a: f64, b: f64) -> Result<Sample, UndefinedError> {
        let left = self.at(a)?;
        if left.g <= 0.0 || b == a {
            return Ok(left);
        }
        let right = self.at(b)?;
        if right.g >= 0.0 {
            return Ok(right);
        }
        self.refine_from(left, right, left)
    }

    /// The local maximum of F in `[lo.a, hi.a]` given `F′(lo) ≥ 0 ≥ F′(hi)`, not both zero:
    /// Newton on F′ = 0 inside the bracket, bisection where Newton would leave it; across a
    /// slope kink (F′ drops by more than 10⁶ times the bracket's width) where the tangents at
    /// its ends meet, until they bound every point of it within 10⁻¹⁵ mm of the best sample.
    fn refine(&self, lo: Sample, hi: Sample) -> Result<Sample, UndefinedError> {
        self.refine_from(lo, hi, lo)
    }

    /// [`Section::refine`] with Newton's first step taken from `x`, a sample in the bracket.
    fn refine_from(
        &self,
        mut lo: Sample,
        mut hi: Sample,
        mut x: Sample,
    ) -> Result<Sample, UndefinedError> {
        let mut best = if lo.f > hi.f { lo } else { hi };
        for _ in 0..100 {
            let width = hi.a - lo.a;
            let a = if lo.g - hi.g > 1e6 * width {
                // A slope kink inside (a ridge: F′ drops far more than a smooth F′ could over
                // the width): F is concave across it, so below both end tangents, which meet
                // over the kink (each side straight to rounding over such a width). Done when
                // no point can top the best sample by 10⁻¹⁵ mm, else sampled where they meet.
                let (a, top) = tangents_meet(&lo, &hi);
                if top - best.f <= 1e-15 || !(a > lo.a && a < hi.a) {
                    break;
                }
                a
            } else {
                // Done when the bracket is at rounding level, or no point in it can exceed
                // its ends by more than 1e-13 mm (F′ lies between its end values near a
                // maximum).
                if width < 1e-14 || width * lo.g.abs().max(hi.g.abs()) < 1e-13 {
                    break;
                }
                let newton = if x.gg < 0.0 {
                    x.a - x.g / x.gg
                } else {
                    f64::NAN
                };
                if newton > lo.a && newton < hi.a && (newton - x.a).abs() < 0.5 * width {
                    newton
                } else {
                    0.5 * (lo.a + hi.a)
                }
            };
            x = self.at_near(&x, a)?;
            if x.f > best.f {
                best = x;
            }
            if x.g > 0.0 {
                lo = x;
            } else if x.g < 0.0 {
                hi = x;
            } else {
                break;
            }
            if x.g.abs() < 1e-15 * self.r {
                break;
            }
        }
        // Near the maximum F is flat to rounding: prefer the converged iterate over one that
        // only wins by an ulp, so the contact point is as exact as the height.
        let ulps = 8.0 * f64::EPSILON * best.f.abs().max(self.r);
        Ok(if x.f >= best.f - ulps { x } else { best })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::ToolAngles;
    use crate::surface::{Asphere, AsphereSpec};

    fn tool(r: f64) -> ToolSpec {
        ToolSpec {
            nose_radius_mm: r,
            included_angle_deg: 100.0,
            ..ToolSpec::with_nose_radius(0.0)
        }
    }

    #[test]
    fn a_trail_extrapolates_the_cubic_through_four_contacts_and_the_line_after_a_jump() {
        let contact = |a: f64| Contact {
            z_center: 0.0,
            z_tip: 0.0,
            angle: a,
            rho: 0.0,
            z: 0.0,
            at_arc_end: false,
            sin_cos: a.sin_cos(),
            refined_angle: a,
        };
        let cubic = |k: f64| 0.01 + 1e-3 * k - 2e-6 * k * k + 3e-8 * k * k * k;
        let mut trail = ContactTrail::new(&contact(cubic(0.0)));
        assert_eq!(trail.start.angle(), cubic(0.0));
        for k in 1..10 {
            trail.push(&contact(cubic(k as f64)));
            let line = 2.0 * cubic(k as f64) - cubic(k as f64 - 1.0);
            let expected = if k >= 3 { cubic(k as f64 + 1.0) } else { line };
            assert!((trail.start.angle() - expected).abs() < 1e-15, "{k}");
            // It rotates from the last contact.
            assert_eq!(trail.start.last, cubic(k as f64));
        }
        // The contact jumps to another side of the arc: the line through the last two.
        trail.push(&contact(-0.3));
        assert_eq!(trail.start.angle(), 2.0 * -0.3 - cubic(9.0));
    }

    #[test]
    fn on_a_sphere_the_centre_lies_on_the_offset_sphere() {
        // Concave sphere R: the nose centre follows the sphere of radius R − r about the same
        // centre (0, 0, R): z_c = R − √((R − r)² − ρ²).
        let (big, r) = (20.0, 0.5);
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(big),
            ..Default::default()
        })
        .unwrap();
        let comp = NoseCompensator::new(&tool(r), s.feature_length_mm(), 10.0).unwrap();
        for rho in [0.0, 1.0, 4.0, 7.5, 9.0] {
            let c = comp.compensate(&s, rho, 0.6, 0.8).unwrap();
            let expect = big - ((big - r).powi(2) - rho * rho).sqrt();
            assert!(
                (c.z_center - expect).abs() < 1e-10,
                "ρ {rho}: {} vs {expect}",
                c.z_center
            );
            assert!((c.z_tip - (expect - r)).abs() < 1e-10);
            // The contact lies on the ray from the sphere centre through the nose centre.
            assert!(
                (c.rho - rho * big / (big - r)).abs() < 1e-9,
                "{} vs {}",
                c.rho,
                rho * big / (big - r)
            );
        }
    }

    #[test]
    fn the_jet_at_the_contact_is_the_surfaces_there() {
        // compensate_with_local hands back the search's own evaluation at the contact: the
        // contact of compensate_from and the jet of Surface::local at it, to the bit, for the
        // concave shortcut, the whole-arc search and a sharp tool.
        use crate::surface::{LensArray, LensArraySpec, PartDisc};
        let array = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        for r in [0.0, 0.5] {
            let comp = NoseCompensator::new(&tool(r), array.feature_length_mm(), 5.0).unwrap();
            for concavity in [comp.concavity(&array), None] {
                for k in 0..200 {
                    let (rho, theta) = (4.9 * k as f64 / 200.0, 0.37 * k as f64);
                    let (s, c) = theta.sin_cos();
                    let found = comp.compensate_from(&array, concavity, rho, c, s, None);
                    let (contact, local) = comp
                        .compensate_with_local(&array, concavity, rho, c, s, None)
                        .unwrap();
                    assert_eq!(found.unwrap(), contact);
                    let there = array.local(contact.rho * c, contact.rho * s).unwrap();
                    assert_eq!(local, there, "r {r} ρ {rho} θ {theta}");
                }
            }
        }
    }

    /// The 4 000 points of the shortcut tests, from beyond a 5 mm part's rim to its centre at
    /// 0.7 rad steps: each point's θ, its section under a nose of r 0.5 mm, and its arc.
    fn spiral_sections<'a>(
        surface: &'a dyn Surface,
        comp: &'a NoseCompensator,
    ) -> impl Iterator<Item = (f64, Section<'a>, (f64, f64))> {
        (0..4000).map(move |i| {
            let (rho, theta) = (5.2 - 5.4 * i as f64 / 4000.0, 0.7 * i as f64);
            let (s, c) = f64::sin_cos(theta);
            let section = Section {
                surface,
                rho_s: rho,
                c,
                s,
                r: 0.5,
                edge: None,
                kept: true,
            };
            (theta, section, comp.arc_range(rho))
        })
    }

    #[test]
    fn the_concave_shortcut_agrees_with_the_whole_arc_search() {
        // Where SectionBounds proves F concave the shortcut (Newton from a = 0, kinks probed)
        // must find the height and the contact of the sampled search of the whole arc.
        use crate::surface::{LensArray, LensArraySpec, PartDisc};
        let asphere = Asphere::new(&AsphereSpec {
            radius_mm: Some(40.0),
            conic: -1.2,
            coefficients: vec![1.5e-6, -2e-9],
            ..Default::default()
        })
        .unwrap();
        let lenses = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        let surfaces: [&dyn Surface; 2] = [&asphere, &lenses];
        for (k, s) in surfaces.into_iter().enumerate() {
            let comp = NoseCompensator::new(&tool(0.5), s.feature_length_mm(), 5.0).unwrap();
            let bounds = s.section_bounds(5.0).unwrap();
            assert!(
                bounds
                    .nose_height_concavity(0.5, comp.half_angle())
                    .is_some()
            );
            let (mut rims, mut n) = (0, 0);
            for (theta, section, (lo, hi)) in spiral_sections(s, &comp) {
                let (rho, cs, sn) = (section.rho_s, section.c, section.s);
                let fast = comp.compensate(s, rho, cs, sn).unwrap();
                let full = comp.search(&section, lo, hi).unwrap();
                assert!(
                    (fast.z_center - full.f).abs() < 1e-13,
                    "{} ρ {rho} θ {theta}: {} vs {}",
                    s.describe(),
                    fast.z_center,
                    full.f
                );
                assert!((fast.angle - full.a).abs() < 1e-6, "ρ {rho}: angle");
                rims += usize::from(fast.z.abs() < 1e-9 && fast.angle.abs() > 1e-3);
                n += 1;
            }
            assert_eq!(n, 4000);
            if k == 1 {
                assert!(rims > 100, "{rims} contacts on the land beside a rim");
            }
        }
    }

    #[test]
    fn the_search_leaves_out_only_groups_that_cannot_hold_its_answer() {
        // Scattered data on a 0.05 mm grid (concave lenslets of paper 004 on land, r 2.84 mm,
        // pitch 1 mm) through the L1 RBF, whose kept section bounds each group of the grid:
        // at 4 000 points of a spiral the search with the groups left out finds the sample
        // the scan of every group finds, to the bit, and leaves out some at most points.
        use crate::surface::DataFile;
        use crate::surface::PartDisc;
        use crate::surface::scattered::interpolate::data::Samples;
        use crate::surface::scattered::{Method, Scattered, ScatteredSpec};
        let lenslets = |x: f64, y: f64| {
            let (u, v) = (x - x.round(), y - y.round());
            let rho2 = u * u + v * v;
            let r: f64 = 2.84;
            if rho2 < 0.2 {
                (r * r - 0.2).sqrt() - (r * r - rho2).sqrt()
            } else {
                0.0
            }
        };
        let (h, k) = (0.05, 120);
        let points: Vec<[f64; 3]> = (-k..=k)
            .flat_map(|j| (-k..=k).map(move |i| (f64::from(i) * h, f64::from(j) * h)))
            .map(|(x, y)| [x, y, lenslets(x, y)])
            .collect();
        let spec = ScatteredSpec {
            method: Method::Rbf,
            ..ScatteredSpec::new(DataFile::default())
        };
        let samples = Samples::from_points(&points).unwrap();
        let surface = Scattered::from_samples(&spec, samples, PartDisc::centred(5.0)).unwrap();
        let comp = NoseCompensator::new(&tool(0.5), surface.feature_length_mm(), 5.0).unwrap();
        let (mut pruned, mut n) = (0, 0);
        for (theta, section, (lo, hi)) in spiral_sections(&surface, &comp) {
            if section.rho_s.abs() > 5.0 - 0.5 {
                continue;
            }
            let kinks = comp.kink_angles(&section, lo, hi, lo, hi);
            let live = comp
                .live_groups(&section, [lo, hi], &comp.group_ends(lo, hi))
                .unwrap();
            let every = comp.scan(&section, lo, hi, &kinks, &vec![true; live.len()]);
            let found = comp.search(&section, lo, hi).unwrap();
            let every = every.unwrap();
            assert_eq!(
                (found.a.to_bits(), found.f.to_bits()),
                (every.a.to_bits(), every.f.to_bits()),
                "ρ {} θ {theta}",
                section.rho_s
            );
            pruned += usize::from(live.contains(&false));
            n += 1;
        }
        assert!(
            n > 3000 && pruned * 2 > n,
            "{pruned} of {n} points left groups out"
        );
    }

    #[test]
    fn the_piecewise_search_agrees_with_the_whole_arc_search_across_valleys() {
        // Convex lenslets (valleys at the rims) and concave ones turned over (ridges become
        // valleys): the bounds make F concave between the kinks only, and the stretches'
        // maxima must give the height and contact of the sampled search of the whole arc.
        use crate::surface::lens_array::Form;
        use crate::surface::{LensArray, LensArraySpec, PartDisc, Turned};
        let convex = LensArraySpec {
            form: Form::Convex,
            ..LensArraySpec::paper004()
        };
        let convex = LensArray::new(&convex, PartDisc::centred(5.0)).unwrap();
        let concave = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        let turned = Turned::new(Box::new(concave));
        let surfaces: [&dyn Surface; 2] = [&convex, &turned];
        for s in surfaces {
            let comp = NoseCompensator::new(&tool(0.5), s.feature_length_mm(), 5.0).unwrap();
            let concavity = comp.concavity(s).unwrap();
            assert!(concavity.valleys);
            let (mut beside, mut n) = (0, 0);
            for (theta, section, (lo, hi)) in spiral_sections(s, &comp) {
                let (rho, cs, sn) = (section.rho_s, section.c, section.s);
                let fast = comp
                    .compensate_from(s, Some(concavity), rho, cs, sn, None)
                    .unwrap();
                let full = comp.compensate_from(s, None, rho, cs, sn, None).unwrap();
                assert!(
                    (fast.z_center - full.z_center).abs() < 1e-13,
                    "{} ρ {rho} θ {theta}: {} vs {}",
                    s.describe(),
                    fast.z_center,
                    full.z_center
                );
                assert!((fast.angle - full.angle).abs() < 1e-6, "ρ {rho}: angle");
                // Contacts away from the arc's middle: the maximum was on another stretch.
                beside += usize::from(fast.angle.abs() > 0.2);
                // Extra cuts where F is smooth change nothing, nor kinks within their offset of
                // the arc's ends (each end then a stretch of its own), warm start or not.
                let mut kinks = comp.kink_centres(&section, lo, hi);
                let ends = [lo + 0.5 * KINK_OFFSET, hi - 0.5 * KINK_OFFSET];
                kinks.extend(ends.into_iter().chain([lo - 0.1, 0.5 * (lo + hi)]));
                kinks.sort_by(f64::total_cmp);
                let warm = WarmStart::toward(0.0, (0.0, 1.0), fast.angle + 0.01);
                for start in [None, Some(warm)] {
                    let cut = section
                        .piecewise_peak(&kinks, lo, hi, concavity.m, start)
                        .unwrap();
                    assert!((cut.f - full.z_center).abs() < 1e-13, "ρ {rho}: cut");
                }
                n += 1;
            }
            assert_eq!(n, 4000);
            assert!(beside > 50, "{beside} contacts away from the middle");
        }
    }

    #[test]
    fn the_kinks_under_part_of_the_arc_are_the_whole_arcs_there() {
        // The concave shortcut asks for the kinks between a Newton step's ends only: they must
        // be those of the whole arc in that stretch, to the bit (the lens array's rims, the
        // compound eye's polished seams), and within 10⁻¹² rad where the kinks are found by an
        // iteration along the line (a lens array on a tilted normal axis).
        use crate::surface::{
            CompoundEye, CompoundEyeSpec, LensArray, LensArraySpec, PartDisc, Reframed,
        };
        let lenses = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(5.0)).unwrap();
        let eye = CompoundEye::new(&CompoundEyeSpec::paper000(), PartDisc::centred(5.0)).unwrap();
        let tilted = Reframed::new(Box::new(lenses.clone()), 1.3, 0.2).unwrap();
        let surfaces: [(&dyn Surface, f64); 3] = [(&lenses, 0.0), (&eye, 0.0), (&tilted, 1e-12)];
        for (surface, tolerance) in surfaces {
            let comp = NoseCompensator::new(&tool(0.5), surface.feature_length_mm(), 5.0).unwrap();
            let (mut stretches, mut found) = (0, 0);
            for (theta, section, (lo, hi)) in spiral_sections(surface, &comp).step_by(7) {
                let whole = comp.kink_angles(&section, lo, hi, lo, hi);
                // Stretches ending on a kink's side, just short of it, across it, and between.
                let mut ends = vec![lo, hi, 0.5 * (lo + hi), lo + 0.3 * (hi - lo)];
                for &k in &whole {
                    ends.extend([k, k - 1e-13, k + 1e-13, k - 3e-12, k + 3e-12, k + 0.01]);
                }
                for (i, &from) in ends.iter().enumerate() {
                    for &to in &ends[i + 1..] {
                        let (from, to) = (from.min(to).max(lo), from.max(to).min(hi));
                        let part = comp.kink_angles(&section, lo, hi, from, to);
                        // Each found is one of the whole arc's in the stretch, and each of
                        // those is found (but within the tolerance of the stretch's ends).
                        let within =
                            |a: f64, lo: f64, hi: f64| a >= lo - tolerance && a <= hi + tolerance;
                        let near =
                            |a: f64, list: &[f64]| list.iter().any(|b| (a - b).abs() <= tolerance);
                        let found_all = whole.iter().all(|&a| {
                            !within(a, from + 2.0 * tolerance, to - 2.0 * tolerance)
                                || near(a, &part)
                        });
                        let all_kinks =
                            part.iter().all(|&a| within(a, from, to) && near(a, &whole));
                        assert!(
                            found_all && all_kinks && part.is_sorted(),
                            "{} ρ {} θ {theta} [{from}, {to}]: {part:?} of {whole:?}",
                            surface.describe(),
                            section.rho_s
                        );
                        stretches += 1;
                        found += part.len();
                    }
                }
            }
            assert!(stretches > 10_000 && found > 10_000, "{stretches} {found}");
        }
    }

    #[test]
    fn sharp_tool_follows_the_sag() {
        let s = Asphere::new(&AsphereSpec {
            radius_mm: Some(30.0),
            conic: -0.5,
            ..Default::default()
        })
        .unwrap();
        let comp = NoseCompensator::new(&tool(0.0), s.feature_length_mm(), 10.0).unwrap();
        let c = comp.compensate(&s, 6.0, 0.0, 1.0).unwrap();
        assert_eq!(c.z_tip, s.sag(0.0, 6.0).unwrap());
    }

    #[test]
    fn tool_fields_are_checked() {
        let e = NoseCompensator::new(
            &ToolSpec {
                nose_radius_mm: 0.5,
                included_angle_deg: 0.0,
                ..ToolSpec::with_nose_radius(0.0)
            },
            1.0,
            5.0,
        );
        assert_eq!(e.unwrap_err().field, "included_angle_deg");
        let e = NoseCompensator::new(&tool(-1.0), 1.0, 5.0);
        assert_eq!(e.unwrap_err().field, "nose_radius_mm");
        for (rake, clearance, field, allowed) in [
            (85.0, 10.0, "rake_deg", "must lie in [-80, 80]"),
            (f64::NAN, 10.0, "rake_deg", "must lie in [-80, 80]"),
            (0.0, -1.0, "clearance_deg", "must lie in [0, 80]"),
        ] {
            let t = ToolSpec {
                rake_deg: rake,
                clearance_deg: clearance,
                ..tool(0.5)
            };
            let e = NoseCompensator::new(&t, 1.0, 5.0).unwrap_err();
            assert_eq!((e.field.as_str(), e.allowed.as_str()), (field, allowed));
        }
        assert_eq!(
            tool(0.5).angles().unwrap(),
            ToolAngles {
                rake_deg: 0.0,
                clearance_deg: 10.0
            }
        );
    }
}

//! Bounds on a surface's radial sections over a disc about the spindle axis: the largest slope
//! |f′| and the largest and least curvature f″ of `t ↦ f(t·cos θ, t·sin θ)` for |t| ≤ R and
//! every θ between the section's kinks, and whether it has kinks that are ridges (the slope
//! drops across them) and kinks that are not (valleys, where the slope rises, or steps in
//! value). The one-way compensation ([`crate::tool::NoseCompensator`]) reads them to prove
//! that the height of the nose over the arc is concave (see
//! [`SectionBounds::nose_height_concavity`]): across ridges too, so that its one local maximum
//! is the global one; with valleys or steps, only between them, so that each stretch of the arc
//! between them has one (a surface turned over keeps its bounds, its curvature's swapped and
//! negated, its ridges becoming valleys: [`SectionBounds::turned`]).
//!
//! A family gives bounds only where it can prove them from its formula (even and odd aspheres,
//! lens arrays, sinusoidal grid and tilted flat, XY polynomial, Zernike and Chebyshev
//! surfaces on an even asphere, [`crate::surface::polynomial::Bivariate::section_bounds`];
//! Forbes' Q surfaces, [`crate::surface::q_section_bounds`]; the biconic, toroid and off-axis
//! conic; the zoned asphere; the grid sag, from its cells; NURBS surfaces and STEP faces, from
//! their control nets' Bézier pieces; the compound eye, from its caps; composites of these,
//! [`SectionBounds::and`], a decentred term by its bounds on every line,
//! [`crate::surface::Surface::disc_bounds`]); the PAL and scattered data give none and are
//! searched in full.

/// Bounds on a surface's radial sections over a disc (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SectionBounds {
    /// An upper bound of |f′| over the disc.
    pub max_slope: f64,
    /// An upper bound of f″ over the disc (1/mm; may be negative).
    pub max_curvature: f64,
    /// A lower bound of f″ over the disc (1/mm; may be positive): what the upward curvature of
    /// the surface turned over is bounded by ([`SectionBounds::turned`]).
    pub min_curvature: f64,
    /// Whether the sections may have slope kinks in the disc that are ridges.
    pub has_ridges: bool,
    /// Whether they may have kinks that are not ridges (valleys: the slope rises across them)
    /// or steps in value: the nose height is then concave only between them.
    pub has_valleys: bool,
}

impl SectionBounds {
    /// A flat section's bounds: slope and curvature 0, no kinks.
    pub const FLAT: SectionBounds = SectionBounds {
        max_slope: 0.0,
        max_curvature: 0.0,
        min_curvature: 0.0,
        has_ridges: false,
        has_valleys: false,
    };

    /// These bounds with a smooth term's added (a sum's section): `slope` ≥ the term's |f′| and
    /// `curvature` ≥ its |f″| ([`SectionBounds::and`]).
    pub fn plus(self, slope: f64, curvature: f64) -> Option<SectionBounds> {
        self.and(SectionBounds {
            max_slope: slope,
            max_curvature: curvature,
            min_curvature: -curvature,
            has_ridges: false,
            has_valleys: false,
        })
    }

    /// The bounds of the sum of two surfaces: the slope bounds add, and so do the curvature
    /// bounds (each bounds its part's f″), with a relative margin far above the sums' rounding;
    /// the sum's kinks are its parts' (a ridge plus a smooth or ridged section is a ridge, a
    /// valley or step anywhere stays one);
    /// `None` where not finite.
    pub fn and(self, other: SectionBounds) -> Option<SectionBounds> {
        let (a, b) = (self.max_curvature, other.max_curvature);
        let (c, d) = (self.min_curvature, other.min_curvature);
        let sum = SectionBounds {
            max_slope: (self.max_slope + other.max_slope) * (1.0 + 1e-9),
            max_curvature: a + b + 1e-9 * (a.abs() + b.abs()),
            min_curvature: c + d - 1e-9 * (c.abs() + d.abs()),
            has_ridges: self.has_ridges || other.has_ridges,
            has_valleys: self.has_valleys || other.has_valleys,
        };
        let finite = [sum.max_slope, sum.max_curvature, sum.min_curvature];
        finite.iter().all(|v| v.is_finite()).then_some(sum)
    }

    /// The bounds of a surface that is one or the other piece at each point (zones, caps,
    /// Bézier pieces): the larger slope and curvature, the lesser least curvature, either's
    /// kinds of kink.
    pub fn or(self, other: SectionBounds) -> SectionBounds {
        SectionBounds {
            max_slope: self.max_slope.max(other.max_slope),
            max_curvature: self.max_curvature.max(other.max_curvature),
            min_curvature: self.min_curvature.min(other.min_curvature),
            has_ridges: self.has_ridges || other.has_ridges,
            has_valleys: self.has_valleys || other.has_valleys,
        }
    }

    /// These bounds with `ridges` marking slope kinks (ridges) in the disc.
    pub fn with_ridges(self, ridges: bool) -> SectionBounds {
        SectionBounds {
            has_ridges: self.has_ridges || ridges,
            ..self
        }
    }

    /// The bounds of the surface turned over (`f ↦ −f` along every section, as
    /// [`crate::surface::Turned`] does): the slopes keep their bound, the curvature bounds swap
    /// and change sign; its ridges become valleys (and its valleys ridges, its steps steps: any
    /// kink is then counted as either).
    pub fn turned(self) -> Option<SectionBounds> {
        let kinks = self.has_ridges || self.has_valleys;
        Some(SectionBounds {
            max_curvature: -self.min_curvature,
            min_curvature: -self.max_curvature,
            has_ridges: self.has_valleys,
            has_valleys: kinks,
            ..self
        })
    }

    /// A lower bound m > 0 of −F″ for the nose height `F(a) = f(ρ_s + r·sin a) + r·cos a` over
    /// |a| ≤ `half_angle` (< 90°) wherever the arc stays on the disc, F′ dropping by at least
    /// m·Δa over any Δa between valleys and steps (ridges only make it drop more); `None` where
    /// F cannot be proven strictly concave so.
    ///
    /// `F″ = r²·cos²a·f″ − r·sin a·f′ − r·cos a ≤ −r·cos a·(1 − r·K⁺·cos a − S·tan|a|)` with
    /// S ≥ |f′| and K⁺ ≥ max(f″, 0), so `m = r·cos(β/2)·(1 − q)` with
    /// `q = r·K⁺ + S·tan(β/2)`, asked to stay below 0.9 (a margin for the rounding of the
    /// bounds).
    pub fn nose_height_concavity(&self, r: f64, half_angle: f64) -> Option<f64> {
        let q = r * self.max_curvature.max(0.0) + self.max_slope * half_angle.tan();
        (half_angle < std::f64::consts::FRAC_PI_2 && q.is_finite() && q < 0.9 && r > 0.0)
            .then(|| r * half_angle.cos() * (1.0 - q))
    }
}

/// The largest |f′|, the largest f″ and the least f″ of the radial sections of `surface` sampled
/// at `angles` angles (from 0) and `samples` + 1 points of `t ∈ [−radius, radius]` each: what a
/// family's bounds must cover, found by brute force (for their tests).
#[cfg(test)]
fn sampled_extremes(
    surface: &dyn super::Surface,
    radius: f64,
    angles: usize,
    samples: usize,
) -> (f64, f64, f64) {
    let (mut slope, mut curvature, mut least) = (0.0f64, f64::NEG_INFINITY, f64::INFINITY);
    for k in 0..angles {
        let (s, c) = (std::f64::consts::TAU * k as f64 / angles as f64).sin_cos();
        for i in 0..=samples {
            let t = radius * (2.0 * i as f64 / samples as f64 - 1.0);
            let l = surface.local(t * c, t * s).unwrap().radial(c, s);
            slope = slope.max(l.slope.abs());
            curvature = curvature.max(l.curvature_term);
            least = least.min(l.curvature_term);
        }
    }
    (slope, curvature, least)
}

/// `surface`'s bounds over the disc of `radius`, asserted to cover its sections sampled as
/// [`sampled_extremes`] does; with the sampled extremes, for the tests of tightness.
#[cfg(test)]
pub(crate) fn assert_bounds_hold(
    surface: &dyn super::Surface,
    radius: f64,
    angles: usize,
    samples: usize,
) -> (SectionBounds, f64, f64) {
    let b = surface.section_bounds(radius).expect("section bounds");
    let (slope, curvature, least) = sampled_extremes(surface, radius, angles, samples);
    assert!(
        slope <= b.max_slope && curvature <= b.max_curvature && least >= b.min_curvature,
        "{}: {b:?} against the sampled slope {slope} and curvature {least} … {curvature}",
        surface.describe()
    );
    (b, slope, curvature)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_flat_section_is_concave_for_any_angle_below_90_degrees() {
        let b = SectionBounds::FLAT;
        assert!(b.nose_height_concavity(1.0, 89f64.to_radians()).is_some());
        assert!(b.nose_height_concavity(1.0, 90f64.to_radians()).is_none());
    }

    #[test]
    fn the_nose_term_outweighs_a_bowl_no_tighter_than_the_nose() {
        // A bowl of radius 2r: r·K = 0.5, flat: concave; one of radius r·1.05: not proven.
        let bowl = |k: f64| SectionBounds {
            max_curvature: k,
            ..SectionBounds::FLAT
        };
        let m = bowl(0.5).nose_height_concavity(1.0, 0.5).unwrap();
        assert!((m - 0.5f64.cos() * 0.5).abs() < 1e-15, "{m}");
        assert!(bowl(1.0 / 1.05).nose_height_concavity(1.0, 0.5).is_none());
        // Steep flanks: slope 1 at 50° fails (tan 50° > 0.9).
        let steep = SectionBounds {
            max_slope: 1.0,
            ..SectionBounds::FLAT
        };
        assert!(
            steep
                .nose_height_concavity(0.5, 50f64.to_radians())
                .is_none()
        );
    }

    #[test]
    fn a_turned_surface_swaps_and_negates_its_curvature_bounds_and_its_ridges_become_valleys() {
        let b = SectionBounds {
            max_slope: 0.3,
            max_curvature: 0.02,
            min_curvature: -0.05,
            has_ridges: false,
            has_valleys: false,
        };
        let t = b.turned().unwrap();
        assert_eq!(
            (t.max_slope, t.max_curvature, t.min_curvature),
            (0.3, 0.05, -0.02)
        );
        assert_eq!(t.turned(), Some(b));
        // Ridges turned are valleys; valleys (or steps) turned may be either.
        let ridged = b.with_ridges(true).turned().unwrap();
        assert!(!ridged.has_ridges && ridged.has_valleys);
        let valleys = SectionBounds {
            has_valleys: true,
            ..b
        };
        let turned = valleys.turned().unwrap();
        assert!(turned.has_ridges && turned.has_valleys);
        // A sum's kinks are its parts'.
        let sum = b.and(SectionBounds::FLAT.with_ridges(true)).unwrap();
        assert!(sum.has_ridges && sum.min_curvature < -0.05 && sum.max_curvature > 0.02);
        let sum = sum.and(valleys).unwrap();
        assert!(sum.has_ridges && sum.has_valleys);
        // Either piece: the wider of each bound, either's kinks.
        let either = b.or(SectionBounds {
            max_slope: 0.1,
            max_curvature: 0.04,
            min_curvature: -0.01,
            has_ridges: true,
            has_valleys: false,
        });
        assert_eq!(
            (either.max_slope, either.max_curvature, either.min_curvature),
            (0.3, 0.04, -0.05)
        );
        assert!(either.has_ridges && !either.has_valleys);
    }
}

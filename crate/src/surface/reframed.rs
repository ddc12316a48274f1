//! The design seen from a spindle axis along its own normal at a chosen point (paper 001, §3:
//! "the normal line at a point on the middle patch of the designed surface is chosen as the
//! rotation axis `t`").
//!
//! The part is mounted so that the design's normal at `P = (x₀, y₀, f(x₀, y₀))` lies on the
//! spindle axis, with P at the origin. The new frame has `e₃ = n(P)`, `e₁` the design's X axis
//! projected onto the plane normal to `e₃` (so a design without tilt at P keeps its X and Y),
//! and `e₂ = e₃ × e₁`. A point `(u, v)` of the new frame lies on the design where the line
//! `q(s) = P + u·e₁ + v·e₂ + s·e₃` meets it: `h(s) = q_z(s) − f(q_x(s), q_y(s)) = 0`, solved by
//! Newton's method (`h′(s) = N·e₃`, `N = (−f_x, −f_y, 1)`), and the sag in the new frame is
//! `g(u, v) = s`. Implicit differentiation of `F(q) = q_z − f(q_x, q_y) = 0` gives the
//! derivatives exactly:
//!
//! `g_i = −(N·e_i)/(N·e₃)`, and with `a_i = e_i + g_i·e₃`,
//! `g_ij = (f_xx a_ix a_jx + f_xy (a_ix a_jy + a_iy a_jx) + f_yy a_iy a_jy)/(N·e₃)` (i, j = 1, 2).
//!
//! The design must be a graph over the new plane: where its normal is within
//! [`MIN_AXIS_COSINE`] of perpendicular to the axis the point is refused as undefined.
//! Slope kinks of the design (lenslet rims) are mapped exactly when the axis is the design's Z
//! (a translation); under a tilt a straight line of the new frame is a curve in the design's
//! XY, so the kinks are found on a polyline of chords of that curve, each chord with a kink
//! split into shorter ones until the curve is within rounding (1e-16 mm) of it: the
//! compensation samples 1e-12 rad either side of a kink, so its place must be exact. A kink
//! curve that crosses the curve but not the polyline (near a tangency, within the chords'
//! sagitta) can be missed; the tests compare with a brute-force scan and check a planned path
//! for gouges densely. Evaluation costs a Newton solve (3–6 design evaluations): a tilted
//! lens array plans about 12 times slower than the untilted one, a smooth design about 4.

use super::{Line, Local, SectionBounds, Surface, UndefinedError};

/// The smallest cosine allowed between the design's normal and the spindle axis: steeper than
/// about 89.4° to the axis the design is not a graph over the new plane.
pub const MIN_AXIS_COSINE: f64 = 0.01;

/// A design re-expressed in the frame of its normal at a point.
#[derive(Debug)]
pub struct Reframed {
    inner: Box<dyn Surface>,
    at: [f64; 2],
    origin: [f64; 3],
    e1: [f64; 3],
    e2: [f64; 3],
    e3: [f64; 3],
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn normalized(a: [f64; 3]) -> [f64; 3] {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

impl Reframed {
    /// `inner` seen along its normal at `(x₀, y₀)` (mm, in the design's coordinates).
    pub fn new(inner: Box<dyn Surface>, x0: f64, y0: f64) -> Result<Self, UndefinedError> {
        let l = inner.local(x0, y0)?;
        let e3 = l.normal();
        let e1 = normalized([1.0 - e3[0] * e3[0], -e3[0] * e3[1], -e3[0] * e3[2]]);
        let e2 = [
            e3[1] * e1[2] - e3[2] * e1[1],
            e3[2] * e1[0] - e3[0] * e1[2],
            e3[0] * e1[1] - e3[1] * e1[0],
        ];
        Ok(Self {
            inner,
            at: [x0, y0],
            origin: [x0, y0, l.z],
            e1,
            e2,
            e3,
        })
    }

    /// Angle between the spindle axis and the design's Z, degrees.
    pub fn tilt_deg(&self) -> f64 {
        self.e3[2].clamp(-1.0, 1.0).acos().to_degrees()
    }

    /// Azimuth in the design's XY towards which the axis leans (the direction of `e₃`'s XY
    /// part), degrees; 0 without tilt.
    pub fn azimuth_deg(&self) -> f64 {
        self.e3[1].atan2(self.e3[0]).to_degrees()
    }

    /// The design point on the spindle axis, mm (design coordinates).
    pub fn origin(&self) -> [f64; 3] {
        self.origin
    }

    /// The design's XY of the new-frame point `(u, v)` at height `s` above its plane.
    fn design_xy(&self, u: f64, v: f64, s: f64) -> (f64, f64) {
        let p = |k: usize| self.origin[k] + u * self.e1[k] + v * self.e2[k] + s * self.e3[k];
        (p(0), p(1))
    }

    fn undefined(&self, u: f64, v: f64, reason: String) -> UndefinedError {
        UndefinedError {
            surface: "design on the normal axis",
            x_mm: u,
            y_mm: v,
            radius_mm: u.hypot(v),
            reason,
        }
    }

    /// Height `s` where the axis-parallel line at `(u, v)` meets the design, with the design's
    /// local values there. Newton's method from the plane tangent at P, halving a step that
    /// leaves the design or does not reduce |h|.
    fn meet(&self, u: f64, v: f64) -> Result<(f64, Local), UndefinedError> {
        self.meet_from(u, v, 0.0)
    }

    /// [`Self::meet`] with Newton's method started at height `s0`.
    fn meet_from(&self, u: f64, v: f64, s0: f64) -> Result<(f64, Local), UndefinedError> {
        let h_at = |s: f64| -> Result<(f64, Local), UndefinedError> {
            let (x, y) = self.design_xy(u, v, s);
            let l = self.inner.local(x, y)?;
            let z = self.origin[2] + u * self.e1[2] + v * self.e2[2] + s * self.e3[2];
            Ok((z - l.z, l))
        };
        let mut s = s0;
        let (mut h, mut l) = match h_at(s) {
            Ok(first) => first,
            Err(_) if s0 != 0.0 => return self.meet(u, v),
            Err(e) => return Err(e),
        };
        for _ in 0..100 {
            let slope = self.e3[2] - l.zx * self.e3[0] - l.zy * self.e3[1];
            if slope <= MIN_AXIS_COSINE * (1.0 + l.zx * l.zx + l.zy * l.zy).sqrt() {
                let limit = MIN_AXIS_COSINE.acos().to_degrees();
                let why = format!("the design is steeper than {limit:.1}° to the spindle axis");
                return Err(self.undefined(u, v, why));
            }
            if h == 0.0 {
                break;
            }
            let mut ds = -h / slope;
            if ds.abs() <= 1e-15 * (1.0 + s.abs()) {
                break;
            }
            let mut next = None;
            for _ in 0..60 {
                match h_at(s + ds) {
                    Ok((hn, ln)) if hn.abs() < h.abs() => {
                        next = Some((hn, ln));
                        break;
                    }
                    _ => ds /= 2.0,
                }
            }
            // No step reduces |h| any more: converged to rounding, or stuck (judged below).
            let Some((hn, ln)) = next else { break };
            (s, h, l) = (s + ds, hn, ln);
        }
        if h.abs() <= 1e-12 {
            return Ok((s, l));
        }
        let why =
            format!("the line along the spindle axis does not meet the design (gap {h:e} mm)");
        Err(self.undefined(u, v, why))
    }

    /// Kinks along the image of `line` in the design's XY, which is a curve under a tilt: the
    /// kinks on a polyline of chords a quarter feature long; a chord with kinks is split at
    /// 1/64 of its length either side of each until its sagitta (the curve's distance from the
    /// chord at its middle) is below 1e-16 mm or it is shorter than 1e-12 mm. The polyline stays continuous, so a kink curve crossing
    /// it is found on one of its chords.
    fn curved_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let piece = (self.inner.feature_length_mm() / 4.0).max(1e-6);
        let pieces = ((t1 - t0) / piece).ceil().clamp(1.0, 1e6) as usize;
        let width = (t1 - t0) / pieces as f64;
        let mut from = self.image(line, t0, 0.0);
        for k in 1..=pieces {
            let b = if k == pieces {
                t1
            } else {
                t0 + k as f64 * width
            };
            let to = self.image(line, b, from.map_or(0.0, |p| p.2));
            if let (Some(pa), Some(pb)) = (from, to) {
                self.kinks_between(line, (b - width, pa), (b, pb), out);
            }
            from = to;
        }
    }

    /// The design's XY of the point of `line` at `t`, with its height (Newton from `s0`).
    fn image(&self, line: Line, t: f64, s0: f64) -> Option<(f64, f64, f64)> {
        let (u, v) = line.at(t);
        let (s, _) = self.meet_from(u, v, s0).ok()?;
        let (x, y) = self.design_xy(u, v, s);
        Some((x, y, s))
    }

    fn kinks_between(&self, line: Line, a: Image, b: Image, out: &mut Vec<f64>) {
        let ((ta, pa), (tb, pb)) = (a, b);
        let (dx, dy) = (pb.0 - pa.0, pb.1 - pa.1);
        let len = dx.hypot(dy);
        if len == 0.0 {
            return;
        }
        let chord = Line {
            x0: pa.0,
            y0: pa.1,
            c: dx / len,
            s: dy / len,
        };
        let mut on_chord = Vec::new();
        self.inner.slope_kinks(chord, 0.0, len, &mut on_chord);
        if on_chord.is_empty() {
            return;
        }
        let mid = self.image(line, 0.5 * (ta + tb), 0.5 * (pa.2 + pb.2));
        let sagitta = mid.map_or(f64::INFINITY, |m| {
            ((m.0 - pa.0) * chord.s - (m.1 - pa.1) * chord.c).abs()
        });
        if sagitta <= 1e-16 || tb - ta <= 1e-12 || mid.is_none() {
            out.extend(on_chord.into_iter().map(|w| ta + (tb - ta) * w / len));
            return;
        }
        // Around each estimate a chord 1/32 as long: its sagitta is ~1000 times smaller, and
        // the estimate's error (of the order of this chord's sagitta) well inside it.
        let half = (tb - ta) / 64.0;
        let mut cuts: Vec<f64> = on_chord
            .iter()
            .map(|w| ta + (tb - ta) * w / len)
            .flat_map(|t| [t - half, t + half])
            .filter(|t| *t > ta && *t < tb)
            .collect();
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut from = (ta, pa);
        for t in cuts {
            let Some(p) = self.image(line, t, from.1.2) else {
                return;
            };
            self.kinks_between(line, from, (t, p), out);
            from = (t, p);
        }
        self.kinks_between(line, from, (tb, pb), out);
    }
}

/// A point of a line of the new frame: its parameter, and its image (x, y) in the design's XY
/// with its height s.
type Image = (f64, (f64, f64, f64));

impl Surface for Reframed {
    fn local(&self, u: f64, v: f64) -> Result<Local, UndefinedError> {
        let (s, l) = self.meet(u, v)?;
        let n = [-l.zx, -l.zy, 1.0];
        let n3 = dot(n, self.e3);
        let gu = -dot(n, self.e1) / n3;
        let gv = -dot(n, self.e2) / n3;
        let a = |e: [f64; 3], g: f64| [e[0] + g * self.e3[0], e[1] + g * self.e3[1]];
        let (au, av) = (a(self.e1, gu), a(self.e2, gv));
        let second = |p: [f64; 2], q: [f64; 2]| {
            (l.zxx * p[0] * q[0] + l.zxy * (p[0] * q[1] + p[1] * q[0]) + l.zyy * p[1] * q[1]) / n3
        };
        Ok(Local {
            z: s,
            zx: gu,
            zy: gv,
            zxx: second(au, au),
            zxy: second(au, av),
            zyy: second(av, av),
        })
    }

    fn feature_length_mm(&self) -> f64 {
        // A design feature of lateral length L near P appears at least L·cos(tilt) long in the
        // new plane (exact for a design flat at P; a quasi-revolution design stays close).
        self.inner.feature_length_mm() * self.e3[2]
    }

    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        if self.e3[2] == 1.0 {
            // No tilt: the new frame is the design's, moved to P; a line stays a line.
            let moved = Line {
                x0: line.x0 + self.at[0],
                y0: line.y0 + self.at[1],
                ..line
            };
            self.inner.slope_kinks(moved, t0, t1, out);
        } else {
            self.curved_kinks(line, t0, t1, out);
        }
    }

    /// The design's.
    fn keeps_lines(&self) -> bool {
        self.inner.keeps_lines()
    }

    /// The design's at the moved point where the axis is not tilted; under a tilt not said (0:
    /// the kinks are found along the curved image of each stretch).
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        if self.e3[2] == 1.0 {
            self.inner.kink_free_radius(x + self.at[0], y + self.at[1])
        } else {
            0.0
        }
    }

    fn warnings(&self) -> Vec<String> {
        self.inner.warnings()
    }

    /// From the design's [`Surface::disc_bounds`] about its axis over `|P| + 2T` (P the point
    /// on the spindle axis). Within that disc the design's normal leans at most `atan S` from
    /// its Z and so at most `ψ = atan S + τ` from the spindle axis (τ the axis's tilt), so
    /// `G = tan ψ` bounds the new frame's slope; a new-frame point within T of the axis lies
    /// within `T + G·T·sin τ ≤ 2T` of P in the design's XY when `G·sin τ ≤ 1` (asked). A
    /// section's curvature is `a·H·a/(N·e₃)` with `|a|² = 1 + g_d² ≤ 1 + G²` and
    /// `N·e₃ ≥ cos ψ`, so it lies within the design's eigenvalue bounds times `(1 + G²)^(3/2)`
    /// between its kinks. A kink keeps its kind: turned rigidly (with no overhang, ψ < 90°), the
    /// material under a ridge is still a convex wedge, and its cut by any plane a convex corner
    /// (a ridge of the section); under a valley, the space above. None where the design gives
    /// none, or ψ reaches 86°.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let tilt = self.e3[2].clamp(-1.0, 1.0).acos();
        let design = self
            .inner
            .disc_bounds(self.at[0].hypot(self.at[1]) + 2.0 * t)?;
        let psi = design.max_slope.atan() + tilt;
        if psi.is_nan() || psi >= 86f64.to_radians() {
            return None;
        }
        let g = psi.tan();
        if g * tilt.sin() > 1.0 {
            return None;
        }
        let stretch = (1.0 + g * g).powf(1.5);
        SectionBounds::FLAT.and(SectionBounds {
            max_slope: g,
            max_curvature: design.max_curvature.max(0.0) * stretch,
            min_curvature: design.min_curvature.min(0.0) * stretch,
            has_ridges: design.has_ridges,
            has_valleys: design.has_valleys,
        })
    }

    fn describe(&self) -> String {
        format!(
            "{}, on a spindle axis along its normal at ({}, {}) mm (z {:.6} mm): tilted {:.6}° \
             towards azimuth {:.6}°",
            self.inner.describe(),
            self.at[0],
            self.at[1],
            self.origin[2],
            self.tilt_deg(),
            self.azimuth_deg()
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::section_bounds::assert_bounds_hold;
    use crate::surface::{Asphere, AsphereSpec, LensArray, LensArraySpec, PartDisc};

    #[test]
    fn section_bounds_hold_on_the_tilted_axis() {
        let asphere = |r: f64, k: f64| -> Box<dyn Surface> {
            Box::new(
                Asphere::new(&AsphereSpec {
                    radius_mm: Some(r),
                    conic: k,
                    ..Default::default()
                })
                .unwrap(),
            )
        };
        for (design, at, radius) in [
            (asphere(40.0, -1.0), [6.0, 2.0], 3.0),
            (asphere(-30.0, 0.5), [-4.0, 3.0], 2.5),
            (asphere(25.0, 0.0), [0.0, 0.0], 3.0),
        ] {
            let s = Reframed::new(design, at[0], at[1]).unwrap();
            assert_bounds_hold(&s, radius, 36, 2000);
        }
        // Concave lenslets seen along the normal on a lenslet's wall: bounds between the rims,
        // which stay ridges.
        let array = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(3.0)).unwrap();
        let tilted = Reframed::new(Box::new(array), 0.3, 0.2).unwrap();
        let (b, ..) = assert_bounds_hold(&tilted, 1.0, 36, 4000);
        assert!(b.has_ridges && !b.has_valleys);
    }
}

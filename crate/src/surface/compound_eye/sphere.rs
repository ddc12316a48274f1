//! The geometry every piece of a compound eye is made of: a sphere `|X − C| = r` in space, the
//! sag of its upper cap `z = C_z + √(r² − d²)` (d the XY distance from the centre) with its
//! derivatives, the circle where two spheres (or a sphere and the plane z = 0) meet, and where a
//! vertical plane through a line of the XY plane crosses such a circle.
//!
//! Intersection circle (the "radical plane" construction, e.g. Weisstein, *Sphere–Sphere
//! Intersection*, MathWorld): for centres A, B at distance D and radii a, b with
//! |a − b| < D < a + b, the common points satisfy `|X − A|² − a² = |X − B|² − b²`, the plane
//! `(X − A)·u = p` with `u = (B − A)/D`, `p = (D² + a² − b²)/(2D)`; the circle has centre
//! `A + p·u`, normal u and radius `ρ = √(a² − p²)`, computed as
//! `ρ² = (a + p)·(b − a + D)(b + a − D)/(2D)` so that a small circle keeps its digits.
//!
//! Crossing with the vertical plane `n·X = e` over the line (n = (−s, c, 0), e = n·(x₀, y₀, 0)):
//! with `w = n − (n·u)·u` (n's part in the circle's plane), `ê = w/|w|` and `f̂ = u × ê`, the
//! circle point `M + ρ(cos φ·ê + sin φ·f̂)` has `n·X = n·M + ρ|w|·cos φ`, so
//! `cos φ = (e − n·M)/(ρ|w|)` and the two crossings are `M + ρ(κ·ê ± √(1 − κ²)·f̂)`, κ = cos φ.
//! Their line parameter is `t = (X − (x₀, y₀))·(c, s)`. This is the exact closed form of the
//! quadratic "radical plane gives z linear in t, substituted into one sphere" and, unlike the
//! quadratic in t, stays well conditioned when the circle's plane is vertical (two spheres of
//! equal height), where both crossings lie over the same point of the line.

use crate::surface::{Line, Local};

/// A sphere in space, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sphere {
    /// Centre (x, y, z).
    pub centre: [f64; 3],
    /// Radius, > 0.
    pub radius: f64,
}

impl Sphere {
    /// Height of the top point, `C_z + r`.
    pub fn apex(&self) -> f64 {
        self.centre[2] + self.radius
    }

    /// Sag of the upper cap, or `None` at or beyond its rim `d ≥ r`. Written as
    /// `apex − d²/(r + √(r² − d²))`, which has no cancellation near the apex.
    pub fn cap_sag(&self, x: f64, y: f64) -> Option<f64> {
        let (dx, dy) = (x - self.centre[0], y - self.centre[1]);
        let d2 = dx * dx + dy * dy;
        let r = self.radius;
        let w2 = r * r - d2;
        (w2 > 0.0).then(|| self.apex() - d2 / (r + w2.sqrt()))
    }

    /// Sag, gradient and Hessian of the upper cap `z = C_z + w`, `w = √(r² − d²)`:
    /// `∇z = −(dx, dy)/w`, `∂²z/∂x² = −(r² − dy²)/w³`, `∂²z/∂x∂y = −dx·dy/w³`,
    /// `∂²z/∂y² = −(r² − dx²)/w³`; `None` at or beyond the rim.
    pub fn cap_local(&self, x: f64, y: f64) -> Option<Local> {
        let (dx, dy) = (x - self.centre[0], y - self.centre[1]);
        let d2 = dx * dx + dy * dy;
        let r = self.radius;
        let w2 = r * r - d2;
        if w2 <= 0.0 {
            return None;
        }
        let w = w2.sqrt();
        let w3 = w2 * w;
        Some(Local {
            z: self.apex() - d2 / (r + w),
            zx: -dx / w,
            zy: -dy / w,
            zxx: -(r * r - dy * dy) / w3,
            zxy: -dx * dy / w3,
            zyy: -(r * r - dx * dx) / w3,
        })
    }

    /// The circle where this sphere meets `other`, if they meet in more than a point.
    pub fn meet(&self, other: &Sphere) -> Option<Circle> {
        let (a, b) = (self.radius, other.radius);
        let d = sub(other.centre, self.centre);
        let dist = norm(d);
        if !(dist > (a - b).abs() && dist < a + b) {
            return None;
        }
        let u = scale(d, 1.0 / dist);
        let p = (dist * dist + a * a - b * b) / (2.0 * dist);
        // a − p = (b² − (a − D)²)/(2D).
        let a_minus_p = (b - a + dist) * (b + a - dist) / (2.0 * dist);
        let rho2 = (a + p) * a_minus_p;
        (rho2 > 0.0).then(|| Circle {
            centre: add(self.centre, scale(u, p)),
            normal: u,
            radius: rho2.sqrt(),
        })
    }

    /// The circle where this sphere meets the plane z = 0, if it does in more than a point.
    pub fn meet_plane(&self) -> Option<Circle> {
        let [x, y, z] = self.centre;
        let r = self.radius;
        let rho2 = (r - z) * (r + z);
        (rho2 > 0.0).then(|| Circle {
            centre: [x, y, 0.0],
            normal: [0.0, 0.0, 1.0],
            radius: rho2.sqrt(),
        })
    }
}

/// A circle in space: where two pieces meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle {
    /// Centre, mm.
    pub centre: [f64; 3],
    /// Unit normal of its plane.
    pub normal: [f64; 3],
    /// Radius, mm.
    pub radius: f64,
}

impl Circle {
    /// Half the width of its projection on the XY plane (an ellipse): the semi-minor axis
    /// `ρ·|u_z|`, mm.
    pub fn projected_half_width(&self) -> f64 {
        self.radius * self.normal[2].abs()
    }

    /// The points where the circle crosses the vertical plane over `line`, with their line
    /// parameter: `(t, X)`, none, one (tangent) or two.
    pub fn crossings(&self, line: Line) -> impl Iterator<Item = (f64, [f64; 3])> {
        let n = [-line.s, line.c, 0.0];
        let e = n[0] * line.x0 + n[1] * line.y0;
        let u = self.normal;
        let nu = dot(n, u);
        let w = sub(n, scale(u, nu));
        let w_len = norm(w);
        let mut out = [None, None];
        // A circle in a plane parallel to the section's plane never crosses it transversally.
        if w_len > 1e-12 {
            let kappa = (e - dot(n, self.centre)) / (self.radius * w_len);
            if kappa.abs() <= 1.0 {
                let e_hat = scale(w, 1.0 / w_len);
                let f_hat = cross(u, e_hat);
                let along = (1.0 - kappa * kappa).sqrt();
                for (slot, sign) in out.iter_mut().zip([-1.0, 1.0]) {
                    let x = add(
                        self.centre,
                        add(
                            scale(e_hat, self.radius * kappa),
                            scale(f_hat, self.radius * along * sign),
                        ),
                    );
                    let t = (x[0] - line.x0) * line.c + (x[1] - line.y0) * line.s;
                    *slot = Some((t, x));
                }
            }
        }
        out.into_iter().flatten()
    }
}

fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(a: [f64; 3], k: f64) -> [f64; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
        norm(sub(a, b))
    }

    fn sphere(centre: [f64; 3], radius: f64) -> Sphere {
        Sphere { centre, radius }
    }

    /// A large sphere and a small one that cut each other, each also cutting the plane z = 0.
    fn cutting_pair() -> (Sphere, Sphere) {
        (sphere([0.0, 0.0, -5.0], 5.2), sphere([0.7, 0.4, -1.0], 1.3))
    }

    #[test]
    fn cap_sag_is_the_upper_half_of_the_sphere() {
        let s = sphere([0.3, -0.2, -1.5], 2.0);
        for &(x, y) in &[(0.3, -0.2), (1.0, 0.5), (-1.2, -1.1)] {
            let z = s.cap_sag(x, y).unwrap();
            // The point lies on the sphere, above its centre.
            assert!((distance([x, y, z], s.centre) - 2.0).abs() < 1e-15);
            assert!(z > s.centre[2]);
            assert_eq!(s.cap_local(x, y).unwrap().z, z);
        }
        assert_eq!(s.cap_sag(2.31, -0.2), None);
        assert_eq!(s.cap_local(0.3, 1.8), None);
    }

    #[test]
    fn meeting_circles_lie_on_both_spheres_and_the_plane() {
        let (a, b) = cutting_pair();
        for circle in [
            a.meet(&b).unwrap(),
            b.meet(&a).unwrap(),
            b.meet_plane().unwrap(),
        ] {
            // Walk the circle in its plane: every point is on both surfaces.
            let u = circle.normal;
            let e1 = {
                let t = cross(u, [1.0, 0.0, 0.0]);
                scale(t, 1.0 / norm(t))
            };
            let e2 = cross(u, e1);
            for k in 0..12 {
                let phi = k as f64 * 0.5;
                let x = add(
                    circle.centre,
                    add(
                        scale(e1, circle.radius * phi.cos()),
                        scale(e2, circle.radius * phi.sin()),
                    ),
                );
                assert!((distance(x, b.centre) - b.radius).abs() < 1e-14);
                if circle.normal == [0.0, 0.0, 1.0] {
                    assert!(x[2].abs() < 1e-15);
                } else {
                    assert!((distance(x, a.centre) - a.radius).abs() < 1e-14);
                }
            }
        }
        // Apart, nested or touching: no circle.
        let far = sphere([10.0, 0.0, 0.0], 1.0);
        assert_eq!(a.meet(&far), None);
        let inner = sphere([0.0, 0.0, -5.0], 1.0);
        assert_eq!(a.meet(&inner), None);
        assert_eq!(inner.meet_plane(), None);
    }

    #[test]
    fn crossings_are_on_the_circle_and_over_the_line() {
        let (a, b) = cutting_pair();
        // A level pair: the circle's plane is vertical.
        let c = sphere([1.5, 0.4, -1.0], 1.3);
        let line = Line {
            x0: 0.1,
            y0: 0.2,
            c: 0.8,
            s: 0.6,
        };
        for circle in [
            a.meet(&b).unwrap(),
            b.meet(&c).unwrap(),
            b.meet_plane().unwrap(),
        ] {
            let found: Vec<_> = circle.crossings(line).collect();
            assert_eq!(found.len(), 2, "{circle:?}");
            for (t, x) in found {
                let (px, py) = line.at(t);
                assert!((px - x[0]).abs() < 1e-14 && (py - x[1]).abs() < 1e-14);
                assert!((distance(x, b.centre) - b.radius).abs() < 1e-14);
                assert!((distance(x, circle.centre) - circle.radius).abs() < 1e-14);
            }
        }
        // A line that passes by: none.
        let away = Line {
            x0: 0.0,
            y0: 5.0,
            c: 1.0,
            s: 0.0,
        };
        assert_eq!(a.meet(&b).unwrap().crossings(away).count(), 0);
    }
}

//! How a child sphere (an element, a lenslet) is rooted in its parent surface (the base, an
//! element), and for which heights it stays rooted.
//!
//! Placement: the child stands on the parent point S over its layout point (x, y), along the
//! parent's upward unit normal `n = (−z_x, −z_y, 1)/√(1 + z_x² + z_y²)`: its centre is
//! `S + (h − r)·n` and its pole `S + h·n` lies h out of the parent. On a spherical parent the
//! child's centre is then on the parent's radius through S, so the child meets the parent along
//! a circle about that radius: every lenslet sits on its element, and every element on a
//! spherical base, the same way wherever it is, as the patches of a compound eye do (paper 001,
//! section 3: "many small spherical patches on a big sphere").
//!
//! Rooted: the child's equator (the horizontal circle of radius r through its centre) lies
//! strictly inside the parent's material side, so the child rises out of the parent along one
//! circle and is back under it before its sides turn vertical. With β the tilt of the parent's
//! normal at S (`sin β = d/R`, d the XY distance of S from the parent's axis) and L the distance
//! between the two centres, the farthest equator point from the parent's centre lies at
//! `√(L² ± 2Lr·sin β + r²)`, which gives the heights in closed form:
//! - plane: the centre below it, `h < r`;
//! - dome of radius R (`L = R + h − r`, equator inside the sphere):
//!   `L² + 2Lr·sin β + r² < R²`, i.e. `h < r(1 − sin β) − r²cos²β/(R + √(R² − r²cos²β))`;
//! - bowl of radius R (`L = R − h + r`, equator outside the sphere, under the bowl):
//!   `L² − 2Lr·sin β + r² > R²`, i.e. `h < r(1 − sin β) + r²cos²β/(R + √(R² − r²cos²β))`;
//!   also within the bowl's rim, `L·sin β + r < R`, and below the bowl's centre, `L·cos β > r`.
//!
//! The square roots are written without cancellation (`√(R² − a²) − R = −a²/(R + √(R² − a²))`).

use super::sphere::Sphere;
use crate::surface::Local;

/// The surface a child stands on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Parent {
    /// The plane z = 0.
    Plane,
    /// The upper cap of a sphere of this radius (centre on −Z of it): a dome, an element.
    Dome(f64),
    /// The lower cap of a sphere of this radius: a bowl.
    Bowl(f64),
}

/// The sphere of radius `r` standing `h` out of the parent whose sag and gradient at (x, y) are
/// `at`, and its pole.
pub fn rooted_sphere(at: &Local, x: f64, y: f64, h: f64, r: f64) -> (Sphere, [f64; 3]) {
    let k = 1.0 / (1.0 + at.zx * at.zx + at.zy * at.zy).sqrt();
    let n = [-at.zx * k, -at.zy * k, k];
    let s = [x, y, at.z];
    let along = |t: f64| [s[0] + t * n[0], s[1] + t * n[1], s[2] + t * n[2]];
    (
        Sphere {
            centre: along(h - r),
            radius: r,
        },
        along(h),
    )
}

/// The open range of heights h for which a child of radius `r` standing on `parent` at XY
/// distance `d` from the parent's axis is rooted (see the module docs): `(lo, hi)`, empty when
/// `lo ≥ hi`. `d` must lie within the parent's rim.
pub fn height_limits(parent: Parent, r: f64, d: f64) -> (f64, f64) {
    match parent {
        Parent::Plane => (0.0, r),
        Parent::Dome(big) => {
            let (sin_b, cos2_b) = tilt(big, d);
            let a2 = r * r * cos2_b;
            if a2 >= big * big {
                return (0.0, f64::NEG_INFINITY);
            }
            (
                0.0,
                r * (1.0 - sin_b) - a2 / (big + (big * big - a2).sqrt()),
            )
        }
        Parent::Bowl(big) => {
            let (sin_b, cos2_b) = tilt(big, d);
            let a2 = r * r * cos2_b;
            if a2 >= big * big || r >= big {
                return (0.0, f64::NEG_INFINITY);
            }
            let equator = r * (1.0 - sin_b) + a2 / (big + (big * big - a2).sqrt());
            let below_centre = big + r - r / cos2_b.sqrt();
            let within_rim = if sin_b > 0.0 {
                big + r - (big - r) / sin_b
            } else {
                f64::NEG_INFINITY
            };
            (within_rim.max(0.0), equator.min(below_centre))
        }
    }
}

/// `sin β` and `cos² β` of the parent's normal at XY distance d from its axis.
fn tilt(big: f64, d: f64) -> (f64, f64) {
    let sin_b = d / big;
    (sin_b, (1.0 - sin_b) * (1.0 + sin_b))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rooting conditions checked directly on 720 points of the child's equator.
    fn rooted(parent: Parent, child: &Sphere) -> bool {
        let [cx, cy, cz] = child.centre;
        (0..720).all(|k| {
            let (s, c) = (k as f64 * std::f64::consts::TAU / 720.0).sin_cos();
            let (x, y) = (cx + child.radius * c, cy + child.radius * s);
            match parent {
                Parent::Plane => cz < 0.0,
                Parent::Dome(big) => x * x + y * y + (cz + big) * (cz + big) < big * big,
                Parent::Bowl(big) => {
                    let outside = x * x + y * y + (cz - big) * (cz - big) > big * big;
                    outside && x.hypot(y) < big && cz + child.radius < big
                }
            }
        })
    }

    /// The parent's sag and gradient at (d, 0): a sphere through the origin, centre (0, 0, ∓R).
    fn parent_at(parent: Parent, d: f64) -> Local {
        let (big, sign) = match parent {
            Parent::Plane => return Local::default(),
            Parent::Dome(big) => (big, -1.0),
            Parent::Bowl(big) => (big, 1.0),
        };
        let w = (big * big - d * d).sqrt();
        Local {
            z: sign * (big - w),
            zx: sign * d / w,
            ..Local::default()
        }
    }

    #[test]
    fn the_height_limit_is_where_the_equator_leaves_the_parent() {
        // Parents centred on the axis (dome centre (0, 0, −R), bowl centre (0, 0, R)), children
        // at several distances: rooted just below the limit, not just above it.
        let cases = [
            (Parent::Plane, 0.5, 1.3),
            (Parent::Dome(8.0), 2.0, 0.0),
            (Parent::Dome(8.0), 2.0, 1.1),
            (Parent::Dome(40.0), 8.0, 2.6),
            (Parent::Dome(3.0), 0.4, 2.5),
            (Parent::Bowl(40.0), 8.0, 0.0),
            (Parent::Bowl(40.0), 8.0, 2.6),
            (Parent::Bowl(10.0), 1.0, 5.0),
        ];
        for (parent, r, d) in cases {
            let (lo, hi) = height_limits(parent, r, d);
            assert!(hi > lo, "{parent:?} r {r} d {d}: ({lo}, {hi})");
            let at = parent_at(parent, d);
            let shift = |h: f64| rooted_sphere(&at, d, 0.0, h, r).0;
            let eps = 1e-9 * (1.0 + hi.abs());
            assert!(rooted(parent, &shift(hi - eps)), "{parent:?} r {r} d {d}");
            assert!(!rooted(parent, &shift(hi + eps)), "{parent:?} r {r} d {d}");
            if lo > 0.0 {
                assert!(rooted(parent, &shift(lo + eps)));
                assert!(!rooted(parent, &shift(lo - eps)));
            }
        }
        // A child as wide as a dome parent never fits.
        assert!(height_limits(Parent::Dome(1.0), 1.0, 0.0).1 < 0.0);
    }

    #[test]
    fn the_child_stands_on_the_parent_normal() {
        let parent = Parent::Dome(8.0);
        let at = parent_at(parent, 1.5);
        let (s, pole) = rooted_sphere(&at, 1.5, 0.0, 0.02, 2.0);
        // Centre, pole and the parent's centre (0, 0, −8) are collinear; the pole is 0.02 mm
        // out of the parent sphere and on the child.
        let d = |p: [f64; 3]| (p[0] * p[0] + p[1] * p[1] + (p[2] + 8.0) * (p[2] + 8.0)).sqrt();
        assert!((d(pole) - 8.02).abs() < 1e-14);
        assert!((d(s.centre) - (8.02 - 2.0)).abs() < 1e-14);
        let cross = s.centre[0] * (pole[2] + 8.0) - (s.centre[2] + 8.0) * pole[0];
        assert!(cross.abs() < 1e-14);
    }
}

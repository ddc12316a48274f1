//! Mean power and cylinder (surface astigmatism) of any surface, at a point and as maps over
//! the part: the optical reading of a surface's curvature, the measure paper 003 uses to judge
//! its progressive lens (section 4, Figure 12: power and astigmatism maps).
//!
//! **Curvatures** ([`Local::principal_curvatures`]). For the graph z = f(x, y) with p = f_x,
//! q = f_y, W = √(1 + p² + q²), the first fundamental form is `E = 1 + p²`, `F = pq`,
//! `G = 1 + q²` and the second, taken with the unit normal pointing into the material (−Z,
//! away from the tool), `L = −f_xx/W`, `M = −f_xy/W`,
//! `N = −f_yy/W` (do Carmo, Differential Geometry of Curves and Surfaces, §3-3). The principal
//! curvatures κ₁ ≥ κ₂ are the eigenvalues of the shape operator I⁻¹·II; with the Cholesky factor
//! I = C·Cᵀ (C₁₁ = √E, C₂₁ = F/√E, C₂₂ = W/√E) they are those of the symmetric
//! `S = C⁻¹·II·C⁻ᵀ`: `S₁₁ = L/E`, `S₁₂ = (M − L·F/E)/W`, `S₂₂ = (N·E − 2M·F + L·F²/E)/W²`, so
//! `κ = (S₁₁ + S₂₂)/2 ± √(((S₁₁ − S₂₂)/2)² + S₁₂²)`, whose difference is a root of a sum of
//! squares and keeps full relative accuracy at umbilic points (H² − K would cancel there).
//!
//! **Sign convention.** κ > 0 where the surface is convex towards +Z (the tool, the outside of
//! the part), i.e. where its centre of curvature lies on −Z: a sphere of the project's signed
//! radius R (centre on +Z for R > 0, as in `AsphereSpec::radius_mm`) has κ₁ = κ₂ = −1/R.
//!
//! **Powers.** For light entering the material (index n) from the tool side, the surface power
//! along a principal direction is `1000·(n − 1)·κ` dioptres (κ in 1/mm; paper 003 eq 1), so the
//! mean power is `P = 1000·(n − 1)·(κ₁ + κ₂)/2` and the cylinder `C = 1000·(n − 1)·(κ₁ − κ₂) ≥ 0`:
//! positive power for a convex front, the ophthalmic convention.

use crate::field::{FieldError, in_range};
use crate::raster::Raster;
use crate::surface::{Local, PartDisc, Surface};

/// Largest map side accepted, samples.
pub const MAX_MAP_SIZE: usize = 4096;

/// Mean power and cylinder at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfacePower {
    /// Mean power `1000(n − 1)(κ₁ + κ₂)/2`, dioptres; positive for a surface convex towards +Z.
    pub mean_d: f64,
    /// Cylinder `1000(n − 1)(κ₁ − κ₂)`, dioptres, ≥ 0.
    pub cylinder_d: f64,
}

impl SurfacePower {
    /// The powers of the surface whose local derivatives are `l`, for refractive index n.
    pub fn from_local(l: &Local, refractive_index: f64) -> Self {
        let [k1, k2] = l.principal_curvatures();
        let scale = 1000.0 * (refractive_index - 1.0);
        Self {
            mean_d: scale * 0.5 * (k1 + k2),
            cylinder_d: scale * (k1 - k2),
        }
    }
}

/// Mean power and cylinder sampled on a square grid over the part, for drawing as maps.
///
/// Both maps share one grid, which spans the part's bounding square edge to edge (sample (i, j)
/// at [`Raster::position`], stored at `j·size + i`). Samples outside the part disc, and inside
/// it where the surface has no value, are NaN.
#[derive(Debug, Clone, PartialEq)]
pub struct PowerMap {
    /// Mean power per sample, dioptres (NaN outside the part or where undefined).
    pub mean_d: Raster,
    /// Cylinder per sample, dioptres (NaN outside the part or where undefined).
    pub cylinder_d: Raster,
    /// Samples inside the part where the surface had no value.
    pub undefined: usize,
}

impl PowerMap {
    /// Samples `surface` over the disc `part` on a `size` × `size` grid (2 ≤ size ≤
    /// [`MAX_MAP_SIZE`]) for refractive index n in [1, 3].
    pub fn sample(
        surface: &dyn Surface,
        part: PartDisc,
        refractive_index: f64,
        size: usize,
    ) -> Result<Self, FieldError> {
        let n = in_range("refractive_index", refractive_index, 1.0, 3.0)?;
        if !(2..=MAX_MAP_SIZE).contains(&size) {
            return Err(FieldError::new(
                "size",
                size,
                format!("must be an integer in [2, {MAX_MAP_SIZE}]"),
            ));
        }
        let radius = in_range("part.radius_mm", part.radius_mm, f64::MIN_POSITIVE, 1e6)?;
        let grid = Raster {
            x0_mm: part.x_mm - radius,
            y0_mm: part.y_mm - radius,
            ..Raster::over_part(radius, size)
        };
        let mut map = Self {
            mean_d: grid.clone(),
            cylinder_d: grid,
            undefined: 0,
        };
        // A sample on the rim counts as inside despite rounding of x0 + i·step.
        let inside = radius * (1.0 + 1e-12);
        for j in 0..size {
            for i in 0..size {
                let (x, y) = map.mean_d.position(i, j);
                if (x - part.x_mm).hypot(y - part.y_mm) > inside {
                    continue;
                }
                match surface.local(x, y) {
                    Ok(l) => {
                        let p = SurfacePower::from_local(&l, n);
                        map.mean_d.values[j * size + i] = p.mean_d;
                        map.cylinder_d.values[j * size + i] = p.cylinder_d;
                    }
                    Err(_) => map.undefined += 1,
                }
            }
        }
        Ok(map)
    }

    /// Smallest and largest mean power over the defined samples, dioptres.
    pub fn mean_range_d(&self) -> Option<(f64, f64)> {
        self.mean_d.range()
    }

    /// Smallest and largest cylinder over the defined samples, dioptres.
    pub fn cylinder_range_d(&self) -> Option<(f64, f64)> {
        self.cylinder_d.range()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{Asphere, UndefinedError};

    /// The normal curvature `II(t, t)/I(t, t)` along the parameter direction (cos φ, sin φ),
    /// written from the fundamental forms directly.
    fn normal_curvature(l: &Local, phi: f64) -> f64 {
        let (c, s) = (phi.cos(), phi.sin());
        let w = (1.0 + l.zx * l.zx + l.zy * l.zy).sqrt();
        let ii = -(l.zxx * c * c + 2.0 * l.zxy * c * s + l.zyy * s * s) / w;
        let tx = [1.0, 0.0, l.zx];
        let ty = [0.0, 1.0, l.zy];
        let t: Vec<f64> = (0..3).map(|k| c * tx[k] + s * ty[k]).collect();
        ii / t.iter().map(|v| v * v).sum::<f64>()
    }

    /// Largest and smallest normal curvature over directions: 3600 samples of φ ∈ [0, π), then
    /// golden-section search on the bracket around the best sample (unimodal there).
    fn extreme_normal_curvatures(l: &Local) -> [f64; 2] {
        let n = 3600;
        let step = std::f64::consts::PI / n as f64;
        let best = |sign: f64| {
            let i = (0..n)
                .max_by(|&a, &b| {
                    let ka = sign * normal_curvature(l, a as f64 * step);
                    let kb = sign * normal_curvature(l, b as f64 * step);
                    ka.total_cmp(&kb)
                })
                .unwrap();
            let (mut a, mut b) = ((i as f64 - 1.0) * step, (i as f64 + 1.0) * step);
            let g = 0.5 * (5f64.sqrt() - 1.0);
            for _ in 0..80 {
                let (c, d) = (b - g * (b - a), a + g * (b - a));
                if sign * normal_curvature(l, c) > sign * normal_curvature(l, d) {
                    b = d;
                } else {
                    a = c;
                }
            }
            normal_curvature(l, 0.5 * (a + b))
        };
        [best(1.0), best(-1.0)]
    }

    #[test]
    fn a_sphere_has_equal_curvatures_everywhere() {
        // Rounding only: κ to 1e-14 relative; cylinder from a root of a sum of squares of
        // rounding-sized differences, ≤ 1e-12 of the mean power.
        let n = 1.5;
        for r in [-60.0, 25.0] {
            let s = Asphere::sphere(r).unwrap();
            for &(x, y) in &[(0.0, 0.0), (7.0, -3.0), (-12.0, 15.0), (0.0, 23.0)] {
                let l = s.local(x, y).unwrap();
                let [k1, k2] = l.principal_curvatures();
                for k in [k1, k2] {
                    assert!(
                        (k + 1.0 / r).abs() < 1e-14 / r.abs(),
                        "R {r} ({x}, {y}): {k}"
                    );
                }
                let p = SurfacePower::from_local(&l, n);
                let expect = -1000.0 * (n - 1.0) / r;
                assert!((p.mean_d - expect).abs() < 1e-12 * expect.abs());
                assert!(
                    p.cylinder_d.abs() < 1e-12 * expect.abs(),
                    "{}",
                    p.cylinder_d
                );
            }
        }
    }

    /// z = R − √(R² − x²): a cylinder with its axis along y, centre of curvature on +Z.
    #[derive(Debug)]
    struct Cylinder(f64);

    impl Surface for Cylinder {
        fn local(&self, x: f64, _y: f64) -> Result<Local, UndefinedError> {
            let r = self.0;
            let w = (r * r - x * x).sqrt();
            Ok(Local {
                z: r - w,
                zx: x / w,
                zxx: r * r / (w * w * w),
                ..Local::default()
            })
        }
        fn feature_length_mm(&self) -> f64 {
            f64::INFINITY
        }
        fn describe(&self) -> String {
            "cylinder".into()
        }
    }

    #[test]
    fn a_cylinder_has_one_zero_curvature() {
        let c = Cylinder(20.0);
        for &(x, y) in &[(0.0, 0.0), (12.0, 5.0), (-18.0, -9.0)] {
            let [k1, k2] = c.local(x, y).unwrap().principal_curvatures();
            assert_eq!(k1, 0.0, "({x}, {y})");
            assert!((k2 + 1.0 / 20.0).abs() < 1e-15, "({x}, {y}): {k2}");
            let p = SurfacePower::from_local(&c.local(x, y).unwrap(), 1.5);
            assert!((p.cylinder_d - 25.0).abs() < 1e-12);
            assert!((p.mean_d + 12.5).abs() < 1e-12);
        }
    }

    #[test]
    fn a_saddle_matches_the_classical_mean_and_gaussian_curvature() {
        // z = (x² − y²)/(2a): H₊ = ((1+q²)f_xx − 2pq·f_xy + (1+p²)f_yy)/(2W³) with the +Z
        // normal, K = (f_xx·f_yy − f_xy²)/W⁴; with the −Z normal H = −H₊, κ = H ± √(H² − K)
        // (no cancellation: K < 0).
        let a = 15.0;
        for &(x, y) in &[(0.0, 0.0), (6.0, -11.0), (-20.0, 4.0)] {
            let (p, q) = (x / a, -y / a);
            let w2: f64 = 1.0 + p * p + q * q;
            let w = w2.sqrt();
            let (fxx, fyy) = (1.0 / a, -1.0 / a);
            let h = -((1.0 + q * q) * fxx + (1.0 + p * p) * fyy) / (2.0 * w2 * w);
            let k = fxx * fyy / (w2 * w2);
            let root = (h * h - k).sqrt();
            let l = Local {
                z: (x * x - y * y) / (2.0 * a),
                zx: p,
                zy: q,
                zxx: fxx,
                zxy: 0.0,
                zyy: fyy,
            };
            let [k1, k2] = l.principal_curvatures();
            assert!((k1 - (h + root)).abs() < 1e-15, "({x}, {y}): {k1}");
            assert!((k2 - (h - root)).abs() < 1e-15, "({x}, {y}): {k2}");
        }
    }

    #[test]
    fn principal_curvatures_are_the_extreme_normal_curvatures() {
        // Random-looking slopes up to 1.5 and Hessians with a mixed term. The golden search
        // brackets the extremum to 1e-15 rad; a quadratic extremum then loses ≲ 1e-24 relative,
        // so the comparison is at rounding level (1e-12 of the curvature scale).
        let cases = [
            (0.3, -0.2, 0.02, 0.011, -0.005),
            (1.2, 0.7, -0.04, 0.03, 0.01),
            (-0.4, 1.5, 0.001, -0.002, 0.05),
            (0.0, 0.0, 0.01, 0.0, 0.01),
        ];
        for (zx, zy, zxx, zxy, zyy) in cases {
            let l = Local {
                z: 0.0,
                zx,
                zy,
                zxx,
                zxy,
                zyy,
            };
            let got = l.principal_curvatures();
            let want = extreme_normal_curvatures(&l);
            let scale = got[0].abs().max(got[1].abs());
            for (g, w) in got.iter().zip(want) {
                assert!((g - w).abs() <= 1e-12 * scale, "{l:?}: {got:?} vs {want:?}");
            }
        }
    }

    #[test]
    fn maps_cover_the_disc_and_mark_what_is_outside() {
        // A 10 mm sphere on a part of radius 12: the corners of the square are outside the
        // disc, and the ring 10 < ρ ≤ 12 is inside the part but has no sag.
        let s = Asphere::sphere(-10.0).unwrap();
        let part = PartDisc {
            radius_mm: 12.0,
            x_mm: 1.0,
            y_mm: -2.0,
        };
        let map = PowerMap::sample(&s, part, 1.5, 25).unwrap();
        assert_eq!(map.mean_d.step_mm, 1.0);
        assert_eq!(map.mean_d.position(0, 0), (-11.0, -14.0));
        assert_eq!(map.mean_d.position(24, 24), (13.0, 10.0));
        assert_eq!(map.cylinder_d.position(24, 24), (13.0, 10.0));
        let (mut outside, mut defined, mut undefined) = (0, 0, 0);
        for j in 0..25 {
            for i in 0..25 {
                let (x, y) = map.mean_d.position(i, j);
                let k = j * 25 + i;
                let in_part = (x - 1.0).hypot(y + 2.0) <= 12.0;
                let has_sag = x.hypot(y) < 10.0;
                match (in_part, has_sag) {
                    (false, _) => {
                        assert!(map.mean_d.values[k].is_nan() && map.cylinder_d.values[k].is_nan());
                        outside += 1;
                    }
                    (true, true) => {
                        assert!(
                            (map.mean_d.values[k] - 50.0).abs() < 1e-10,
                            "{}",
                            map.mean_d.values[k]
                        );
                        assert!(map.cylinder_d.values[k].abs() < 1e-10);
                        defined += 1;
                    }
                    (true, false) => {
                        assert!(map.mean_d.values[k].is_nan());
                        undefined += 1;
                    }
                }
            }
        }
        assert_eq!(map.undefined, undefined);
        assert!(outside > 0 && defined > 0 && undefined > 0);
        let (lo, hi) = map.mean_range_d().unwrap();
        assert!((lo - 50.0).abs() < 1e-10 && (hi - 50.0).abs() < 1e-10);
    }

    #[test]
    fn map_arguments_are_checked() {
        let s = Asphere::sphere(-10.0).unwrap();
        let part = PartDisc::centred(5.0);
        assert_eq!(
            PowerMap::sample(&s, part, 0.9, 10).unwrap_err().field,
            "refractive_index"
        );
        assert_eq!(
            PowerMap::sample(&s, part, 1.5, 1).unwrap_err().field,
            "size"
        );
        assert_eq!(
            PowerMap::sample(&s, PartDisc::centred(-1.0), 1.5, 10)
                .unwrap_err()
                .field,
            "part.radius_mm"
        );
    }
}

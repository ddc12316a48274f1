//! A design turned 180° about its Y axis: the frame in which a surface is cut from the side its
//! +Z points away from (DESIGN.md, "The lab's workflow": a lens surface cut from the air side).
//!
//! The rotation takes `(x, y, z)` to `(−x, y, −z)` (the matrix diag(−1, 1, −1), determinant
//! +1: a rotation, never a mirror). A design point `(x, y, f(x, y))` lands at `(−x, y, −f)`,
//! so the turned sag is `g(x, y) = −f(−x, y)`, and by the chain rule
//! `g_x = f_x`, `g_y = −f_y`, `g_xx = −f_xx`, `g_xy = f_xy`, `g_yy = −f_yy`, all at (−x, y).
//! A term odd in x keeps its sign under the turn (`g = a·x³` for `f = a·x³`), where a mirror
//! (`z → −z` alone) would flip it: the freeform is cut as designed, not as its mirror image.
//! A line `(x₀, y₀) + t·(c, s)` is the design's line `(−x₀, y₀) + t·(−c, s)` with the same
//! parameter, so slope kinks carry over unchanged.

use super::{Line, Local, Radial, SectionBounds, Surface, UndefinedError};

/// A surface turned 180° about Y.
#[derive(Debug)]
pub struct Turned {
    inner: Box<dyn Surface>,
}

impl Turned {
    /// `inner` turned 180° about its Y axis.
    pub fn new(inner: Box<dyn Surface>) -> Self {
        Self { inner }
    }

    /// An error of the design at (−x, y) restated at the point asked, (x, y).
    fn at(x: f64, e: UndefinedError) -> UndefinedError {
        UndefinedError { x_mm: x, ..e }
    }
}

impl Surface for Turned {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let l = self.inner.local(-x, y).map_err(|e| Self::at(x, e))?;
        Ok(Local {
            z: -l.z,
            zx: l.zx,
            zy: -l.zy,
            zxx: -l.zxx,
            zxy: l.zxy,
            zyy: -l.zyy,
        })
    }

    fn sag(&self, x: f64, y: f64) -> Result<f64, UndefinedError> {
        Ok(-self.inner.sag(-x, y).map_err(|e| Self::at(x, e))?)
    }

    fn feature_length_mm(&self) -> f64 {
        self.inner.feature_length_mm()
    }

    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        let design = Line {
            x0: -line.x0,
            y0: line.y0,
            c: -line.c,
            s: line.s,
        };
        self.inner.slope_kinks(design, t0, t1, out);
    }

    /// The design's.
    fn keeps_lines(&self) -> bool {
        self.inner.keeps_lines()
    }

    /// The design's section along the mirrored line, turned over.
    fn kept_radial(&self, c: f64, s: f64, rho: f64) -> Option<Result<Radial, UndefinedError>> {
        let r = self.inner.kept_radial(-c, s, rho)?;
        Some(
            r.map(|r| Radial {
                z: -r.z,
                slope: -r.slope,
                curvature_term: -r.curvature_term,
            })
            .map_err(|e| Self::at(rho * c, e)),
        )
    }

    /// The design's along the mirrored line, turned over.
    fn kept_ranges(&self, c: f64, s: f64, ts: &[f64]) -> Option<Vec<[f64; 2]>> {
        let ranges = self.inner.kept_ranges(-c, s, ts)?;
        Some(
            ranges
                .into_iter()
                .map(|[low, high]| [-high, -low])
                .collect(),
        )
    }

    /// The design's at the mirrored point (x → −x keeps distances).
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        self.inner.kink_free_radius(-x, y)
    }

    /// The design's bounds turned over ([`SectionBounds::turned`]): the turned section at θ is
    /// the design's at π − θ negated, `g(t) = −f(−t·cos θ, t·sin θ)`; none where the design has
    /// kinks (its ridges are the turned surface's valleys).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        self.inner.section_bounds(radius_mm)?.turned()
    }

    fn describe(&self) -> String {
        format!(
            "{}; turned 180° about Y (x → −x, z → −z)",
            self.inner.describe()
        )
    }

    fn warnings(&self) -> Vec<String> {
        self.inner.warnings()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::{AsphereSpec, xy_polynomial::XyTerm};
    use crate::surface::{LensArray, LensArraySpec, PartDisc, XyPolynomial, XyPolynomialSpec};

    /// A sphere of radius 40 mm plus `0.002·x³ + 0.001·x·y²` (N = 1 mm): odd in x.
    fn freeform() -> XyPolynomial {
        XyPolynomial::new(&XyPolynomialSpec {
            base: AsphereSpec {
                radius_mm: Some(40.0),
                ..Default::default()
            },
            norm_radius_mm: 1.0,
            terms: vec![
                XyTerm {
                    x: 3,
                    y: 0,
                    coefficient_mm: 0.002,
                },
                XyTerm {
                    x: 1,
                    y: 2,
                    coefficient_mm: 0.001,
                },
            ],
        })
        .unwrap()
    }

    #[test]
    fn an_odd_freeform_is_turned_not_mirrored() {
        let t = Turned::new(Box::new(freeform()));
        let (x, y) = (1.5_f64, -0.7_f64);
        let sphere = |x: f64, y: f64| {
            let s = x * x + y * y;
            s / (40.0 + (1600.0 - s).sqrt())
        };
        // g(x, y) = −f(−x, y): the odd terms keep their sign, the sphere turns over.
        let turned = -sphere(x, y) + 0.002 * x.powi(3) + 0.001 * x * y * y;
        assert!((t.sag(x, y).unwrap() - turned).abs() < 1e-15);
        // A mirror (z → −z alone) would give the odd terms the other sign.
        let mirror = -sphere(x, y) - 0.002 * x.powi(3) - 0.001 * x * y * y;
        assert!((t.sag(x, y).unwrap() - mirror).abs() > 1e-3);
    }

    #[test]
    fn section_bounds_are_the_designs_turned_over_and_ridges_become_valleys() {
        use crate::surface::section_bounds::assert_bounds_hold;
        // A convex and a concave asphere, the odd freeform, a biconic: the turned surface's
        // sections against its bounds (the design's upward curvature becomes its downward).
        let designs: Vec<Box<dyn Surface>> = vec![
            Box::new(crate::surface::Asphere::sphere(40.0).unwrap()),
            Box::new(crate::surface::Asphere::sphere(-25.0).unwrap()),
            Box::new(freeform()),
            Box::new(
                crate::surface::Biconic::new(
                    &crate::surface::BiconicSpec {
                        radius_x_mm: Some(30.0),
                        radius_y_mm: Some(-45.0),
                        conic_x: -0.5,
                        ..Default::default()
                    },
                    PartDisc::centred(4.0),
                )
                .unwrap(),
            ),
        ];
        for design in designs {
            let b = design.section_bounds(4.0).unwrap();
            let turned = Turned::new(design);
            let (t, ..) = assert_bounds_hold(&turned, 4.0, 36, 4000);
            assert_eq!(
                (t.max_curvature, t.min_curvature),
                (-b.min_curvature, -b.max_curvature)
            );
        }
        // Concave lenslets' rims are ridges: turned over they are valleys.
        let array = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(3.0)).unwrap();
        assert!(array.section_bounds(3.0).unwrap().has_ridges);
        let turned = Turned::new(Box::new(array)).section_bounds(3.0).unwrap();
        assert!(turned.has_valleys && !turned.has_ridges);
    }

    #[test]
    fn derivatives_match_central_differences() {
        let t = Turned::new(Box::new(freeform()));
        let h = 1e-5;
        for (x, y) in [(1.5, -0.7), (-2.0, 1.1), (0.3, 2.4)] {
            let l = t.local(x, y).unwrap();
            let f = |x: f64, y: f64| t.local(x, y).unwrap();
            let (px, mx, py, my) = (f(x + h, y), f(x - h, y), f(x, y + h), f(x, y - h));
            let close = |a: f64, b: f64, what: &str| {
                assert!((a - b).abs() < 1e-8 * (1.0 + b.abs()), "{what}: {a} vs {b}");
            };
            close(l.zx, (px.z - mx.z) / (2.0 * h), "zx");
            close(l.zy, (py.z - my.z) / (2.0 * h), "zy");
            close(l.zxx, (px.zx - mx.zx) / (2.0 * h), "zxx");
            close(l.zxy, (py.zx - my.zx) / (2.0 * h), "zxy");
            close(l.zyy, (py.zy - my.zy) / (2.0 * h), "zyy");
            assert_eq!(l.z, t.sag(x, y).unwrap());
        }
    }

    #[test]
    fn kinks_and_errors_are_restated_in_the_turned_frame() {
        let array = LensArray::new(&LensArraySpec::paper004(), PartDisc::centred(3.0)).unwrap();
        let line = Line {
            x0: 0.2,
            y0: 0.1,
            c: 0.6,
            s: 0.8,
        };
        let design_line = Line {
            x0: -0.2,
            y0: 0.1,
            c: -0.6,
            s: 0.8,
        };
        let (mut a, mut b) = (Vec::new(), Vec::new());
        array.slope_kinks(design_line, -2.0, 2.0, &mut a);
        let t = Turned::new(Box::new(array));
        t.slope_kinks(line, -2.0, 2.0, &mut b);
        assert!(!a.is_empty());
        assert_eq!(a, b);
        let sphere = Turned::new(Box::new(crate::surface::Asphere::sphere(5.0).unwrap()));
        let e = sphere.local(6.0, 0.0).unwrap_err();
        assert_eq!((e.x_mm, e.y_mm), (6.0, 0.0));
        assert!(
            sphere
                .describe()
                .ends_with("turned 180° about Y (x → −x, z → −z)")
        );
    }
}

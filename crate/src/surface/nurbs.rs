//! NURBS surface from a control net given in the job: a tensor-product rational B-spline patch
//! `S(u, v) = (x, y, z)` (Piegl & Tiller, "The NURBS Book", 2nd ed., eq 4.15), turned into the
//! height field `z(x, y)` the planner needs.
//!
//! - Evaluation (`patch.rs`, `basis.rs`): the basis functions by A2.2 and their derivatives by
//!   eq 2.7 (the recursion of A2.3), the homogeneous surface derivatives by A3.6 and the
//!   rational ones by A4.4, exactly, to second order.
//! - Inversion (`inverse.rs`): for a part point (x, y), the parameters (u, v) with
//!   `S_x = x, S_y = y`, by Newton's method on the 2 × 2 system from the nearest sample of a
//!   coarse (u, v) grid, with backtracking and clamping to the domain, to an XY residual of
//!   1e-14 of the face's size.
//! - Height field (`height.rs`): `z = S_z(u, v)`, and with `J = ∂(S_x, S_y)/∂(u, v)` the chain
//!   rule `[z_x, z_y] = [S_z,u, S_z,v]·J⁻¹`; differentiating `S_z,u = z_x·S_x,u + z_y·S_y,u` (and
//!   its v twin) once more gives `∇²_uv S_z = Jᵀ·H·J + z_x·∇²_uv S_x + z_y·∇²_uv S_y`, so the
//!   Hessian is `H = J⁻ᵀ·(∇²_uv S_z − z_x·∇²_uv S_x − z_y·∇²_uv S_y)·J⁻¹` (the same as
//!   differentiating the inverse Jacobian, `∂(J⁻¹)/∂x = −J⁻¹·(∂J/∂x)·J⁻¹`): exact, no
//!   differencing.
//! - Bounds (`bounds.rs`): the height field's slope and the Hessian's eigenvalues over a disc,
//!   from the Bézier nets of small pieces of the knot cells in interval arithmetic (the
//!   derivative nets' convex hulls through the same chain rule), for the one-way
//!   compensation's concave shortcut ([`Surface::section_bounds`], [`Surface::disc_bounds`]).
//!
//! The face must project one-to-one onto the XY plane: `det J` keeps one sign, away from zero
//! (above 1e-9 of its largest value), over the whole face (checked on the grid when the surface
//! is built and at every query), so that the sag is single valued; a face with a pole (a row of
//! coincident control points, as a revolved surface has on its axis) is refused for the same
//! reason. It must cover the part disc (checked on a polar grid of the part, `coverage.rs`)
//! unless `allow_uncovered` is set, in which case points outside it are undefined. Knots of
//! multiplicity above p − 1 inside the domain would let the slope jump along a curved knot line
//! and are refused. The optical axis is +Z and sag is measured from the vertex plane z = 0: the
//! net is given in those coordinates.

pub(crate) mod basis;
mod bounds;
mod coverage;
mod height;
mod interval;
mod inverse;
mod patch;

pub use basis::MAX_DEGREE;

use super::{Local, PartDisc, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite};
use inverse::{Fold, Inverse, Miss};
use patch::Patch;
use serde::{Deserialize, Serialize};

/// The most control points a net may have.
pub const MAX_POINTS: usize = 1_000_000;

/// Job entry of a NURBS surface (JSON type `"nurbs"`).
///
/// Control point `control_points[i][j]` multiplies `N_{i,p}(u)·N_{j,q}(v)`: rows run along u,
/// the points of a row along v.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NurbsSpec {
    /// Degree p along u, 1 … 15.
    pub degree_u: u32,
    /// Degree q along v, 1 … 15.
    pub degree_v: u32,
    /// Knot vector U along u: n + p + 1 non-decreasing numbers for n rows, clamped (end knots
    /// repeated p + 1 times) or not; the domain is `[U[p], U[n]]`. A knot strictly inside the
    /// domain may repeat at most p − 1 times (the slope must stay continuous).
    pub knots_u: Vec<f64>,
    /// Knot vector V along v: m + q + 1 numbers for m points per row; as `knots_u`.
    pub knots_v: Vec<f64>,
    /// Control points `[x, y, z]`, mm: n ≥ p + 1 rows of m ≥ q + 1 points each (at most
    /// 1 000 000 in all), in part coordinates (+Z the optical axis, towards the tool).
    pub control_points: Vec<Vec<[f64; 3]>>,
    /// Weights, > 0, in the shape of `control_points`; default all 1 (a polynomial B-spline).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub weights: Option<Vec<Vec<f64>>>,
    /// Accept a face that does not cover the whole part disc; points outside it are then
    /// undefined (an error when the planner reaches them). Default false: such a face is
    /// refused when the surface is built, naming the first uncovered point.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub allow_uncovered: bool,
}

/// A NURBS height field, validated: the patch, its XY inversion and its feature length.
#[derive(Debug, Clone)]
pub struct Nurbs {
    patch: Patch,
    inverse: Inverse,
    family: &'static str,
    rows: usize,
    cols: usize,
    feature: f64,
}

impl Nurbs {
    /// Checks a spec and builds the surface for the part disc `part`.
    pub fn new(spec: &NurbsSpec, part: PartDisc) -> Result<Self, FieldError> {
        Self::build(spec, part, "NURBS surface")
    }

    /// As [`Nurbs::new`], with the family name its errors give (`STEP face` for an import).
    pub(crate) fn build(
        spec: &NurbsSpec,
        part: PartDisc,
        family: &'static str,
    ) -> Result<Self, FieldError> {
        let (p, q) = (
            degree("degree_u", spec.degree_u)?,
            degree("degree_v", spec.degree_v)?,
        );
        let (rows, cols) = shape(spec, p, q)?;
        let points = points(spec)?;
        let weights = weights(spec, rows, cols)?;
        let u = basis::KnotVector::new("knots_u", p, rows, &spec.knots_u)?;
        let v = basis::KnotVector::new("knots_v", q, cols, &spec.knots_v)?;
        let patch = Patch::new(u, v, &points, &weights);
        let inverse = Inverse::new(&patch).map_err(|f| fold_error(rows, cols, f))?;
        let feature = inverse.shortest_span() / p.max(q) as f64;
        let nurbs = Self {
            patch,
            inverse,
            family,
            rows,
            cols,
            feature,
        };
        if !spec.allow_uncovered {
            nurbs.check_coverage(part)?;
        }
        Ok(nurbs)
    }

    /// The point S(u, v), mm (parameters clamped to the domain).
    pub fn point(&self, u: f64, v: f64) -> [f64; 3] {
        self.patch.eval(u, v, 0).s
    }

    /// The parameter domain `[u_min, u_max, v_min, v_max]`.
    pub fn domain(&self) -> [f64; 4] {
        self.patch.domain()
    }

    /// The XY extent of the face, `[x_min, x_max, y_min, y_max]` in mm, as sampled on the
    /// inversion grid (the face may bulge slightly beyond it between samples).
    pub fn extent(&self) -> [f64; 4] {
        self.inverse.extent()
    }

    /// The parameters (u, v) of the face point above (x, y).
    pub fn parameters(&self, x: f64, y: f64) -> Result<(f64, f64), UndefinedError> {
        self.solve(x, y)
            .map(|(u, v, _)| (u, v))
            .map_err(|m| self.undefined(x, y, m.reason()))
    }

    fn solve(&self, x: f64, y: f64) -> Result<(f64, f64, patch::Derivs), Miss> {
        self.inverse.solve(&self.patch, x, y)
    }

    fn check_coverage(&self, part: PartDisc) -> Result<(), FieldError> {
        let Some(gap) = coverage::first_gap(part, |x, y| self.solve(x, y).map(|_| ())) else {
            return Ok(());
        };
        let [x0, x1, y0, y1] = self.extent();
        Err(FieldError::new(
            "control_points",
            format!(
                "a {} × {} net spanning x in [{x0:.4}, {x1:.4}] mm, y in [{y0:.4}, {y1:.4}] mm",
                self.rows, self.cols
            ),
            format!(
                "does not cover the part (radius {} mm about ({}, {}) mm): first uncovered at \
                 radius {:.4} mm, angle {:.2}° (x {:.4} mm, y {:.4} mm): {}; extend the face \
                 or set allow_uncovered: true",
                part.radius_mm,
                part.x_mm,
                part.y_mm,
                gap.radius,
                gap.angle_deg,
                gap.x,
                gap.y,
                gap.miss.reason()
            ),
        ))
    }

    fn undefined(&self, x: f64, y: f64, reason: String) -> UndefinedError {
        UndefinedError {
            surface: self.family,
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        }
    }
}

impl Surface for Nurbs {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        if !(x.is_finite() && y.is_finite()) {
            return Err(self.undefined(x, y, "the point is not finite".into()));
        }
        let (_, _, d) = self
            .solve(x, y)
            .map_err(|m| self.undefined(x, y, m.reason()))?;
        Ok(height::height(&d))
    }

    fn feature_length_mm(&self) -> f64 {
        self.feature
    }

    /// From the control net, cell by cell (`bounds.rs`); they hold on every line.
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        bounds::disc_bounds(&self.patch, radius_mm)
    }

    fn disc_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        bounds::disc_bounds(&self.patch, radius_mm)
    }

    fn describe(&self) -> String {
        let [x0, x1, y0, y1] = self.extent();
        format!(
            "{} degree {} × {}, {} × {} control points ({}), x in [{x0:.4}, {x1:.4}] mm, \
             y in [{y0:.4}, {y1:.4}] mm",
            self.family,
            self.patch.knots_u().degree(),
            self.patch.knots_v().degree(),
            self.rows,
            self.cols,
            if self.patch.rational() {
                "rational"
            } else {
                "polynomial B-spline"
            }
        )
    }
}

fn degree(field: &str, d: u32) -> Result<usize, FieldError> {
    if (1..=MAX_DEGREE as u32).contains(&d) {
        Ok(d as usize)
    } else {
        Err(FieldError::new(
            field,
            d,
            format!("must be an integer in [1, {MAX_DEGREE}]"),
        ))
    }
}

/// Rows n and points per row m: n ≥ p + 1, m ≥ q + 1, every row alike, n·m ≤ MAX_POINTS.
fn shape(spec: &NurbsSpec, p: usize, q: usize) -> Result<(usize, usize), FieldError> {
    let rows = spec.control_points.len();
    if rows < p + 1 {
        return Err(FieldError::new(
            "control_points",
            format!("{rows} rows"),
            format!("degree_u {p} needs at least p + 1 = {} rows", p + 1),
        ));
    }
    let cols = spec.control_points[0].len();
    for (i, row) in spec.control_points.iter().enumerate() {
        if row.len() != cols {
            return Err(FieldError::new(
                format!("control_points[{i}]"),
                format!("{} points", row.len()),
                format!("every row needs as many points as row 0 ({cols})"),
            ));
        }
    }
    if cols < q + 1 {
        return Err(FieldError::new(
            "control_points[0]",
            format!("{cols} points"),
            format!(
                "degree_v {q} needs at least q + 1 = {} points per row",
                q + 1
            ),
        ));
    }
    if rows.saturating_mul(cols) > MAX_POINTS {
        return Err(FieldError::new(
            "control_points",
            format!("{rows} × {cols} points"),
            format!("at most {MAX_POINTS} control points"),
        ));
    }
    Ok((rows, cols))
}

fn points(spec: &NurbsSpec) -> Result<Vec<[f64; 3]>, FieldError> {
    let mut out = Vec::new();
    for (i, row) in spec.control_points.iter().enumerate() {
        for (j, point) in row.iter().enumerate() {
            for (c, &value) in point.iter().enumerate() {
                finite(&format!("control_points[{i}][{j}][{c}]"), value)?;
            }
            out.push(*point);
        }
    }
    Ok(out)
}

fn weights(spec: &NurbsSpec, rows: usize, cols: usize) -> Result<Vec<f64>, FieldError> {
    let Some(weights) = &spec.weights else {
        return Ok(vec![1.0; rows * cols]);
    };
    if weights.len() != rows {
        return Err(FieldError::new(
            "weights",
            format!("{} rows", weights.len()),
            format!("the shape of control_points: {rows} rows of {cols}"),
        ));
    }
    let mut out = Vec::with_capacity(rows * cols);
    for (i, row) in weights.iter().enumerate() {
        if row.len() != cols {
            return Err(FieldError::new(
                format!("weights[{i}]"),
                format!("{} weights", row.len()),
                format!("the shape of control_points: {cols} per row"),
            ));
        }
        for (j, &w) in row.iter().enumerate() {
            if !(w.is_finite() && w > 0.0) {
                return Err(FieldError::new(
                    format!("weights[{i}][{j}]"),
                    w,
                    "must be a finite number > 0",
                ));
            }
            out.push(w);
        }
    }
    Ok(out)
}

fn fold_error(rows: usize, cols: usize, f: Fold) -> FieldError {
    FieldError::new(
        "control_points",
        format!("a {rows} × {cols} net"),
        format!(
            "the face's projection onto XY folds or degenerates at (u, v) = ({}, {}), near \
             (x, y) = ({:.4}, {:.4}) mm (det ∂(x, y)/∂(u, v) = {:e} changes sign or vanishes): \
             the sag would not be single valued",
            f.u, f.v, f.x, f.y, f.det
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bilinear plane z = 0.1x − 0.2y + 0.3 over [−2, 2]².
    fn plane() -> NurbsSpec {
        let z = |x: f64, y: f64| 0.1 * x - 0.2 * y + 0.3;
        NurbsSpec {
            degree_u: 1,
            degree_v: 1,
            knots_u: vec![0.0, 0.0, 1.0, 1.0],
            knots_v: vec![0.0, 0.0, 1.0, 1.0],
            control_points: vec![
                vec![[-2.0, -2.0, z(-2.0, -2.0)], [-2.0, 2.0, z(-2.0, 2.0)]],
                vec![[2.0, -2.0, z(2.0, -2.0)], [2.0, 2.0, z(2.0, 2.0)]],
            ],
            weights: None,
            allow_uncovered: false,
        }
    }

    #[test]
    fn a_bilinear_plane_is_exact() {
        let s = Nurbs::new(&plane(), PartDisc::centred(1.9)).unwrap();
        let l = s.local(0.7, -1.1).unwrap();
        assert!((l.z - (0.07 + 0.22 + 0.3)).abs() < 1e-15);
        assert!((l.zx - 0.1).abs() < 1e-15 && (l.zy + 0.2).abs() < 1e-15);
        // A bilinear patch has Z_uv = 0 only up to rounding.
        assert!(
            l.zxx.abs() < 1e-15 && l.zxy.abs() < 1e-15 && l.zyy.abs() < 1e-15,
            "{l:?}"
        );
        assert!(s.describe().contains("degree 1 × 1"), "{}", s.describe());
    }

    #[test]
    fn shape_and_value_errors_name_the_field() {
        let mut bad = plane();
        bad.degree_u = 0;
        assert_eq!(
            Nurbs::new(&bad, PartDisc::centred(1.0)).unwrap_err().field,
            "degree_u"
        );
        let mut bad = plane();
        bad.control_points[1].pop();
        let e = Nurbs::new(&bad, PartDisc::centred(1.0)).unwrap_err();
        assert_eq!(e.field, "control_points[1]");
        let mut bad = plane();
        bad.control_points[0][1][2] = f64::INFINITY;
        let e = Nurbs::new(&bad, PartDisc::centred(1.0)).unwrap_err();
        assert_eq!(e.field, "control_points[0][1][2]");
        let mut bad = plane();
        bad.weights = Some(vec![vec![1.0, 1.0], vec![1.0, 0.0]]);
        let e = Nurbs::new(&bad, PartDisc::centred(1.0)).unwrap_err();
        assert_eq!(e.field, "weights[1][1]");
        let mut bad = plane();
        bad.knots_v = vec![0.0, 0.0, 1.0];
        let e = Nurbs::new(&bad, PartDisc::centred(1.0)).unwrap_err();
        assert_eq!(e.field, "knots_v");
    }

    #[test]
    fn a_part_larger_than_the_face_is_refused_unless_allowed() {
        let e = Nurbs::new(&plane(), PartDisc::centred(2.5)).unwrap_err();
        assert_eq!(e.field, "control_points");
        assert!(e.allowed.contains("does not cover the part"), "{e}");
        // The square's half width is 2: the first probe outside is on the +x spoke.
        assert!(e.allowed.contains("angle 0.00°"), "{e}");
        let mut ok = plane();
        ok.allow_uncovered = true;
        let s = Nurbs::new(&ok, PartDisc::centred(2.5)).unwrap();
        let err = s.local(2.2, 0.0).unwrap_err();
        assert!(
            err.to_string().contains("does not cover this point"),
            "{err}"
        );
        assert_eq!(err.radius_mm, 2.2);
    }
}

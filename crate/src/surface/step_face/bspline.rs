//! B-spline surfaces of a STEP file (ISO 10303-42 geometry as AP203/AP214 files write it) read
//! into a NURBS net:
//!
//! - `B_SPLINE_SURFACE_WITH_KNOTS(name, u_degree, v_degree, ((#p, …), …), form, u_closed,
//!   v_closed, self_intersect, (u multiplicities), (v multiplicities), (u knots), (v knots),
//!   knot_type)`, a polynomial B-spline;
//! - the complex instance `(BOUNDED_SURFACE() B_SPLINE_SURFACE(u_degree, v_degree, points, form,
//!   u_closed, v_closed, self_intersect) B_SPLINE_SURFACE_WITH_KNOTS(u mults, v mults, u knots,
//!   v knots, knot_type) GEOMETRIC_REPRESENTATION_ITEM() RATIONAL_B_SPLINE_SURFACE(((w, …), …))
//!   REPRESENTATION_ITEM(name) SURFACE())`, a rational one (or, without the RATIONAL part, a
//!   polynomial one written as a complex instance).
//!
//! Control points are `CARTESIAN_POINT(name, (x, y, z))`; `control_points[i][j]` runs along u
//! with i, as in the job's `nurbs` surface. Knots are expanded by their multiplicities. The
//! closed and self-intersect flags and the knot type are not needed to evaluate the surface and
//! are ignored; trimming (the face's bounds) is not read.

use super::part21::{Exchange, Instance, Param};
use crate::surface::NurbsSpec;

/// The B-spline surfaces of the file, in file order.
pub fn candidates(ex: &Exchange) -> Vec<&Instance> {
    ex.instances
        .iter()
        .filter(|i| i.record("B_SPLINE_SURFACE_WITH_KNOTS").is_some())
        .collect()
}

/// The other surfaces of the file (`PLANE #3`), for the message when there is no B-spline.
pub fn other_surfaces(ex: &Exchange) -> Vec<String> {
    ex.instances
        .iter()
        .filter(|i| {
            i.records
                .iter()
                .any(|r| r.name == "PLANE" || r.name.ends_with("_SURFACE"))
        })
        .map(|i| format!("{} #{}", i.names(), i.id))
        .collect()
}

/// A short description: `#12 'name' (line 30, degree 3 × 3, 7 × 7 points, rational)`.
pub fn summary(instance: &Instance) -> String {
    let parts = Parts::of(instance).ok();
    let name = parts.as_ref().map(|p| p.name.as_str()).unwrap_or("");
    let shape = parts
        .as_ref()
        .map(|p| {
            let deg = |k: usize| p.head[k].count().map_or("?".into(), |d| d.to_string());
            let rows = p.head[2].list().map_or(0, |l| l.len());
            let cols = p.head[2]
                .list()
                .and_then(|l| l.first())
                .and_then(Param::list)
                .map_or(0, |l| l.len());
            let kind = if p.weights.is_some() {
                "rational"
            } else {
                "polynomial"
            };
            format!(
                ", degree {} × {}, {rows} × {cols} points, {kind}",
                deg(0),
                deg(1)
            )
        })
        .unwrap_or_default();
    format!("#{} '{name}' (line {}{shape})", instance.id, instance.line)
}

/// The net of the surface `instance`, coordinates times `scale` (mm per file unit).
pub fn read(ex: &Exchange, instance: &Instance, scale: f64) -> Result<NurbsSpec, String> {
    let parts = Parts::of(instance)?;
    let at = |what: String| format!("#{} {}: {what}", instance.id, instance.names());
    let degree = |k: usize, dir: &str| {
        parts.head[k]
            .count()
            .and_then(|d| u32::try_from(d).ok())
            .ok_or_else(|| at(format!("the {dir} degree must be a whole number")))
    };
    let (degree_u, degree_v) = (degree(0, "u")?, degree(1, "v")?);
    let control_points = points(ex, &parts.head[2], scale).map_err(&at)?;
    let rows = control_points.len();
    let cols = control_points.first().map_or(0, Vec::len);
    let knots_u = knots(&parts.knots[0], &parts.knots[2], rows, degree_u, "u").map_err(&at)?;
    let knots_v = knots(&parts.knots[1], &parts.knots[3], cols, degree_v, "v").map_err(&at)?;
    let weights = match parts.weights {
        Some(w) => Some(weights(w, rows, cols).map_err(&at)?),
        None => None,
    };
    Ok(NurbsSpec {
        degree_u,
        degree_v,
        knots_u,
        knots_v,
        control_points,
        weights,
        allow_uncovered: false,
    })
}

/// The parameters of a surface instance, simple or complex.
struct Parts<'a> {
    name: String,
    /// u_degree, v_degree, control points, form, u_closed, v_closed, self_intersect.
    head: &'a [Param],
    /// u multiplicities, v multiplicities, u knots, v knots, knot type.
    knots: &'a [Param],
    weights: Option<&'a Param>,
}

impl<'a> Parts<'a> {
    fn of(instance: &'a Instance) -> Result<Self, String> {
        let with_knots = instance
            .record("B_SPLINE_SURFACE_WITH_KNOTS")
            .ok_or_else(|| format!("#{} is not a B_SPLINE_SURFACE_WITH_KNOTS", instance.id))?;
        let count_error = |record: &str, got: usize, want: usize| {
            format!(
                "#{} {}: {record} has {got} parameters, expected {want}",
                instance.id,
                instance.names()
            )
        };
        if instance.records.len() == 1 {
            let p = &with_knots.params;
            if p.len() != 13 {
                return Err(count_error("B_SPLINE_SURFACE_WITH_KNOTS", p.len(), 13));
            }
            return Ok(Self {
                name: p[0].string().unwrap_or("").to_string(),
                head: &p[1..8],
                knots: &p[8..13],
                weights: None,
            });
        }
        let head = instance.record("B_SPLINE_SURFACE").ok_or_else(|| {
            format!(
                "#{}: the complex instance has no B_SPLINE_SURFACE",
                instance.id
            )
        })?;
        if head.params.len() != 7 {
            return Err(count_error("B_SPLINE_SURFACE", head.params.len(), 7));
        }
        if with_knots.params.len() != 5 {
            return Err(count_error(
                "B_SPLINE_SURFACE_WITH_KNOTS",
                with_knots.params.len(),
                5,
            ));
        }
        let weights = match instance.record("RATIONAL_B_SPLINE_SURFACE") {
            Some(r) if r.params.len() == 1 => Some(&r.params[0]),
            Some(r) => return Err(count_error("RATIONAL_B_SPLINE_SURFACE", r.params.len(), 1)),
            None => None,
        };
        let name = instance
            .record("REPRESENTATION_ITEM")
            .and_then(|r| r.params.first())
            .and_then(Param::string)
            .unwrap_or("")
            .to_string();
        Ok(Self {
            name,
            head: &head.params,
            knots: &with_knots.params,
            weights,
        })
    }
}

/// The control net: a list of rows of `#CARTESIAN_POINT` references.
fn points(ex: &Exchange, list: &Param, scale: f64) -> Result<Vec<Vec<[f64; 3]>>, String> {
    let rows = list
        .list()
        .ok_or("the control points must be a list of lists of #points")?;
    rows.iter()
        .enumerate()
        .map(|(i, row)| {
            let row = row
                .list()
                .ok_or_else(|| format!("control point row {i} is not a list"))?;
            row.iter()
                .enumerate()
                .map(|(j, p)| {
                    point(ex, p, scale).map_err(|e| format!("control point [{i}][{j}]: {e}"))
                })
                .collect()
        })
        .collect()
}

fn point(ex: &Exchange, p: &Param, scale: f64) -> Result<[f64; 3], String> {
    let id = p
        .reference()
        .ok_or("expected a #reference to a CARTESIAN_POINT")?;
    let instance = ex
        .get(id)
        .ok_or_else(|| format!("#{id} is not in the file"))?;
    let record = instance
        .record("CARTESIAN_POINT")
        .ok_or_else(|| format!("#{id} is a {}, not a CARTESIAN_POINT", instance.names()))?;
    let coords = record
        .params
        .get(1)
        .and_then(Param::list)
        .ok_or_else(|| format!("#{id} CARTESIAN_POINT has no coordinate list"))?;
    if coords.len() != 3 {
        return Err(format!(
            "#{id} CARTESIAN_POINT has {} coordinates, expected 3",
            coords.len()
        ));
    }
    let mut out = [0.0; 3];
    for (o, c) in out.iter_mut().zip(coords) {
        *o = c.number().filter(|v| v.is_finite()).ok_or_else(|| {
            format!("#{id} CARTESIAN_POINT has a coordinate that is not a number")
        })? * scale;
    }
    Ok(out)
}

/// The knot vector from distinct knots and their multiplicities; their sum must be
/// `count + degree + 1`.
fn knots(
    mults: &Param,
    values: &Param,
    count: usize,
    degree: u32,
    dir: &str,
) -> Result<Vec<f64>, String> {
    let (Some(mults), Some(values)) = (mults.list(), values.list()) else {
        return Err(format!("the {dir} multiplicities and knots must be lists"));
    };
    if mults.len() != values.len() {
        return Err(format!(
            "{} {dir} multiplicities for {} {dir} knots",
            mults.len(),
            values.len()
        ));
    }
    let mut out = Vec::new();
    for (k, (m, v)) in mults.iter().zip(values).enumerate() {
        let m = m
            .count()
            .filter(|&m| (1..=64).contains(&m))
            .ok_or_else(|| format!("{dir} multiplicity {k} must be a whole number in [1, 64]"))?;
        let v = v
            .number()
            .ok_or_else(|| format!("{dir} knot {k} is not a number"))?;
        out.extend(std::iter::repeat_n(v, m));
    }
    let wanted = count + degree as usize + 1;
    if out.len() != wanted {
        return Err(format!(
            "the {dir} multiplicities add up to {}, but {count} control points of degree {degree} \
             need {count} + {degree} + 1 = {wanted}",
            out.len()
        ));
    }
    Ok(out)
}

fn weights(list: &Param, rows: usize, cols: usize) -> Result<Vec<Vec<f64>>, String> {
    let rows_list = list.list().ok_or("the weights must be a list of lists")?;
    if rows_list.len() != rows {
        return Err(format!(
            "{} rows of weights for {rows} rows of control points",
            rows_list.len()
        ));
    }
    rows_list
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let row = row
                .list()
                .filter(|r| r.len() == cols)
                .ok_or_else(|| format!("weight row {i} must list {cols} numbers"))?;
            row.iter()
                .enumerate()
                .map(|(j, w)| {
                    w.number()
                        .ok_or_else(|| format!("weight [{i}][{j}] is not a number"))
                })
                .collect()
        })
        .collect()
}

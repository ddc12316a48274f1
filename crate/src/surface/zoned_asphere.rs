//! Zoned (multi-zone) asphere: concentric zones about one axis, each an even asphere of its own
//! (radius, conic, A4 … A20, [`super::asphere`]) measured from the common vertex plane, plus an
//! optional piston offset, zone k covering `r_{k−1} < r ≤ r_k` of its outer radius r_k (the
//! first from the axis, the last to its outer radius or without limit):
//! `z(r) = asphere_k(r) + offset_k`.
//!
//! **Continuity.** At each boundary r_b between zones k and k + 1 the step
//! `Δz = z_{k+1}(r_b) − z_k(r_b)` and the slope jump `Δz′ = z′_{k+1}(r_b) − z′_k(r_b)` (radial
//! slopes, rad) are computed when the surface is built and stated in [`Surface::describe`];
//! above [`STEP_WARNING_MM`] (1 nm) or [`SLOPE_WARNING`] (1 µrad) they are a warning in the
//! plan's report ([`Surface::warnings`]): a step cannot be cut by a round nose, and at a concave
//! slope jump the nose leaves a fillet of its own radius (the report's concave zones measure it).
//! Wherever the value or the slope differs at all, the boundary circle is a slope kink of every
//! section that crosses it ([`Surface::slope_kinks`]), so the compensation samples both sides.
//!
//! Each zone's conic must stay defined over its zone (its rim outside its outer radius), checked
//! when the surface is built.

use super::{Asphere, AsphereSpec, Line, Local, SectionBounds, Surface, UndefinedError};
use crate::field::{FieldError, finite, positive};
use serde::{Deserialize, Serialize};

/// The most zones.
pub const MAX_ZONES: usize = 100;
/// A step at a boundary above this is a warning, mm (1 nm).
pub const STEP_WARNING_MM: f64 = 1e-6;
/// A slope jump at a boundary above this is a warning, rad (1 µrad).
pub const SLOPE_WARNING: f64 = 1e-6;
/// The largest step at a boundary that still gives section bounds, mm (0.1 pm: offsets written
/// to the rounding of their digits; the nose height's maximum is then found to within it).
pub const MAX_BOUNDED_STEP_MM: f64 = 1e-13;

/// One zone: its outer radius and its asphere. Give exactly one of `radius_mm` and
/// `curvature_per_mm`.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZoneSpec {
    /// Outer radius of the zone, mm, > 0, larger than the previous zone's; required for every
    /// zone but the last, whose absence means the zone extends without limit.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub outer_radius_mm: Option<f64>,
    /// Vertex radius of curvature of the zone's asphere, mm, non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius_mm: Option<f64>,
    /// Its vertex curvature, 1/mm; 0 for a plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub curvature_per_mm: Option<f64>,
    /// Its conic constant; default 0.
    #[serde(default)]
    pub conic: f64,
    /// Its A4 … A20, mm^(1−2i); at most 9, default none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub coefficients: Vec<f64>,
    /// A piston added to the zone's sag, mm; default 0.
    #[serde(default)]
    pub offset_mm: f64,
}

/// Job entry of a zoned asphere: the zones from the axis outwards.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ZonedAsphereSpec {
    /// At least one zone, at most 100, by increasing outer radius.
    pub zones: Vec<ZoneSpec>,
}

/// The continuity of the sag at one boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Boundary {
    /// Radius of the boundary, mm.
    pub radius_mm: f64,
    /// Outer zone's sag minus inner zone's, mm.
    pub step_mm: f64,
    /// Outer zone's radial slope minus inner zone's, rad.
    pub slope_jump: f64,
}

impl Boundary {
    /// Whether the value or the slope differs at all (a kink for the samplers).
    fn is_kink(&self) -> bool {
        self.step_mm != 0.0 || self.slope_jump != 0.0
    }

    /// Whether it exceeds the warning thresholds.
    fn is_warning(&self) -> bool {
        self.step_mm.abs() > STEP_WARNING_MM || self.slope_jump.abs() > SLOPE_WARNING
    }
}

/// One zone, validated.
#[derive(Debug, Clone, PartialEq)]
struct Zone {
    asphere: Asphere,
    offset: f64,
}

/// A zoned asphere, validated.
#[derive(Debug, Clone, PartialEq)]
pub struct ZonedAsphere {
    zones: Vec<Zone>,
    /// Outer radii of every zone but the last; the last's, if bounded.
    outer: Vec<f64>,
    last_outer: Option<f64>,
    boundaries: Vec<Boundary>,
}

/// The outer radius of zone `k` of `n`, checked against the previous one.
fn outer_radius(
    k: usize,
    n: usize,
    z: &ZoneSpec,
    previous: f64,
) -> Result<Option<f64>, FieldError> {
    let field = format!("zones[{k}].outer_radius_mm");
    let Some(r) = z.outer_radius_mm else {
        if k + 1 < n {
            return Err(FieldError::new(
                field,
                "missing",
                "every zone but the last needs its outer radius",
            ));
        }
        return Ok(None);
    };
    positive(&field, r)?;
    if r <= previous {
        return Err(FieldError::new(
            field,
            r,
            format!("must exceed the previous zone's outer radius {previous} mm"),
        ));
    }
    Ok(Some(r))
}

/// A zone's asphere, checked to be defined out to `reach` (its outer radius).
fn zone(k: usize, z: &ZoneSpec, reach: Option<f64>) -> Result<Zone, FieldError> {
    let asphere = Asphere::new(&AsphereSpec {
        radius_mm: z.radius_mm,
        curvature_per_mm: z.curvature_per_mm,
        conic: z.conic,
        coefficients: z.coefficients.clone(),
    })
    .map_err(|e| e.within(&format!("zones[{k}]")))?;
    if let (Some(rim), Some(r)) = (asphere.rim_radius_mm(), reach)
        && rim <= r
    {
        return Err(FieldError::new(
            format!("zones[{k}].conic"),
            z.conic,
            format!(
                "the zone's conic turns vertical at radius {rim} mm, inside its outer radius {r} mm"
            ),
        ));
    }
    let offset = finite(&format!("zones[{k}].offset_mm"), z.offset_mm)?;
    Ok(Zone { asphere, offset })
}

impl Zone {
    /// Sag and radial slope at radius r.
    fn profile(&self, r: f64) -> (f64, f64) {
        match self.asphere.in_s(r * r) {
            Ok([z, zs, _]) => (z + self.offset, 2.0 * r * zs),
            Err(_) => (f64::NAN, f64::NAN),
        }
    }
}

impl ZonedAsphere {
    /// Checks a spec and builds the surface, with the continuity at every boundary.
    pub fn new(spec: &ZonedAsphereSpec) -> Result<Self, FieldError> {
        let n = spec.zones.len();
        if n == 0 || n > MAX_ZONES {
            return Err(FieldError::new(
                "zones",
                format!("{n} zones"),
                format!("between 1 and {MAX_ZONES} zones"),
            ));
        }
        let (mut zones, mut outer, mut last_outer) = (Vec::new(), Vec::new(), None);
        let mut previous = 0.0;
        for (k, z) in spec.zones.iter().enumerate() {
            let r = outer_radius(k, n, z, previous)?;
            zones.push(zone(k, z, r)?);
            match r {
                Some(r) if k + 1 < n => outer.push(r),
                r => last_outer = r,
            }
            previous = r.unwrap_or(previous);
        }
        let boundaries = outer
            .iter()
            .enumerate()
            .map(|(k, &r)| {
                let ((z0, s0), (z1, s1)) = (zones[k].profile(r), zones[k + 1].profile(r));
                let (step_mm, slope_jump) = (z1 - z0, s1 - s0);
                if !(step_mm.is_finite() && slope_jump.is_finite()) {
                    return Err(FieldError::new(
                        format!("zones[{k}].outer_radius_mm"),
                        r,
                        format!(
                            "zones {k} and {} have no finite sag and slope there to join",
                            k + 1
                        ),
                    ));
                }
                Ok(Boundary {
                    radius_mm: r,
                    step_mm,
                    slope_jump,
                })
            })
            .collect::<Result<_, _>>()?;
        Ok(Self {
            zones,
            outer,
            last_outer,
            boundaries,
        })
    }

    /// The boundaries between zones, from the axis outwards.
    pub fn boundaries(&self) -> &[Boundary] {
        &self.boundaries
    }

    /// The zone holding radius r (boundaries belong to the inner zone).
    fn zone_at(&self, r: f64) -> &Zone {
        &self.zones[self.outer.partition_point(|&b| b < r)]
    }

    fn undefined(x: f64, y: f64, reason: String) -> UndefinedError {
        UndefinedError {
            surface: "zoned asphere",
            x_mm: x,
            y_mm: y,
            radius_mm: x.hypot(y),
            reason,
        }
    }
}

impl Surface for ZonedAsphere {
    fn local(&self, x: f64, y: f64) -> Result<Local, UndefinedError> {
        let r = x.hypot(y);
        if let Some(last) = self.last_outer
            && r > last
        {
            return Err(Self::undefined(
                x,
                y,
                format!("beyond the outermost zone's outer radius {last} mm"),
            ));
        }
        let zone = self.zone_at(r);
        let mut l = zone
            .asphere
            .local(x, y)
            .map_err(|e| Self::undefined(x, y, e.reason))?;
        l.z += zone.offset;
        Ok(l)
    }

    /// The narrowest zone (the first one's width is its outer radius).
    fn feature_length_mm(&self) -> f64 {
        let mut edges = self.outer.clone();
        edges.extend(self.last_outer);
        let mut inner = 0.0;
        let mut shortest = f64::INFINITY;
        for r in edges {
            shortest = shortest.min(r - inner);
            inner = r;
        }
        shortest
    }

    /// The largest of the zones' asphere bounds, each over the disc to its outer radius (or T):
    /// a zone's sections are its asphere's. A boundary inside T whose slope drops outwards
    /// (`slope_jump ≤ 0`) and whose value is continuous (a step of at most
    /// [`MAX_BOUNDED_STEP_MM`], the rounding of the offsets) is a ridge; any other kink is a
    /// valley or a step (`has_valleys`: the nose height is then concave only between them).
    fn section_bounds(&self, radius_mm: f64) -> Option<SectionBounds> {
        let t = radius_mm.abs();
        let inside = self.boundaries.iter().take_while(|b| b.radius_mm < t);
        let mut bounds = SectionBounds {
            max_slope: 0.0,
            max_curvature: f64::NEG_INFINITY,
            min_curvature: f64::INFINITY,
            has_ridges: inside.clone().any(|b| {
                b.is_kink() && b.slope_jump <= 0.0 && b.step_mm.abs() <= MAX_BOUNDED_STEP_MM
            }),
            has_valleys: inside
                .clone()
                .any(|b| b.step_mm.abs() > MAX_BOUNDED_STEP_MM || b.slope_jump > 0.0),
        };
        for (k, zone) in self.zones.iter().enumerate().take(inside.count() + 1) {
            let reach = self.outer.get(k).map_or(t, |&r| r.min(t));
            bounds = bounds.or(zone.asphere.section_bounds(reach)?);
        }
        Some(bounds)
    }

    /// The crossings of the line with every boundary circle where the value or slope jumps.
    fn slope_kinks(&self, line: Line, t0: f64, t1: f64, out: &mut Vec<f64>) {
        // |p(t)|² = t² + 2bt + c with b = p₀·u, c = |p₀|²; roots −b ± √(b² − c + r²).
        let b = line.x0 * line.c + line.y0 * line.s;
        let c = line.x0 * line.x0 + line.y0 * line.y0;
        for boundary in self.boundaries.iter().filter(|b| b.is_kink()) {
            let disc = b * b - c + boundary.radius_mm * boundary.radius_mm;
            if disc <= 0.0 {
                continue;
            }
            let w = disc.sqrt();
            for t in [-b - w, -b + w] {
                if t > t0 && t < t1 {
                    out.push(t);
                }
            }
        }
    }

    /// The nearest kinked boundary circle's distance, `|ρ − r_b|`.
    fn kink_free_radius(&self, x: f64, y: f64) -> f64 {
        let rho = (x * x + y * y).sqrt();
        self.boundaries
            .iter()
            .filter(|b| b.is_kink())
            .map(|b| (rho - b.radius_mm).abs())
            .fold(f64::INFINITY, f64::min)
    }

    fn warnings(&self) -> Vec<String> {
        self.boundaries
            .iter()
            .filter(|b| b.is_warning())
            .map(|b| {
                let mut what = Vec::new();
                if b.step_mm.abs() > STEP_WARNING_MM {
                    what.push("a round nose cannot cut the step");
                }
                if b.slope_jump > SLOPE_WARNING {
                    what.push("the slope rises there, a concave corner where the nose leaves a fillet of its radius");
                } else if b.slope_jump < -SLOPE_WARNING {
                    what.push("the slope falls there, a convex edge the nose rounds");
                }
                format!(
                    "zoned asphere: at the zone boundary r = {} mm the sag steps by {:.3} nm and \
                     the slope jumps by {:.3} µrad (warned above {} nm or {} µrad): {}",
                    b.radius_mm,
                    b.step_mm * 1e6,
                    b.slope_jump * 1e6,
                    STEP_WARNING_MM * 1e6,
                    SLOPE_WARNING * 1e6,
                    what.join("; ")
                )
            })
            .collect()
    }

    fn describe(&self) -> String {
        let mut inner = 0.0;
        let zones: Vec<String> = self
            .zones
            .iter()
            .enumerate()
            .map(|(k, z)| {
                let outer = self.outer.get(k).copied().or(self.last_outer);
                let range = match outer {
                    Some(r) => format!("r {inner} … {r} mm"),
                    None => format!("r > {inner} mm"),
                };
                inner = outer.unwrap_or(inner);
                let offset = if z.offset != 0.0 {
                    format!(", offset {} mm", z.offset)
                } else {
                    String::new()
                };
                format!("{range}: {}{offset}", z.asphere.describe())
            })
            .collect();
        let boundaries: Vec<String> = self
            .boundaries
            .iter()
            .map(|b| {
                format!(
                    "at {} mm step {:.3e} mm, slope jump {:.3e} rad",
                    b.radius_mm, b.step_mm, b.slope_jump
                )
            })
            .collect();
        format!(
            "zoned asphere, {} zones [{}]; boundaries [{}]",
            self.zones.len(),
            zones.join("; "),
            boundaries.join("; ")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zone_spec(outer: Option<f64>, radius: f64, conic: f64, offset: f64) -> ZoneSpec {
        ZoneSpec {
            outer_radius_mm: outer,
            radius_mm: Some(radius),
            conic,
            offset_mm: offset,
            ..Default::default()
        }
    }

    #[test]
    fn section_bounds_hold_on_dense_sections_and_name_valleys_and_steps() {
        use crate::surface::section_bounds::assert_bounds_hold;
        // Parabolas of R 40, 50, 60 meeting in value at 0.6 and 1.1 mm: the slope drops
        // outwards at both (0.015 → 0.012, 0.022 → 0.0183), ridges.
        let ridges = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(0.6), 40.0, -1.0, 0.0),
                zone_spec(Some(1.1), 50.0, -1.0, 0.0009),
                zone_spec(None, 60.0, -1.0, 0.013 - 1.21 / 120.0),
            ],
        })
        .unwrap();
        let (b, ..) = assert_bounds_hold(&ridges, 3.0, 16, 20_000);
        // The outer zone's own bounds over the whole disc are the largest here.
        assert!(b.max_slope <= 3.0 / 60.0 * (1.0 + 1e-8), "{b:?}");
        // The same zones with the middle one flatter inside: a valley at 0.6 mm.
        let valley = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(0.6), 60.0, -1.0, 0.0),
                zone_spec(None, 40.0, -1.0, 0.36 / 120.0 - 0.36 / 80.0),
            ],
        })
        .unwrap();
        let v = valley.section_bounds(3.0).unwrap();
        assert!(v.has_valleys && !v.has_ridges);
        // ... and a disc inside the first zone has none.
        assert!(!valley.section_bounds(0.5).unwrap().has_valleys);
        // A step counts as a valley.
        let step = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(0.6), 40.0, -1.0, 0.0),
                zone_spec(None, 50.0, -1.0, 0.0019),
            ],
        })
        .unwrap();
        assert!(step.section_bounds(3.0).unwrap().has_valleys);
        assert!(!b.has_valleys && b.has_ridges);
    }

    #[test]
    fn a_zone_boundary_reports_its_step_and_slope_jump() {
        // Two spheres of R 20 and R 30 meeting at r = 3 mm, the outer one lifted to meet the
        // inner's sag: no step, a slope jump of 3/√391 − 3/√891.
        let inner_sag = 20.0 - (400.0f64 - 9.0).sqrt();
        let outer_sag = 30.0 - (900.0f64 - 9.0).sqrt();
        let s = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(3.0), 20.0, 0.0, 0.0),
                zone_spec(None, 30.0, 0.0, inner_sag - outer_sag),
            ],
        })
        .unwrap();
        let b = s.boundaries()[0];
        assert!(b.step_mm.abs() < 1e-15, "{b:?}");
        let jump = 3.0 / 891f64.sqrt() - 3.0 / 391f64.sqrt();
        assert!((b.slope_jump - jump).abs() < 1e-15, "{b:?}");
        assert_eq!(s.warnings().len(), 1);
        assert!(s.describe().contains("at 3 mm step"), "{}", s.describe());
        let mut kinks = Vec::new();
        s.slope_kinks(Line::radial(0.6, 0.8), -10.0, 10.0, &mut kinks);
        kinks.sort_by(f64::total_cmp);
        assert_eq!(kinks, vec![-3.0, 3.0]);
        assert_eq!(s.feature_length_mm(), 3.0);
    }

    #[test]
    fn spec_errors_name_the_zone() {
        let e = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(None, 20.0, 0.0, 0.0),
                zone_spec(None, 30.0, 0.0, 0.0),
            ],
        })
        .unwrap_err();
        assert_eq!(e.field, "zones[0].outer_radius_mm");
        let e = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(3.0), 20.0, 0.0, 0.0),
                zone_spec(Some(2.0), 30.0, 0.0, 0.0),
            ],
        })
        .unwrap_err();
        assert_eq!(e.field, "zones[1].outer_radius_mm");
        let e = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(3.0), 20.0, 0.0, 0.0),
                zone_spec(Some(6.0), 5.0, 0.0, 0.0),
            ],
        })
        .unwrap_err();
        assert_eq!(e.field, "zones[1].conic");
        let e = ZonedAsphere::new(&ZonedAsphereSpec { zones: vec![] }).unwrap_err();
        assert_eq!(e.field, "zones");
        let e = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![ZoneSpec::default()],
        })
        .unwrap_err();
        assert_eq!(e.field, "zones[0].radius_mm");
        // A boundary where the zones' sags overflow (r² beyond the largest double) gave a step
        // of NaN in the program's header.
        let e = ZonedAsphere::new(&ZonedAsphereSpec {
            zones: vec![
                zone_spec(Some(2.0), 40.0, -1.0, 0.0),
                zone_spec(Some(1e300), -1e300, 0.0, 0.0),
                zone_spec(None, 40.0, -1.0, 0.0),
            ],
        })
        .unwrap_err();
        assert_eq!(e.field, "zones[1].outer_radius_mm", "{e}");
    }
}

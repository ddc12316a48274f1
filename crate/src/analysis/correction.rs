//! The closed loop of issue 15: a measured part in, a corrected job out. The measured map
//! ([`crate::surface::measured`]) is registered to the design ([`super::registration`]), its
//! residual (measured − design, positive where material is left) summed up as PV, RMS and 37
//! Fringe Zernike terms ([`super::zernike_fit`]), put on a grid over the part
//! ([`super::residual`]) and continued where nothing was measured ([`super::extension`]), and the
//! corrected job is the design minus gain × residual:
//!
//! `surface = composite { base: the design, terms: [ grid_sag (−gain × residual), correction ] }`
//!
//! a surface the job format already has, so the corrected job plans, verifies and is corrected
//! again like any job. The correction term carries `"correction": true`; correcting a corrected
//! job registers the new measurement to the design (the job without that term: the form the
//! part should have) and writes one term holding the old correction plus the new one, node by
//! node on the same grid, so the corrections add.
//!
//! **After the re-cut.** If the machine repeats its error, cutting `design − gain·ĝ` leaves
//! `e − gain·ĝ` (ĝ the grid's bicubic interpolation of the residual). That is evaluated at every
//! measured point and reported as the predicted residual (`(1 − gain)·e` plus what the grid
//! cannot hold: measurement noise and detail finer than its spacing).
//!
//! **Checks.** Before anything is computed: the job valid and on the design's own axis; at least
//! [`MIN_POINTS`] finite points; after registration, every point on the part (within its radius
//! and 0.1 %); the design defined at every point. A residual PV larger than the design's own sag
//! range over the part is a warning (heights in the wrong unit).

use super::extension::{self, ExtensionReport};
use super::registration::{MeasuredKind, RegisterTerms, Registration, register};
use super::residual::{
    GridLayout, MAX_GRID_SIDE, MIN_GRID_SIDE, ResidualFigures, ResidualGrid, bounds,
};
use super::zernike_fit::{FringeBasis, ZernikeFit};
use crate::field::{FieldError, short};
use crate::job::Job;
use crate::raster::Raster;
use crate::surface::grid_sag::dat::{DatUnit, GridData, GridNode};
use crate::surface::measured::{MeasuredData, MeasuredMap};
use crate::surface::{
    CompositeSpec, DataFile, GridSag, GridSagSpec, Surface, SurfaceSpec, TermSpec, UndefinedError,
};
use serde::Serialize;
use thiserror::Error;

/// The fewest measured points a correction accepts.
pub const MIN_POINTS: usize = 100;
/// The largest gain accepted: beyond 2 a correction overshoots by more than the error.
pub const MAX_GAIN: f64 = 2.0;

/// A correction that cannot be made.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum CorrectionError {
    /// The job, or a setting, is wrong.
    ///
    /// ```
    /// use spiralcam::analysis::correction::{Correction, CorrectionSettings};
    /// use spiralcam::analysis::registration::MeasuredKind;
    /// use spiralcam::surface::measured::{MeasuredData, MeasuredMap, PointCloud};
    /// let map = MeasuredMap::new(MeasuredData::Cloud(PointCloud::default()), "none");
    /// let settings = CorrectionSettings { gain: 3.0, ..CorrectionSettings::new(MeasuredKind::Error) };
    /// let e = Correction::run(&spiralcam::job::Job::default_job(), &map, &settings).unwrap_err();
    /// assert_eq!(e.to_string(), "gain = 3: must lie in (0, 2]");
    /// ```
    #[error(transparent)]
    Field(#[from] FieldError),
    /// Fewer points than a correction needs.
    ///
    /// ```
    /// use spiralcam::analysis::correction::{Correction, CorrectionSettings};
    /// use spiralcam::analysis::registration::MeasuredKind;
    /// use spiralcam::surface::measured::{MeasuredData, MeasuredMap, PointCloud};
    /// let cloud = PointCloud { points: vec![[0.0, 0.0, 0.0]; 5] };
    /// let map = MeasuredMap::new(MeasuredData::Cloud(cloud), "five points");
    /// let settings = CorrectionSettings::new(MeasuredKind::Error);
    /// let e = Correction::run(&spiralcam::job::Job::default_job(), &map, &settings).unwrap_err();
    /// assert!(e.to_string().starts_with("the measured data hold 5 points: at least 100"), "{e}");
    /// ```
    #[error(
        "the measured data hold {points} points: at least {needed} are needed for a \
         registration and a 37-term Zernike fit"
    )]
    TooFewPoints {
        /// Points found.
        points: usize,
        /// The least accepted.
        needed: usize,
    },
    /// A point is not a finite number.
    ///
    /// ```
    /// use spiralcam::analysis::correction::CorrectionError;
    /// let e = CorrectionError::NotFinite { index: 7, point: "(1, NaN, 0)".into() };
    /// assert_eq!(e.to_string(), "measured point 8 is not finite: (1, NaN, 0)");
    /// ```
    #[error("measured point {} is not finite: {point}", index + 1)]
    NotFinite {
        /// Its index from 0.
        index: usize,
        /// The point as read.
        point: String,
    },
    /// Points lie outside the part after registration.
    ///
    /// ```
    /// use spiralcam::analysis::correction::CorrectionError;
    /// let e = CorrectionError::OutsidePart {
    ///     outside: 3, points: 100, farthest: "(12.5, 0)".into(), distance_mm: 12.5,
    ///     radius_mm: 10.0,
    /// };
    /// assert!(e.to_string().starts_with("3 of 100 measured points lie outside the part"), "{e}");
    /// ```
    #[error(
        "{outside} of {points} measured points lie outside the part (radius {radius_mm} mm, \
         part.diameter_mm): the farthest at {farthest} mm, {distance_mm} mm from its centre; \
         check the file's lateral unit (µm read as mm?), --rotate and --mirror, and that the \
         map is centred on the part"
    )]
    OutsidePart {
        /// Points outside.
        outside: usize,
        /// All points.
        points: usize,
        /// The farthest point, on the part's frame.
        farthest: String,
        /// Its distance from the centre, mm.
        distance_mm: f64,
        /// The part radius, mm.
        radius_mm: f64,
    },
    /// The design is not defined where a measured point falls.
    ///
    /// ```
    /// use spiralcam::analysis::correction::CorrectionError;
    /// use spiralcam::surface::UndefinedError;
    /// let u = UndefinedError { surface: "even asphere", x_mm: 30.0, y_mm: 0.0, radius_mm: 30.0,
    ///     reason: "beyond the sphere".into() };
    /// let e = CorrectionError::from(u);
    /// assert!(e.to_string().starts_with("the design at a measured point: "), "{e}");
    /// ```
    #[error("the design at a measured point: {0}")]
    Undefined(#[from] UndefinedError),
}

/// How to correct.
#[derive(Debug, Clone, PartialEq)]
pub struct CorrectionSettings {
    /// What the file holds.
    pub kind: MeasuredKind,
    /// The terms registered besides piston and tilt.
    pub terms: RegisterTerms,
    /// The fraction of the residual taken off, (0, 2]; default 1.
    pub gain: f64,
    /// Samples per side of the before and after maps (0: none).
    pub map_size: usize,
}

impl CorrectionSettings {
    /// The defaults for `kind`: its terms ([`RegisterTerms::default_for`]), gain 1, 256 × 256
    /// maps.
    pub fn new(kind: MeasuredKind) -> Self {
        Self {
            kind,
            terms: RegisterTerms::default_for(kind),
            gain: 1.0,
            map_size: 256,
        }
    }
}

/// Where the measurement came from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MeasuredSummary {
    /// The reader's line: the file, its format and how it was converted.
    pub source: String,
    /// The orientation applied to it.
    pub orientation: String,
    /// What it holds.
    pub kind: MeasuredKind,
    /// Points read.
    pub points: usize,
}

/// The residual of the registration.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ResidualReport {
    /// Peak to valley over the measured points, µm.
    pub pv_um: f64,
    /// RMS over the measured points, µm.
    pub rms_um: f64,
    /// Measured points.
    pub points: usize,
    /// Coefficients of Fringe Z1 … Z37, µm, normalised at `zernike_norm_radius_mm`.
    pub zernike_fringe_um: Vec<f64>,
    /// The Zernike normalisation radius: the part radius, mm.
    pub zernike_norm_radius_mm: f64,
    /// The grid the residual is written on.
    pub grid: GridLayout,
    /// How the residual was continued over the part.
    pub extension: ExtensionReport,
}

/// The corrected job.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorrectedReport {
    /// The corrected job's file, when written.
    pub job_file: Option<String>,
    /// Its correction grid's file (beside it), when written.
    pub data_file: Option<String>,
    /// The gain applied.
    pub gain: f64,
    /// Whether the job already held a correction, to which this one was added.
    pub previous_correction: bool,
    /// The residual predicted after the re-cut, at the measured points (see the module docs).
    pub predicted_residual: ResidualFigures,
}

/// The report of a correction (`spiralcam correct --report`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorrectionReport {
    /// The job corrected.
    pub job: String,
    /// The measurement.
    pub measured: MeasuredSummary,
    /// The set-up fitted and removed.
    pub registration: Registration,
    /// The residual.
    pub residual: ResidualReport,
    /// The corrected job.
    pub corrected: CorrectedReport,
    /// What deserves a second look.
    pub warnings: Vec<String>,
}

/// A correction made: its report, the corrected job and the maps.
#[derive(Debug, Clone)]
pub struct Correction {
    /// The report.
    pub report: CorrectionReport,
    /// The corrected job, its correction grid inline (`text`).
    pub corrected_job: Job,
    /// The correction term's grid (−gain × the residual, plus any earlier correction).
    pub correction_grid: GridData,
    /// The residual before, µm, mean per cell over the part.
    pub before: Raster,
    /// The residual predicted after the re-cut, µm.
    pub after: Raster,
}

/// The design and the correction a job's surface holds.
struct Split {
    design: SurfaceSpec,
    correction: Option<GridSagSpec>,
}

/// Splits the job's surface into the design and its correction term, if any.
fn split(surface: &SurfaceSpec) -> Result<Split, FieldError> {
    let SurfaceSpec::Composite(c) = surface else {
        return Ok(Split {
            design: surface.clone(),
            correction: None,
        });
    };
    let Some(k) = c.terms.iter().position(|t| t.correction) else {
        return Ok(Split {
            design: surface.clone(),
            correction: None,
        });
    };
    let term = &c.terms[k];
    let field = format!("surface.terms[{k}]");
    let SurfaceSpec::GridSag(grid) = &term.surface else {
        return Err(FieldError::new(
            format!("{field}.surface.type"),
            "not grid_sag",
            "a correction term is the grid_sag that spiralcam correct wrote",
        ));
    };
    if term.decenter_x_mm != 0.0
        || term.decenter_y_mm != 0.0
        || term.rotation_deg != 0.0
        || grid.base.is_some()
    {
        return Err(FieldError::new(
            field,
            "moved or on a base",
            "a correction term lies on the spindle axis, unturned, without a base",
        ));
    }
    if c.terms.iter().filter(|t| t.correction).count() > 1 {
        return Err(FieldError::new(
            "surface.terms",
            "two correction terms",
            "at most one term has \"correction\": true",
        ));
    }
    let mut rest = c.clone();
    rest.terms.remove(k);
    let design = if rest.terms.is_empty() {
        (*rest.base).clone()
    } else {
        SurfaceSpec::Composite(rest)
    };
    Ok(Split {
        design,
        correction: Some(grid.clone()),
    })
}

/// The grid of an earlier correction term.
fn old_grid(spec: &GridSagSpec) -> Result<GridData, FieldError> {
    let field = "surface.correction.data";
    let text = spec.data.text(field)?;
    GridData::parse(text).map_err(|e| FieldError::new(field, spec.data.name(), e.to_string()))
}

/// The layout of an earlier correction's grid, on which the new correction is added node by
/// node: a square grid of odd side centred on the axis, as [`Correction::run`] writes it.
fn layout_of(g: &GridData, radius: f64) -> Result<GridLayout, FieldError> {
    let square = g.nx == g.ny
        && g.nx % 2 == 1
        && (MIN_GRID_SIDE..=MAX_GRID_SIDE).contains(&g.nx)
        && (g.dx_mm - g.dy_mm).abs() <= 1e-12 * g.dx_mm
        && g.x_decenter_mm == 0.0
        && g.y_decenter_mm == 0.0;
    if !square {
        return Err(FieldError::new(
            "surface.correction.data",
            format!(
                "{} × {} nodes, {} × {} mm apart, decentred ({}, {}) mm",
                g.nx,
                g.ny,
                short(g.dx_mm),
                short(g.dy_mm),
                short(g.x_decenter_mm),
                short(g.y_decenter_mm)
            ),
            format!(
                "must be the square grid centred on the axis that spiralcam correct writes (odd \
                 side of {MIN_GRID_SIDE} to {MAX_GRID_SIDE} nodes, equal spacings)"
            ),
        ));
    }
    Ok(GridLayout::with_nodes(radius, g.nx, g.dx_mm))
}

/// The typical distance between measured points, mm: a grid's spacing, or `√(area/points)` of
/// a cloud's bounding box.
fn data_spacing(map: &MeasuredMap, points: &[[f64; 3]]) -> f64 {
    match &map.data {
        MeasuredData::Grid(g) => g.dx_mm.max(g.dy_mm),
        MeasuredData::Cloud(_) => {
            let [x0, y0, x1, y1] = bounds(points);
            ((x1 - x0).max(0.0) * (y1 - y0).max(0.0) / points.len().max(1) as f64).sqrt()
        }
    }
}

/// The mean of the values at the points `[x, y, v]` per cell of a `size` raster over the disc
/// of `radius` mm, in µm.
fn mean_map(points: impl Iterator<Item = [f64; 3]>, radius: f64, size: usize) -> Raster {
    let mut r = Raster::over_part(radius, size);
    let mut count = vec![0u32; r.values.len()];
    let mut sum = vec![0.0; r.values.len()];
    for [x, y, v] in points {
        if let Some(k) = r.index_of(x, y) {
            sum[k] += v;
            count[k] += 1;
        }
    }
    for (k, v) in r.values.iter_mut().enumerate() {
        if count[k] > 0 {
            *v = 1e3 * sum[k] / f64::from(count[k]);
        }
    }
    r
}

/// The grid sag data of node values `z` (mm) on `layout`, nodes not kept without data.
fn grid_data(layout: &GridLayout, kept: &[bool], z: &[f64]) -> GridData {
    GridData {
        nx: layout.n,
        ny: layout.n,
        dx_mm: layout.step_mm,
        dy_mm: layout.step_mm,
        x_decenter_mm: 0.0,
        y_decenter_mm: 0.0,
        unit: DatUnit::Millimetre,
        nodes: z
            .iter()
            .zip(kept)
            .map(|(&z_mm, &valid)| GridNode {
                z_mm: if valid { z_mm } else { 0.0 },
                valid,
                ..GridNode::default()
            })
            .collect(),
        first_data_line: None,
    }
}

impl Correction {
    /// Corrects `job` with the measured `map` (already oriented) under `settings` (see the
    /// module docs).
    pub fn run(
        job: &Job,
        map: &MeasuredMap,
        settings: &CorrectionSettings,
    ) -> Result<Self, CorrectionError> {
        let gain = settings.gain;
        if !(gain > 0.0 && gain <= MAX_GAIN) {
            return Err(FieldError::new("gain", gain, "must lie in (0, 2]").into());
        }
        let points = map.points();
        if points.len() < MIN_POINTS {
            return Err(CorrectionError::TooFewPoints {
                points: points.len(),
                needed: MIN_POINTS,
            });
        }
        if let Some(index) = points.iter().position(|p| p.iter().any(|v| !v.is_finite())) {
            let [x, y, z] = points[index];
            return Err(CorrectionError::NotFinite {
                index,
                point: format!("({}, {}, {})", short(x), short(y), short(z)),
            });
        }
        job.validate().map_err(|e| match e {
            crate::job::JobError::Field(f) => f,
            other => FieldError::new("job", "", other.to_string()),
        })?;
        if let Some([x, y]) = job.part.normal_axis_at_mm {
            return Err(FieldError::new(
                "part.normal_axis_at_mm",
                format!("[{x}, {y}]"),
                "a correction needs the design on the spindle axis: remove the field (the \
                 residual is registered and written in the design's own frame)",
            )
            .into());
        }
        let parts = split(&job.surface)?;
        let radius = job.part_radius_mm();
        let design = parts
            .design
            .build(radius)
            .map_err(|e| e.within("surface"))?;
        let (registration, residual) = register(
            &points,
            settings.kind,
            settings.terms,
            design.as_ref(),
            radius,
        )?;
        check_on_part(&residual, radius)?;
        let before = ResidualFigures::of(residual.iter().map(|p| p[2]));
        let fit = ZernikeFit::fit(&residual, radius);
        let old = parts.correction.as_ref().map(old_grid).transpose()?;
        let spacing = data_spacing(map, &points);
        let layout = match &old {
            Some(g) => layout_of(g, radius)?,
            None => GridLayout::covering(radius, spacing),
        };
        let mut grid = ResidualGrid::measure(layout, &residual, spacing);
        let basis = FringeBasis::new();
        let extension = extension::fill(&mut grid, |x, y| {
            let r = x.hypot(y);
            let s = if r > radius { radius / r } else { 1.0 };
            fit.value(&basis, x * s, y * s)
        });
        // The correction: the earlier one (if any) at the nodes, less gain × the residual.
        let n = layout.n;
        let mut increment = vec![0.0; n * n];
        let mut total = vec![0.0; n * n];
        for k in 0..n * n {
            if !grid.kept[k] {
                continue;
            }
            increment[k] = -gain * grid.values_mm[k];
            let earlier = match &old {
                Some(g) if g.nodes[k].valid => g.nodes[k].z_mm,
                Some(_) => {
                    let (x, y) = layout.node(k % n, k / n);
                    return Err(FieldError::new(
                        "surface.correction",
                        format!("no value at ({}, {}) mm", short(x), short(y)),
                        "must cover the part and its margin as spiralcam correct wrote it (was \
                         part.diameter_mm changed?)",
                    )
                    .into());
                }
                None => 0.0,
            };
            total[k] = earlier + increment[k];
        }
        let step = GridSag::from_grid(grid_data(&layout, &grid.kept, &increment), None)?;
        let mut after = Vec::with_capacity(residual.len());
        for &[x, y, e] in &residual {
            after.push([x, y, e + step.sag(x, y)?]);
        }
        let predicted = ResidualFigures::of(after.iter().map(|p| p[2]));
        let correction_grid = grid_data(&layout, &grid.kept, &total);
        let corrected_job = corrected_job(job, &parts.design, &correction_grid);
        let mut warnings = registration.notes.clone();
        warnings.extend(unit_warning(design.as_ref(), radius, before.pv_um));
        if fit.underdetermined {
            warnings.push(
                "the measured points do not determine all 37 Zernike terms (too small an area, \
                 or profiles): the least-norm coefficients are given"
                    .into(),
            );
        }
        if !extension.converged {
            warnings.push(format!(
                "the extension beyond the measured area stopped after {} iterations before \
                 converging: it is smooth, but not quite the least-curvature continuation",
                extension.iterations
            ));
        }
        if !registration.converged {
            warnings.push("the registration did not converge".into());
        }
        let report = CorrectionReport {
            job: job.name.clone(),
            measured: MeasuredSummary {
                source: map.source.clone(),
                orientation: map.orientation.to_string(),
                kind: settings.kind,
                points: points.len(),
            },
            registration,
            residual: ResidualReport {
                pv_um: before.pv_um,
                rms_um: before.rms_um,
                points: before.points,
                zernike_fringe_um: fit.coefficients_mm.iter().map(|c| c * 1e3).collect(),
                zernike_norm_radius_mm: radius,
                grid: layout,
                extension,
            },
            corrected: CorrectedReport {
                job_file: None,
                data_file: None,
                gain,
                previous_correction: parts.correction.is_some(),
                predicted_residual: predicted,
            },
            warnings,
        };
        Ok(Self {
            report,
            before: mean_map(residual.iter().copied(), radius, settings.map_size.max(2)),
            after: mean_map(after.into_iter(), radius, settings.map_size.max(2)),
            corrected_job,
            correction_grid,
        })
    }

    /// The report as pretty JSON.
    pub fn report_json(&self) -> String {
        serde_json::to_string_pretty(&self.report).unwrap_or_default()
    }
}

/// Every residual point within the part (its radius and 0.1 %), else the error naming them.
fn check_on_part(residual: &[[f64; 3]], radius: f64) -> Result<(), CorrectionError> {
    let limit = radius * 1.001 + 1e-9;
    let mut outside = 0;
    let mut farthest = (0.0, [0.0; 2]);
    for p in residual {
        let d = p[0].hypot(p[1]);
        if d > limit {
            outside += 1;
            if d > farthest.0 {
                farthest = (d, [p[0], p[1]]);
            }
        }
    }
    if outside == 0 {
        return Ok(());
    }
    Err(CorrectionError::OutsidePart {
        outside,
        points: residual.len(),
        farthest: format!("({}, {})", short(farthest.1[0]), short(farthest.1[1])),
        distance_mm: farthest.0,
        radius_mm: radius,
    })
}

/// A warning when the residual's PV exceeds the design's own sag range over the part (sampled
/// on a 65 × 65 grid): the heights are likely in the wrong unit.
fn unit_warning(design: &dyn Surface, radius: f64, pv_um: f64) -> Option<String> {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for j in 0..65 {
        for i in 0..65 {
            let (x, y) = (
                radius * (i as f64 / 32.0 - 1.0),
                radius * (j as f64 / 32.0 - 1.0),
            );
            if x.hypot(y) <= radius
                && let Ok(z) = design.sag(x, y)
            {
                lo = lo.min(z);
                hi = hi.max(z);
            }
        }
    }
    let range_um = (hi - lo) * 1e3;
    (pv_um > range_um).then(|| {
        format!(
            "the residual's PV {} µm exceeds the design's own sag range {} µm over the part: are \
             the heights in the wrong unit (µm read as mm, or nm as µm)?",
            short(pv_um),
            short(range_um)
        )
    })
}

/// The job with its surface the design plus the correction term holding `grid` inline.
fn corrected_job(job: &Job, design: &SurfaceSpec, grid: &GridData) -> Job {
    let term = TermSpec {
        surface: SurfaceSpec::GridSag(GridSagSpec {
            data: DataFile {
                path: None,
                text: Some(grid.to_dat()),
            },
            base: None,
        }),
        decenter_x_mm: 0.0,
        decenter_y_mm: 0.0,
        rotation_deg: 0.0,
        correction: true,
    };
    let surface = match design {
        SurfaceSpec::Composite(c) => {
            let mut c = c.clone();
            c.terms.push(term);
            SurfaceSpec::Composite(c)
        }
        other => SurfaceSpec::Composite(CompositeSpec {
            base: Box::new(other.clone()),
            terms: vec![term],
        }),
    };
    let mut out = job.clone();
    out.surface = surface;
    if !out.name.ends_with("-corrected") {
        let keep: String = out
            .name
            .chars()
            .take(crate::job::MAX_NAME_CHARS - 10)
            .collect();
        out.name = format!("{keep}-corrected");
    }
    out
}

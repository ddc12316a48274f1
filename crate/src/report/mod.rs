//! The plan report: figures gathered while the path streams by ([`Stats`]) and the checks, as a
//! serialisable [`Report`] (the command line's `--report` JSON and the page's report panel).
//!
//! `max_dz_dtheta_um_per_deg` is the largest commanded `|ΔZ/ΔC|` between consecutive points,
//! the slope the Z axis (or FTS) must follow; with the spindle speed it gives the Z velocity.
//! `surface_pv_um` is the peak-to-valley of the sag over the contact points. The cycle time is
//! the total spindle angle at the job's speed.
//!
//! X motion, for both compensations (one-way X is the spiral itself: no reversal, no
//! acceleration beyond rounding): `x_reversals` counts the points where ΔX between consecutive
//! points changes sign (zero steps skipped), a servo burden on SSS; `max_x_acceleration_mm_s2`
//! is the largest |d²X/dt²| from the second difference of three consecutive points on their
//! (possibly unequal) C steps, `2·(ΔX₂/ΔC₂ − ΔX₁/ΔC₁)/(ΔC₁ + ΔC₂)` times ω², the spindle's
//! angular speed at the job's rpm, placed at the middle point. `two_way_loops` counts the runs
//! of consecutive points where the two-way offset folds (a path loop, see
//! [`crate::tool`]), `two_way_loop_points` their points and `first_two_way_loop_at` the
//! first; always 0 (and null) for one-way, which cannot loop.

mod stats;

pub use stats::Stats;

use crate::path::Location;
use crate::tool::ToolPath;
use crate::tool::reach::{ConcaveZone, Reach};
use serde::Serialize;
use std::f64::consts::TAU;

/// What a job will cost.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Cost {
    /// Points on the path.
    pub points: u64,
    /// Times the path is computed: 2 when the machine dynamics run first.
    pub passes: u32,
    /// Size of the NC program, bytes.
    pub nc_bytes: u64,
    /// Size of the CSV table, bytes.
    pub csv_bytes: u64,
    /// Size of the servo's table, bytes, for a split path.
    pub fts_table_bytes: Option<u64>,
    /// The most the servo's gridded table (PMAC text and CSV together) may weigh, bytes, for a
    /// split path: its size is known only once the grid is sized against the tolerance, after
    /// the dynamics, so the estimate is the bound of its entries
    /// ([`crate::dynamics::fts_grid::MAX_ENTRIES`]) at the widest entry and number.
    pub fts_grid_bytes: Option<u64>,
    /// Samples of the machine dynamics' uniform grid, when they run: at least the points, more
    /// where the path's densest turn is denser than the others
    /// ([`crate::dynamics::grid_samples`]).
    pub dynamics_samples: Option<u64>,
    /// Memory the machine dynamics hold, bytes, when they run
    /// ([`crate::dynamics::memory_bytes`]).
    pub dynamics_memory_bytes: Option<u64>,
    /// Time to plan and write, seconds (with a clock; none in the browser's estimate), the
    /// machine dynamics' analysis included.
    pub seconds: Option<f64>,
    /// Of [`Self::seconds`], the machine dynamics' analysis, when they run: timed on a short
    /// synthetic path on this machine and scaled by their grid's samples
    /// ([`crate::dynamics::seconds_per_sample`], [`crate::dynamics::grid_samples`]).
    pub dynamics_seconds: Option<f64>,
}

/// Which files a run writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Outputs {
    /// The NC program.
    pub nc: bool,
    /// The CSV table.
    pub csv: bool,
    /// The servo's table.
    pub fts_table: bool,
    /// The servo's gridded table and its CSV.
    pub fts_grid: bool,
}

impl Cost {
    /// Bytes of the files `outputs` names.
    pub fn output_bytes(&self, outputs: Outputs) -> u64 {
        let pick = |on: bool, bytes: u64| if on { bytes } else { 0 };
        pick(outputs.nc, self.nc_bytes)
            + pick(outputs.csv, self.csv_bytes)
            + pick(outputs.fts_table, self.fts_table_bytes.unwrap_or(0))
            + pick(outputs.fts_grid, self.fts_grid_bytes.unwrap_or(0))
    }

    /// One line for the user: points, the files' sizes, the time.
    pub fn summary(&self, outputs: Outputs) -> String {
        let mut parts = vec![format!("{} points", self.points)];
        if outputs.nc {
            parts.push(format!("NC {}", bytes(self.nc_bytes)));
        }
        if outputs.csv {
            parts.push(format!("CSV {}", bytes(self.csv_bytes)));
        }
        if let (true, Some(b)) = (outputs.fts_table, self.fts_table_bytes) {
            parts.push(format!("servo table {}", bytes(b)));
        }
        if let (true, Some(b)) = (outputs.fts_grid, self.fts_grid_bytes) {
            parts.push(format!("servo grid at most {}", bytes(b)));
        }
        if let Some(m) = self.dynamics_memory_bytes {
            parts.push(format!("dynamics {} in memory", bytes(m)));
        }
        if let Some(s) = self.seconds {
            parts.push(format!("about {}", duration(s)));
        }
        parts.join(", ")
    }
}

/// Bytes in kB, MB, GB (powers of 1000), 3 significant digits.
pub fn bytes(n: u64) -> String {
    let n = n as f64;
    let (value, unit) = match n {
        _ if n < 1e3 => return format!("{n} B"),
        _ if n < 1e6 => (n / 1e3, "kB"),
        _ if n < 1e9 => (n / 1e6, "MB"),
        _ => (n / 1e9, "GB"),
    };
    format!("{} {unit}", three_digits(value))
}

/// A duration in s, min or h.
pub fn duration(s: f64) -> String {
    match s {
        _ if s < 120.0 => format!("{} s", three_digits(s)),
        _ if s < 7200.0 => format!("{} min", three_digits(s / 60.0)),
        _ => format!("{} h", three_digits(s / 3600.0)),
    }
}

fn three_digits(v: f64) -> String {
    match v {
        _ if v >= 100.0 => format!("{v:.0}"),
        _ if v >= 10.0 => format!("{v:.1}"),
        _ => format!("{v:.2}"),
    }
}

/// A program's passes and files (jobs with a `program` section).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ProgramReport {
    /// The stock before the first pass, mm.
    pub stock_mm: f64,
    /// How the passes are written.
    pub loop_kind: crate::job::LoopKind,
    /// The safe height the program starts and ends at, mm.
    pub safe_z_mm: f64,
    /// Every pass, in order.
    pub passes: Vec<PassReport>,
    /// The child programs, in the order called (none when the program is one file).
    pub children: Vec<crate::nc::program::ChildProgram>,
}

/// One pass of a program.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassReport {
    /// Its group in `program.passes`.
    pub group: usize,
    /// The stock left after it, mm (the design is raised by it).
    pub stock_left_mm: f64,
    /// Its spiral's feed, mm/rev.
    pub feed_mm_per_rev: f64,
    /// Its spindle speed, rev/min.
    pub spindle_rpm: f64,
    /// Points on its path.
    pub points: u64,
    /// Its cutting time (the spiral alone), s.
    pub cutting_time_s: f64,
}

/// What a plan produced and what it found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Job name.
    pub job: String,
    /// The surface, restated.
    pub surface: String,
    /// What is cut and in which frame (`part.cut`), restated; null when the job does not say.
    pub cut: Option<String>,
    /// The NC dialect.
    pub dialect: String,
    /// Points on the path.
    pub points: u64,
    /// Spindle revolutions from start to centre.
    pub revolutions: f64,
    /// Radius of the first point, mm.
    pub start_radius_mm: f64,
    /// Size of the NC program, bytes.
    pub nc_bytes: u64,
    /// Cutting time at the spindle speed, s.
    pub cycle_time_s: f64,
    /// Largest |ΔZ/ΔC| between consecutive points, µm per degree.
    pub max_dz_dtheta_um_per_deg: f64,
    /// Where it occurs.
    pub max_dz_dtheta_at: Location,
    /// Peak-to-valley of the sag over the contact points, µm.
    pub surface_pv_um: f64,
    /// Lowest commanded Z (tool tip), mm.
    pub z_min_mm: f64,
    /// Highest commanded Z (tool tip), mm.
    pub z_max_mm: f64,
    /// Points whose contact lies at an end of the nose arc.
    pub arc_end_contacts: u64,
    /// Points where the X motion changes direction (see the module docs).
    pub x_reversals: u64,
    /// Largest X acceleration at the spindle speed, mm/s².
    pub max_x_acceleration_mm_s2: f64,
    /// Where it occurs (X and C of the middle point).
    pub max_x_acceleration_at: Location,
    /// Runs of consecutive points where the two-way offset folds (loops); 0 for one-way.
    pub two_way_loops: u64,
    /// Points in those runs.
    pub two_way_loop_points: u64,
    /// The first loop point (X and C), if any.
    pub first_two_way_loop_at: Option<Location>,
    /// Zones the nose cannot reach, deepest first (form error ≥ 0.1 nm, at most 500).
    pub concave_zones: Vec<ConcaveZone>,
    /// Further zones with a form error below 0.1 nm, counted only.
    pub shallow_concave_zones: usize,
    /// Zones found but not measured (beyond the most the report measures, the least sharp).
    pub unmeasured_concave_zones: usize,
    /// What lies beyond the part's edge and where the spiral starts (`part.beyond_edge`,
    /// `strategy.overtravel_mm`).
    pub part_edge: String,
    /// Findings an operator must read before cutting.
    pub warnings: Vec<String>,
    /// What the job was estimated to cost before it was planned (set by the caller that
    /// admitted it, [`crate::plan::Planner::cost`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub estimate: Option<Cost>,
    /// The program's passes and files, for a job with a `program` section.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub program: Option<ProgramReport>,
    /// Spectrum, split and axis checks, when the job asks for them
    /// ([`crate::dynamics::wanted`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub dynamics: Option<crate::dynamics::DynamicsReport>,
}

impl Report {
    /// Assembles the report of a finished run.
    pub fn new(tool_path: &ToolPath, stats: &Stats, nc_bytes: u64, reach: Reach) -> Self {
        let concave_zones = reach.zones;
        let job = tool_path.job();
        let mut warnings = tool_path.surface().warnings();
        if let Some((rho, theta)) = stats.first_arc_end {
            let at = Location::new(rho, theta);
            warnings.push(format!(
                "at {} points the radial section is steeper than half the included angle ({} deg): \
                 the contact is at the end of the nose arc and the tool flank may cut; first at radius \
                 {:.4} mm, angle {:.2} deg",
                stats.arc_end, job.tool.included_angle_deg / 2.0, at.rho_mm, at.theta_deg
            ));
        }
        if let Some(deepest) = concave_zones.first() {
            warnings.push(format!(
                "{} zone(s) are concave with a curvature radius below the nose radius {} mm: form error \
                 up to {:.4} um, deepest at radius {:.4} mm, angle {:.2} deg",
                concave_zones.len() + reach.unlisted_zones,
                job.tool.nose_radius_mm,
                deepest.depth_um,
                deepest.at.rho_mm,
                deepest.at.theta_deg
            ));
        }
        if reach.unmeasured_zones > 0 {
            warnings.push(format!(
                "{} more concave zone(s) were found but not measured (the report measures the \
                 {} sharpest): the surface has features much finer than the nose radius {} mm",
                reach.unmeasured_zones,
                crate::tool::reach::MAX_MEASURED_ZONES,
                job.tool.nose_radius_mm
            ));
        }
        if let Some((rho, theta)) = stats.first_loop {
            let at = Location::new(rho, theta);
            warnings.push(format!(
                "two-way compensation leaves {} loop(s) ({} points) where the surface is concave with a \
                 curvature radius below the nose radius {} mm: the offset path self-intersects; first at \
                 X {:.4} mm, C {:.2} deg",
                stats.loops, stats.loop_points, job.tool.nose_radius_mm, at.rho_mm, at.theta_deg
            ));
        }
        let start = tool_path.spiral().start_radius_mm();
        let omega = job.machine.spindle_rpm / 60.0 * TAU;
        if start > job.outer_radius_mm() + 1e-12 {
            warnings.push(format!(
                "the path starts at radius {start:.6} mm, {:.3} um outside the outer radius, so that \
                 every step is whole and the last point is at the centre",
                (start - job.outer_radius_mm()) * 1e3
            ));
        }
        Self {
            job: job.name.clone(),
            surface: tool_path.surface().describe(),
            cut: job.part.cut.map(|c| c.describe()),
            dialect: job.output.style().name.to_string(),
            points: stats.points,
            revolutions: tool_path.spiral().revolutions(),
            start_radius_mm: start,
            nc_bytes,
            cycle_time_s: stats.total_angle() / TAU / job.machine.spindle_rpm * 60.0,
            max_dz_dtheta_um_per_deg: stats.max_slope * 1e3,
            max_dz_dtheta_at: Location::new(stats.max_slope_at.0, stats.max_slope_at.1),
            surface_pv_um: (stats.sag_max - stats.sag_min) * 1e3,
            z_min_mm: stats.z_min,
            z_max_mm: stats.z_max,
            arc_end_contacts: stats.arc_end,
            x_reversals: stats.x_reversals,
            max_x_acceleration_mm_s2: stats.max_x_curv * omega * omega,
            max_x_acceleration_at: Location::new(stats.max_x_curv_at.0, stats.max_x_curv_at.1),
            two_way_loops: stats.loops,
            two_way_loop_points: stats.loop_points,
            first_two_way_loop_at: stats.first_loop.map(|(r, t)| Location::new(r, t)),
            concave_zones,
            estimate: None,
            program: None,
            dynamics: None,
            shallow_concave_zones: reach.shallow_zones,
            unmeasured_concave_zones: reach.unmeasured_zones,
            part_edge: job.edge_description(),
            warnings,
        }
    }

    /// The report as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}

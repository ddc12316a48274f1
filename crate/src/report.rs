//! The plan report: figures gathered while the path streams by ([`Stats`]) and the checks, as a
//! serialisable [`Report`] (the command line's `--report` JSON and the page's report panel).
//!
//! `max_dz_dtheta_um_per_deg` is the largest commanded `|ΔZ/ΔC|` between consecutive points,
//! the slope the Z axis (or FTS) must follow; with the spindle speed it gives the Z velocity.
//! `surface_pv_um` is the peak-to-valley of the sag over the contact points. The cycle time is
//! the total spindle angle at the job's speed.

use crate::plan::{PathPoint, Planner};
use crate::reach::{ConcaveZone, Reach};
use serde::Serialize;
use std::f64::consts::TAU;

/// Running figures of a path.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    /// Points seen.
    pub points: u64,
    first_theta: f64,
    last: Option<PathPoint>,
    z_min: f64,
    z_max: f64,
    sag_min: f64,
    sag_max: f64,
    max_slope: f64,
    max_slope_at: (f64, f64),
    arc_end: u64,
    first_arc_end: Option<(f64, f64)>,
}

impl Stats {
    /// Adds one point.
    pub fn add(&mut self, p: &PathPoint) {
        match &self.last {
            None => {
                self.first_theta = p.theta;
                (self.z_min, self.z_max) = (p.z, p.z);
                (self.sag_min, self.sag_max) = (p.contact[2], p.contact[2]);
            }
            Some(q) => {
                let slope = ((p.z - q.z) / (p.theta - q.theta).to_degrees()).abs();
                if slope > self.max_slope {
                    self.max_slope = slope;
                    self.max_slope_at = (p.rho, p.theta);
                }
                self.z_min = self.z_min.min(p.z);
                self.z_max = self.z_max.max(p.z);
                self.sag_min = self.sag_min.min(p.contact[2]);
                self.sag_max = self.sag_max.max(p.contact[2]);
            }
        }
        if p.at_arc_end {
            self.arc_end += 1;
            self.first_arc_end.get_or_insert((p.rho, p.theta));
        }
        self.points += 1;
        self.last = Some(*p);
    }

    /// Total spindle angle, radians.
    pub fn total_angle(&self) -> f64 {
        self.last
            .map_or(0.0, |l| (l.theta - self.first_theta).abs())
    }
}

/// Where on the part: polar radius and angle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Location {
    /// Radius, mm.
    pub rho_mm: f64,
    /// Polar angle, degrees in [0, 360).
    pub theta_deg: f64,
}

impl Location {
    /// From ρ and a cumulative θ in radians.
    pub fn new(rho: f64, theta: f64) -> Self {
        Self {
            rho_mm: rho,
            theta_deg: theta.to_degrees().rem_euclid(360.0),
        }
    }
}

/// What a plan produced and what it found.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// Job name.
    pub job: String,
    /// The surface, restated.
    pub surface: String,
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
    /// Zones the nose cannot reach, deepest first (form error ≥ 0.1 nm, at most 500).
    pub concave_zones: Vec<ConcaveZone>,
    /// Further zones with a form error below 0.1 nm, counted only.
    pub shallow_concave_zones: usize,
    /// Findings an operator must read before cutting.
    pub warnings: Vec<String>,
}

impl Report {
    /// Assembles the report of a finished run.
    pub fn new(planner: &Planner, stats: &Stats, nc_bytes: u64, reach: Reach) -> Self {
        let concave_zones = reach.zones;
        let job = planner.job();
        let mut warnings = Vec::new();
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
        let start = planner.spiral().start_radius_mm();
        if start > job.outer_radius_mm() + 1e-12 {
            warnings.push(format!(
                "the path starts at radius {start:.6} mm, {:.3} um outside the outer radius, so that \
                 every step is whole and the last point is at the centre",
                (start - job.outer_radius_mm()) * 1e3
            ));
        }
        Self {
            job: job.name.clone(),
            surface: planner.surface().describe(),
            dialect: job.output.style().name.to_string(),
            points: stats.points,
            revolutions: planner.spiral().revolutions(),
            start_radius_mm: start,
            nc_bytes,
            cycle_time_s: stats.total_angle() / TAU / job.machine.spindle_rpm * 60.0,
            max_dz_dtheta_um_per_deg: stats.max_slope * 1e3,
            max_dz_dtheta_at: Location::new(stats.max_slope_at.0, stats.max_slope_at.1),
            surface_pv_um: (stats.sag_max - stats.sag_min) * 1e3,
            z_min_mm: stats.z_min,
            z_max_mm: stats.z_max,
            arc_end_contacts: stats.arc_end,
            concave_zones,
            shallow_concave_zones: reach.shallow_zones,
            warnings,
        }
    }

    /// The report as pretty JSON.
    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(self).unwrap_or_default()
    }
}

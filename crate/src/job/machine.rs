//! The machine model: spindle speed, the X and Z slides' velocity, acceleration and servo
//! bandwidth, the fast tool servo's (FTS, the W axis riding on Z) stroke, bandwidth and
//! acceleration, and the controller's block rate — the limits that decide which part of a
//! freeform path the slow slide servo (SSS) can follow and which needs the FTS (paper 000,
//! introduction and "Hybrid Hilbert transform/fast Fourier transform methodology for geometry
//! splitting": the FTS has a short stroke and a high bandwidth, the SSS a long stroke and a low
//! bandwidth).
//!
//! Everything but the spindle speed is optional: a limit that is not given is not checked, and
//! without `fts` the machine has no fast tool servo. The checks against these limits are in
//! [`crate::dynamics::axis_checks`] (velocity, acceleration, block rate, FTS stroke); the
//! bandwidths are used by the splitter.
//!
//! [`presets`] gives three example machines. Their numbers are plausible orders of magnitude
//! for the class of machine, chosen for this program's examples and tests; they are **not** any
//! vendor's specification: take the real figures from the machine's documentation.

use crate::field::{FieldError, positive};
use serde::{Deserialize, Serialize};

/// The fastest spindle accepted, rev/min: ten times the fastest air-bearing spindles of
/// diamond-turning lathes, so that a typo (rev/s for rev/min, a stray exponent) is caught.
pub const MAX_SPINDLE_RPM: f64 = 100_000.0;

/// The machine.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MachineSpec {
    /// Spindle speed, rev/min, > 0: sets the time per block (inverse-time feed) and the cycle
    /// time.
    pub spindle_rpm: f64,
    /// Blocks the controller executes per second, Hz, > 0; `None`: not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub block_rate_hz: Option<f64>,
    /// The X (radial) slide; `None`: not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub x_slide: Option<SlideSpec>,
    /// The Z (axial) slide, the slow slide servo; `None`: not checked.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub z_slide: Option<SlideSpec>,
    /// The fast tool servo (W axis); `None`: the machine has none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fts: Option<FtsSpec>,
}

/// Limits of a linear slide.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SlideSpec {
    /// Largest velocity, mm/min, > 0.
    pub velocity_mm_per_min: f64,
    /// Largest acceleration, mm/s², > 0.
    pub acceleration_mm_per_s2: f64,
    /// Servo (position loop) bandwidth, Hz, > 0: the highest frequency the slide follows.
    pub bandwidth_hz: f64,
}

/// Limits of a fast tool servo.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FtsSpec {
    /// Full stroke (peak to valley), µm, > 0.
    pub stroke_um: f64,
    /// Bandwidth, Hz, > 0: the highest frequency the servo follows.
    pub bandwidth_hz: f64,
    /// Largest acceleration, m/s², > 0.
    pub acceleration_m_per_s2: f64,
}

impl MachineSpec {
    /// A machine with only a spindle speed: no limit is checked, no FTS.
    pub fn spindle_only(spindle_rpm: f64) -> Self {
        Self {
            spindle_rpm,
            block_rate_hz: None,
            x_slide: None,
            z_slide: None,
            fts: None,
        }
    }

    /// Checks every value: each must be finite and > 0. Field paths are relative to the
    /// machine (`spindle_rpm`, `fts.stroke_um`); the job puts `machine.` in front.
    ///
    /// ```
    /// let mut m = spiralcam::job::machine::presets()[1].machine(600.0);
    /// m.validate().unwrap();
    /// m.fts.as_mut().unwrap().stroke_um = 0.0;
    /// assert_eq!(m.validate().unwrap_err().to_string(),
    ///            "fts.stroke_um = 0: must be a finite number > 0");
    /// ```
    pub fn validate(&self) -> Result<(), FieldError> {
        if positive("spindle_rpm", self.spindle_rpm)? > MAX_SPINDLE_RPM {
            return Err(FieldError::new(
                "spindle_rpm",
                self.spindle_rpm,
                format!(
                    "at most {MAX_SPINDLE_RPM} rev/min (no diamond-turning spindle runs faster)"
                ),
            ));
        }
        if let Some(rate) = self.block_rate_hz {
            positive("block_rate_hz", rate)?;
        }
        if let Some(slide) = &self.x_slide {
            slide.validate().map_err(|e| e.within("x_slide"))?;
        }
        if let Some(slide) = &self.z_slide {
            slide.validate().map_err(|e| e.within("z_slide"))?;
        }
        if let Some(fts) = &self.fts {
            fts.validate().map_err(|e| e.within("fts"))?;
        }
        Ok(())
    }
}

impl SlideSpec {
    /// Checks every value: finite and > 0.
    pub fn validate(&self) -> Result<(), FieldError> {
        positive("velocity_mm_per_min", self.velocity_mm_per_min)?;
        positive("acceleration_mm_per_s2", self.acceleration_mm_per_s2)?;
        positive("bandwidth_hz", self.bandwidth_hz)?;
        Ok(())
    }

    /// Largest velocity, mm/s.
    pub fn velocity_mm_per_s(&self) -> f64 {
        self.velocity_mm_per_min / 60.0
    }
}

impl FtsSpec {
    /// Checks every value: finite and > 0.
    pub fn validate(&self) -> Result<(), FieldError> {
        positive("stroke_um", self.stroke_um)?;
        positive("bandwidth_hz", self.bandwidth_hz)?;
        positive("acceleration_m_per_s2", self.acceleration_m_per_s2)?;
        Ok(())
    }

    /// Largest acceleration, mm/s².
    pub fn acceleration_mm_per_s2(&self) -> f64 {
        self.acceleration_m_per_s2 * 1e3
    }

    /// Full stroke, mm.
    pub fn stroke_mm(&self) -> f64 {
        self.stroke_um * 1e-3
    }
}

/// An example machine (see [`presets`]): everything of a [`MachineSpec`] but the spindle speed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MachinePreset {
    /// Short name, used by the page and the command line.
    pub key: &'static str,
    /// Name to show.
    pub label: &'static str,
    /// What the example stands for and where its numbers come from.
    pub description: &'static str,
    /// Controller blocks per second, Hz.
    pub block_rate_hz: f64,
    /// The X slide.
    pub x_slide: SlideSpec,
    /// The Z slide.
    pub z_slide: SlideSpec,
    /// The fast tool servo, if any.
    pub fts: Option<FtsSpec>,
}

impl MachinePreset {
    /// The machine at `spindle_rpm`, every limit set.
    pub fn machine(&self, spindle_rpm: f64) -> MachineSpec {
        MachineSpec {
            spindle_rpm,
            block_rate_hz: Some(self.block_rate_hz),
            x_slide: Some(self.x_slide),
            z_slide: Some(self.z_slide),
            fts: self.fts,
        }
    }
}

/// The slides of the example lathe, X and Z alike. A hydrostatic (or aerostatic) slide of a
/// diamond-turning lathe traverses at a few metres per minute: 2 000 mm/min (33 mm/s) is within
/// the 1–4 m/min usually quoted. Heavy slides that must not excite the machine are run at a
/// fraction of a g in slow slide servo: 2 000 mm/s² (0.2 g), within the 1–5 m/s² range. Their
/// position loops follow tens of hertz: 20 Hz lies between the two frequencies paper 000 found on
/// its compound eye (6.098 Hz and 47.03 Hz, split into a low-frequency part for the slide and a
/// high-frequency part for the FTS), so that example splits the same way on these presets.
const LATHE_SLIDE: SlideSpec = SlideSpec {
    velocity_mm_per_min: 2000.0,
    acceleration_mm_per_s2: 2000.0,
    bandwidth_hz: 20.0,
};

/// The three example machines: keys `sss_lathe`, `fts_500um_1khz`, `fts_70um_700hz`. Examples
/// of the orders of magnitude of each class, for the page's presets and the tests — **not** any
/// vendor's specification.
///
/// * `sss_lathe`: a two-slide diamond-turning lathe in slow slide servo, no FTS; slides as
///   described at their constant (2 000 mm/min, 2 000 mm/s², 20 Hz); 5 000 blocks/s, within the
///   1–10 kHz at which ultraprecision motion controllers execute short point-to-point blocks.
/// * `fts_500um_1khz`: the same lathe with a long-stroke piezo FTS: 500 µm stroke, 1 kHz
///   bandwidth, 500 m/s² (a full-stroke sine then reaches its acceleration limit at
///   √(a/A)/2π ≈ 225 Hz; smaller amplitudes use the full bandwidth); 10 000 blocks/s, as an FTS
///   is usually fed from a table at the servo's own rate.
/// * `fts_70um_700hz`: the same lathe with a short-stroke piezo FTS: 70 µm, 700 Hz, 300 m/s²
///   (full-stroke sine limited at ≈ 470 Hz); 10 000 blocks/s.
///
/// ```
/// let keys = spiralcam::job::machine::presets().map(|p| p.key);
/// assert_eq!(keys, ["sss_lathe", "fts_500um_1khz", "fts_70um_700hz"]);
/// ```
pub fn presets() -> [MachinePreset; 3] {
    [
        MachinePreset {
            key: "sss_lathe",
            label: "SSS lathe (example)",
            description: "Example of a two-slide diamond-turning lathe in slow slide servo, no \
                FTS: slides 2000 mm/min, 2000 mm/s2, 20 Hz; 5000 blocks/s. Orders of magnitude, \
                not any vendor's specification.",
            block_rate_hz: 5000.0,
            x_slide: LATHE_SLIDE,
            z_slide: LATHE_SLIDE,
            fts: None,
        },
        MachinePreset {
            key: "fts_500um_1khz",
            label: "FTS 500 um, 1 kHz (example)",
            description: "Example of the same lathe with a long-stroke piezo fast tool servo: \
                500 um stroke, 1 kHz, 500 m/s2; 10000 blocks/s. Orders of magnitude, not any \
                vendor's specification.",
            block_rate_hz: 10_000.0,
            x_slide: LATHE_SLIDE,
            z_slide: LATHE_SLIDE,
            fts: Some(FtsSpec {
                stroke_um: 500.0,
                bandwidth_hz: 1000.0,
                acceleration_m_per_s2: 500.0,
            }),
        },
        MachinePreset {
            key: "fts_70um_700hz",
            label: "FTS 70 um, 700 Hz (example)",
            description: "Example of the same lathe with a short-stroke piezo fast tool servo: \
                70 um stroke, 700 Hz, 300 m/s2; 10000 blocks/s. Orders of magnitude, not any \
                vendor's specification.",
            block_rate_hz: 10_000.0,
            x_slide: LATHE_SLIDE,
            z_slide: LATHE_SLIDE,
            fts: Some(FtsSpec {
                stroke_um: 70.0,
                bandwidth_hz: 700.0,
                acceleration_m_per_s2: 300.0,
            }),
        },
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Job;

    #[test]
    fn presets_validate_and_round_trip_through_a_job() {
        for preset in presets() {
            let machine = preset.machine(750.0);
            machine.validate().unwrap();
            let mut job = Job::default_job();
            job.machine = machine.clone();
            job.validate().unwrap();
            assert_eq!(Job::from_json(&job.to_json()).unwrap().machine, machine);
        }
        assert!(presets()[0].fts.is_none());
        assert_eq!(presets()[1].fts.map(|f| f.stroke_um), Some(500.0));
        assert_eq!(presets()[2].fts.map(|f| f.bandwidth_hz), Some(700.0));
    }

    #[test]
    fn a_spindle_only_machine_reads_and_writes_as_before() {
        let m: MachineSpec = serde_json::from_str(r#"{"spindle_rpm": 800}"#).unwrap();
        assert_eq!(m, MachineSpec::spindle_only(800.0));
        assert_eq!(
            serde_json::to_string(&m).unwrap(),
            r#"{"spindle_rpm":800.0}"#
        );
    }

    /// The example in crate/docs/job-format.md is the `fts_70um_700hz` preset.
    #[test]
    fn the_documented_example_is_the_preset() {
        let text = r#"{ "spindle_rpm": 300.0, "block_rate_hz": 10000.0,
             "x_slide": { "velocity_mm_per_min": 2000.0, "acceleration_mm_per_s2": 2000.0, "bandwidth_hz": 20.0 },
             "z_slide": { "velocity_mm_per_min": 2000.0, "acceleration_mm_per_s2": 2000.0, "bandwidth_hz": 20.0 },
             "fts": { "stroke_um": 70.0, "bandwidth_hz": 700.0, "acceleration_m_per_s2": 300.0 } }"#;
        let m: MachineSpec = serde_json::from_str(text).unwrap();
        assert_eq!(m, presets()[2].machine(300.0));
    }

    #[test]
    fn unknown_fields_are_rejected() {
        let text = r#"{"spindle_rpm": 800, "fts": {"stroke_um": 70, "bandwidth_hz": 700,
            "acceleration_m_per_s2": 300, "stroke_mm": 1}}"#;
        let e = serde_json::from_str::<MachineSpec>(text).unwrap_err();
        assert!(e.to_string().contains("stroke_mm"), "{e}");
    }

    /// Every limit, set to each kind of bad value, is named with its full path by the job.
    #[test]
    fn every_bad_value_is_named_by_its_path() {
        let paths = [
            "spindle_rpm",
            "block_rate_hz",
            "x_slide.velocity_mm_per_min",
            "x_slide.acceleration_mm_per_s2",
            "x_slide.bandwidth_hz",
            "z_slide.velocity_mm_per_min",
            "z_slide.acceleration_mm_per_s2",
            "z_slide.bandwidth_hz",
            "fts.stroke_um",
            "fts.bandwidth_hz",
            "fts.acceleration_m_per_s2",
        ];
        for (k, path) in paths.iter().enumerate() {
            for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
                let mut m = presets()[1].machine(600.0);
                let v = match k {
                    0 => &mut m.spindle_rpm,
                    1 => m.block_rate_hz.as_mut().unwrap(),
                    2 => &mut m.x_slide.as_mut().unwrap().velocity_mm_per_min,
                    3 => &mut m.x_slide.as_mut().unwrap().acceleration_mm_per_s2,
                    4 => &mut m.x_slide.as_mut().unwrap().bandwidth_hz,
                    5 => &mut m.z_slide.as_mut().unwrap().velocity_mm_per_min,
                    6 => &mut m.z_slide.as_mut().unwrap().acceleration_mm_per_s2,
                    7 => &mut m.z_slide.as_mut().unwrap().bandwidth_hz,
                    8 => &mut m.fts.as_mut().unwrap().stroke_um,
                    9 => &mut m.fts.as_mut().unwrap().bandwidth_hz,
                    _ => &mut m.fts.as_mut().unwrap().acceleration_m_per_s2,
                };
                *v = bad;
                let mut job = Job::default_job();
                job.machine = m;
                assert_eq!(
                    job.validate().unwrap_err().to_string(),
                    format!("machine.{path} = {bad}: must be a finite number > 0")
                );
            }
        }
    }
}

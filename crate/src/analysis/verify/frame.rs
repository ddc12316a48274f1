//! The part's frame of a program's machine positions: the inverse of the writers' conventions
//! ([`crate::nc::Conventions`]: `X = x_sign·ρ`, `Z = z_sign·z_tip`, `C = c_sign·θ`, the servo's
//! word W adding to Z), with X on either side of the spindle axis: a point at X < x_sign·0 (the
//! tool past the axis) is the point at radius |X| half a turn further on, `(|X|, θ + π)`.
//!
//! C is unwrapped as it is read: each move's ΔC is taken modulo 360° into (−180°, 180°], so a
//! program that wraps C to [0, 360) and one that writes it cumulative give the same continuous
//! θ (no cutting block turns the spindle half a turn at once).

use crate::job::OutputSpec;
use crate::nc::Conventions;
use crate::nc::reader::{MachineAxis, Position};

/// A machine position in the part's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PartPoint {
    /// Radius, mm, ≥ 0.
    pub rho: f64,
    /// Polar angle, radians, continuous along the program.
    pub theta: f64,
    /// The commanded tool tip's height, mm (Z plus the servo's W, signs undone).
    pub z: f64,
    /// The tool is past the spindle axis (the program's X on the other side).
    pub past_axis: bool,
}

/// The conventions a program is read with, and the continuous C.
#[derive(Debug, Clone)]
pub struct PartFrame {
    conventions: Conventions,
    servo: Option<MachineAxis>,
    /// The last C read, degrees as written, and the continuous C, degrees.
    c: Option<(f64, f64)>,
}

impl PartFrame {
    /// The frame of programs written with `output`'s conventions.
    pub fn new(output: &OutputSpec) -> Self {
        let conventions = output.conventions();
        Self {
            servo: MachineAxis::from_letter(conventions.fts_word),
            conventions,
            c: None,
        }
    }

    /// The servo's axis (the job's `output.fts_word`, or the dialect's).
    pub fn servo(&self) -> Option<MachineAxis> {
        self.servo
    }

    /// The continuous C, degrees, after reading C `c_deg` as written.
    pub fn unwrap_c(&mut self, c_deg: f64) -> f64 {
        let continuous = match self.c {
            None => c_deg,
            Some((last, cont)) => cont + half_turn_step(c_deg - last),
        };
        self.c = Some((c_deg, continuous));
        continuous
    }

    /// The continuous C of the last position read, degrees.
    pub fn continuous_c(&self) -> f64 {
        self.c.map_or(0.0, |c| c.1)
    }

    /// `position` in the part's frame, its C already unwrapped to `c_deg` (continuous).
    pub fn part_point(&self, position: &Position, c_deg: f64) -> PartPoint {
        let k = &self.conventions;
        let w = self.servo.map_or(0.0, |a| position.get(a));
        let signed = position.x() * k.x_sign;
        let theta = (c_deg * k.c_sign).to_radians();
        let past_axis = signed < 0.0;
        PartPoint {
            rho: signed.abs(),
            theta: if past_axis {
                theta + std::f64::consts::PI
            } else {
                theta
            },
            z: (position.z() + w) * k.z_sign,
            past_axis,
        }
    }

    /// The servo's share W of `position`, mm (0 without a servo word).
    pub fn servo_value(&self, position: &Position) -> f64 {
        self.servo.map_or(0.0, |a| position.get(a))
    }
}

/// `d` degrees taken modulo 360 into (−180, 180].
pub fn half_turn_step(d: f64) -> f64 {
    let m = d.rem_euclid(360.0);
    if m > 180.0 { m - 360.0 } else { m }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::Dialect;

    #[test]
    fn wrapped_and_cumulative_c_give_the_same_continuous_angle() {
        let mut wrapped = PartFrame::new(&OutputSpec::default());
        let mut cumulative = wrapped.clone();
        for k in 0..2000 {
            let c = k as f64 * 0.7;
            let a = wrapped.unwrap_c(c.rem_euclid(360.0));
            let b = cumulative.unwrap_c(c);
            assert!(
                (a - c).abs() < 1e-9 && (b - c).abs() < 1e-9,
                "{k}: {a} {b} {c}"
            );
        }
        assert_eq!(half_turn_step(-359.5), 0.5);
        assert_eq!(half_turn_step(180.0), 180.0);
    }

    #[test]
    fn x_past_the_axis_is_half_a_turn_on_and_signs_are_undone() {
        let output = OutputSpec {
            dialect: Dialect::Precitech,
            z_sign: Some(-1),
            ..OutputSpec::default()
        };
        let frame = PartFrame::new(&output);
        let mut p = Position::default();
        p.0[0] = -2.0;
        p.0[2] = 0.5;
        p.0[MachineAxis::W as usize] = 0.25;
        let q = frame.part_point(&p, 30.0);
        assert_eq!((q.rho, q.past_axis), (2.0, false));
        assert!((q.theta - 30f64.to_radians()).abs() < 1e-15);
        assert_eq!(q.z, -0.75);
        p.0[0] = 2.0;
        let q = frame.part_point(&p, 30.0);
        assert_eq!((q.rho, q.past_axis), (2.0, true));
        assert!((q.theta - 210f64.to_radians()).abs() < 1e-15);
    }
}

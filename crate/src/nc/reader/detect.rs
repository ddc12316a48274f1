//! What a program's text shows about its conventions, detected from what was read, never
//! assumed: the units it states, whether C is wrapped to [0, 360) or cumulative, on which side
//! of the spindle X works, and which dialect the text looks like.
//!
//! - C: cumulative if any commanded C lies outside [0, 360); wrapped if all lie inside and some
//!   feed move jumps by more than 180° (a wrapped program crossing 0°, which a spiral written
//!   cumulatively never does in one block; the count is reported, as a program that turns C by
//!   more than half a turn in one feed block would read as wrapped too); undetermined if neither
//!   (less than a turn: both readings agree).
//! - Dialect (a guess with its evidence): LinuxCNC ISO shows `o` words, `G20`/`G21` or `M2`;
//!   the Fanuc-style controls (Moore, Precitech) show `G70`/`G71`, `WHILE`/`IF`/`GOTO`, `M98`;
//!   among those, motion blocks without a G word (bare `C X Z`) are the Moore style, `G1` on
//!   every block the Precitech style (spiralcam's dialects, README "NC dialects").

use super::block::Code;
use super::modal::{AxisSet, MoveKind, Position, Units};
use crate::job::Dialect;

/// How C was written.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CWrapping {
    /// No move commands C.
    NoC,
    /// Every C in [0, 360) and the program crosses 0° in a block.
    Wrapped,
    /// Some C outside [0, 360).
    Cumulative,
    /// Every C in [0, 360) and no crossing: less than a turn, either reading.
    Undetermined,
}

/// The dialect the text looks like, with what shows it.
#[derive(Debug, Clone, PartialEq)]
pub struct DialectGuess {
    /// The dialect, if the evidence points to one.
    pub dialect: Option<Dialect>,
    /// What was seen, in words.
    pub evidence: Vec<String>,
}

/// What the reader saw of a program.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    /// Lines read: executed or passed over, every pass of every loop counted.
    pub lines_read: u64,
    /// Rapid (G0) moves.
    pub rapid_moves: u64,
    /// Linear (G1) moves.
    pub linear_moves: u64,
    /// Arc (G2/G3) moves.
    pub arc_moves: u64,
    /// Axes commanded anywhere.
    pub axes: AxisSet,
    /// The units the program states first (`None`: it never says; mm were assumed).
    pub units: Option<Units>,
    /// The program states both units somewhere.
    pub mixed_units: bool,
    /// How C was written.
    pub c: CWrapping,
    /// Smallest and largest commanded C, degrees.
    pub c_range: Option<(f64, f64)>,
    /// Feed moves that turn C by more than 180° at once (the evidence of wrapping).
    pub c_half_turn_jumps: u64,
    /// Feed moves with X < 0 and with X > 0 (the tool past the spindle axis, or on its side).
    pub x_negative: u64,
    /// See [`Summary::x_negative`].
    pub x_positive: u64,
    /// The dialect it looks like.
    pub dialect: DialectGuess,
}

/// Features the interpreter reports as it reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// An `o` word (LinuxCNC).
    OWord,
    /// `WHILE`, `DO`, `END`, `IF`, `GOTO` (Fanuc custom macro).
    FanucMacro,
    /// `M98` (Fanuc-style call).
    M98,
}

/// Collects the evidence while the program runs.
#[derive(Debug, Default, Clone)]
pub struct Detector {
    rapid: u64,
    linear: u64,
    arcs: u64,
    axes: AxisSet,
    units: Option<Units>,
    mixed: bool,
    iso_codes: u64,
    fanuc_codes: u64,
    o_words: u64,
    macros: u64,
    m98: u64,
    m2: u64,
    m30: u64,
    bare: u64,
    with_g: u64,
    c_min: f64,
    c_max: f64,
    c_seen: bool,
    c_jumps: u64,
    last_c: Option<f64>,
    x_neg: u64,
    x_pos: u64,
}

impl Detector {
    /// Moves so far.
    pub fn moves(&self) -> u64 {
        self.rapid + self.linear + self.arcs
    }

    /// A G or M code on a line that ran.
    pub fn code(&mut self, code: Code) {
        let units = match (code.letter, code.tenths) {
            (b'G', 200 | 700) => Some(Units::Inches),
            (b'G', 210 | 710) => Some(Units::Millimetres),
            (b'M', 20) => {
                self.m2 += 1;
                None
            }
            (b'M', 300) => {
                self.m30 += 1;
                None
            }
            _ => None,
        };
        if units.is_some() {
            if code.tenths < 700 {
                self.iso_codes += 1;
            } else {
                self.fanuc_codes += 1;
            }
        }
        if let Some(u) = units {
            match self.units {
                None => self.units = Some(u),
                Some(first) if first != u => self.mixed = true,
                _ => {}
            }
        }
    }

    /// A control feature.
    pub fn feature(&mut self, f: Feature) {
        match f {
            Feature::OWord => self.o_words += 1,
            Feature::FanucMacro => self.macros += 1,
            Feature::M98 => self.m98 += 1,
        }
    }

    /// A move to `target`, commanding `words`; `bare` when its line has no motion G code.
    pub fn motion(&mut self, kind: MoveKind, target: &Position, words: AxisSet, bare: bool) {
        for a in words.iter() {
            self.axes.insert(a);
        }
        let feed = match kind {
            MoveKind::Rapid => {
                self.rapid += 1;
                false
            }
            MoveKind::Linear => {
                self.linear += 1;
                true
            }
            MoveKind::Arc { .. } => {
                self.arcs += 1;
                true
            }
        };
        if feed {
            if bare {
                self.bare += 1;
            } else {
                self.with_g += 1;
            }
            if target.x() < 0.0 {
                self.x_neg += 1;
            } else if target.x() > 0.0 {
                self.x_pos += 1;
            }
        }
        if words.contains(super::modal::MachineAxis::C) {
            let c = target.c();
            if !self.c_seen {
                (self.c_min, self.c_max, self.c_seen) = (c, c, true);
            }
            self.c_min = self.c_min.min(c);
            self.c_max = self.c_max.max(c);
            if let Some(prev) = self.last_c
                && feed
                && (c - prev).abs() > 180.0
            {
                self.c_jumps += 1;
            }
            self.last_c = Some(c);
        }
    }

    /// The summary so far.
    pub fn summary(&self, lines_read: u64) -> Summary {
        let c = if !self.c_seen {
            CWrapping::NoC
        } else if self.c_min < 0.0 || self.c_max >= 360.0 {
            CWrapping::Cumulative
        } else if self.c_jumps > 0 {
            CWrapping::Wrapped
        } else {
            CWrapping::Undetermined
        };
        Summary {
            lines_read,
            rapid_moves: self.rapid,
            linear_moves: self.linear,
            arc_moves: self.arcs,
            axes: self.axes,
            units: self.units,
            mixed_units: self.mixed,
            c,
            c_range: self.c_seen.then_some((self.c_min, self.c_max)),
            c_half_turn_jumps: self.c_jumps,
            x_negative: self.x_neg,
            x_positive: self.x_pos,
            dialect: self.guess(),
        }
    }

    fn guess(&self) -> DialectGuess {
        let mut evidence = Vec::new();
        let mut note = |n: u64, what: &str| {
            if n > 0 {
                evidence.push(format!("{what} ({n})"));
            }
        };
        note(self.o_words, "o words (LinuxCNC)");
        note(self.iso_codes, "G20/G21 units (ISO)");
        note(self.m2, "M2 end (LinuxCNC)");
        note(self.fanuc_codes, "G70/G71 units (Fanuc style)");
        note(self.macros, "WHILE/IF/GOTO macros (Fanuc style)");
        note(self.m98, "M98 calls (Fanuc style)");
        note(self.m30, "M30 end");
        note(self.bare, "feed blocks without a G word (Moore style)");
        note(self.with_g, "feed blocks with G1 (ISO or Precitech style)");
        let iso = self.o_words + self.iso_codes + self.m2;
        let fanuc = self.fanuc_codes + self.macros + self.m98;
        let dialect = if iso > 0 && fanuc == 0 {
            Some(Dialect::Iso)
        } else if fanuc > 0 && iso == 0 {
            if self.bare > self.with_g {
                Some(Dialect::Moore)
            } else {
                Some(Dialect::Precitech)
            }
        } else {
            None
        };
        if iso > 0 && fanuc > 0 {
            evidence.push("both ISO and Fanuc-style features: no single dialect".into());
        }
        DialectGuess { dialect, evidence }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::reader::modal::MachineAxis;

    fn at(x: f64, c: f64) -> Position {
        let mut p = Position::default();
        p.0[0] = x;
        p.0[5] = c;
        p
    }

    fn xc() -> AxisSet {
        let mut s = AxisSet::default();
        s.insert(MachineAxis::X);
        s.insert(MachineAxis::C);
        s
    }

    #[test]
    fn c_wrapping_is_detected_from_the_values() {
        let run = |cs: &[f64]| {
            let mut d = Detector::default();
            for &c in cs {
                d.motion(MoveKind::Linear, &at(1.0, c), xc(), true);
            }
            d.summary(0).c
        };
        assert_eq!(run(&[]), CWrapping::NoC);
        assert_eq!(run(&[350.0, 355.0, 0.5, 5.0]), CWrapping::Wrapped);
        assert_eq!(run(&[350.0, 355.0, 360.5]), CWrapping::Cumulative);
        assert_eq!(run(&[10.0, -5.0]), CWrapping::Cumulative);
        assert_eq!(run(&[10.0, 100.0, 190.0, 280.0]), CWrapping::Undetermined);
    }

    #[test]
    fn dialects_are_guessed_from_features() {
        let mut iso = Detector::default();
        iso.code(Code::g(210));
        iso.motion(MoveKind::Linear, &at(1.0, 0.0), xc(), false);
        iso.code(Code::m(20));
        assert_eq!(iso.summary(0).dialect.dialect, Some(Dialect::Iso));
        assert_eq!(iso.summary(0).units, Some(Units::Millimetres));
        let mut moore = Detector::default();
        moore.code(Code::g(710));
        moore.motion(MoveKind::Linear, &at(1.0, 0.0), xc(), false);
        moore.motion(MoveKind::Linear, &at(1.0, 1.0), xc(), true);
        moore.motion(MoveKind::Linear, &at(1.0, 2.0), xc(), true);
        assert_eq!(moore.summary(0).dialect.dialect, Some(Dialect::Moore));
        let mut pt = Detector::default();
        pt.code(Code::g(710));
        pt.motion(MoveKind::Linear, &at(-1.0, 0.0), xc(), false);
        let s = pt.summary(0);
        assert_eq!(s.dialect.dialect, Some(Dialect::Precitech));
        assert_eq!((s.x_negative, s.x_positive), (1, 0));
        let mut both = Detector::default();
        both.code(Code::g(210));
        both.code(Code::g(700));
        let s = both.summary(0);
        assert_eq!(s.dialect.dialect, None);
        assert!(s.mixed_units);
    }
}

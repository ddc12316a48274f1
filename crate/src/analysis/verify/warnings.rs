//! What a program does that the verification reads but does not interpret: machine M codes,
//! accepted controller codes, stops, dwells, constant surface speed, diameter mode, block
//! delete, axes other than X, Z, C and the servo's, units never stated. Each kind is reported
//! once with how often and where first, at most [`MAX_KINDS`] kinds.

use crate::nc::reader::{Change, EventKind, Location};
use std::collections::BTreeMap;

/// The most kinds of warnings kept.
pub const MAX_KINDS: usize = 100;

/// M codes the verification understands as having no effect on the path: spindle on and off,
/// tool change, coolant, program end and subprogram calls (the reader runs those).
const QUIET_M: [u16; 10] = [30, 40, 50, 60, 70, 80, 90, 20, 300, 980];

/// Warnings, by kind.
#[derive(Debug, Clone, Default)]
pub struct Warnings {
    kinds: BTreeMap<String, (u64, Location)>,
    dropped: u64,
}

impl Warnings {
    /// Notes `what`, written at `at`.
    pub fn note(&mut self, what: String, at: &Location) {
        if let Some(k) = self.kinds.get_mut(&what) {
            k.0 += 1;
        } else if self.kinds.len() < MAX_KINDS {
            self.kinds.insert(what, (1, at.clone()));
        } else {
            self.dropped += 1;
        }
    }

    /// Notes what an event means for the verification, if anything.
    pub fn event(&mut self, kind: &EventKind, at: &Location) {
        let what = match kind {
            EventKind::Change(Change::M(code)) if !QUIET_M.contains(&code.tenths) => {
                format!("{code}: a machine code, not interpreted")
            }
            EventKind::Change(Change::Accepted(code)) => {
                format!("{code}: a controller code accepted without effect")
            }
            EventKind::Change(Change::Stop(code)) => format!("{code}: a program stop"),
            EventKind::Change(Change::Dwell(_)) => {
                "G4 dwell: not counted in the cycle time".to_string()
            }
            EventKind::Change(Change::ConstantSurfaceSpeed(true)) => {
                "G96 constant surface speed: the spindle speed is not followed".to_string()
            }
            EventKind::Change(Change::DiameterMode(true)) => {
                "G7 diameter mode: X words are read as diameters".to_string()
            }
            EventKind::BlockDelete { executed } => format!(
                "block delete (/) line {}",
                if *executed { "run" } else { "skipped" }
            ),
            _ => return,
        };
        self.note(what, at);
    }

    /// The warnings as lines: what, how often, where first.
    pub fn lines(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .kinds
            .iter()
            .map(|(what, (n, at))| {
                let times = if *n == 1 {
                    String::new()
                } else {
                    format!(" ({n} times)")
                };
                format!("{}:{}: {what}{times}", at.file, at.line)
            })
            .collect();
        if self.dropped > 0 {
            out.push(format!(
                "{} more warnings of other kinds not listed",
                self.dropped
            ));
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::nc::reader::Code;
    use std::sync::Arc;

    #[test]
    fn kinds_are_counted_once_with_their_first_place() {
        let mut w = Warnings::default();
        let at = |line| Location {
            file: Arc::from("p.nc"),
            line,
        };
        let m26 = EventKind::Change(Change::M(Code::parse("M26.1").unwrap()));
        w.event(&m26, &at(4));
        w.event(&m26, &at(9));
        w.event(
            &EventKind::Change(Change::M(Code::parse("M3").unwrap())),
            &at(5),
        );
        assert_eq!(
            w.lines(),
            vec!["p.nc:4: M26.1: a machine code, not interpreted (2 times)"]
        );
    }
}

//! The first read of a program: its moves counted, whether any feed move turns C, and its
//! passes, so that the verification knows, before it starts, which moves cut (the rule
//! [`CuttingRule`]), which pass is the last (the one the accuracy analysis follows) and how many
//! moves it will read (its progress). Reading a program costs a fraction of verifying it (the
//! reader runs at about 0.6 µs a line natively; each cutting point costs a compensation).

use super::VerifyError;
use crate::nc::reader::{Move, MoveKind, Position, Reader, Step};
use crate::progress::{PROGRESS_EVERY, Progress, ProgressFn, Stage};

/// Which moves cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CuttingRule {
    /// A feed move (G1, G2, G3) that turns C: the rule of any program that turns C.
    TurnsC,
    /// A feed move that moves X: the rule of a 2-D turning program (no move turns C).
    MovesX,
}

impl CuttingRule {
    /// Whether `m`, from `from`, cuts.
    pub fn cuts(self, from: &Position, m: &Move) -> bool {
        if m.kind == MoveKind::Rapid {
            return false;
        }
        match self {
            CuttingRule::TurnsC => m.target.c() != from.c(),
            CuttingRule::MovesX => m.target.x() != from.x(),
        }
    }

    /// In words, for the report.
    pub fn describe(self) -> &'static str {
        match self {
            CuttingRule::TurnsC => "feed moves that turn C",
            CuttingRule::MovesX => "feed moves in X (the program never turns C: 2-D turning)",
        }
    }
}

/// Passes of consecutive cutting moves, counted under one rule.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct PassCount {
    /// Passes seen.
    pub passes: u64,
    /// Cutting moves in all.
    pub moves: u64,
    /// Cutting moves of the last pass.
    pub last: u64,
    in_pass: bool,
}

impl PassCount {
    /// Adds a move that cuts or not; returns whether it starts a pass.
    pub fn add(&mut self, cuts: bool) -> bool {
        let starts = cuts && !self.in_pass;
        if starts {
            self.passes += 1;
            self.last = 0;
        }
        if cuts {
            self.moves += 1;
            self.last += 1;
        }
        self.in_pass = cuts;
        starts
    }
}

/// What the first read found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Scan {
    /// Moves read.
    pub moves: u64,
    /// The rule: [`CuttingRule::TurnsC`] when any feed move turns C.
    pub rule: CuttingRule,
    /// The passes under that rule.
    pub passes: PassCount,
}

/// Reads `reader` through; `progress` sees the moves read ([`Stage::Scan`], no total).
pub fn scan(mut reader: Reader<'_>, progress: &mut ProgressFn) -> Result<Scan, VerifyError> {
    let mut from = reader_start(&reader);
    let (mut by_c, mut by_x) = (PassCount::default(), PassCount::default());
    let mut moves = 0u64;
    while let Some(step) = reader.next_step()? {
        let Step::Move(m) = step else { continue };
        by_c.add(CuttingRule::TurnsC.cuts(&from, &m));
        by_x.add(CuttingRule::MovesX.cuts(&from, &m));
        from = m.target;
        moves += 1;
        if moves.is_multiple_of(PROGRESS_EVERY)
            && progress(Progress {
                stage: Stage::Scan,
                done: moves,
                total: 0,
            })
            .is_break()
        {
            return Err(VerifyError::Cancelled);
        }
    }
    let (rule, passes) = if by_c.moves > 0 {
        (CuttingRule::TurnsC, by_c)
    } else {
        (CuttingRule::MovesX, by_x)
    };
    Ok(Scan {
        moves,
        rule,
        passes,
    })
}

/// Where the machine is when `reader`'s program starts.
pub fn reader_start(reader: &Reader<'_>) -> Position {
    reader.modal().position
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_are_runs_of_cutting_moves() {
        let mut p = PassCount::default();
        let starts: Vec<bool> = [
            false, true, true, false, true, false, false, true, true, true,
        ]
        .iter()
        .map(|&c| p.add(c))
        .collect();
        assert_eq!(p.passes, 3);
        assert_eq!(p.moves, 6);
        assert_eq!(p.last, 3);
        assert_eq!(starts.iter().filter(|s| **s).count(), 3);
        assert!(starts[1] && starts[4] && starts[7]);
    }
}

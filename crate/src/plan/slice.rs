//! A plan in slices: the stretch of the path between two indices planned alone, its program
//! text, its report figures and its display copy joined in order with the others' into exactly
//! what one walk gives (the page's Web Workers each plan a slice; the command line walks the
//! whole path as one slice). A point's position and compensation depend on its index alone
//! ([`crate::tool::ToolPath::for_each_pair_in`]); a block's text depends on its point and the
//! two before it (the C step that sets F under `G93`, and the F last written), so each slice
//! also computes the two points before it, as context, without writing them. The first slice
//! writes the header and the approach, the one in which the path ends the retract and the end.

use super::{Extras, PlanError, Planner, Sinks};
use crate::display::DisplayPath;
use crate::nc::{Header, NcWriter};
use crate::progress::{ProgressFn, Stage};
use crate::report::Stats;
use crate::tool::Batched;
use serde::{Deserialize, Serialize};
use std::io::Write;
use std::ops::Range;

/// What a slice of a plan gives besides its program text and display copy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanSlice {
    /// Index of the slice's first point.
    pub first: u64,
    /// The report's figures over the slice ([`Stats::merge`] joins them).
    pub stats: Stats,
    /// Bytes of program text the slice wrote.
    pub nc_bytes: u64,
    /// The path ends in this slice.
    pub ended: bool,
}

impl Planner {
    /// Whether the job can be planned in slices: not a program with passes (its frame and child
    /// programs are written around whole passes), nor a path with machine dynamics (its split
    /// filters the whole path at once), nor a space spiral (its points are held in memory, 16
    /// bytes each, by every planner of it). The error says which.
    pub fn slicing(&self) -> Result<(), &'static str> {
        if self.job().program.is_some() {
            return Err("a program with passes is written in one piece");
        }
        if crate::dynamics::wanted(self.job()) {
            return Err("the machine dynamics need the whole path at once");
        }
        if matches!(
            self.job().strategy.sampling,
            crate::job::Sampling::SpaceSpiral { .. }
        ) {
            return Err("a space spiral is held in memory by the planner that samples it");
        }
        Ok(())
    }

    /// Plans the points whose index lies in `range` (its end may lie past the path's): writes
    /// their program text into `nc` (the header first in the first slice, the end in the one
    /// where the path ends) and their display copy into `display` ([`DisplayPath::starting_at`]
    /// the range's start). Concatenated in order, the slices' texts are the whole program byte
    /// for byte, and their figures merge into the whole path's.
    pub fn run_slice<'a>(
        &self,
        range: Range<u64>,
        nc: Option<&'a mut dyn Write>,
        display: Option<&'a mut DisplayPath>,
        progress: &mut ProgressFn,
    ) -> Result<PlanSlice, PlanError> {
        self.slicing()
            .map_err(|why| crate::field::FieldError::new("program", "sliced", why))?;
        let header = (range.start == 0).then(|| self.header());
        let sinks = Sinks {
            nc,
            display,
            ..Default::default()
        };
        self.walk(range, header.as_ref(), sinks, progress)
    }

    /// Streams the points of `range` into the sinks: the header into the program when given
    /// (the first slice), the end when the path ends in the range. Each batch's blocks and
    /// figures are made on the worker that computes it ([`Planner::format_batch`]); this thread
    /// writes them and the CSV, the servo's table and the display's copy in order.
    pub(super) fn walk(
        &self,
        range: Range<u64>,
        header: Option<&Header>,
        sinks: Sinks,
        progress: &mut ProgressFn,
    ) -> Result<PlanSlice, PlanError> {
        let mut counter = std::io::sink();
        let nc_out: &mut dyn Write = match sinks.nc {
            Some(w) => w,
            None => &mut counter,
        };
        let output = &self.job().output;
        let mut nc = match header {
            Some(h) => NcWriter::new(nc_out, output, h)?,
            None => NcWriter::resume(nc_out, output, self.job().machine.spindle_rpm),
        };
        let mut extras = Extras::new(
            self.job(),
            sinks.csv,
            sinks.fts_table,
            sinks.display,
            sinks.z_slide,
        )?;
        let z_slide = sinks.z_slide;
        let first = range.start;
        let walked = self.path.for_each_batch_in(
            range,
            Stage::Path,
            progress,
            |batch, out: &mut FormattedBatch| self.format_batch(batch, z_slide, out),
            &mut |batch, out: &FormattedBatch| {
                // The context comes first in a batch, the points handed on after it.
                let handed_on = &batch[batch.partition_point(|b| !b.handed_on)..];
                if let Some(last) = handed_on.last() {
                    nc.append(&out.nc, last.point.z)?;
                }
                extras.merge(out.stats.clone());
                if extras.copies_wanted() {
                    handed_on.iter().try_for_each(|b| extras.copies(&b.point))?;
                }
                Ok(())
            },
        )?;
        let stats = extras.finish()?;
        let ends = walked.ended && (stats.points > 0 || first == 0);
        Ok(PlanSlice {
            first,
            nc_bytes: nc.finish_slice(ends)?,
            stats,
            ended: walked.ended,
        })
    }

    /// The blocks of a batch's points handed on (after its context, taken as the writer of the
    /// whole program would: [`NcWriter::context`]) and their figures.
    fn format_batch(
        &self,
        batch: &[Batched],
        z_slide: Option<&[f64]>,
        out: &mut FormattedBatch,
    ) -> Result<(), PlanError> {
        out.nc.clear();
        out.stats = Stats::default();
        let spec = &self.job().output;
        let mut nc = NcWriter::resume(&mut out.nc, spec, self.job().machine.spindle_rpm);
        for b in batch {
            let p = &b.point;
            let slide = super::slide_of(z_slide, p)?;
            if !b.handed_on {
                nc.context(p, slide)?;
                continue;
            }
            match slide {
                None => nc.point(p)?,
                Some(z) => nc.point_split(p, z)?,
            }
            out.stats.add(p);
            if b.folds {
                out.stats.add_loop_point(p);
            }
        }
        Ok(())
    }
}

/// A batch's program text and figures, made on a worker.
#[derive(Default)]
struct FormattedBatch {
    nc: Vec<u8>,
    stats: Stats,
}

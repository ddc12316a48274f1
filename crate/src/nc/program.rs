//! Programs an operator runs as written (issue 12): the set-up words, the passes with their
//! stock, a controller loop or every pass written out, a staged approach, and child programs
//! past a size limit. The cutting blocks themselves are [`Blocks`]'.
//!
//! The shape, in the Moore style (Fanuc macro B; Precitech style alike; ISO in LinuxCNC's
//! o-words, `#<named>` variables and `o<name> call`):
//!
//! ```text
//! (header comments)
//! G71 G18 G90 G40 G94              preamble
//! G55                              program.work_offset
//! T0303                            program.tool
//! M26.1                            program.c_axis_on
//! G0 Z20.000000                    program.safe_z_mm
//! #100 = 3                         a controller loop: passes of the group,
//! #101 = 0.005000                  its depth of cut (mm),
//! #102 = 0.015000                  the stock before it (mm)
//! #103 = 0                         and a counter
//! WHILE [#103 LT #100] DO 1
//! #102 = [#102 - #101]             the stock left after this pass
//! G52 Z[#102]                      the pass cuts the design raised by it
//! G0 Z1.000000                     program.retract_height_mm
//! G0 C0.00000 X5.000000            to the first point
//! G1 Z5.000000 F500.000            program.approach, heights above the first point
//! G1 Z0.000000 F20.000             the plunge (output.plunge_feed_mm_per_min)
//! G93
//! C0.50000 X4.999986 Z-0.000001 F288000.000    the cutting blocks (or M98 P1, M98 P2 …)
//! …
//! G94
//! G0 Z1.000000
//! #103 = [#103 + 1]
//! END 1
//! G52 Z0
//! G0 Z20.000000
//! M29                              program.c_axis_off
//! M30
//! ```
//!
//! Written out (`loop: unrolled`) each pass has its blocks with Z raised by its stock and no
//! `G52`. Past `program.max_program_bytes` the blocks of each body go into child programs
//! (`O1` … `M99` called by `M98 P1`; ISO `o<stem-1> sub` … `endsub` called by
//! `o<stem-1> call`, LinuxCNC finding `stem-1.ngc` on its subroutine path), numbered in the
//! order they are first called; the main program keeps the frame and the calls. Each child's
//! first block carries F. These are styles, not vendor specifications.

use super::{Blocks, Macros, NcError, Words, comment_lines};
use crate::job::program::{Pass, ProgramSpec};
use crate::job::{LoopKind, OutputSpec};
use crate::path::PathPoint;
use std::io::Write;

/// Where child programs go: the command line writes `STEM-1.nc` … beside the main program;
/// the page collects them for a zip.
pub trait ChildFiles {
    /// The writer of child `number` (1, 2, …), named `name` (`STEM-1.nc`).
    fn child(&mut self, number: usize, name: &str) -> std::io::Result<&mut dyn Write>;
}

/// A child program written.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ChildProgram {
    /// Its number (`M98 P…`).
    pub number: usize,
    /// Its file name.
    pub name: String,
    /// Its size, bytes.
    pub bytes: u64,
}

/// What a group of passes is, for the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroupFrame {
    /// Index of the group.
    pub group: usize,
    /// Passes in it.
    pub count: u32,
    /// Depth of cut, mm.
    pub depth_mm: f64,
    /// Stock before its first pass, mm.
    pub stock_before_mm: f64,
}

/// A pass's frame: where it starts and the heights around it, in its own frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PassFrame {
    /// Raise of every height (the stock left) when the pass is written out; 0 in a controller
    /// loop, where `G52` applies it.
    pub lift_mm: f64,
    /// The first point's words (already raised).
    pub first: Words,
    /// Its height, mm (not raised).
    pub first_z_mm: f64,
    /// Its angle, radians.
    pub first_theta: f64,
    /// Retract height, mm (not raised).
    pub retract_mm: f64,
}

/// Streams a program with a `program` section.
pub struct ProgramWriter<'a> {
    main_out: &'a mut dyn Write,
    children_out: Option<&'a mut dyn ChildFiles>,
    spec: ProgramSpec,
    blocks: Blocks,
    plunge_feed: f64,
    feed_mm_per_min: f64,
    /// The main program: written as it comes with no children, held (small) with them, since
    /// it is written after them.
    main: Vec<u8>,
    main_bytes: u64,
    /// Child programs: `Some(limit)` when the blocks go into them.
    child_limit: Option<u64>,
    stem: String,
    child: Option<OpenChild>,
    children: Vec<ChildProgram>,
    /// Children of the pass being written (called from it).
    pass_children: Vec<usize>,
    /// In a controller loop, the children of the group's body are written once.
    lift: f64,
    safe_z: f64,
}

/// The child program being written.
struct OpenChild {
    number: usize,
    name: String,
    bytes: u64,
    /// The footer it still needs, bytes.
    footer: u64,
}

impl<'a> ProgramWriter<'a> {
    /// Starts a program into `main` (and `children` when `child_limit` is set): writes the
    /// header comments, the preamble, the set-up words and the move to `safe_z_mm`. `stem`
    /// names the child programs.
    #[allow(clippy::too_many_arguments)]
    pub fn new(
        main: &'a mut dyn Write,
        children: Option<&'a mut dyn ChildFiles>,
        output: &OutputSpec,
        spec: &ProgramSpec,
        (header, rpm): (&[String], f64),
        stem: &str,
        safe_z_mm: f64,
        child_limit: Option<u64>,
    ) -> Result<Self, NcError> {
        let mut w = Self {
            main_out: main,
            children_out: children,
            spec: spec.clone(),
            blocks: Blocks::new(output, rpm),
            plunge_feed: output.plunge_feed_mm_per_min,
            feed_mm_per_min: output.feed_mm_per_min.unwrap_or(0.0),
            main: Vec::new(),
            main_bytes: 0,
            child_limit,
            stem: stem.to_string(),
            child: None,
            children: Vec::new(),
            pass_children: Vec::new(),
            lift: 0.0,
            safe_z: safe_z_mm,
        };
        let max = output.max_line();
        let mut text = String::new();
        for l in header {
            for c in comment_lines(l, max) {
                text.push_str(&c);
                text.push('\n');
            }
        }
        for l in w.blocks.style.preamble {
            text.push_str(l);
            text.push('\n');
        }
        for word in [&spec.work_offset, &spec.tool, &spec.c_axis_on]
            .into_iter()
            .flatten()
        {
            text.push_str(word);
            text.push('\n');
        }
        w.main_text(&text)?;
        w.rapid_z(safe_z_mm)?;
        Ok(w)
    }

    /// The words of `p` raised by `lift`, split with the slide at `z_slide` when given.
    pub fn words(&self, p: &PathPoint, z_slide: Option<f64>, lift: f64) -> Result<Words, NcError> {
        self.blocks.words(p, z_slide, lift)
    }

    /// Sets the spindle speed of the blocks that follow (a group with its own speed).
    pub fn set_rpm(&mut self, output: &OutputSpec, rpm: f64) {
        self.blocks = Blocks::new(output, rpm);
    }

    fn main_text(&mut self, text: &str) -> Result<(), NcError> {
        self.main_bytes += text.len() as u64;
        if self.child_limit.is_some() {
            self.main.extend_from_slice(text.as_bytes());
        } else {
            self.main_out.write_all(text.as_bytes())?;
        }
        Ok(())
    }

    fn main_line(&mut self) -> Result<(), NcError> {
        self.blocks.fits(u64::MAX)?;
        let line = std::mem::take(&mut self.blocks.line);
        let r = self.main_text(&String::from_utf8_lossy(&line));
        self.blocks.line = line;
        r
    }

    fn rapid_z(&mut self, z: f64) -> Result<(), NcError> {
        self.blocks.line.clear();
        self.blocks.line.extend_from_slice(b"G0 ");
        self.blocks.push_z(z)?;
        self.blocks.line.push(b'\n');
        self.main_line()
    }

    /// Starts a group: with a controller loop, its variables and the loop's head (the stock
    /// left and the `G52` shift); a comment either way.
    pub fn begin_group(&mut self, g: GroupFrame) -> Result<(), NcError> {
        let passes = if g.count == 1 { "pass" } else { "passes" };
        // Without `passes` the one pass cuts the design: no group to name.
        let mut text = if self.spec.passes.is_empty() {
            String::new()
        } else {
            format!(
                "(group {}: {} {passes} of {} um; stock {} mm before)\n",
                g.group + 1,
                g.count,
                fmt(g.depth_mm * 1e3),
                fmt(g.stock_before_mm)
            )
        };
        if self.spec.loop_kind == LoopKind::Controller {
            let label = 100 + g.group;
            let shift = if self.blocks.conv.z_sign < 0.0 {
                "-"
            } else {
                ""
            };
            text.push_str(&match self.blocks.style.macros {
                Macros::Fanuc => format!(
                    "#100 = {}\n#101 = {}\n#102 = {}\n#103 = 0\nWHILE [#103 LT #100] DO 1\n\
                     #102 = [#102 - #101]\nG52 Z[{shift}#102]\n",
                    g.count,
                    fmt6(g.depth_mm),
                    fmt6(g.stock_before_mm)
                ),
                Macros::LinuxCnc => format!(
                    "#<depth> = {}\n#<stock> = {}\no{label} repeat [{}]\n\
                     #<stock> = [#<stock> - #<depth>]\nG52 Z[{shift}#<stock>]\n",
                    fmt6(g.depth_mm),
                    fmt6(g.stock_before_mm),
                    g.count
                ),
            });
        }
        self.main_text(&text)
    }

    /// Ends a group: the loop's tail and the `G52` shift cleared.
    pub fn end_group(&mut self, g: GroupFrame) -> Result<(), NcError> {
        if self.spec.loop_kind != LoopKind::Controller {
            return Ok(());
        }
        let text = match self.blocks.style.macros {
            Macros::Fanuc => "#103 = [#103 + 1]\nEND 1\nG52 Z0\n".to_string(),
            Macros::LinuxCnc => format!("o{} endrepeat\nG52 Z0\n", 100 + g.group),
        };
        self.main_text(&text)
    }

    /// Starts a pass body: link to the first point over the retract height, the staged
    /// approach, the plunge, the cutting feed mode. A written-out pass gets a comment with its
    /// stock.
    pub fn begin_pass(&mut self, pass: &Pass, f: PassFrame) -> Result<(), NcError> {
        self.lift = f.lift_mm;
        if self.spec.loop_kind == LoopKind::Unrolled && !self.spec.passes.is_empty() {
            self.main_text(&format!(
                "(pass: group {}, stock {} mm left after it)\n",
                pass.group + 1,
                fmt(pass.stock_mm)
            ))?;
        }
        self.rapid_z(f.retract_mm + f.lift_mm)?;
        let b = &mut self.blocks;
        b.line.clear();
        b.line.extend_from_slice(b"G0 ");
        b.push_xc(f.first);
        b.line.push(b'\n');
        self.main_line()?;
        for step in self.spec.approach.clone() {
            let b = &mut self.blocks;
            b.line.clear();
            b.line.extend_from_slice(b"G1 ");
            b.push_z(f.first_z_mm + f.lift_mm + step.height_mm)?;
            b.push_feed(step.feed_mm_per_min);
            b.line.push(b'\n');
            self.main_line()?;
        }
        let b = &mut self.blocks;
        b.line.clear();
        b.line.extend_from_slice(b"G1 Z");
        super::number::push_scaled(&mut b.line, f.first.z, b.conv.decimals_xz);
        b.push_fts_word(f.first);
        b.push_feed(self.plunge_feed);
        b.line.push(b'\n');
        b.push_cutting_mode(self.feed_mm_per_min);
        self.main_line()?;
        self.blocks.start(f.first_theta);
        self.pass_children.clear();
        Ok(())
    }

    /// Writes the block that reaches `p` (raised by the pass's lift), split with the slide at
    /// `z_slide` when given; into the open child (a new one when the longest line would not
    /// fit in it) when the blocks go into children.
    pub fn point(&mut self, p: &PathPoint, z_slide: Option<f64>) -> Result<(), NcError> {
        if let Some(limit) = self.child_limit {
            let room = self.blocks.max_line() as u64 + 1;
            if self
                .child
                .as_ref()
                .is_some_and(|c| c.bytes + room + c.footer > limit)
            {
                self.close_child()?;
            }
            if self.child.is_none() {
                self.open_child()?;
            }
        }
        let w = self.blocks.words(p, z_slide, self.lift)?;
        self.blocks.block(p, w)?;
        let n = self.blocks.line.len() as u64;
        match self.child.as_mut() {
            None => {
                self.main_out.write_all(&self.blocks.line)?;
                self.main_bytes += n;
            }
            Some(child) => {
                if let Some(out) = self.children_out.as_deref_mut() {
                    out.child(child.number, &child.name)?
                        .write_all(&self.blocks.line)?;
                }
                child.bytes += n;
            }
        }
        Ok(())
    }

    fn open_child(&mut self) -> Result<(), NcError> {
        let number = self.children.len() + 1;
        let name = child_name(&self.stem, number, self.blocks.style);
        let (head, foot) = match self.blocks.style.macros {
            Macros::Fanuc => (format!("O{number}\n"), "M99\n".to_string()),
            Macros::LinuxCnc => {
                let sub = name.trim_end_matches(".ngc");
                (format!("o<{sub}> sub\n"), format!("o<{sub}> endsub\nM2\n"))
            }
        };
        if let Some(out) = self.children_out.as_deref_mut() {
            out.child(number, &name)?.write_all(head.as_bytes())?;
        }
        self.child = Some(OpenChild {
            number,
            name: name.clone(),
            bytes: head.len() as u64,
            footer: foot.len() as u64,
        });
        self.children.push(ChildProgram {
            number,
            name,
            bytes: 0,
        });
        self.pass_children.push(number);
        // The child's first block carries F.
        self.blocks.restart_feed();
        Ok(())
    }

    fn close_child(&mut self) -> Result<(), NcError> {
        let Some(child) = self.child.take() else {
            return Ok(());
        };
        let name = child.name.clone();
        let foot = match self.blocks.style.macros {
            Macros::Fanuc => "M99\n".to_string(),
            Macros::LinuxCnc => {
                let sub = name.trim_end_matches(".ngc");
                format!("o<{sub}> endsub\nM2\n")
            }
        };
        if let Some(out) = self.children_out.as_deref_mut() {
            let w = out.child(child.number, &name)?;
            w.write_all(foot.as_bytes())?;
            w.flush()?;
        }
        if let Some(c) = self.children.iter_mut().find(|c| c.number == child.number) {
            c.bytes = child.bytes + child.footer;
        }
        Ok(())
    }

    /// Ends a pass body: the calls of its children (when the blocks went into them), the
    /// feed mode back to G94, the retract.
    pub fn end_pass(&mut self, retract_mm: f64) -> Result<(), NcError> {
        if self.child_limit.is_some() {
            self.close_child()?;
            let calls: String = self
                .pass_children
                .clone()
                .into_iter()
                .map(|n| match self.blocks.style.macros {
                    Macros::Fanuc => format!("M98 P{n}\n"),
                    Macros::LinuxCnc => {
                        let name = child_name(&self.stem, n, self.blocks.style);
                        format!("o<{}> call\n", name.trim_end_matches(".ngc"))
                    }
                })
                .collect();
            self.main_text(&calls)?;
        }
        if self.blocks.feed_mode().per_block() {
            self.main_text("G94\n")?;
        }
        self.rapid_z(retract_mm + self.lift)
    }

    /// Ends the program: back to the safe height, the C-axis mode off, the end; with children,
    /// writes the main program. Returns the main program's size and the children.
    pub fn finish(mut self) -> Result<(u64, Vec<ChildProgram>), NcError> {
        self.rapid_z(self.safe_z)?;
        let mut text = String::new();
        if let Some(m) = &self.spec.c_axis_off {
            text.push_str(m);
            text.push('\n');
        }
        for l in self.blocks.style.end {
            text.push_str(l);
            text.push('\n');
        }
        self.main_text(&text)?;
        if self.child_limit.is_some() {
            self.main_out.write_all(&self.main)?;
        }
        self.main_out.flush()?;
        Ok((self.main_bytes, self.children))
    }
}

/// The file name of child `number`: `STEM-1.nc`; in ISO lower case (LinuxCNC looks for the
/// lower-case name of an `o<…> call` on its subroutine path).
pub fn child_name(stem: &str, number: usize, style: &super::Style) -> String {
    match style.macros {
        Macros::Fanuc => format!("{stem}-{number}.{}", style.extension),
        Macros::LinuxCnc => format!("{}-{number}.{}", stem.to_lowercase(), style.extension),
    }
}

/// A length in mm with 6 decimals, for variables.
fn fmt6(v: f64) -> String {
    format!("{v:.6}")
}

/// A number as Rust writes it, short.
fn fmt(v: f64) -> String {
    crate::field::short((v * 1e9).round() / 1e9)
}

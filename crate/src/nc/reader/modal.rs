//! The interpreter's modal state and what a block does with it, in LinuxCNC's order of
//! execution (`interp_execute.cc`, `execute_block`: feed mode, F, S, T, M codes, G codes —
//! plane, units, offsets, distance mode, then motion — and last the stops).
//!
//! - Units: `G20`/`G70` inch, `G21`/`G71` mm (G70/G71 as the Fanuc-style lathes and the Moore
//!   and Precitech styles use them; LinuxCNC's own G70/G71 are lathe cycles, not read). Every
//!   length given out is in mm (inch words × 25.4); A, B, C are angles, never scaled.
//! - Distance: `G90` absolute, `G91` incremental; arc centres `G91.1` incremental (default),
//!   `G90.1` absolute. `G7` makes X a diameter (LinuxCNC lathes), `G8` a radius (default).
//! - Offsets: the machine target of an axis word v is `v + work[cs] + local`, where `work` is
//!   the table of `G54`…`G59`, `G59.1`…`G59.3` the caller gives ([`OffsetTable`], zero by
//!   default) and `G10 L2`/`L20` change, and `local` is the register that `G52` sets directly
//!   and `G92` sets from the current position (LinuxCNC shares one register between them);
//!   `G92.1`/`G92.2` clear it. An axis not named keeps its offset. `G52` alone clears every axis
//!   (a lab's Moore program writes it so; LinuxCNC refuses it). `G53` moves in machine
//!   coordinates for its block. Tool offsets (`T0303`, `G43`) are not applied: T is reported,
//!   G43 refused.
//! - Feed: `G93` inverse time, `G94` per minute, `G95` per revolution; F is modal within a
//!   mode (LinuxCNC wants F on each `G93` block; the Moore style writes it when it changes) and
//!   unknown after the mode changes until the program gives it again (the old number meant
//!   something else). F is kept in mm (per minute or revolution); an F on the line that
//!   changes the units is read in the units before the change, as LinuxCNC does (it sets the
//!   feed before the units: rs274 prints `SET_FEED_RATE` before `USE_LENGTH_UNITS`).
//! - Motion: `G0`, `G1`, and `G2`/`G3` arcs in the `G18` (Z-X) plane with X and Z only, their
//!   centre by `I`/`K` or `R` as LinuxCNC finds it (`interp_arc.cc`, `arc_data_ijk`,
//!   `arc_data_r`, with its tolerance `CENTER_ARC_RADIUS_TOLERANCE_MM` = 2·0.01·√2 mm);
//!   anything else (other planes, helices, canned cycles, cutter compensation, homing) is
//!   refused with a message. The motion mode is none until the program names one, as in
//!   LinuxCNC, unless the caller says the control starts in G0 or G1 ([`InitialMotion`]).

use super::block::{AXIS_LETTERS, Block, Code};
use super::error::Problem;

/// Length units of the words.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Units {
    /// G21 / G71.
    Millimetres,
    /// G20 / G70.
    Inches,
}

/// How axis words are read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DistanceMode {
    /// G90.
    Absolute,
    /// G91.
    Incremental,
}

/// What F means.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FeedRateMode {
    /// G93: F is 1 / (the block's time in minutes).
    InverseTime,
    /// G94: mm per minute.
    PerMinute,
    /// G95: mm per spindle revolution.
    PerRevolution,
}

/// The arc plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plane {
    /// G17.
    XY,
    /// G18, the lathe's plane.
    ZX,
    /// G19.
    YZ,
}

/// An axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MachineAxis {
    /// Radial slide.
    X,
    /// Cross slide (FTS channel on some set-ups).
    Y,
    /// Axial slide.
    Z,
    /// Rotary about X, or a servo channel.
    A,
    /// Rotary about Y, or a servo channel.
    B,
    /// The spindle, degrees.
    C,
    /// Linear, parallel to X.
    U,
    /// Linear, parallel to Y.
    V,
    /// Linear, parallel to Z: the fast tool servo by default.
    W,
}

impl MachineAxis {
    /// Every axis, in the order of [`Position`].
    pub const ALL: [MachineAxis; 9] = [
        MachineAxis::X,
        MachineAxis::Y,
        MachineAxis::Z,
        MachineAxis::A,
        MachineAxis::B,
        MachineAxis::C,
        MachineAxis::U,
        MachineAxis::V,
        MachineAxis::W,
    ];

    /// The axis of a letter (either case).
    pub fn from_letter(letter: u8) -> Option<Self> {
        let l = letter.to_ascii_lowercase();
        AXIS_LETTERS
            .iter()
            .position(|&a| a == l)
            .map(|i| Self::ALL[i])
    }

    /// The upper-case letter.
    pub fn letter(self) -> char {
        AXIS_LETTERS[self as usize].to_ascii_uppercase() as char
    }

    /// A, B and C are angles; the others lengths.
    pub fn is_rotary(self) -> bool {
        matches!(self, MachineAxis::A | MachineAxis::B | MachineAxis::C)
    }
}

/// A position of the nine axes: lengths in mm, A B C in degrees (as commanded, not wrapped).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Position(pub [f64; 9]);

impl Position {
    /// The value of `axis`.
    pub fn get(&self, axis: MachineAxis) -> f64 {
        self.0[axis as usize]
    }

    /// X, mm.
    pub fn x(&self) -> f64 {
        self.0[0]
    }

    /// Y, mm.
    pub fn y(&self) -> f64 {
        self.0[1]
    }

    /// Z, mm.
    pub fn z(&self) -> f64 {
        self.0[2]
    }

    /// C, degrees.
    pub fn c(&self) -> f64 {
        self.0[5]
    }
}

/// A set of axes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct AxisSet(pub u16);

impl AxisSet {
    /// Whether `axis` is in the set.
    pub fn contains(self, axis: MachineAxis) -> bool {
        self.0 & (1 << axis as u16) != 0
    }

    /// Adds `axis`.
    pub fn insert(&mut self, axis: MachineAxis) {
        self.0 |= 1 << axis as u16;
    }

    /// The axes in the set.
    pub fn iter(self) -> impl Iterator<Item = MachineAxis> {
        MachineAxis::ALL
            .into_iter()
            .filter(move |&a| self.contains(a))
    }

    /// The letters, e.g. `"XZC"`.
    pub fn letters(self) -> String {
        self.iter().map(MachineAxis::letter).collect()
    }
}

/// Number of work coordinate systems: G54…G59, G59.1…G59.3.
pub const WORK_SYSTEMS: usize = 9;

/// The work offsets of `G54`…`G59.3`, in mm and degrees, in machine coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct OffsetTable(pub [Position; WORK_SYSTEMS]);

/// The feed in effect for a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Feed {
    /// What F means.
    pub mode: FeedRateMode,
    /// F: mm/min (G94), mm/rev (G95) or 1/min (G93); `None` until the program gives one in
    /// this mode.
    pub f: Option<f64>,
}

/// The kind of a move.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MoveKind {
    /// G0.
    Rapid,
    /// G1.
    Linear,
    /// G2 (`clockwise`) or G3 in the Z-X plane, centre in machine coordinates.
    Arc {
        /// G2.
        clockwise: bool,
        /// Centre X, mm.
        centre_x: f64,
        /// Centre Z, mm.
        centre_z: f64,
    },
}

/// The motion mode before the program names one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum InitialMotion {
    /// None (LinuxCNC starts in G80): axis words before G0 or G1 are an error.
    #[default]
    None,
    /// G0 (a Fanuc-style control set so by parameter).
    Rapid,
    /// G1 (a Fanuc-style control set so by parameter; a lab's Moore program relies on it).
    Linear,
}

/// What the interpreter must do after a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Flow {
    /// Go on.
    Next,
    /// `M98 P… L…`: call program `number` `repeats` times.
    Call {
        /// P.
        number: u64,
        /// L (1 without).
        repeats: u64,
    },
    /// `M99`.
    Return,
    /// `M2` or `M30`.
    End(Code),
}

/// A change the reader reports.
#[derive(Debug, Clone, PartialEq)]
pub enum Change {
    /// Units changed.
    Units(Units),
    /// Distance mode changed.
    Distance(DistanceMode),
    /// Feed mode changed.
    FeedMode(FeedRateMode),
    /// Plane changed.
    Plane(Plane),
    /// X became a diameter (G7) or a radius (G8).
    DiameterMode(bool),
    /// The work system in use (1 = G54 … 9 = G59.3) and its offset.
    WorkSystem(u8, Position),
    /// The local offset (G52/G92 register).
    LocalOffset(Position),
    /// An M code other than the stops and calls (spindle, coolant, the machine's own modes).
    M(Code),
    /// M0, M1 or M60.
    Stop(Code),
    /// A T word.
    Tool(u64),
    /// An S word.
    Spindle(f64),
    /// G96 (true) or G97.
    ConstantSurfaceSpeed(bool),
    /// G4 with its P (or X/U) value as written.
    Dwell(f64),
    /// A code the caller asked to accept without effect.
    Accepted(Code),
}

/// The modal state.
#[derive(Debug, Clone)]
pub struct Modal {
    /// Units of the words.
    pub units: Units,
    /// G90/G91.
    pub distance: DistanceMode,
    /// G90.1 (true) / G91.1.
    pub arc_absolute: bool,
    /// G93/G94/G95.
    pub feed_mode: FeedRateMode,
    /// F in mm-based units (1/min in G93).
    pub f: Option<f64>,
    /// The plane.
    pub plane: Plane,
    /// G0…G3, none until given (or after G80).
    pub motion: Option<u16>,
    /// G7.
    pub diameter: bool,
    /// Work system index (0 = G54).
    pub system: usize,
    /// The work offsets.
    pub offsets: OffsetTable,
    /// The G52/G92 register.
    pub local: Position,
    /// Machine position.
    pub position: Position,
    /// Codes accepted without effect.
    pub accepted: Vec<Code>,
}

/// mm per inch.
const INCH: f64 = 25.4;
/// LinuxCNC's `CENTER_ARC_RADIUS_TOLERANCE_MM`.
const ARC_RADIUS_TOLERANCE_MM: f64 = 2.0 * 0.01 * std::f64::consts::SQRT_2;

impl Modal {
    /// The state at the start of a program: mm, absolute, per-minute feed, G18, G54, the
    /// motion mode `initial`, the machine at `start`.
    pub fn new(
        offsets: OffsetTable,
        start: Position,
        initial: InitialMotion,
        accepted: Vec<Code>,
    ) -> Self {
        Self {
            units: Units::Millimetres,
            distance: DistanceMode::Absolute,
            arc_absolute: false,
            feed_mode: FeedRateMode::PerMinute,
            f: None,
            plane: Plane::ZX,
            motion: match initial {
                InitialMotion::None => None,
                InitialMotion::Rapid => Some(0),
                InitialMotion::Linear => Some(10),
            },
            diameter: false,
            system: 0,
            offsets,
            local: Position::default(),
            position: start,
            accepted,
        }
    }

    /// The feed in effect.
    pub fn feed(&self) -> Feed {
        Feed {
            mode: self.feed_mode,
            f: self.f,
        }
    }

    fn scale(&self) -> f64 {
        match self.units {
            Units::Millimetres => 1.0,
            Units::Inches => INCH,
        }
    }

    /// The value of axis word `i` in mm (or degrees), before offsets.
    fn program_value(&self, i: usize, v: f64) -> f64 {
        if MachineAxis::ALL[i].is_rotary() {
            v
        } else if i == 0 && self.diameter {
            v * self.scale() / 2.0
        } else {
            v * self.scale()
        }
    }

    fn offset(&self, i: usize) -> f64 {
        self.offsets.0[self.system].0[i] + self.local.0[i]
    }

    /// Executes a block; reports changes through `report` and returns the move, if any, and
    /// what the interpreter must do next.
    pub fn execute(
        &mut self,
        block: &mut Block,
        report: &mut dyn FnMut(Change),
    ) -> Result<(Option<(MoveKind, AxisSet)>, Flow), Problem> {
        let mut flow = Flow::Next;
        let mut g: Vec<Code> = std::mem::take(&mut block.g);
        // Feed mode first, then F.
        for code in &g {
            let mode = match code.tenths {
                930 => FeedRateMode::InverseTime,
                940 => FeedRateMode::PerMinute,
                950 => FeedRateMode::PerRevolution,
                _ => continue,
            };
            if mode != self.feed_mode {
                // F meant something else in the old mode: it must be given again.
                self.feed_mode = mode;
                self.f = None;
                report(Change::FeedMode(mode));
            }
        }
        if let Some(f) = block.take(b'f') {
            if f < 0.0 {
                return Err(Problem::Syntax(format!("F{f}: a feed is not negative")));
            }
            self.f = Some(match self.feed_mode {
                FeedRateMode::InverseTime => f,
                _ => f * self.scale(),
            });
        }
        if let Some(s) = block.take(b's') {
            if s < 0.0 {
                return Err(Problem::Syntax(format!("S{s}: a speed is not negative")));
            }
            report(Change::Spindle(s));
        }
        if let Some(t) = block.take(b't') {
            report(Change::Tool(whole("T", t)?));
        }
        let m = std::mem::take(&mut block.m);
        for &code in &m {
            match code.tenths {
                0 | 10 | 600 => report(Change::Stop(code)),
                20 | 300 => flow = Flow::End(code),
                980 => {
                    let p = block
                        .take(b'p')
                        .ok_or_else(|| Problem::Syntax("M98 needs P, the program number".into()))?;
                    let repeats = block.take(b'l').map_or(Ok(1), |l| whole("L", l))?;
                    flow = Flow::Call {
                        number: whole("P", p)?,
                        repeats,
                    };
                }
                990 => flow = Flow::Return,
                _ => report(Change::M(code)),
            }
        }
        block.m = m;
        let motion = self.g_codes(block, &mut g, report)?;
        block.g = g;
        let moved = match motion {
            Some(m) => Some(self.motion(block, m)?),
            None => None,
        };
        unused_words(block)?;
        Ok((moved, flow))
    }

    /// Applies the non-motion G codes; returns the motion code to run, if any.
    fn g_codes(
        &mut self,
        block: &mut Block,
        g: &mut [Code],
        report: &mut dyn FnMut(Change),
    ) -> Result<Option<Motion>, Problem> {
        let mut axes_used_by: Option<Code> = None;
        let mut machine_coordinates = false;
        let mut motion_code = None;
        for &code in g.iter() {
            let t = code.tenths;
            match t {
                0 | 10 | 20 | 30 => {
                    if let Some(prev) = motion_code.replace(t) {
                        return Err(Problem::Syntax(format!(
                            "two motion codes on one line: {} and {code}",
                            Code::g(prev)
                        )));
                    }
                }
                40 => {
                    let v = block
                        .take(b'p')
                        .or_else(|| block.axes[0].take())
                        .or_else(|| block.axes[6].take())
                        .ok_or_else(|| Problem::Syntax("G4 needs P (the dwell)".into()))?;
                    report(Change::Dwell(v));
                }
                170 | 180 | 190 => {
                    let plane = match t {
                        170 => Plane::XY,
                        180 => Plane::ZX,
                        _ => Plane::YZ,
                    };
                    set(&mut self.plane, plane, report, Change::Plane);
                }
                200 | 700 | 210 | 710 => {
                    let units = if t == 200 || t == 700 {
                        Units::Inches
                    } else {
                        Units::Millimetres
                    };
                    set(&mut self.units, units, report, Change::Units);
                }
                70 | 80 => set(&mut self.diameter, t == 70, report, Change::DiameterMode),
                400 | 490 | 610 | 611 | 640 | 930 | 940 | 950 | 980 | 990 => {}
                800 => self.motion = None,
                900 | 910 => {
                    let d = if t == 900 {
                        DistanceMode::Absolute
                    } else {
                        DistanceMode::Incremental
                    };
                    set(&mut self.distance, d, report, Change::Distance);
                }
                901 | 911 => self.arc_absolute = t == 901,
                960 | 970 => report(Change::ConstantSurfaceSpeed(t == 960)),
                540 | 550 | 560 | 570 | 580 | 590 | 591 | 592 | 593 => {
                    let s = match t {
                        591..=593 => 6 + (t - 591) as usize,
                        _ => ((t - 540) / 10) as usize,
                    };
                    if s != self.system {
                        self.system = s;
                        report(Change::WorkSystem(s as u8 + 1, self.offsets.0[s]));
                    }
                }
                530 => machine_coordinates = true,
                100 | 520 | 920 | 921 | 922 => {
                    if let Some(prev) = axes_used_by.replace(code) {
                        return Err(Problem::Syntax(format!(
                            "{prev} and {code} on one line both use the axis words"
                        )));
                    }
                }
                _ => self.other_code(code, report)?,
            }
        }
        if let Some(code) = axes_used_by {
            if let Some(m) = motion_code {
                return Err(Problem::Syntax(format!(
                    "{code} and {} on one line both use the axis words",
                    Code::g(m)
                )));
            }
            self.offset_code(code, block, report)?;
            return Ok(None);
        }
        if let Some(m) = motion_code {
            self.motion = Some(m);
        }
        if !block.has_axes() {
            return Ok(None);
        }
        let code = self.motion.ok_or_else(|| {
            Problem::Syntax(
                "axis words without a motion mode in effect: G0, G1, G2 or G3 must come first \
                 (a control that starts in G0 or G1 by parameter: ReaderOptions::initial_motion)"
                    .into(),
            )
        })?;
        Ok(Some(Motion {
            code,
            machine_coordinates,
        }))
    }

    /// Codes that are refused (with why) or that the caller accepts without effect.
    fn other_code(&self, code: Code, report: &mut dyn FnMut(Change)) -> Result<(), Problem> {
        if self.accepted.contains(&code) {
            report(Change::Accepted(code));
            return Ok(());
        }
        let why = match code.tenths {
            410 | 411 | 420 | 421 => {
                "cutter radius compensation changes the path by the tool's radius"
            }
            430..=432 => "tool length offsets need the tool table",
            280 | 281 | 300 | 301 => {
                "homing moves go to stored positions this reader does not know"
            }
            50..=53 => "splines are not read",
            330 | 331 | 380..=389 | 730 | 740 | 760 | 810..=890 => {
                "canned cycles, threading and probing are not read"
            }
            923 => "G92.3 restores offsets stored outside the program",
            _ => {
                return Err(Problem::Unknown(format!(
                    "{code} (a code of your controller that does not move the axes can be \
                     accepted through the reader's options)"
                )));
            }
        };
        Err(Problem::Unsupported(format!("{code}: {why}")))
    }

    /// G10, G52, G92 and its family.
    fn offset_code(
        &mut self,
        code: Code,
        block: &mut Block,
        report: &mut dyn FnMut(Change),
    ) -> Result<(), Problem> {
        let given: Vec<(usize, f64)> = block
            .axes
            .iter_mut()
            .enumerate()
            .filter_map(|(i, v)| v.take().map(|v| (i, v)))
            .collect();
        match code.tenths {
            100 => return self.g10(block, &given, report),
            520 if given.is_empty() => self.local = Position::default(),
            520 => {
                for &(i, v) in &given {
                    self.local.0[i] = self.program_value(i, v);
                }
            }
            920 => {
                if given.is_empty() {
                    return Err(Problem::Syntax("G92 needs at least one axis word".into()));
                }
                for &(i, v) in &given {
                    self.local.0[i] = self.position.0[i]
                        - self.offsets.0[self.system].0[i]
                        - self.program_value(i, v);
                }
            }
            _ => self.local = Position::default(),
        }
        report(Change::LocalOffset(self.local));
        Ok(())
    }

    fn g10(
        &mut self,
        block: &mut Block,
        given: &[(usize, f64)],
        report: &mut dyn FnMut(Change),
    ) -> Result<(), Problem> {
        let l = block.take(b'l');
        let p = block.take(b'p');
        if block.take(b'r').is_some_and(|r| r != 0.0) {
            return Err(Problem::Unsupported(
                "G10 with R: rotated coordinate systems".into(),
            ));
        }
        let (Some(l @ (2.0 | 20.0)), Some(p)) = (l, p) else {
            return Err(Problem::Unsupported(
                "G10 other than G10 L2 P… or G10 L20 P… (work offsets)".into(),
            ));
        };
        let p = whole("P", p)? as usize;
        if p > WORK_SYSTEMS {
            return Err(Problem::Syntax(format!(
                "G10 P{p}: the work system is 0 (the current) or 1 to {WORK_SYSTEMS}"
            )));
        }
        let s = if p == 0 { self.system } else { p - 1 };
        for &(i, v) in given {
            let v = self.program_value(i, v);
            self.offsets.0[s].0[i] = if l == 2.0 {
                v
            } else {
                self.position.0[i] - self.local.0[i] - v
            };
        }
        report(Change::WorkSystem(s as u8 + 1, self.offsets.0[s]));
        Ok(())
    }

    fn motion(&mut self, block: &mut Block, m: Motion) -> Result<(MoveKind, AxisSet), Problem> {
        let start = self.position;
        let mut words = AxisSet::default();
        for (i, slot) in block.axes.iter_mut().enumerate() {
            let Some(v) = slot.take() else { continue };
            words.insert(MachineAxis::ALL[i]);
            let p = self.program_value(i, v);
            self.position.0[i] = if m.machine_coordinates {
                p
            } else if self.distance == DistanceMode::Incremental {
                self.position.0[i] + p
            } else {
                p + self.offset(i)
            };
        }
        let kind = match m.code {
            0 => MoveKind::Rapid,
            10 => MoveKind::Linear,
            _ => self.arc(block, m.code == 20, start, words)?,
        };
        Ok((kind, words))
    }

    fn arc(
        &self,
        block: &mut Block,
        clockwise: bool,
        start: Position,
        words: AxisSet,
    ) -> Result<MoveKind, Problem> {
        let code = if clockwise { "G2" } else { "G3" };
        if self.plane != Plane::ZX {
            return Err(Problem::Unsupported(format!(
                "{code} outside the G18 (Z-X) plane"
            )));
        }
        if words
            .iter()
            .any(|a| a != MachineAxis::X && a != MachineAxis::Z)
        {
            return Err(Problem::Unsupported(format!(
                "{code} moving {}: only X and Z arcs (2-D turning) are read",
                words.letters()
            )));
        }
        if self.diameter {
            return Err(Problem::Unsupported(format!(
                "{code} in diameter mode (G7)"
            )));
        }
        if block.take(b'p').is_some_and(|p| p != 1.0) {
            return Err(Problem::Unsupported(format!("{code} with P turns")));
        }
        // LinuxCNC's plane coordinates for G18: first Z, second X.
        let (a0, b0) = (start.z(), start.x());
        let (a1, b1) = (self.position.z(), self.position.x());
        let (i, k, r) = (block.take(b'i'), block.take(b'k'), block.take(b'r'));
        let tol = ARC_RADIUS_TOLERANCE_MM;
        let (ca, cb) = match (r, i.is_some() || k.is_some()) {
            (Some(_), true) => {
                return Err(Problem::Syntax(format!("{code} with both R and I/K")));
            }
            (None, false) => {
                return Err(Problem::Syntax(format!("{code} needs I and K, or R")));
            }
            (Some(r), false) => arc_centre_r(clockwise, (a0, b0), (a1, b1), r * self.scale())
                .ok_or_else(|| {
                    Problem::Syntax(format!(
                        "{code} R{r}: the radius does not reach the end point, or the end is \
                         the start"
                    ))
                })?,
            (None, true) => {
                let (di, dk) = (
                    i.unwrap_or(0.0) * self.scale(),
                    k.unwrap_or(0.0) * self.scale(),
                );
                let c = if self.arc_absolute {
                    (dk + self.offset(2), di + self.offset(0))
                } else {
                    (a0 + dk, b0 + di)
                };
                let r0 = (c.0 - a0).hypot(c.1 - b0);
                let r1 = (c.0 - a1).hypot(c.1 - b1);
                if r0 < 0.1 * tol || r1 < 0.1 * tol || (r0 - r1).abs() > tol {
                    return Err(Problem::Syntax(format!(
                        "{code}: the radius to the start ({r0:.4} mm) and to the end \
                         ({r1:.4} mm) differ by more than {tol:.4} mm, or one is zero"
                    )));
                }
                c
            }
        };
        Ok(MoveKind::Arc {
            clockwise,
            centre_x: cb,
            centre_z: ca,
        })
    }
}

/// The motion a block runs.
#[derive(Debug, Clone, Copy)]
struct Motion {
    code: u16,
    machine_coordinates: bool,
}

/// LinuxCNC's `arc_data_r`: the centre of the arc of radius `r` (negative: more than half a
/// turn) from `p0` to `p1` in plane coordinates.
fn arc_centre_r(clockwise: bool, p0: (f64, f64), p1: (f64, f64), r: f64) -> Option<(f64, f64)> {
    const TINY: f64 = 1e-12;
    if p0 == p1 || r == 0.0 {
        return None;
    }
    let abs_r = r.abs();
    let mid = ((p0.0 + p1.0) / 2.0, (p0.1 + p1.1) / 2.0);
    let mut half = (mid.0 - p1.0).hypot(mid.1 - p1.1);
    if half - abs_r > ARC_RADIUS_TOLERANCE_MM {
        return None;
    }
    if half / abs_r > 1.0 - TINY {
        half = abs_r;
    }
    let dir = (p1.1 - p0.1).atan2(p1.0 - p0.0);
    let theta = if (clockwise && r > 0.0) || (!clockwise && r < 0.0) {
        dir - std::f64::consts::FRAC_PI_2
    } else {
        dir + std::f64::consts::FRAC_PI_2
    };
    let offset = abs_r * (half / abs_r).asin().cos();
    Some((mid.0 + offset * theta.cos(), mid.1 + offset * theta.sin()))
}

/// Sets a mode, reporting it when it changes.
fn set<T: PartialEq + Copy>(
    slot: &mut T,
    v: T,
    report: &mut dyn FnMut(Change),
    change: fn(T) -> Change,
) {
    if *slot != v {
        *slot = v;
        report(change(v));
    }
}

/// `v` as a whole number ≥ 0 (P, L, T words).
pub fn whole(letter: &str, v: f64) -> Result<u64, Problem> {
    if v >= 0.0 && v.fract() == 0.0 && v < 1e15 {
        Ok(v as u64)
    } else {
        Err(Problem::Syntax(format!(
            "{letter}{v}: must be a whole number ≥ 0"
        )))
    }
}

/// Words left in the block after execution are used by nothing: an error, never skipped.
fn unused_words(block: &Block) -> Result<(), Problem> {
    use super::block::OTHER_LETTERS;
    let words = OTHER_LETTERS
        .iter()
        .zip(&block.other)
        .chain(AXIS_LETTERS.iter().zip(&block.axes));
    for (letter, v) in words {
        if let Some(v) = v {
            let letter = letter.to_ascii_uppercase() as char;
            return Err(Problem::Syntax(format!(
                "{letter}{v} is used by nothing on its line"
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn r_arcs_find_linuxcncs_centre() {
        // From rs274: G18, (X5, Z0) → G2 X3 Z2 I-2 K0 has centre (X3, Z0); the same arc by R.
        let c = arc_centre_r(true, (0.0, 5.0), (2.0, 3.0), 2.0).unwrap();
        assert!(
            (c.0 - 0.0).abs() < 1e-12 && (c.1 - 3.0).abs() < 1e-12,
            "{c:?}"
        );
        // G3 X5 Z4 R2 from (X3, Z2): centre (X5, Z2) (rs274's ARC_FEED(4, 5, 2, 5, 1, …)).
        let c = arc_centre_r(false, (2.0, 3.0), (4.0, 5.0), 2.0).unwrap();
        assert!(
            (c.0 - 2.0).abs() < 1e-12 && (c.1 - 5.0).abs() < 1e-12,
            "{c:?}"
        );
        // Too small a radius.
        assert!(arc_centre_r(true, (0.0, 5.0), (0.0, -5.0), 4.0).is_none());
    }

    #[test]
    fn whole_numbers_only() {
        assert_eq!(whole("P", 1000.0), Ok(1000));
        assert!(whole("P", 1.5).is_err());
        assert!(whole("L", -1.0).is_err());
    }
}

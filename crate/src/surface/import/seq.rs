//! CODE V sequence files (`.seq`): the lens's surfaces with their radii or curvatures,
//! conics, aspheric coefficients, XY polynomials and Qbfs terms, apertures, glasses and
//! mirrors, in the lens units of `DIM`.
//!
//! **Syntax**, as the public readers take it (ray-optics `codev/reader.py` and `cmdproc.py`, M.
//! J. Hayford, with its test files, and optiland's `fileio/codev`): `!` starts a comment, `&`
//! at the end of a line continues it, `;` separates commands, words are separated by blanks
//! and `'…'` or `"…"` quote a title. A command is its first word, matched on its first three
//! letters and in any case. `SO r t` is the object surface (number 0), each `S r t [glass]`
//! the next surface (`S3` too), `SI r t` the image; `r` is the radius (`RDM Y`, the default)
//! or the curvature (`RDM N`), `REFL` as glass (or `RMD REFL`) makes a mirror. The commands
//! after a surface line apply to it, or to the surface a qualifier `Sk`, `SO` or `SI` names.
//!
//! | commands | read as |
//! |---|---|
//! | `SPH`, `CON`, `ASP`, `K`, `A B C D E F G H J` (r⁴ … r²⁰), `CUY`, `RDY` | `asphere` |
//! | `SPS XYP`, `SCO Cj v` (C1 = the conic, then x, y, x², xy, y², …: j = ((m+n)² + m + 3n)/2 + 1 for xᵐyⁿ, to C66), `SCO NRADIUS` | `xy_polynomial` |
//! | `SPS QBF`, `SCO C1` or `NRADIUS` the normalisation radius, `SCO C3…` or `QB4, QB6, …` a₀, a₁, … | `q_bfs` on the surface's radius |
//! | `CIR v` (clear, else `CIR EDG`) | the semi-diameter |
//! | `DIM M` / `C` / `I` | millimetres / centimetres / inches |
//!
//! The XY polynomial's index formula and C1 = K, and `SCO NRADIUS`, are those of a public
//! CODE V XY-polynomial listing (a MATLAB converter's comments: `SCO C3` y, `C4` x², `C8` x²y,
//! `C11` x⁴, … `C45` y⁸). The Qbfs layout is CODE V's own listing of ray-optics' test lens
//! `threemrc_qbfs.lis` (`SPS QBF`: `NRADIUS` as `SCC C1`, `QB4` … `QB14` as `C3` … `C8`), and
//! checked against it: that listing's Qbfs mirror (R −449.67012 mm, NRADIUS 189.86, QB4 …
//! QB14) reproduces the ASP mirror it was converted from (`threemir.seq`: R −453.96516 mm,
//! K 0.226106, A 3.6895e-11) to 26 nm over its 190 mm aperture, with QB(2m+4) = aₘ of
//! Forbes' Qbfs (a test below).
//!
//! **Inferred, not found documented:** `DIM` absent means millimetres; `NRADIUS` absent means
//! 1 lens unit (un-normalised coefficients); the Qbfs coefficient `C2` (absent from the
//! listing) must be zero; a decentre or tilt (`XDE YDE ZDE ADE BDE CDE`) moves the surface's
//! frame, and without `DAR` every later surface's. **Not read** (refused naming the type):
//! `SPS` types other than XYP and QBF (Zernike `ZFR`/`ZRN`, `QCN` and the rest: no public
//! material gives their coefficients' layout), toroids and cylinders (`XTO`, `YTO`, `CYL`,
//! `CUX`, `RDX`), anamorphic aspheres (`AAS`). Commands that set the system (fields,
//! wavelengths, pupil, coupling codes, solves) are not read; any other command on a surface is
//! listed with it.

use super::convert::{EvenAsphere, Scale, conic};
use super::{Aperture, Design, DesignFormat, DesignSurface, ImportError, LengthUnit, Optics, Role};
use crate::surface::xy_polynomial::XyTerm;
use crate::surface::{QBfsSpec, SurfaceSpec, XyPolynomialSpec};
use std::collections::BTreeMap;

/// The surface types read, for error messages.
pub const TYPES_READ: &[&str] = &["SPH", "CON", "ASP", "SPS XYP", "SPS QBF"];

/// The highest XY polynomial coefficient (x¹⁰ … y¹⁰ end at C66).
pub const MAX_XYP: usize = 66;

/// Commands that set the system, not a surface's shape: title, wavelengths, pupil, fields,
/// vignetting, environment, polarisation, thickness and stop, coupling codes (variables),
/// solves.
const SYSTEM: &[&str] = &[
    "LEN", "TIT", "INI", "WL", "REF", "WTW", "CWL", "EPD", "FNO", "NA", "NAO", "XAN", "YAN", "XOB",
    "YOB", "XIM", "YIM", "XRI", "YRI", "VUX", "VLX", "VUY", "VLY", "WTF", "WID", "TEM", "PRE",
    "POL", "CA", "GO", "THI", "STO", "PIM", "THC", "CCY", "GLC", "SCC", "KC", "AC", "BC", "CC",
    "DC", "EC", "FC", "GC", "HC", "JC", "XDC", "YDC", "ZDC", "ADC", "BDC", "CDC", "CUF",
];

/// A value with its line.
type At = (f64, usize);

/// What the commands say about one surface, before conversion.
#[derive(Default)]
struct Raw {
    number: usize,
    line: usize,
    role: Option<Role>,
    /// Radius or curvature of the surface line, and whether it was a radius.
    r: f64,
    radius: bool,
    profile: Option<(String, usize)>,
    sps: Option<(String, usize)>,
    k: Option<At>,
    asp: [Option<At>; 9],
    sco: BTreeMap<String, At>,
    glass: Option<String>,
    mirror: bool,
    clear: Option<At>,
    edge: Option<At>,
    decentre: Option<usize>,
    returns: bool,
    aperture_decentre: [f64; 2],
    label: Option<String>,
    refused: Vec<String>,
    read: Vec<String>,
    not_read: Vec<String>,
}

/// A command: its line, its name (upper case) and its words.
struct Command {
    line: usize,
    name: String,
    words: Vec<String>,
}

/// The commands of the text: comments removed, continuations joined, `;` split, quoted words
/// kept whole.
fn commands(text: &str) -> Vec<Command> {
    let mut out = Vec::new();
    let mut pending = String::new();
    let mut start = 0;
    for (k, raw) in text.lines().enumerate() {
        if pending.is_empty() {
            start = k + 1;
        }
        let mut quote = None;
        let mut line = String::new();
        for c in raw.chars() {
            match (quote, c) {
                (None, '!') => break,
                (None, '\'' | '"') => quote = Some(c),
                (Some(q), c) if c == q => quote = None,
                _ => {}
            }
            line.push(c);
        }
        let trimmed = line.trim_end();
        if let Some(head) = trimmed.strip_suffix('&') {
            pending.push_str(head);
            pending.push(' ');
            continue;
        }
        pending.push_str(trimmed);
        for part in split_outside_quotes(&pending) {
            let words = words(&part);
            if let Some((first, rest)) = words.split_first() {
                out.push(Command {
                    line: start,
                    name: first.to_ascii_uppercase(),
                    words: rest.to_vec(),
                });
            }
        }
        pending.clear();
    }
    out
}

fn split_outside_quotes(text: &str) -> Vec<String> {
    let mut parts = vec![String::new()];
    let mut quote = None;
    for c in text.chars() {
        match (quote, c) {
            (None, ';') => {
                parts.push(String::new());
                continue;
            }
            (None, '\'' | '"') => quote = Some(c),
            (Some(q), c) if c == q => quote = None,
            _ => {}
        }
        if let Some(p) = parts.last_mut() {
            p.push(c);
        }
    }
    parts
}

/// Words separated by blanks; a quoted run is one word, without its quotes.
fn words(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    let mut quote = None;
    for c in text.chars() {
        match (quote, c) {
            (None, '\'' | '"') if word.is_empty() => quote = Some(c),
            (Some(q), c) if c == q => {
                out.push(std::mem::take(&mut word));
                quote = None;
            }
            (Some(_), c) => word.push(c),
            (None, c) if c.is_whitespace() => {
                if !word.is_empty() {
                    out.push(std::mem::take(&mut word));
                }
            }
            (None, c) => word.push(c),
        }
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

/// The command's name as CODE V matches it: its first three letters.
fn tla(name: &str) -> &str {
    if name.len() > 3 && name.is_char_boundary(3) {
        &name[..3]
    } else {
        name
    }
}

/// A surface command (`S`, `SO`, `SI`, `S3`)?
fn surface_role(name: &str) -> Option<Role> {
    match name {
        "SO" => Some(Role::Object),
        "SI" => Some(Role::Image),
        "S" => Some(Role::Surface),
        n if n.len() > 1 && n.starts_with('S') && n[1..].bytes().all(|b| b.is_ascii_digit()) => {
            Some(Role::Surface)
        }
        _ => None,
    }
}

struct Reader<'a> {
    file: &'a str,
    radius_mode: bool,
    unit: Option<(LengthUnit, usize)>,
    surfaces: Vec<Raw>,
    current: Option<usize>,
    notes: Vec<String>,
}

fn number(file: &str, line: usize, what: &str, word: Option<&String>) -> Result<f64, ImportError> {
    match word.map(|w| (w, w.parse::<f64>())) {
        Some((_, Ok(v))) if v.is_finite() => Ok(v),
        Some((w, _)) => Err(ImportError::line(
            file,
            line,
            format!("{what} {w:?}: expected a finite number"),
        )),
        None => Err(ImportError::line(
            file,
            line,
            format!("{what}: a number is missing"),
        )),
    }
}

impl Reader<'_> {
    fn err(&self, line: usize, problem: impl Into<String>) -> ImportError {
        ImportError::line(self.file, line, problem)
    }

    /// A surface line.
    fn surface(&mut self, c: &Command, role: Role) -> Result<(), ImportError> {
        if role != Role::Object && self.surfaces.is_empty() {
            return Err(self.err(
                c.line,
                format!("{}: the object surface SO must come first", c.name),
            ));
        }
        if role == Role::Object && !self.surfaces.is_empty() {
            return Err(self.err(c.line, "SO: the object surface again"));
        }
        if self
            .surfaces
            .last()
            .is_some_and(|s| s.role == Some(Role::Image))
        {
            return Err(self.err(
                c.line,
                format!("{}: a surface after the image surface SI", c.name),
            ));
        }
        let r = number(
            self.file,
            c.line,
            &format!("{} radius", c.name),
            c.words.first(),
        )?;
        number(
            self.file,
            c.line,
            &format!("{} thickness", c.name),
            c.words.get(1),
        )?;
        let mut s = Raw {
            number: self.surfaces.len(),
            line: c.line,
            role: Some(role),
            r,
            radius: self.radius_mode,
            ..Default::default()
        };
        for w in c.words.iter().skip(2) {
            if w.eq_ignore_ascii_case("REFL") {
                s.mirror = true;
            } else if s.glass.is_none() && !w.eq_ignore_ascii_case("AIR") {
                s.glass = Some(w.clone());
            }
        }
        self.surfaces.push(s);
        self.current = Some(self.surfaces.len() - 1);
        Ok(())
    }

    /// The surface a command applies to: its `Sk`/`SO`/`SI` qualifier, else the current one;
    /// the other words.
    fn target(&self, c: &Command) -> Result<(usize, Vec<String>), ImportError> {
        let mut target = None;
        let mut rest = Vec::new();
        for w in &c.words {
            let u = w.to_ascii_uppercase();
            let named = match u.as_str() {
                "SO" => Some(0),
                "SI" => match self.surfaces.last() {
                    Some(s) if s.role == Some(Role::Image) => Some(s.number),
                    _ => {
                        return Err(
                            self.err(c.line, format!("{}: SI names no image surface yet", c.name))
                        );
                    }
                },
                n if n.len() > 1
                    && n.starts_with('S')
                    && n[1..].bytes().all(|b| b.is_ascii_digit()) =>
                {
                    Some(n[1..].parse::<usize>().unwrap_or(usize::MAX))
                }
                _ => None,
            };
            match named {
                Some(k) if k < self.surfaces.len() => target = Some(k),
                Some(_) => {
                    return Err(self.err(
                        c.line,
                        format!("{}: {w} names a surface not defined yet", c.name),
                    ));
                }
                None if u.starts_with("L'") || u.starts_with("L\"") => {}
                None => rest.push(w.clone()),
            }
        }
        match target.or(self.current) {
            Some(k) => Ok((k, rest)),
            None => Err(self.err(
                c.line,
                format!("{}: no surface to apply it to (it comes before SO)", c.name),
            )),
        }
    }

    fn command(&mut self, c: &Command) -> Result<(), ImportError> {
        let name = tla(&c.name).to_string();
        match name.as_str() {
            "RDM" => {
                let w = c.words.first().map(|w| w.to_ascii_uppercase());
                self.radius_mode = !matches!(w.as_deref(), Some("N" | "NO"));
                return Ok(());
            }
            "DIM" => {
                let w = c
                    .words
                    .first()
                    .map(|w| w.to_ascii_uppercase())
                    .unwrap_or_default();
                let unit = match w.as_str() {
                    "M" | "MM" => LengthUnit::MM,
                    "C" | "CM" => LengthUnit {
                        name: "cm",
                        mm: 10.0,
                    },
                    "I" | "IN" => LengthUnit {
                        name: "in",
                        mm: 25.4,
                    },
                    _ => {
                        return Err(self.err(
                            c.line,
                            format!("DIM {w}: expected M (mm), C (cm) or I (inches)"),
                        ));
                    }
                };
                self.unit = Some((unit, c.line));
                return Ok(());
            }
            n if SYSTEM.contains(&n) => return Ok(()),
            _ => {}
        }
        let (k, words) = self.target(c)?;
        let file = self.file;
        let s = &mut self.surfaces[k];
        let value = |what: &str| number(file, c.line, what, words.last());
        match name.as_str() {
            "SPH" | "CON" | "ASP" => s.profile = Some((name.clone(), c.line)),
            "XTO" | "YTO" | "CYL" | "AAS" => s.refused.push(format!(
                "{name} (line {}): CODE V's toroids, cylinders and anamorphic aspheres are not read",
                c.line
            )),
            "CUX" | "RDX" => s.refused.push(format!(
                "{name} (line {}): an x curvature makes an anamorphic surface, not read",
                c.line
            )),
            "SPS" => {
                let t = words.first().map(|w| w.to_ascii_uppercase()).unwrap_or_default();
                if words.len() > 1 {
                    s.not_read.push(format!(
                        "SPS {t}: the words after the type, {:?} (line {})",
                        &words[1..],
                        c.line
                    ));
                }
                s.sps = Some((t, c.line));
            }
            "SCO" => {
                let Some(key) = words.first().filter(|_| words.len() == 2) else {
                    return Err(ImportError::line(
                        file,
                        c.line,
                        "SCO: expected a coefficient (Cj or its name) and its value",
                    ));
                };
                let v = value("SCO value")?;
                let key = key.to_ascii_uppercase();
                if let Some((_, first)) = s.sco.insert(key.clone(), (v, c.line)) {
                    return Err(ImportError::line(
                        file,
                        c.line,
                        format!("SCO {key} given twice (first on line {first})"),
                    ));
                }
            }
            "K" => s.k = Some((value("K")?, c.line)),
            "A" | "B" | "C" | "D" | "E" | "F" | "G" | "H" | "J" => {
                let i = "ABCDEFGHJ".find(name.as_str()).unwrap_or(0);
                s.asp[i] = Some((value(&name)?, c.line));
            }
            "CUY" => {
                s.r = value("CUY")?;
                s.radius = false;
            }
            "RDY" => {
                s.r = value("RDY")?;
                s.radius = true;
            }
            "CIR" => {
                let quals: Vec<String> = c.words.iter().map(|w| w.to_ascii_uppercase()).collect();
                let v = value("CIR")?;
                if quals.iter().any(|q| q == "OBS" || q == "HOL") {
                    s.read.push(format!("CIR {v} (line {}): an obscuration or hole, not the part's edge", c.line));
                } else if quals.iter().any(|q| q == "EDG") {
                    s.edge = Some((v, c.line));
                } else {
                    s.clear = Some((v, c.line));
                }
            }
            "ADX" => s.aperture_decentre[0] = value("ADX")?,
            "ADY" => s.aperture_decentre[1] = value("ADY")?,
            "XDE" | "YDE" | "ZDE" | "ADE" | "BDE" | "CDE" => {
                if value(&name)? != 0.0 {
                    s.decentre = Some(c.line);
                }
            }
            "DAR" => s.returns = true,
            "BEN" | "REV" | "RET" => s.returns = false,
            "GLA" => {
                let g = words.first().cloned().unwrap_or_default();
                s.glass = (!g.eq_ignore_ascii_case("AIR") && !g.is_empty()).then_some(g);
            }
            "RMD" => {
                s.mirror = words.first().is_some_and(|w| w.eq_ignore_ascii_case("REFL"));
            }
            "SLB" => s.label = words.first().cloned(),
            _ => s.not_read.push(format!("{} (line {})", c.name, c.line)),
        }
        Ok(())
    }
}

/// Reads a `.seq` text (see the module docs).
pub fn parse(file: &str, text: &str) -> Result<Design, ImportError> {
    let mut r = Reader {
        file,
        radius_mode: true,
        unit: None,
        surfaces: Vec::new(),
        current: None,
        notes: Vec::new(),
    };
    let mut private = false;
    for c in commands(text) {
        let name = tla(&c.name);
        if private {
            private = name != "END";
            continue;
        }
        if name == "PRV" {
            private = true;
            continue;
        }
        match surface_role(&c.name) {
            Some(role) => r.surface(&c, role)?,
            None => r.command(&c)?,
        }
    }
    if r.surfaces.is_empty() {
        return Err(ImportError::Format {
            file: file.to_string(),
            problem: "no surface (no SO or S line): not a CODE V sequence file".into(),
        });
    }
    let (unit, unit_from) = match r.unit {
        Some((u, l)) => (u, format!("DIM, line {l}")),
        None => (LengthUnit::MM, "not stated (no DIM): millimetres".into()),
    };
    let scale = Scale(unit.mm);
    let mut surfaces = Vec::new();
    let mut medium: Option<String> = None;
    let mut plus = true;
    let mut moved: Option<String> = None;
    for s in &r.surfaces {
        let before = medium.clone();
        let after = if s.mirror {
            before.clone()
        } else {
            s.glass.clone()
        };
        let optics = Optics {
            mirror: s.mirror,
            before,
            after: after.clone(),
            light_along_plus_z: plus,
            known: true,
        };
        let own = s
            .decentre
            .map(|l| format!("the surface itself is decentred or tilted (line {l})"));
        surfaces.push(design_surface(s, scale, optics, moved.clone().or(own)));
        medium = after;
        if s.mirror {
            plus = !plus;
        }
        if let (Some(l), false) = (s.decentre, s.returns) {
            moved = Some(format!(
                "it lies behind surface {}, decentred or tilted without DAR (line {l})",
                s.number
            ));
        }
    }
    Ok(Design {
        file: file.to_string(),
        format: DesignFormat::Seq,
        encoding: super::Encoding::Utf8,
        unit,
        unit_from,
        surfaces,
        notes: r.notes,
    })
}

fn design_surface(
    s: &Raw,
    scale: Scale,
    optics: Optics,
    frame_moved: Option<String>,
) -> DesignSurface {
    let mut read = Vec::new();
    let shape = shape(s, scale, &mut read);
    read.extend(s.read.iter().cloned());
    let mut aperture = Aperture::default();
    if let Some((v, l)) = s.clear.or(s.edge).filter(|v| v.0 > 0.0) {
        let which = if s.clear.is_some() { "CIR" } else { "CIR EDG" };
        aperture.semi_diameter_mm = Some(scale.length(v));
        aperture.from = format!("{which}, line {l}");
        read.push(format!(
            "{which} {v} (line {l}): semi-diameter {} mm",
            scale.length(v)
        ));
    }
    if s.aperture_decentre != [0.0, 0.0] {
        let d = s.aperture_decentre.map(|v| scale.length(v));
        aperture.decentre_mm = Some(d);
        read.push(format!(
            "aperture decentred by ({}, {}) mm (ADX, ADY)",
            d[0], d[1]
        ));
    }
    if let Some(g) = &s.glass {
        read.push(format!("glass {g}"));
    }
    if s.mirror {
        read.push("REFL: a mirror".into());
    }
    let kind = match (&s.sps, &s.profile) {
        (Some((t, _)), _) => format!("SPS {t}"),
        (None, Some((p, _))) => p.clone(),
        (None, None) => "SPH".into(),
    };
    DesignSurface {
        number: s.number,
        line: s.line,
        kind,
        label: s.label.clone(),
        role: s.role.unwrap_or(Role::Surface),
        shape,
        aperture,
        optics,
        frame_moved,
        read,
        not_read: s.not_read.clone(),
    }
}

/// The vertex curvature in 1/mm, listed.
fn curvature(s: &Raw, scale: Scale, read: &mut Vec<String>) -> f64 {
    let c = if s.radius {
        if s.r == 0.0 { 0.0 } else { 1.0 / s.r }
    } else {
        s.r
    };
    let c = scale.curvature(c);
    let what = if s.radius { "radius" } else { "curvature" };
    read.push(if c == 0.0 {
        format!("{what} {} (line {}): flat", s.r, s.line)
    } else {
        format!(
            "{what} {} (line {}): vertex radius {} mm",
            s.r,
            s.line,
            1.0 / c
        )
    });
    c
}

/// `SCO` value of `Cj` or its name.
fn coefficient(s: &Raw, j: usize, name: &str) -> Option<At> {
    match (s.sco.get(&format!("C{j}")), s.sco.get(name)) {
        (Some(a), _) | (None, Some(a)) => Some(*a),
        (None, None) => None,
    }
}

/// The XY polynomial index of xᵐyⁿ: j = ((m+n)² + m + 3n)/2 + 1.
pub fn xyp_index(m: u32, n: u32) -> usize {
    (((m + n) * (m + n) + m + 3 * n) / 2 + 1) as usize
}

fn shape(s: &Raw, scale: Scale, read: &mut Vec<String>) -> Result<SurfaceSpec, String> {
    if let Some(why) = s.refused.first() {
        return Err(why.clone());
    }
    let c = curvature(s, scale, read);
    let k = s.k.map_or(0.0, |v| v.0);
    if let Some((v, l)) = s.k {
        read.push(format!("K {v} (line {l})"));
    }
    let Some((t, line)) = &s.sps else {
        let p = |i: usize| 4 + 2 * i as i32;
        let mut alpha = vec![0.0];
        for (i, a) in s.asp.iter().enumerate() {
            let v = a.map_or(0.0, |a| a.0);
            let mm = scale.coefficient(v, p(i));
            if let Some((v, l)) = a {
                read.push(format!(
                    "{} {v} (line {l}): r^{} → {mm} mm^{}",
                    &"ABCDEFGHJ"[i..i + 1],
                    p(i),
                    1 - p(i)
                ));
            }
            alpha.push(mm);
        }
        return Ok(EvenAsphere::new(c, k, &alpha).spec());
    };
    if s.asp.iter().any(Option::is_some) {
        return Err(format!(
            "SPS {t} (line {line}) with aspheric coefficients A … J: which the surface takes is not known"
        ));
    }
    match t.as_str() {
        "XYP" => xy_polynomial(s, c, scale, read),
        "QBF" => qbfs(s, c, scale, read),
        _ => Err(format!(
            "SPS {t} (line {line}): no public material gives the coefficients' layout of this \
             type (spiralcam reads SPS XYP and SPS QBF)"
        )),
    }
}

fn xy_polynomial(
    s: &Raw,
    c: f64,
    scale: Scale,
    read: &mut Vec<String>,
) -> Result<SurfaceSpec, String> {
    let mut k = s.k.map_or(0.0, |v| v.0);
    let mut norm = 1.0;
    let mut terms = Vec::new();
    for (key, &(v, l)) in &s.sco {
        if key == "NRADIUS" {
            if v <= 0.0 {
                return Err(format!("SCO NRADIUS {v} (line {l}): must be > 0"));
            }
            norm = v;
            continue;
        }
        let j = key
            .strip_prefix('C')
            .and_then(|d| d.parse::<usize>().ok())
            .filter(|j| (1..=MAX_XYP).contains(j))
            .ok_or_else(|| {
                format!("SCO {key} (line {l}): an XY polynomial takes C1 … C{MAX_XYP} and NRADIUS")
            })?;
        if j == 1 {
            if s.k.is_some_and(|kk| kk.0 != v) {
                return Err(format!("SCO C1 {v} (line {l}), the conic, differs from K"));
            }
            k = v;
            read.push(format!("SCO C1 {v} (line {l}): the conic"));
            continue;
        }
        let (m, n) = (0..=10u32)
            .flat_map(|d| (0..=d).map(move |n| (d - n, n)))
            .find(|&(m, n)| xyp_index(m, n) == j)
            .unwrap_or((0, 0));
        let mm = scale.length(v);
        read.push(format!(
            "SCO C{j} {v} (line {l}): x^{m}·y^{n} → {mm} mm (normalised)"
        ));
        if v != 0.0 {
            terms.push(XyTerm {
                x: m,
                y: n,
                coefficient_mm: mm,
            });
        }
    }
    let norm_mm = scale.length(norm);
    read.push(match s.sco.get("NRADIUS") {
        Some((v, l)) => format!("SCO NRADIUS {v} (line {l}): normalisation radius {norm_mm} mm"),
        None => format!("NRADIUS not given: 1 lens unit ({norm_mm} mm), un-normalised"),
    });
    Ok(SurfaceSpec::XyPolynomial(XyPolynomialSpec {
        base: conic(c, k),
        norm_radius_mm: norm_mm,
        terms,
    }))
}

fn qbfs(s: &Raw, c: f64, scale: Scale, read: &mut Vec<String>) -> Result<SurfaceSpec, String> {
    if let Some((v, l)) = s.k.filter(|k| k.0 != 0.0) {
        return Err(format!(
            "K {v} (line {l}) on a Qbfs surface, which has no conic"
        ));
    }
    let Some((norm, l)) = coefficient(s, 1, "NRADIUS") else {
        return Err("SPS QBF without its normalisation radius (SCO C1 or NRADIUS)".into());
    };
    if norm <= 0.0 {
        return Err(format!(
            "the normalisation radius {norm} (line {l}) must be > 0"
        ));
    }
    read.push(format!(
        "NRADIUS (C1) {norm} (line {l}): {} mm",
        scale.length(norm)
    ));
    if let Some((v, l)) = coefficient(s, 2, "C2").filter(|v| v.0 != 0.0) {
        return Err(format!(
            "SCO C2 {v} (line {l}): its meaning on a Qbfs surface is not known"
        ));
    }
    for (key, (_, l)) in &s.sco {
        let known = key == "NRADIUS"
            || key
                .strip_prefix('C')
                .and_then(|d| d.parse::<usize>().ok())
                .is_some_and(|j| (1..=33).contains(&j))
            || key
                .strip_prefix("QB")
                .and_then(|d| d.parse::<usize>().ok())
                .is_some_and(|p| p >= 4 && p % 2 == 0 && p <= 64);
        if !known {
            return Err(format!(
                "SCO {key} (line {l}): a Qbfs takes NRADIUS (C1) and QB4, QB6, … (C3, C4, …)"
            ));
        }
    }
    let mut a = Vec::new();
    for m in 0..31 {
        let name = format!("QB{}", 2 * m + 4);
        let v = coefficient(s, m + 3, &name);
        if let Some((v, l)) = v {
            read.push(format!(
                "{name} (C{}) {v} (line {l}): a{m} → {} mm",
                m + 3,
                scale.length(v)
            ));
        }
        a.push(scale.length(v.map_or(0.0, |v| v.0)));
    }
    while a.last() == Some(&0.0) {
        a.pop();
    }
    let base = conic(c, 0.0);
    Ok(SurfaceSpec::QBfs(QBfsSpec {
        radius_mm: base.radius_mm,
        curvature_per_mm: base.curvature_per_mm,
        norm_radius_mm: scale.length(norm),
        coefficients_mm: a,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_split_join_and_quote() {
        let c =
            commands("TIT 'F/4; 3 mirrors!'  ! a title\nS -1058.9 -276 REFL; CON\nK &\n -1.3\n");
        let names: Vec<&str> = c.iter().map(|c| c.name.as_str()).collect();
        assert_eq!(names, ["TIT", "S", "CON", "K"]);
        assert_eq!(c[0].words, ["F/4; 3 mirrors!"]);
        assert_eq!(c[3].words, ["-1.3"]);
        assert_eq!(c[3].line, 3);
    }

    #[test]
    fn the_xy_index_is_code_vs() {
        // The public listing: C3 y, C4 x², C6 y², C8 x²y, C10 y³, C11 x⁴, C37 x⁸, C45 y⁸.
        for (m, n, j) in [
            (1, 0, 2),
            (0, 1, 3),
            (2, 0, 4),
            (0, 2, 6),
            (2, 1, 8),
            (0, 3, 10),
            (4, 0, 11),
            (8, 0, 37),
            (0, 8, 45),
            (0, 10, 66),
        ] {
            assert_eq!(xyp_index(m, n), j, "x^{m} y^{n}");
        }
    }

    /// The tertiary mirror of ray-optics' `threemir.seq` (ASP) and CODE V's listing of the same
    /// mirror converted to Qbfs (`threemrc_qbfs.lis`), written in both coefficient spellings.
    #[test]
    fn the_public_qbfs_listing_reproduces_its_asphere() {
        let asp = "RDM Y\nDIM M\nSO 0 1e11\nS -453.96516 -321.621031 REFL\nASP\nK 0.226106; A 0.368950E-10\nSI 0 0\n";
        let qbf_named = "SO 0 1e11\nS -449.67012 -321.621031 REFL\nSPS QBF\nSCO NRADIUS 1.8986E+02\n\
            SCO QB4 4.2605E-01; SCO QB6 -1.6782E-02; SCO QB8 8.2673E-04\n\
            SCO QB10 -4.4487E-05; SCO QB12 2.5242E-06; SCO QB14 -1.3595E-07\nSI 0 0\n";
        let qbf_c = "SO 0 1e11\nS -449.67012 -321.621031 REFL\nSPS QBF\nSCO C1 1.8986E+02\n\
            SCO C3 4.2605E-01; SCO C4 -1.6782E-02; SCO C5 8.2673E-04\n\
            SCO C6 -4.4487E-05; SCO C7 2.5242E-06; SCO C8 -1.3595E-07\nSI 0 0\n";
        let surface = |text: &str| {
            let d = parse("m.seq", text).unwrap();
            let s = &d.surfaces[1];
            assert!(s.optics.mirror);
            s.shape.clone().unwrap().build(190.0).unwrap()
        };
        let a = surface(asp);
        for q in [surface(qbf_named), surface(qbf_c)] {
            for r in [0.0, 40.0, 80.0, 120.0, 160.0, 189.86] {
                let d = (a.sag(r, 0.0).unwrap() - q.sag(0.0, r).unwrap()).abs();
                // The listing's five significant digits: 26 nm at the rim.
                assert!(d < 30e-6, "r {r}: {d} mm");
            }
        }
    }
}

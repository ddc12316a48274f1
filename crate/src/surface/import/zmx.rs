//! OpticStudio `.zmx` lens files (sequential mode): the surfaces and their types, curvatures,
//! conics, parameters, extra data, semi-diameters and media, in the lens units of `UNIT`.
//!
//! **Layout.** Zemax has not published the format since about 2005 (a Zemax staff answer on
//! the Zemax community forum, "ZMX file specification"); it is read here as the public readers
//! read it and as vendors' files show it: ray-optics `zemax/zmxread.py` (M. J. Hayford: `SURF`
//! opens a surface, `TYPE`, `CURV` (the curvature, first field), `CONI`, `PARM i v`,
//! `XDAT i v`, `DIAM v` the semi-diameter, `UNIT MM …` the lens unit first, EVENASPH's
//! `PARM i` the coefficient of r^(2i), TOROIDAL's `PARM 1` the radius of rotation and the rest
//! the y terms, Extended Polynomial's `XDAT 1` the number of terms and `XDAT 2` the
//! normalisation radius), optiland's `fileio/zemax/reader/parser.py` (`GLAS MIRROR` a mirror,
//! `CLAP r_min r_max` a circular aperture), and the vendor files in ray-optics' tests
//! (Thorlabs and Edmund lenses: UTF-16LE with a byte-order mark, surface lines indented by two
//! spaces, `MIRR 2 0` on every surface, which is not a mirror).
//!
//! **Surface types** (the parameters as the OpticStudio User Guide defines them; lengths in lens
//! units, converted to mm by the shared conversion of `convert.rs`):
//!
//! | `TYPE` | read as | parameters |
//! |---|---|---|
//! | `STANDARD` | `asphere` (conic) | `CURV`, `CONI` |
//! | `EVENASPH` | `asphere`, or `odd_asphere` with α1 | `PARM 1–8` α1…α8 on r², r⁴, … r¹⁶ |
//! | `ODDASPHE` | `odd_asphere` | `PARM 1–8` β1…β8 on r¹ … r⁸ ("Odd Asphere") |
//! | `TOROIDAL` | `toroid` (+ Zernike Standard as a `composite`) | `CURV` the YZ curvature, `PARM 1` the radius of rotation (0 = infinite: a cylinder), `PARM 2–8` α1…α7 on y², … y¹⁴; `XDAT 1` the number of Zernike terms, `XDAT 2` their normalisation radius, `XDAT 3…` Z1… ("Toroidal") |
//! | `BICONICX` | `biconic` | `CURV`, `CONI` the Y section, `PARM 1` Rx (0 = flat), `PARM 2` kx ("Biconic") |
//! | `XPOLYNOM` | `xy_polynomial` | `XDAT 1` the number of terms, `XDAT 2` the normalisation radius, `XDAT 3…` the terms x, y, x², xy, y², x³, … ("Extended Polynomial": term 1 is x, term 12 x²y²) |
//! | `SZERNSAG`, `FZERNSAG` | `zernike` standard / fringe on the even asphere | `PARM 1–8` α, `PARM 9–10` the Zernike decentre; `XDAT 1` the number of terms, `XDAT 2` the normalisation radius, `XDAT 3…` Z1… |
//! | `GRIDSAG` | `grid_sag` on the even asphere | `PARM 1–8` α; the grid from the `.DAT` the surface names |
//!
//! `PARM 0` (the Extrapolate flag of the Toroidal and Zernike surfaces) is read and listed:
//! spiralcam always extends the polynomials beyond the normalisation radius (Extrapolate 1).
//! Every other parameter or extra-data value a type does not use must be zero: a non-zero one is
//! an error naming it, so that a layout misread can never pass silently.
//!
//! **Not read.** `QED_TYPE` (OpticStudio's Q-type asphere) appears in vendors' files (Thorlabs'
//! ASL5040-UV: `XDAT 1 0`, `XDAT 2 6`, `XDAT 3 27`, then six coefficients, with a conic), and
//! a Zemax staff post says "Type 0 indicates Qbfs polynomials, and Type 1 indicates Qcon"; but
//! with that reading the vendor's surface (R 17.4 mm, semi-diameter 22.9 mm) would be a Qbfs
//! beyond its sphere's rim, so which value selects the type is not established: the type is
//! refused with that explanation. Any other type (a coordinate break, a user DLL, a paraxial
//! surface) is refused naming the types read.
//!
//! **Inferred, not found documented:** the type name `BICONICX` (from the issue); the Zernike
//! sags' extra-data layout (as the Extended Polynomial's and the issue's); `PARM 9–10` of a
//! Zernike sag as the Zernike decentre (the User Guide says so of the Grid Sag's base), the
//! terms placed at +decentre; `SCBD` (a surface's own tilt and decentre, seen in a public file
//! with a 90° tilt) as tilted or decentred when any of its values after the third is non-zero;
//! the `UNIT` names other than `MM` and `IN` (`CM`, `METER`, `M`); a Grid Sag's `.DAT` as the
//! one word ending in `.DAT` on its lines (OpticStudio may keep an imported grid inside the
//! lens file instead, in a layout not published: such a surface is refused, pointing to the
//! `.DAT`).
//!
//! **Frames.** A surface after a coordinate break (`TYPE COORDBRK`) or after a surface with its
//! own tilt or decentre lies in a moved frame ([`DesignSurface::frame_moved`]); the job layer
//! refuses to cut it. Lines at the top level (fields, wavelengths, tolerances) do not describe
//! surfaces and are not read; `MODE` must be `SEQ`, and several configurations (`MNUM`) are
//! noted: the values read are those stored with the surfaces.

use super::convert::{EvenAsphere, Scale, conic};
use super::{Aperture, Design, DesignFormat, DesignSurface, ImportError, LengthUnit, Optics, Role};
use crate::surface::xy_polynomial::{MAX_DEGREE, XyTerm};
use crate::surface::zernike::Convention;
use crate::surface::{
    BiconicSpec, DataFile, GridSagSpec, OddAsphereSpec, SurfaceSpec, ToroidSpec, XyPolynomialSpec,
    ZernikeSpec,
};
use std::collections::BTreeMap;

/// The highest parameter index read (OpticStudio's go to 254).
pub const MAX_PARM: usize = 300;
/// The highest extra-data index read (OpticStudio's Zernike Standard takes 2 + 231).
pub const MAX_XDAT: usize = 1000;

/// The surface types read.
pub const TYPES_READ: &[&str] = &[
    "STANDARD", "EVENASPH", "ODDASPHE", "TOROIDAL", "BICONICX", "XPOLYNOM", "SZERNSAG", "FZERNSAG",
    "GRIDSAG",
];

/// Surface keywords that do not describe the shape: thickness, stop, display, mechanical
/// aperture, coatings, solve and variable flags, physical-optics settings, the mirror
/// substrate's display (`MIRR`).
const IGNORED: &[&str] = &[
    "DISZ", "STOP", "HIDE", "MIRR", "SLAB", "POPS", "MEMA", "OEMA", "FIMP", "FLAP", "COAT", "PZUP",
    "VPAR", "VCON", "PPAR", "EDGE", "THIC", "SQAP", "ELAP", "OBSC", "RCMF", "TCE", "MAZH",
];

/// Keywords that belong to a surface even when a writer does not indent them.
const SURFACE_KEYWORDS: &[&str] = &[
    "TYPE", "CURV", "CONI", "PARM", "XDAT", "DIAM", "GLAS", "COMM", "CLAP", "OBDC", "SCBD",
];

/// One line of a surface: number, keyword (upper case), the words after it, the raw text.
struct Line<'a> {
    line: usize,
    key: String,
    args: Vec<&'a str>,
    raw: &'a str,
}

/// A surface's lines.
struct Block<'a> {
    number: usize,
    line: usize,
    lines: Vec<Line<'a>>,
}

/// A value with the line it was read on.
type At = (f64, usize);

/// Indexed values (`PARM i v`, `XDAT i v`).
struct Indexed {
    key: &'static str,
    values: BTreeMap<usize, At>,
}

impl Indexed {
    fn new(key: &'static str) -> Self {
        Self {
            key,
            values: BTreeMap::new(),
        }
    }

    fn get(&self, i: usize) -> f64 {
        self.values.get(&i).map_or(0.0, |v| v.0)
    }

    /// `KEY i v (line n)`.
    fn show(&self, i: usize) -> String {
        match self.values.get(&i) {
            Some((v, l)) => format!("{} {i} = {v} (line {l})", self.key),
            None => format!("{} {i} not given (0)", self.key),
        }
    }

    /// Every value whose index `used` rejects must be zero.
    fn only(&self, used: impl Fn(usize) -> bool, kind: &str, uses: &str) -> Result<(), String> {
        match self
            .values
            .iter()
            .find(|(i, (v, _))| !used(**i) && *v != 0.0)
        {
            Some((i, (v, l))) => Err(format!(
                "{} {i} = {v} (line {l}) is not read for TYPE {kind}: {uses}; spiralcam reads \
                 no other value of this type, so a non-zero one would be lost",
                self.key
            )),
            None => Ok(()),
        }
    }
}

/// What a surface's lines say, before conversion.
struct Raw {
    number: usize,
    line: usize,
    kind: String,
    kind_rest: String,
    curv: Option<At>,
    coni: Option<At>,
    parm: Indexed,
    xdat: Indexed,
    diam: Option<At>,
    clap: Option<At>,
    obdc: Option<([f64; 2], usize)>,
    glass: Option<(String, usize)>,
    comment: Option<String>,
    tilted: Option<usize>,
    dat_names: Vec<(String, usize)>,
    not_read: Vec<String>,
}

/// A finite number from a word, or an error naming the line.
fn number(file: &str, line: usize, what: &str, word: Option<&&str>) -> Result<f64, ImportError> {
    let Some(w) = word else {
        return Err(ImportError::line(
            file,
            line,
            format!("{what}: a number is missing"),
        ));
    };
    match w.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(ImportError::line(
            file,
            line,
            format!("{what} = {w:?}: expected a finite number"),
        )),
    }
}

/// An index `0 ≤ i ≤ max` from a word.
fn index(
    file: &str,
    line: usize,
    what: &str,
    word: Option<&&str>,
    max: usize,
) -> Result<usize, ImportError> {
    match word.and_then(|w| w.parse::<usize>().ok()) {
        Some(i) if i <= max => Ok(i),
        _ => Err(ImportError::line(
            file,
            line,
            format!(
                "{what} index {:?}: expected a whole number from 0 to {max}",
                word.copied().unwrap_or("")
            ),
        )),
    }
}

fn set(file: &str, slot: &mut Option<At>, what: &str, l: &Line) -> Result<(), ImportError> {
    if let Some((_, first)) = slot {
        return Err(ImportError::line(
            file,
            l.line,
            format!("{what} given twice on one surface (first on line {first})"),
        ));
    }
    *slot = Some((number(file, l.line, what, l.args.first())?, l.line));
    Ok(())
}

impl Raw {
    fn read(file: &str, b: &Block) -> Result<Self, ImportError> {
        let mut r = Raw {
            number: b.number,
            line: b.line,
            kind: "STANDARD".into(),
            kind_rest: String::new(),
            curv: None,
            coni: None,
            parm: Indexed::new("PARM"),
            xdat: Indexed::new("XDAT"),
            diam: None,
            clap: None,
            obdc: None,
            glass: None,
            comment: None,
            tilted: None,
            dat_names: Vec::new(),
            not_read: Vec::new(),
        };
        for l in &b.lines {
            for w in &l.args {
                let w = w.trim_matches('"');
                if w.len() > 4 && w.to_ascii_lowercase().ends_with(".dat") {
                    r.dat_names.push((w.to_string(), l.line));
                }
            }
            match l.key.as_str() {
                "TYPE" => {
                    let t = l.args.first().copied().unwrap_or("");
                    r.kind = t.to_ascii_uppercase();
                    r.kind_rest = l.args[1.min(l.args.len())..].join(" ");
                }
                "CURV" => set(file, &mut r.curv, "CURV", l)?,
                "CONI" => set(file, &mut r.coni, "CONI", l)?,
                "DIAM" => set(file, &mut r.diam, "DIAM", l)?,
                "PARM" | "XDAT" => {
                    let (max, values) = if l.key == "PARM" {
                        (MAX_PARM, &mut r.parm)
                    } else {
                        (MAX_XDAT, &mut r.xdat)
                    };
                    let i = index(file, l.line, &l.key, l.args.first(), max)?;
                    let v = number(file, l.line, &format!("{} {i}", l.key), l.args.get(1))?;
                    if let Some((_, first)) = values.values.insert(i, (v, l.line)) {
                        return Err(ImportError::line(
                            file,
                            l.line,
                            format!("{} {i} given twice (first on line {first})", l.key),
                        ));
                    }
                }
                "CLAP" => {
                    let outer = number(file, l.line, "CLAP maximum radius", l.args.get(1))?;
                    r.clap = Some((outer, l.line));
                }
                "OBDC" => {
                    let dx = number(file, l.line, "OBDC x", l.args.first())?;
                    let dy = number(file, l.line, "OBDC y", l.args.get(1))?;
                    r.obdc = Some(([dx, dy], l.line));
                }
                "GLAS" => {
                    let name = l.args.first().copied().unwrap_or("").to_string();
                    r.glass = Some((name, l.line));
                }
                "COMM" => {
                    let text = l.raw.trim_start()[4..].trim();
                    r.comment = (!text.is_empty()).then(|| text.to_string());
                }
                "SCBD" => {
                    let moved = l
                        .args
                        .iter()
                        .skip(3)
                        .any(|w| w.parse::<f64>().is_ok_and(|v| v != 0.0));
                    if moved {
                        r.tilted = Some(l.line);
                    }
                }
                k if IGNORED.contains(&k) => {}
                k => r.not_read.push(format!("{k} (line {})", l.line)),
            }
        }
        Ok(r)
    }

    fn mirror(&self) -> bool {
        self.glass
            .as_ref()
            .is_some_and(|(g, _)| g.eq_ignore_ascii_case("MIRROR"))
    }

    /// The glass after the surface, `None` for air.
    fn medium(&self) -> Option<String> {
        match &self.glass {
            Some((g, _)) if !g.is_empty() && !g.eq_ignore_ascii_case("AIR") => Some(g.clone()),
            _ => None,
        }
    }
}

/// The lens unit of `UNIT`'s first word.
fn unit(file: &str, line: usize, word: Option<&&str>) -> Result<LengthUnit, ImportError> {
    let w = word.copied().unwrap_or("").to_ascii_uppercase();
    Ok(match w.as_str() {
        "MM" => LengthUnit::MM,
        "CM" => LengthUnit {
            name: "cm",
            mm: 10.0,
        },
        "IN" | "INCH" | "INCHES" => LengthUnit {
            name: "in",
            mm: 25.4,
        },
        "M" | "METER" | "METERS" | "METRE" | "METRES" => LengthUnit {
            name: "m",
            mm: 1000.0,
        },
        _ => {
            return Err(ImportError::line(
                file,
                line,
                format!("lens unit {w}: expected MM, CM, IN or METER"),
            ));
        }
    })
}

/// Reads a `.zmx` text (see the module docs).
pub fn parse(file: &str, text: &str) -> Result<Design, ImportError> {
    let mut unit_read: Option<(LengthUnit, usize)> = None;
    let mut notes = Vec::new();
    let mut blocks: Vec<Block> = Vec::new();
    let mut open = false;
    for (k, raw) in text.lines().enumerate() {
        let line = k + 1;
        let trimmed = raw.trim();
        let mut words = trimmed.split_whitespace();
        let Some(first) = words.next() else {
            continue;
        };
        let key = first.to_ascii_uppercase();
        let args: Vec<&str> = words.collect();
        if key == "SURF" {
            let n = index(file, line, "SURF", args.first(), usize::MAX)?;
            if let Some(b) = blocks.iter().find(|b| b.number == n) {
                return Err(ImportError::line(
                    file,
                    line,
                    format!("SURF {n} again (first on line {})", b.line),
                ));
            }
            blocks.push(Block {
                number: n,
                line,
                lines: Vec::new(),
            });
            open = true;
            continue;
        }
        let indented = raw.starts_with(char::is_whitespace);
        if open && (indented || SURFACE_KEYWORDS.contains(&key.as_str())) {
            if let Some(b) = blocks.last_mut() {
                b.lines.push(Line {
                    line,
                    key,
                    args,
                    raw,
                });
            }
            continue;
        }
        open = false;
        match key.as_str() {
            "UNIT" => unit_read = Some((unit(file, line, args.first())?, line)),
            "MODE" => {
                let mode = args.first().copied().unwrap_or("").to_ascii_uppercase();
                if mode != "SEQ" {
                    return Err(ImportError::line(
                        file,
                        line,
                        format!(
                            "MODE {mode}: only sequential lens files (MODE SEQ) have surfaces \
                             spiralcam reads"
                        ),
                    ));
                }
            }
            "MNUM" => {
                let n = args
                    .first()
                    .and_then(|w| w.parse::<u32>().ok())
                    .unwrap_or(1);
                if n > 1 {
                    notes.push(format!(
                        "{n} configurations (MNUM, line {line}): the values read are those \
                         stored with the surfaces, the configuration current when the file was \
                         saved; the multi-configuration operands are not applied"
                    ));
                }
            }
            _ => {}
        }
    }
    if blocks.is_empty() {
        return Err(ImportError::Format {
            file: file.to_string(),
            problem: "no surface (no SURF line): not an OpticStudio lens file".into(),
        });
    }
    let (unit, unit_from) = match unit_read {
        Some((u, l)) => (u, format!("UNIT, line {l}")),
        None => (
            LengthUnit::MM,
            "not stated (no UNIT line): millimetres, OpticStudio's default".into(),
        ),
    };
    let scale = Scale(unit.mm);
    let raws = blocks
        .iter()
        .map(|b| Raw::read(file, b))
        .collect::<Result<Vec<_>, _>>()?;
    let mut surfaces = Vec::with_capacity(raws.len());
    let mut medium: Option<String> = None;
    let mut plus = true;
    let mut moved: Option<String> = None;
    let last = raws.len() - 1;
    for (k, r) in raws.iter().enumerate() {
        let mirror = r.mirror();
        let before = medium.clone();
        let after = if mirror { before.clone() } else { r.medium() };
        let optics = Optics {
            mirror,
            before,
            after: after.clone(),
            light_along_plus_z: plus,
            known: true,
        };
        let own = r
            .tilted
            .map(|l| format!("the surface itself is tilted or decentred (SCBD, line {l})"));
        let frame_moved = moved.clone().or(own);
        surfaces.push(surface(r, scale, optics, frame_moved, k, last));
        medium = after;
        if mirror {
            plus = !plus;
        }
        if r.kind == "COORDBRK" {
            moved = Some(format!(
                "it lies behind the coordinate break of surface {} (line {})",
                r.number, r.line
            ));
        } else if let Some(l) = r.tilted {
            moved = Some(format!(
                "it lies behind surface {}, which is tilted or decentred (SCBD, line {l})",
                r.number
            ));
        }
    }
    Ok(Design {
        file: file.to_string(),
        format: DesignFormat::Zmx,
        encoding: super::Encoding::Utf8,
        unit,
        unit_from,
        surfaces,
        notes,
    })
}

/// A surface read: its shape, aperture and listing.
fn surface(
    r: &Raw,
    scale: Scale,
    optics: Optics,
    frame_moved: Option<String>,
    k: usize,
    last: usize,
) -> DesignSurface {
    let mut read = Vec::new();
    let shape = shape(r, scale, &mut read);
    let mut aperture = Aperture::default();
    if let Some((d, l)) = r.diam.filter(|d| d.0 > 0.0) {
        aperture.semi_diameter_mm = Some(scale.length(d));
        aperture.from = format!("DIAM, line {l}");
    } else if let Some((c, l)) = r.clap.filter(|c| c.0 > 0.0) {
        aperture.semi_diameter_mm = Some(scale.length(c));
        aperture.from = format!("CLAP (circular aperture) maximum radius, line {l}");
    }
    if let Some(d) = aperture.semi_diameter_mm {
        read.push(format!("semi-diameter {} mm ({})", d, aperture.from));
    }
    if let Some(([dx, dy], l)) = r.obdc.filter(|o| o.0 != [0.0, 0.0]) {
        aperture.decentre_mm = Some([scale.length(dx), scale.length(dy)]);
        read.push(format!(
            "aperture decentred by ({}, {}) mm (OBDC, line {l})",
            scale.length(dx),
            scale.length(dy)
        ));
    }
    if let Some((g, l)) = &r.glass {
        read.push(format!("GLAS {g} (line {l})"));
    }
    let role = match k {
        0 => Role::Object,
        k if k == last => Role::Image,
        _ => Role::Surface,
    };
    DesignSurface {
        number: r.number,
        line: r.line,
        kind: if r.kind_rest.is_empty() {
            r.kind.clone()
        } else {
            format!("{} {}", r.kind, r.kind_rest)
        },
        label: r.comment.clone(),
        role,
        shape,
        aperture,
        optics,
        frame_moved,
        read,
        not_read: r.not_read.clone(),
    }
}

/// The vertex curvature (1/mm) and conic, listed.
fn base(r: &Raw, scale: Scale, read: &mut Vec<String>) -> (f64, f64) {
    let c = scale.curvature(r.curv.map_or(0.0, |v| v.0));
    let k = r.coni.map_or(0.0, |v| v.0);
    match r.curv {
        Some((v, l)) if c != 0.0 => {
            read.push(format!("CURV {v} (line {l}): vertex radius {} mm", 1.0 / c))
        }
        Some((v, l)) => read.push(format!("CURV {v} (line {l}): flat")),
        None => read.push("CURV not given: flat".into()),
    }
    if let Some((v, l)) = r.coni {
        read.push(format!("CONI {v} (line {l})"));
    }
    (c, k)
}

/// `count` indexed terms from `first`, each the coefficient of a power `power(i)` of a length,
/// converted to mm and listed with `name(i)`.
fn terms(
    values: &Indexed,
    first: usize,
    count: usize,
    scale: Scale,
    power: impl Fn(usize) -> i32,
    name: impl Fn(usize) -> String,
    read: &mut Vec<String>,
) -> Vec<f64> {
    (0..count)
        .map(|i| {
            let v = values.get(first + i);
            let mm = scale.coefficient(v, power(i));
            if values.values.contains_key(&(first + i)) && v != 0.0 {
                read.push(format!(
                    "{}: {} → {mm} mm^{}",
                    values.show(first + i),
                    name(i),
                    1 - power(i)
                ));
            }
            mm
        })
        .collect()
}

/// α1 … α8 of `PARM 1–8` on r² … r¹⁶.
fn even_terms(r: &Raw, scale: Scale, read: &mut Vec<String>) -> Vec<f64> {
    let p = |i: usize| 2 * (i as i32 + 1);
    terms(
        &r.parm,
        1,
        8,
        scale,
        p,
        |i| format!("α{} (r^{})", i + 1, p(i)),
        read,
    )
}

/// The normalisation radius in `XDAT 2` (> 0), in lens units, listed with `XDAT 1` read as
/// `count`.
fn norm_radius(r: &Raw, scale: Scale, count: &str, read: &mut Vec<String>) -> Result<f64, String> {
    let norm = r.xdat.get(2);
    if norm <= 0.0 {
        return Err(format!(
            "{}: the normalisation radius must be > 0",
            r.xdat.show(2)
        ));
    }
    read.push(format!("{}: {count}", r.xdat.show(1)));
    read.push(format!(
        "{}: normalisation radius {} mm",
        r.xdat.show(2),
        scale.length(norm)
    ));
    Ok(norm)
}

/// The Zernike terms of the extra data: `XDAT 1` their number, `XDAT 2` the normalisation
/// radius, `XDAT 3…` Z1…; `None` without any. `max` is the convention's count.
fn zernike_terms(
    r: &Raw,
    scale: Scale,
    max: usize,
    read: &mut Vec<String>,
) -> Result<Option<(f64, Vec<f64>)>, String> {
    let n = r.xdat.get(1);
    if n == 0.0 {
        r.xdat.only(
            |i| i == 2,
            &r.kind,
            "XDAT 1 (the number of Zernike terms) is 0",
        )?;
        return Ok(None);
    }
    if n.fract() != 0.0 || n < 0.0 || n > max as f64 {
        return Err(format!(
            "{}: the number of Zernike terms must be a whole number from 0 to {max}",
            r.xdat.show(1)
        ));
    }
    let n = n as usize;
    let norm = norm_radius(r, scale, &format!("{n} Zernike terms"), read)?;
    let c = terms(&r.xdat, 3, n, scale, |_| 0, |i| format!("Z{}", i + 1), read);
    let beyond: Vec<usize> = r
        .xdat
        .values
        .iter()
        .filter(|(i, (v, _))| **i > n + 2 && *v != 0.0)
        .map(|(i, _)| *i)
        .collect();
    if let Some(i) = beyond.first() {
        read.push(format!(
            "{} and any later extra data lie beyond the {n} terms: not used (as OpticStudio)",
            r.xdat.show(*i)
        ));
    }
    Ok(Some((scale.length(norm), c)))
}

/// The term of Zemax's Extended Polynomial `i` (from 1): x, y, x², xy, y², x³, … as
/// `(power of x, power of y)`.
pub fn extended_polynomial_term(i: usize) -> (u32, u32) {
    let mut d = 1;
    while (d + 1) * (d + 2) / 2 <= i {
        d += 1;
    }
    let k = i - d * (d + 1) / 2;
    ((d - k) as u32, k as u32)
}

/// The surface's spec, or why there is none.
fn shape(r: &Raw, scale: Scale, read: &mut Vec<String>) -> Result<SurfaceSpec, String> {
    let kind = r.kind.as_str();
    let extrapolate = |read: &mut Vec<String>| {
        if r.parm.values.contains_key(&0) {
            read.push(format!(
                "{}: Extrapolate; spiralcam extends the polynomial beyond its normalisation \
                 radius (Extrapolate 1)",
                r.parm.show(0)
            ));
        }
    };
    match kind {
        "STANDARD" => {
            r.parm
                .only(|_| false, kind, "the Standard surface has no parameters")?;
            r.xdat
                .only(|_| false, kind, "the Standard surface has no extra data")?;
            let (c, k) = base(r, scale, read);
            Ok(SurfaceSpec::Asphere(conic(c, k)))
        }
        "EVENASPH" => {
            r.parm.only(
                |i| (1..=8).contains(&i),
                kind,
                "Even Asphere uses PARM 1–8 (α1 … α8)",
            )?;
            r.xdat
                .only(|_| false, kind, "Even Asphere has no extra data")?;
            let (c, k) = base(r, scale, read);
            let alpha = even_terms(r, scale, read);
            Ok(EvenAsphere::new(c, k, &alpha).spec())
        }
        "ODDASPHE" => {
            r.parm.only(
                |i| (1..=8).contains(&i),
                kind,
                "Odd Asphere uses PARM 1–8 (β1 … β8)",
            )?;
            r.xdat
                .only(|_| false, kind, "Odd Asphere has no extra data")?;
            let (c, k) = base(r, scale, read);
            let mut beta = terms(
                &r.parm,
                1,
                8,
                scale,
                |i| i as i32 + 1,
                |i| format!("β{} (r^{})", i + 1, i + 1),
                read,
            );
            while beta.last() == Some(&0.0) {
                beta.pop();
            }
            let c0 = conic(c, k);
            Ok(SurfaceSpec::OddAsphere(OddAsphereSpec {
                radius_mm: c0.radius_mm,
                curvature_per_mm: c0.curvature_per_mm,
                conic: k,
                coefficients: beta,
            }))
        }
        "TOROIDAL" => {
            r.parm.only(
                |i| i <= 8,
                kind,
                "Toroidal uses PARM 0 (Extrapolate), 1 (radius of rotation) and 2–8 (α1 … α7)",
            )?;
            let (cy, ky) = base(r, scale, read);
            extrapolate(read);
            let rotation = scale.length(r.parm.get(1));
            read.push(if rotation == 0.0 {
                format!(
                    "{}: radius of rotation 0, infinite: a cylinder",
                    r.parm.show(1)
                )
            } else {
                format!("{}: radius of rotation {rotation} mm", r.parm.show(1))
            });
            let p = |i: usize| 2 * (i as i32 + 1);
            let mut alpha = terms(
                &r.parm,
                2,
                7,
                scale,
                p,
                |i| format!("α{} (y^{})", i + 1, p(i)),
                read,
            );
            while alpha.last() == Some(&0.0) {
                alpha.pop();
            }
            let c0 = conic(cy, ky);
            let toroid = SurfaceSpec::Toroid(ToroidSpec {
                radius_x_mm: (rotation != 0.0).then_some(rotation),
                curvature_x_per_mm: (rotation == 0.0).then_some(0.0),
                radius_y_mm: c0.radius_mm,
                curvature_y_per_mm: c0.curvature_per_mm,
                conic_y: ky,
                profile_coefficients: alpha,
            });
            let max = Convention::Standard.max_terms();
            r.xdat.only(
                |i| i <= max + 2,
                kind,
                "Toroidal's extra data are its Zernike Standard terms",
            )?;
            match zernike_terms(r, scale, max, read)? {
                None => Ok(toroid),
                Some((norm, c)) => Ok(SurfaceSpec::Composite(crate::surface::CompositeSpec {
                    base: Box::new(toroid),
                    terms: vec![crate::surface::TermSpec {
                        surface: zernike(Convention::Standard, conic(0.0, 0.0), norm, c),
                        decenter_x_mm: 0.0,
                        decenter_y_mm: 0.0,
                        rotation_deg: 0.0,
                        correction: false,
                    }],
                })),
            }
        }
        "BICONICX" => {
            r.parm.only(
                |i| i == 1 || i == 2,
                kind,
                "Biconic uses PARM 1 (Rx) and 2 (kx)",
            )?;
            r.xdat.only(|_| false, kind, "Biconic has no extra data")?;
            let (cy, ky) = base(r, scale, read);
            let rx = scale.length(r.parm.get(1));
            let kx = r.parm.get(2);
            read.push(if rx == 0.0 {
                format!("{}: Rx 0, infinite: flat in x", r.parm.show(1))
            } else {
                format!("{}: Rx {rx} mm", r.parm.show(1))
            });
            read.push(format!("{}: kx", r.parm.show(2)));
            let y = conic(cy, ky);
            Ok(SurfaceSpec::Biconic(BiconicSpec {
                radius_x_mm: (rx != 0.0).then_some(rx),
                curvature_x_per_mm: (rx == 0.0).then_some(0.0),
                radius_y_mm: y.radius_mm,
                curvature_y_per_mm: y.curvature_per_mm,
                conic_x: kx,
                conic_y: ky,
            }))
        }
        "XPOLYNOM" => extended_polynomial(r, scale, read),
        "SZERNSAG" | "FZERNSAG" => {
            let convention = if kind == "SZERNSAG" {
                Convention::Standard
            } else {
                Convention::Fringe
            };
            r.parm.only(|i| i <= 10, kind, "the Zernike sags use PARM 0 (Extrapolate), 1–8 (α1 … α8) and 9–10 (the Zernike decentre)")?;
            let max = convention.max_terms();
            r.xdat.only(
                |i| i <= max + 2,
                kind,
                &format!("{max} Zernike terms at most"),
            )?;
            let (c, k) = base(r, scale, read);
            extrapolate(read);
            let alpha = even_terms(r, scale, read);
            let decentre = [scale.length(r.parm.get(9)), scale.length(r.parm.get(10))];
            if decentre != [0.0, 0.0] {
                read.push(format!(
                    "{}, {}: the Zernike terms decentred to ({}, {}) mm",
                    r.parm.show(9),
                    r.parm.show(10),
                    decentre[0],
                    decentre[1]
                ));
            }
            let even = EvenAsphere::new(c, k, &alpha);
            match zernike_terms(r, scale, max, read)? {
                None => Ok(even.spec()),
                Some((norm, coefficients)) => Ok(even.with_family(decentre, |b| {
                    zernike(convention, b, norm, coefficients.clone())
                })),
            }
        }
        "GRIDSAG" => {
            r.parm.only(
                |i| (1..=8).contains(&i),
                kind,
                "Grid Sag's base uses PARM 1–8 (α1 … α8)",
            )?;
            r.xdat.only(|_| false, kind, "the grid comes from its .DAT file; OpticStudio's extra data of a Grid Sag are not read")?;
            let (c, k) = base(r, scale, read);
            let alpha = even_terms(r, scale, read);
            let name = grid_file(r)?;
            read.push(format!("grid: {name} (line {})", r.dat_names[0].1));
            let even = EvenAsphere::new(c, k, &alpha);
            Ok(even.with_family([0.0, 0.0], |b| {
                let plane = b == conic(0.0, 0.0);
                SurfaceSpec::GridSag(GridSagSpec {
                    data: DataFile {
                        path: Some(name.clone()),
                        text: None,
                    },
                    base: (!plane).then_some(b),
                })
            }))
        }
        "QED_TYPE" => Err(
            "OpticStudio's Q-type asphere: which of its values selects Qbfs or Qcon is not \
             publicly documented (read as Qbfs, a vendor's example would lie beyond its \
             sphere's rim), so it is not guessed: enter its coefficients in a q_bfs or q_con \
             job by hand"
                .into(),
        ),
        "COORDBRK" => Err("a coordinate break, not a surface to cut".into()),
        _ => Err("a type spiralcam does not read".into()),
    }
}

fn zernike(
    convention: Convention,
    base: crate::surface::AsphereSpec,
    norm: f64,
    c: Vec<f64>,
) -> SurfaceSpec {
    SurfaceSpec::Zernike(ZernikeSpec {
        convention,
        base,
        norm_radius_mm: norm,
        coefficients_mm: c,
    })
}

/// The `.DAT` a Grid Sag surface names.
fn grid_file(r: &Raw) -> Result<String, String> {
    let mut names: Vec<&String> = r.dat_names.iter().map(|(n, _)| n).collect();
    names.dedup();
    match names.as_slice() {
        [one] => Ok((*one).clone()),
        [] => Err(
            "no .DAT file is named on the surface's lines: OpticStudio may keep the \
                   imported grid inside the lens file, in a layout not publicly documented; \
                   import the .DAT itself (spiralcam import FILE.DAT)"
                .into(),
        ),
        many => Err(format!(
            "several .DAT files are named on the surface's lines ({}): which holds the grid is \
             not known",
            many.iter()
                .map(|n| n.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Zemax's Extended Polynomial: `XDAT 1` the number of terms, `XDAT 2` the normalisation
/// radius, `XDAT 3…` the terms in Zemax's order, as an `xy_polynomial` (degree ≤ 10).
fn extended_polynomial(
    r: &Raw,
    scale: Scale,
    read: &mut Vec<String>,
) -> Result<SurfaceSpec, String> {
    let kind = r.kind.as_str();
    r.parm.only(
        |_| false,
        kind,
        "Extended Polynomial keeps its terms in the extra data",
    )?;
    let (c, k) = base(r, scale, read);
    let n = r.xdat.get(1);
    if n.fract() != 0.0 || !(0.0..=230.0).contains(&n) {
        return Err(format!(
            "{}: the number of terms must be a whole number from 0 to 230",
            r.xdat.show(1)
        ));
    }
    let n = n as usize;
    r.xdat.only(
        |i| i <= 232,
        kind,
        "Extended Polynomial has 230 terms at most",
    )?;
    if let Some((i, _)) = r
        .xdat
        .values
        .iter()
        .find(|(i, (v, _))| **i > n + 2 && *v != 0.0)
    {
        read.push(format!(
            "{} and any later extra data lie beyond the {n} terms: not used (as OpticStudio)",
            r.xdat.show(*i)
        ));
    }
    let norm = norm_radius(r, scale, &format!("{n} terms"), read)?;
    let mut terms = Vec::new();
    for i in 1..=n {
        let v = r.xdat.get(i + 2);
        if v == 0.0 {
            continue;
        }
        let (px, py) = extended_polynomial_term(i);
        if px + py > MAX_DEGREE {
            return Err(format!(
                "{}: term {i} (x^{px}·y^{py}, degree {}) lies beyond spiralcam's XY polynomial, \
                 which goes to degree {MAX_DEGREE} (term 65)",
                r.xdat.show(i + 2),
                px + py
            ));
        }
        let mm = scale.length(v);
        read.push(format!(
            "{}: A{i} on (x/N)^{px}·(y/N)^{py} → {mm} mm",
            r.xdat.show(i + 2)
        ));
        terms.push(XyTerm {
            x: px,
            y: py,
            coefficient_mm: mm,
        });
    }
    Ok(SurfaceSpec::XyPolynomial(XyPolynomialSpec {
        base: conic(c, k),
        norm_radius_mm: scale.length(norm),
        terms,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extended_polynomial_terms_run_x_first_by_order() {
        let names: Vec<(u32, u32)> = (1..=13).map(extended_polynomial_term).collect();
        assert_eq!(
            names,
            vec![
                (1, 0),
                (0, 1),
                (2, 0),
                (1, 1),
                (0, 2),
                (3, 0),
                (2, 1),
                (1, 2),
                (0, 3),
                (4, 0),
                (3, 1),
                (2, 2),
                (1, 3)
            ]
        );
        // The User Guide: term 12 is x²y², term 13 xy³; degree 10 ends at term 65.
        assert_eq!(extended_polynomial_term(65), (0, 10));
        assert_eq!(extended_polynomial_term(66), (11, 0));
    }
}

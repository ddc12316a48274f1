//! A job from a designer's file: one surface of a [`Design`] ([`crate::surface::import`])
//! with the part the file describes, the rest of the job the page's example defaults
//! ([`Job::default_job`]: tool, machine, strategy, output).
//!
//! - **The surface**: the one asked for, else the only surface between object and image; it
//!   must be read as a spiralcam family (an unsupported type is refused naming the surface,
//!   its type and the types read) and lie in the system's frame (not behind a coordinate break).
//! - **The piece and the frame** (`part.cut`, [`super::cut`]): the piece (optic or mould) is
//!   required for a refracting surface and defaults to the optic for a mirror; the frame
//!   follows from the side the piece's material lies on
//!   ([`crate::surface::import::Optics::material_side`]): the optic is cut from the other side,
//!   a mould from that side; from −Z the design is turned 180° about Y.
//! - **The diameter**: the one asked for, else twice the file's semi-diameter; a decentred
//!   aperture needs the diameter given (the spindle turns the part about the vertex).
//! - **Checks**: the job validates, its data files are read, and the surface is defined over
//!   the whole part (9 circles of 32 points out to the rim): a wrong unit or semi-diameter
//!   shows here, before a job is written.

use super::{CutSpec, Frame, Job, JobError, MAX_NAME_CHARS, Piece};
use crate::field::short;
use crate::surface::Surface;
use crate::surface::import::{Design, DesignFormat, DesignSurface, Role, seq, zmx};
use thiserror::Error;

/// What the user chose; `None` leaves the choice to the file.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DesignChoice {
    /// The surface's number in the file.
    pub surface: Option<usize>,
    /// The optic or a mould.
    pub piece: Option<Piece>,
    /// The part's diameter, mm.
    pub diameter_mm: Option<f64>,
}

/// A job made from a design, and what was read for it.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignJob {
    /// The job; its data files carry their text.
    pub job: Job,
    /// The surface's number in the file.
    pub surface: usize,
    /// What was read and decided, one line each, for the user to compare with the
    /// prescription report.
    pub listing: Vec<String>,
}

/// A design that gives no job as it stands.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DesignError {
    /// No surface of that number.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// let d = spiralcam::surface::import::read_design("l.zmx", b"SURF 0\nSURF 1\nSURF 2\n").unwrap();
    /// let choice = DesignChoice { surface: Some(7), ..Default::default() };
    /// let e = job_from_design(&d, &choice, |_| Err("no files".into())).unwrap_err();
    /// assert!(e.to_string().starts_with("l.zmx has no surface 7"), "{e}");
    /// ```
    #[error("{file} has no surface {number}; its surfaces: {surfaces}")]
    NoSuchSurface {
        /// The design file.
        file: String,
        /// The number asked for.
        number: usize,
        /// The surfaces, one summary each.
        surfaces: String,
    },
    /// Several surfaces could be meant.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// let d = spiralcam::surface::import::read_design("l.zmx", b"SURF 0\nSURF 1\nSURF 2\nSURF 3\n").unwrap();
    /// let e = job_from_design(&d, &DesignChoice::default(), |_| Err("".into())).unwrap_err();
    /// assert!(e.to_string().starts_with("l.zmx has 2 surfaces between object and image"), "{e}");
    /// ```
    #[error(
        "{file} has {count} surfaces between object and image: choose one by its number: {surfaces}"
    )]
    ChooseSurface {
        /// The design file.
        file: String,
        /// How many could be meant.
        count: usize,
        /// The surfaces, one summary each.
        surfaces: String,
    },
    /// The surface is of a type not read.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// let d = spiralcam::surface::import::read_design("l.zmx", b"SURF 0\nSURF 1\n TYPE USERSURF us_x.dll\nSURF 2\n").unwrap();
    /// let e = job_from_design(&d, &DesignChoice::default(), |_| Err("".into())).unwrap_err();
    /// assert!(e.to_string().starts_with("l.zmx: surface 1 (line 2) is of type USERSURF us_x.dll"), "{e}");
    /// ```
    #[error(
        "{file}: surface {number} (line {line}) is of type {kind}: {reason}; the types read: {types}"
    )]
    Unsupported {
        /// The design file.
        file: String,
        /// The surface's number.
        number: usize,
        /// Its line.
        line: usize,
        /// Its type as the file names it.
        kind: String,
        /// Why it is not read.
        reason: String,
        /// The types the reader reads.
        types: String,
    },
    /// The surface's frame is moved (a coordinate break, a tilt or a decentre).
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// let d = spiralcam::surface::import::read_design("l.zmx",
    ///     b"SURF 0\nSURF 1\n TYPE COORDBRK\nSURF 2\n CURV 0.01\nSURF 3\n").unwrap();
    /// let choice = DesignChoice { surface: Some(2), ..Default::default() };
    /// let e = job_from_design(&d, &choice, |_| Err("".into())).unwrap_err();
    /// assert!(e.to_string().contains("behind the coordinate break of surface 1"), "{e}");
    /// ```
    #[error(
        "{file}: surface {number} ({kind}) is not in the system's frame: {why}; the side it is cut \
         from cannot be told there, and spiralcam reads surfaces before any coordinate break"
    )]
    FrameMoved {
        /// The design file.
        file: String,
        /// The surface's number.
        number: usize,
        /// Its type.
        kind: String,
        /// Why.
        why: String,
    },
    /// A refracting surface needs the piece chosen.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// let d = spiralcam::surface::import::read_design("l.zmx",
    ///     b"SURF 0\nSURF 1\n CURV 0.02\n GLAS N-BK7\n DIAM 5\nSURF 2\n").unwrap();
    /// let e = job_from_design(&d, &DesignChoice::default(), |_| Err("".into())).unwrap_err();
    /// assert!(e.to_string().contains("choose optic (its own surface, cut from the air side) or mould"), "{e}");
    /// ```
    #[error(
        "{file}: surface {number} is {why}: choose optic (its own surface, cut from the air side) \
         or mould (an insert forming it, cut from the glass side)"
    )]
    ChoosePiece {
        /// The design file.
        file: String,
        /// The surface's number.
        number: usize,
        /// The media.
        why: String,
    },
    /// No diameter in the file and none given.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design, DesignError};
    /// let d = spiralcam::surface::import::read_design("l.zmx",
    ///     b"SURF 0\nSURF 1\n CURV 0.02\n GLAS MIRROR\nSURF 2\n").unwrap();
    /// let e = job_from_design(&d, &DesignChoice::default(), |_| Err("".into())).unwrap_err();
    /// assert!(matches!(e, DesignError::NoDiameter { .. }), "{e}");
    /// ```
    #[error(
        "{file}: surface {number} has no semi-diameter ({what}): give the part's diameter in mm"
    )]
    NoDiameter {
        /// The design file.
        file: String,
        /// The surface's number.
        number: usize,
        /// What the format would have held.
        what: &'static str,
    },
    /// The aperture is decentred from the vertex.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// let d = spiralcam::surface::import::read_design("l.zmx",
    ///     b"SURF 0\nSURF 1\n GLAS MIRROR\n DIAM 5\n OBDC 0 12\nSURF 2\n").unwrap();
    /// let e = job_from_design(&d, &DesignChoice::default(), |_| Err("".into())).unwrap_err();
    /// assert!(e.to_string().contains("decentred by (0, 12) mm"), "{e}");
    /// ```
    #[error(
        "{file}: surface {number}'s aperture is decentred by ({x}, {y}) mm from its vertex, and \
         the spindle turns the part about the vertex: give the diameter of the disc about the \
         vertex to cut"
    )]
    ApertureDecentred {
        /// The design file.
        file: String,
        /// The surface's number.
        number: usize,
        /// The decentre, mm.
        x: String,
        /// The decentre, mm.
        y: String,
    },
    /// The job made is not valid, a data file cannot be read, or the surface is undefined
    /// somewhere on the part.
    ///
    /// ```
    /// use spiralcam::job::design::{DesignChoice, job_from_design};
    /// // A sphere of radius 5 mm on a part of radius 6 mm.
    /// let d = spiralcam::surface::import::read_design("l.zmx",
    ///     b"SURF 0\nSURF 1\n CURV 0.2\n GLAS MIRROR\n DIAM 6\nSURF 2\n").unwrap();
    /// let e = job_from_design(&d, &DesignChoice::default(), |_| Err("".into())).unwrap_err();
    /// assert!(e.to_string().contains("undefined within the part"), "{e}");
    /// ```
    #[error("{file}: surface {number}: {problem}")]
    Job {
        /// The design file.
        file: String,
        /// The surface's number.
        number: usize,
        /// What is wrong.
        problem: String,
    },
}

/// The surfaces, one summary each, joined.
fn summaries<'a>(surfaces: impl Iterator<Item = &'a DesignSurface>) -> String {
    surfaces
        .map(DesignSurface::summary)
        .collect::<Vec<_>>()
        .join("; ")
}

/// The surface chosen, or the only one between object and image.
fn chosen<'a>(design: &'a Design, choice: &DesignChoice) -> Result<&'a DesignSurface, DesignError> {
    let file = design.file.clone();
    if let Some(n) = choice.surface {
        return design.surface(n).ok_or_else(|| DesignError::NoSuchSurface {
            file,
            number: n,
            surfaces: summaries(design.surfaces.iter()),
        });
    }
    let inner = candidates(design);
    match inner.as_slice() {
        [one] => Ok(one),
        _ => Err(DesignError::ChooseSurface {
            file,
            count: inner.len(),
            surfaces: summaries(design.surfaces.iter()),
        }),
    }
}

/// The surfaces that could be meant when none is chosen: those between object and image (a
/// design of one surface, a Grid Sag `.DAT`, that one).
fn candidates(design: &Design) -> Vec<&DesignSurface> {
    design
        .surfaces
        .iter()
        .filter(|s| s.role == Role::Surface || design.surfaces.len() == 1)
        .collect()
}

/// The surface [`job_from_design`] takes when none is chosen, if there is exactly one.
pub fn default_surface(design: &Design) -> Option<usize> {
    match candidates(design).as_slice() {
        [one] => Some(one.number),
        _ => None,
    }
}

/// A job name from the file's name and the surface: letters, digits, `-`, `_`, `.`.
fn job_name(file: &str, number: usize) -> String {
    let base = file.rsplit(['/', '\\']).next().unwrap_or(file);
    let stem = base.rsplit_once('.').map_or(base, |(s, _)| s);
    let clean: String = stem
        .chars()
        .map(|c| match c {
            c if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') => c,
            _ => '-',
        })
        .take(MAX_NAME_CHARS - 12)
        .collect();
    let clean = if clean.is_empty() {
        "design".into()
    } else {
        clean
    };
    format!("{clean}-s{number}")
}

/// The first point of the part where the surface is undefined: 9 circles of 32 points from
/// the axis to the rim.
fn undefined_on(surface: &dyn Surface, radius_mm: f64) -> Option<String> {
    for k in 0..=8 {
        let r = radius_mm * k as f64 / 8.0;
        for j in 0..32 {
            let t = std::f64::consts::TAU * j as f64 / 32.0;
            if let Err(e) = surface.local(r * t.cos(), r * t.sin()) {
                return Some(e.to_string());
            }
            if k == 0 {
                break;
            }
        }
    }
    None
}

/// The types a format's reader reads.
fn types_read(format: DesignFormat) -> String {
    match format {
        DesignFormat::Zmx => zmx::TYPES_READ.join(", "),
        DesignFormat::Seq => seq::TYPES_READ.join(", "),
        DesignFormat::GridSag => "Grid Sag".into(),
    }
}

/// The job for the surface `choice` names (see the module docs); `read` gives the text of a
/// data file the surface names (a Grid Sag's `.DAT`), by the name the design gives it.
pub fn job_from_design(
    design: &Design,
    choice: &DesignChoice,
    read: impl FnMut(&str) -> Result<String, String>,
) -> Result<DesignJob, DesignError> {
    let s = chosen(design, choice)?;
    let file = design.file.clone();
    let spec = s.shape.clone().map_err(|reason| DesignError::Unsupported {
        file: file.clone(),
        number: s.number,
        line: s.line,
        kind: s.kind.clone(),
        reason,
        types: types_read(design.format),
    })?;
    if let Some(why) = &s.frame_moved {
        return Err(DesignError::FrameMoved {
            file,
            number: s.number,
            kind: s.kind.clone(),
            why: why.clone(),
        });
    }
    let piece = match (choice.piece, s.optics.mirror) {
        (Some(p), _) => p,
        (None, true) => Piece::Optic,
        (None, false) => {
            return Err(DesignError::ChoosePiece {
                file,
                number: s.number,
                why: s.optics.material_side().1,
            });
        }
    };
    let (side, why) = s.optics.material_side();
    let tool = match piece {
        Piece::Optic => -side,
        Piece::Mould => side,
    };
    let frame = if tool > 0.0 {
        Frame::Design
    } else {
        Frame::Turned
    };
    let diameter = diameter(design, s, choice)?;
    let mut job = Job::default_job();
    // A job spiralcam writes says which format it is in.
    job.format = Some(crate::job::format::FORMAT);
    job.name = job_name(&design.file, s.number);
    job.part.diameter_mm = diameter.0;
    job.part.normal_axis_at_mm = None;
    job.part.cut = Some(CutSpec { piece, frame });
    job.surface = spec;
    let problem = |problem: String| DesignError::Job {
        file: design.file.clone(),
        number: s.number,
        problem,
    };
    job.load_files(read).map_err(|e| problem(e.to_string()))?;
    job.validate().map_err(|e| problem(e.to_string()))?;
    let surface = job
        .design_surface()
        .map_err(|e| problem(JobError::from(e).to_string()))?;
    if let Some(e) = undefined_on(surface.as_ref(), job.part_radius_mm()) {
        return Err(problem(format!(
            "the surface is undefined within the part (diameter {} mm): {e}; check the units \
             and the semi-diameter",
            short(diameter.0)
        )));
    }
    let mut listing = vec![format!(
        "{}: {}, {}, lens unit {} ({} mm; {})",
        design.file,
        design.format.name(),
        design.encoding.name(),
        design.unit.name,
        design.unit.mm,
        design.unit_from
    )];
    listing.extend(design.notes.iter().map(|n| format!("note: {n}")));
    listing.push(format!("surface {}", s.summary()));
    listing.extend(s.read.iter().map(|l| format!("  {l}")));
    if !s.not_read.is_empty() {
        listing.push(format!(
            "  lines of the surface not read (they do not describe its shape): {}",
            s.not_read.join(", ")
        ));
    }
    listing.push(format!("part diameter {} mm ({})", diameter.0, diameter.1));
    let chose = if choice.piece.is_some() {
        "as chosen"
    } else {
        "a mirror's default"
    };
    listing.push(format!("side: {why}"));
    listing.push(format!(
        "cut: {} ({chose}): {}",
        piece.name(),
        CutSpec { piece, frame }.describe()
    ));
    listing.push(format!("job surface: {}", surface.describe()));
    Ok(DesignJob {
        job,
        surface: s.number,
        listing,
    })
}

/// The part's diameter and where it came from.
fn diameter(
    design: &Design,
    s: &DesignSurface,
    choice: &DesignChoice,
) -> Result<(f64, String), DesignError> {
    if let Some(d) = choice.diameter_mm {
        return Ok((d, "as given".into()));
    }
    if let Some([x, y]) = s.aperture.decentre_mm {
        return Err(DesignError::ApertureDecentred {
            file: design.file.clone(),
            number: s.number,
            x: short(x),
            y: short(y),
        });
    }
    match s.aperture.semi_diameter_mm {
        Some(r) => Ok((
            2.0 * r,
            format!("twice the semi-diameter, {}", s.aperture.from),
        )),
        None => Err(DesignError::NoDiameter {
            file: design.file.clone(),
            number: s.number,
            what: match design.format {
                DesignFormat::Zmx => "DIAM",
                DesignFormat::Seq => "CIR",
                DesignFormat::GridSag => "a Grid Sag file has none",
            },
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_made_of_the_file_and_the_surface() {
        assert_eq!(job_name("dir/My lens (v2).zmx", 3), "My-lens--v2--s3");
        assert_eq!(job_name("C:\\a\\b.seq", 1), "b-s1");
        assert_eq!(job_name(".zmx", 1), "design-s1");
    }
}

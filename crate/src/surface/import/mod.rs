//! Designers' files in (issue 13): an OpticStudio `.zmx`, a CODE V `.seq` or a Zemax Grid Sag
//! `.DAT` read into a [`Design`]: its surfaces, each as the [`SurfaceSpec`] of a spiralcam
//! family in millimetres (or why it cannot be one), with what the file says about the part:
//! the semi-diameter, the media on either side and whether it is a mirror, the direction the
//! light travels there, and whether its frame is moved by a coordinate break. The job layer
//! ([`crate::job::design`]) turns one surface into a job; the parsers read files only, never
//! the file system (the command line and the page hand them bytes).
//!
//! | format | reader | surfaces read |
//! |---|---|---|
//! | OpticStudio `.zmx` (UTF-16 with its mark, UTF-8, ASCII or ISO-8859-1) | [`zmx`] | STANDARD, EVENASPH, ODDASPHE, TOROIDAL, BICONICX, XPOLYNOM, SZERNSAG, FZERNSAG, GRIDSAG |
//! | CODE V `.seq` | [`seq`] | spheres, conics, ASP (A…J), SPS XYP, SPS QBF |
//! | Zemax Grid Sag `.DAT` | [`dat`] | the grid on a plane |
//!
//! Each reader's module docs name the public material its layout was taken from and the
//! conventions inferred where none was found. Lengths are converted from the file's lens units
//! (`UNIT`, `DIM`, the DAT's unit flag) to millimetres: a coefficient of rⁿ in lensunit^(1−n)
//! is multiplied by s^(1−n), s the unit in mm.
//!
//! **Bounds.** A file of at most [`MAX_DESIGN_BYTES`] bytes (checked before it is decoded);
//! parameter and extra-data indices are bounded ([`zmx::MAX_PARM`], [`zmx::MAX_XDAT`]), so no
//! line can make a reader allocate beyond the file's size. Anything a reader does not
//! understand on a surface is listed with the surface ([`DesignSurface::not_read`]), never
//! skipped silently.

mod convert;
pub mod dat;
mod error;
pub mod seq;
pub mod text;
pub mod zmx;

pub use error::ImportError;
pub use text::Encoding;

use super::SurfaceSpec;

/// The largest design file read, bytes (64 MiB).
pub const MAX_DESIGN_BYTES: u64 = 64 << 20;

/// The format of a designer's file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DesignFormat {
    /// OpticStudio lens file.
    Zmx,
    /// CODE V sequence file.
    Seq,
    /// Zemax Grid Sag data.
    GridSag,
}

impl DesignFormat {
    /// The format a file name says (`.zmx`, `.seq`, `.dat`, any case).
    pub fn of_name(name: &str) -> Result<Self, ImportError> {
        let ext = name.rsplit_once('.').map(|(_, e)| e.to_ascii_lowercase());
        match ext.as_deref() {
            Some("zmx") => Ok(Self::Zmx),
            Some("seq") => Ok(Self::Seq),
            Some("dat") => Ok(Self::GridSag),
            _ => Err(ImportError::Format {
                file: name.to_string(),
                problem: "not a design file spiralcam reads: expected an OpticStudio lens file \
                          (.zmx), a CODE V sequence file (.seq) or a Zemax Grid Sag file (.DAT)"
                    .into(),
            }),
        }
    }

    /// The format's name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Zmx => "OpticStudio lens file (.zmx)",
            Self::Seq => "CODE V sequence file (.seq)",
            Self::GridSag => "Zemax Grid Sag file (.DAT)",
        }
    }
}

/// The lens unit of a file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LengthUnit {
    /// Its name as the listing prints it.
    pub name: &'static str,
    /// Millimetres per unit.
    pub mm: f64,
}

impl LengthUnit {
    /// Millimetres.
    pub const MM: LengthUnit = LengthUnit {
        name: "mm",
        mm: 1.0,
    };
}

/// Where a surface lies in the system.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The object surface (OpticStudio's surface 0, CODE V's `SO`).
    Object,
    /// A surface between object and image.
    Surface,
    /// The image surface (the last one, CODE V's `SI`).
    Image,
}

/// The aperture a file gives a surface.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Aperture {
    /// The semi-diameter, mm: `DIAM` (or a circular aperture's outer radius) in a `.zmx`, the
    /// clear (else edge) `CIR` in a `.seq`.
    pub semi_diameter_mm: Option<f64>,
    /// Where it came from (`DIAM, line 80`).
    pub from: String,
    /// The aperture's centre when it is decentred from the vertex, mm.
    pub decentre_mm: Option<[f64; 2]>,
}

/// What the file says about the media around a surface and the light that meets it.
#[derive(Debug, Clone, PartialEq)]
pub struct Optics {
    /// A mirror (`GLAS MIRROR`, `REFL`).
    pub mirror: bool,
    /// The medium before the surface: a glass's name, `None` for air.
    pub before: Option<String>,
    /// The medium after it.
    pub after: Option<String>,
    /// The light travels along +Z at the surface (false after an odd number of mirrors).
    pub light_along_plus_z: bool,
    /// Whether the file says anything about media at all (a Grid Sag `.DAT` does not).
    pub known: bool,
}

impl Optics {
    /// Nothing known: a surface alone (a `.DAT`).
    pub fn unknown() -> Self {
        Self {
            mirror: false,
            before: None,
            after: None,
            light_along_plus_z: true,
            known: false,
        }
    }

    /// The side of the surface, +1 for the design's +Z or −1, on which the piece's material
    /// lies, and why: a mirror's substrate lies beyond its face (the side the light travels
    /// to); a refracting surface's material is the glass after it (on the side the light
    /// travels to) or else the glass before it. With glass on both sides (a cemented surface)
    /// the element after is taken, with none (a surface alone, a dummy) the material is taken
    /// to lie after the surface; the reason says so.
    pub fn material_side(&self) -> (f64, String) {
        let d = if self.light_along_plus_z { 1.0 } else { -1.0 };
        let towards = |s: f64| if s > 0.0 { "+Z" } else { "−Z" };
        let light = format!(
            "the light travels along {}",
            if d > 0.0 {
                "+Z"
            } else {
                "−Z (after an odd number of mirrors)"
            }
        );
        if !self.known {
            return (
                1.0,
                "between media the file does not give: the piece's material is taken to lie on \
                 +Z (light along +Z, material after the surface)"
                    .into(),
            );
        }
        if self.mirror {
            return (
                d,
                format!(
                    "a mirror: {light}, so its face looks along {} and its substrate lies on {}",
                    towards(-d),
                    towards(d)
                ),
            );
        }
        let name = |m: &Option<String>| m.clone().unwrap_or_else(|| "air".into());
        let media = format!("{} before, {} after", name(&self.before), name(&self.after));
        let (side, which) = match (&self.before, &self.after) {
            (_, Some(_)) if self.before.is_none() => (d, "the glass after it"),
            (Some(_), None) => (-d, "the glass before it"),
            (Some(_), Some(_)) => (d, "the element after it (glass on both sides: cemented)"),
            _ => (
                d,
                "taken to lie after it (air on both sides: the file does not say)",
            ),
        };
        (
            side,
            format!(
                "refracting ({media}); {light}; the material is {which}, on {}",
                towards(side)
            ),
        )
    }
}

/// One surface of a design.
#[derive(Debug, Clone, PartialEq)]
pub struct DesignSurface {
    /// Its number in the file (OpticStudio's `SURF n`; CODE V counts `SO` as 0).
    pub number: usize,
    /// The line where it starts.
    pub line: usize,
    /// Its type as the file names it (`EVENASPH`, `SPS XYP`).
    pub kind: String,
    /// A comment or label the file gives it.
    pub label: Option<String>,
    /// Object, image or a surface between.
    pub role: Role,
    /// The surface as a spiralcam family in millimetres, or why it cannot be one.
    pub shape: Result<SurfaceSpec, String>,
    /// The semi-diameter and where it came from.
    pub aperture: Aperture,
    /// The media and the light.
    pub optics: Optics,
    /// Why the surface's frame is not the system's (behind a coordinate break, or tilted or
    /// decentred itself), if it is not.
    pub frame_moved: Option<String>,
    /// What was read, one line per value: the file's keyword and value, and what it became.
    pub read: Vec<String>,
    /// The surface's lines that were not read (keyword and line), which do not describe its
    /// shape as far as the public material says.
    pub not_read: Vec<String>,
}

impl DesignSurface {
    /// One line for a list of surfaces: `2 EVENASPH "front" (semi-diameter 12.5 mm)`.
    pub fn summary(&self) -> String {
        let mut s = format!("{} {}", self.number, self.kind);
        if let Some(l) = &self.label {
            s.push_str(&format!(" \"{l}\""));
        }
        match self.role {
            Role::Object => s.push_str(" (object)"),
            Role::Image => s.push_str(" (image)"),
            Role::Surface => {}
        }
        if self.optics.mirror {
            s.push_str(", mirror");
        }
        if let Some(r) = self.aperture.semi_diameter_mm {
            s.push_str(&format!(", semi-diameter {} mm", crate::field::short(r)));
        }
        if self.shape.is_err() {
            s.push_str(", not read");
        }
        s
    }
}

/// A designer's file, read.
#[derive(Debug, Clone, PartialEq)]
pub struct Design {
    /// The file's name.
    pub file: String,
    /// Its format.
    pub format: DesignFormat,
    /// How its text was stored.
    pub encoding: Encoding,
    /// Its lens unit.
    pub unit: LengthUnit,
    /// Where the unit came from (`UNIT MM, line 8`, or that it was not stated).
    pub unit_from: String,
    /// Its surfaces, in the file's order.
    pub surfaces: Vec<DesignSurface>,
    /// Facts about the whole file the user should read (several configurations, keywords of
    /// the file not read).
    pub notes: Vec<String>,
}

impl Design {
    /// The surface numbered `number`.
    pub fn surface(&self, number: usize) -> Option<&DesignSurface> {
        self.surfaces.iter().find(|s| s.number == number)
    }
}

/// Reads the design file `name` from its bytes, in the format its name says
/// ([`DesignFormat::of_name`]).
pub fn read_design(name: &str, bytes: &[u8]) -> Result<Design, ImportError> {
    let format = DesignFormat::of_name(name)?;
    if bytes.len() as u64 > MAX_DESIGN_BYTES {
        return Err(ImportError::TooLarge {
            file: name.to_string(),
            bytes: bytes.len() as u64,
            limit: MAX_DESIGN_BYTES,
        });
    }
    let (text, encoding) = text::decode(bytes).map_err(|problem| ImportError::Encoding {
        file: name.to_string(),
        problem,
    })?;
    let mut design = match format {
        DesignFormat::Zmx => zmx::parse(name, &text)?,
        DesignFormat::Seq => seq::parse(name, &text)?,
        DesignFormat::GridSag => dat::parse(name, &text)?,
    };
    design.encoding = encoding;
    Ok(design)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn optics(mirror: bool, before: Option<&str>, after: Option<&str>, plus: bool) -> Optics {
        Optics {
            mirror,
            before: before.map(String::from),
            after: after.map(String::from),
            light_along_plus_z: plus,
            known: true,
        }
    }

    #[test]
    fn the_material_lies_behind_a_mirror_and_in_the_glass() {
        // A lens's front surface: the glass after it, on +Z.
        assert_eq!(
            optics(false, None, Some("N-BK7"), true).material_side().0,
            1.0
        );
        // Its rear surface: the glass before it, on −Z.
        assert_eq!(
            optics(false, Some("N-BK7"), None, true).material_side().0,
            -1.0
        );
        // A first mirror: light along +Z meets its face from −Z; the substrate is on +Z.
        assert_eq!(optics(true, None, None, true).material_side().0, 1.0);
        // A second mirror (light along −Z): the substrate is on −Z.
        let (side, why) = optics(true, None, None, false).material_side();
        assert_eq!(side, -1.0);
        assert!(why.contains("face looks along +Z"), "{why}");
        // A lens behind one mirror: the glass after it lies on −Z.
        assert_eq!(
            optics(false, None, Some("F2"), false).material_side().0,
            -1.0
        );
        let (side, why) = optics(false, Some("A"), Some("B"), true).material_side();
        assert_eq!(side, 1.0);
        assert!(why.contains("cemented"), "{why}");
        assert!(
            Optics::unknown()
                .material_side()
                .1
                .contains("does not give")
        );
    }

    #[test]
    fn formats_are_told_by_name() {
        assert_eq!(DesignFormat::of_name("a.ZMX").unwrap(), DesignFormat::Zmx);
        assert_eq!(DesignFormat::of_name("b.seq").unwrap(), DesignFormat::Seq);
        assert_eq!(
            DesignFormat::of_name("c.DAT").unwrap(),
            DesignFormat::GridSag
        );
        assert!(DesignFormat::of_name("d").is_err());
    }
}

//! `part.cut`: which piece is cut and the frame the design is cut in.
//!
//! A design's sag is measured along its +Z; spiralcam's +Z points at the tool. Cutting the
//! surface from the side its +Z points to keeps the design's frame (`"frame": "design"`);
//! cutting it from the other side turns the design 180° about its Y axis (`"turned"`: x → −x,
//! z → −z, [`crate::surface::Turned`]), a rotation, never a mirror, so that a freeform odd in x
//! is cut as designed and not as its mirror image. Which side the tool comes from depends on
//! the piece: the optic itself is cut from the air side, a mould insert forming the surface
//! from the side the glass fills; for a lens's front surface (glass after it, light along +Z)
//! the optic is cut turned and the mould in the design's frame, for its rear surface the
//! reverse, for a mirror the optic is cut from the side the light arrives from. The importer
//! ([`super::design`]) decides the frame from what the design file says and states why.
//!
//! **Why a `part` field and not a surface family, nor rewritten coefficients.** The surface
//! keeps the designer's coefficients exactly as the prescription report lists them, so the two
//! can be compared line by line; the turn applies to any family, data files included (a Grid
//! Sag grid could not be rewritten without resampling it); and the choice sits in one place
//! the NC header and the report restate. The piece is stated with the frame (both required):
//! the frame alone would not say what was meant, the piece alone would not say which side,
//! since that depends on the glass.

use serde::{Deserialize, Serialize};

/// What is cut.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Piece {
    /// The optic's own surface, cut from the air side (a mirror: from the side the light
    /// arrives from).
    Optic,
    /// A mould insert forming the surface, cut from the side the glass fills.
    Mould,
}

/// The frame the design is cut in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Frame {
    /// The design's own frame: its +Z towards the tool, z kept.
    Design,
    /// Turned 180° about the design's Y axis: x → −x, z → −z.
    Turned,
}

/// `part.cut`: the piece and the frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CutSpec {
    /// `optic` or `mould`.
    pub piece: Piece,
    /// `design` or `turned`.
    pub frame: Frame,
}

impl Piece {
    /// The piece's name in the job.
    pub fn name(self) -> &'static str {
        match self {
            Piece::Optic => "optic",
            Piece::Mould => "mould",
        }
    }
}

impl CutSpec {
    /// One line for the NC header and the report: `optic, the design turned 180° about Y
    /// (x -> -x, z -> -z)`.
    pub fn describe(&self) -> String {
        let piece = match self.piece {
            Piece::Optic => "the optic's own surface",
            Piece::Mould => "a mould insert forming the surface",
        };
        let frame = match self.frame {
            Frame::Design => "in the design's frame (z kept)",
            Frame::Turned => "the design turned 180° about Y (x → −x, z → −z)",
        };
        format!("{piece}, {frame}")
    }
}

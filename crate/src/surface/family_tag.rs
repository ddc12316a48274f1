//! Reading a [`SurfaceSpec`] from its `"type"` tag with the field path kept.
//!
//! serde reads an internally tagged enum by buffering the whole object, finding the tag, and
//! reading the variant from the buffer; the buffer does not report where in it an error lies, so
//! an error inside a surface was reported at `surface` alone (serde_path_to_error issue 1, open).
//! Here, when `"type"` is the object's first key (as in every example job and in what the page
//! sends), the rest of the object is read as the family's spec straight from the document, so
//! the document's reader sees every key on the way (`surface.base.type: unknown field `type``).
//! When it is not first, the object is buffered as a JSON value (JSON text has no NaN, which a
//! JSON value cannot hold), the tag taken out and the spec read through
//! [`serde_path_to_error`], whose path travels in the message ([`crate::field::nest_path`]) for
//! the job's reader to join to its own.

use super::SurfaceSpec;
use crate::field::nest_path;
use serde::de::value::MapAccessDeserializer;
use serde::de::{Error, MapAccess, Visitor};
use serde::{Deserialize, Deserializer};
use serde_json::{Map, Value};
use std::fmt;

/// The family names, the values of `"type"`.
pub const FAMILIES: &[&str] = &[
    "asphere",
    "xy_polynomial",
    "lens_array",
    "sinusoid",
    "zernike",
    "biconic",
    "toroid",
    "off_axis_conic",
    "tilted_flat",
    "compound_eye",
    "pal",
    "nurbs",
    "step_face",
    "scattered",
    "composite",
    "odd_asphere",
    "q_bfs",
    "q_con",
    "q_2d",
    "chebyshev",
    "zoned_asphere",
    "grid_sag",
];

/// The spec of family `name` read from `de` (the object without its tag); `None` for an
/// unknown family.
fn family<'de, D: Deserializer<'de>>(name: &str, de: D) -> Option<Result<SurfaceSpec, D::Error>> {
    use SurfaceSpec as S;
    macro_rules! read {
        ($variant:ident) => {
            Deserialize::deserialize(de).map(S::$variant)
        };
    }
    Some(match name {
        "asphere" => read!(Asphere),
        "xy_polynomial" => read!(XyPolynomial),
        "lens_array" => read!(LensArray),
        "sinusoid" => read!(Sinusoid),
        "zernike" => read!(Zernike),
        "biconic" => read!(Biconic),
        "toroid" => read!(Toroid),
        "off_axis_conic" => read!(OffAxisConic),
        "tilted_flat" => read!(TiltedFlat),
        "compound_eye" => read!(CompoundEye),
        "pal" => read!(Pal),
        "nurbs" => read!(Nurbs),
        "step_face" => read!(StepFace),
        "scattered" => read!(Scattered),
        "composite" => read!(Composite),
        "odd_asphere" => read!(OddAsphere),
        "q_bfs" => read!(QBfs),
        "q_con" => read!(QCon),
        "q_2d" => read!(Q2d),
        "chebyshev" => read!(Chebyshev),
        "zoned_asphere" => read!(ZonedAsphere),
        "grid_sag" => read!(GridSag),
        _ => return None,
    })
}

/// Reads a buffered object: takes out the tag and reads the family's spec from the rest,
/// tracking the path of an error.
fn buffered<E: Error>(mut object: Map<String, Value>) -> Result<SurfaceSpec, E> {
    let name = match object.remove("type") {
        Some(Value::String(name)) => name,
        Some(other) => {
            return Err(E::custom(format!(
                "\"type\" must name a surface family (one of {}), not {other}",
                FAMILIES.join(", ")
            )));
        }
        None => return Err(E::missing_field("type")),
    };
    let mut track = serde_path_to_error::Track::new();
    let de = serde_path_to_error::Deserializer::new(Value::Object(object), &mut track);
    match family(&name, de) {
        None => Err(E::unknown_variant(&name, FAMILIES)),
        Some(Ok(spec)) => Ok(spec),
        Some(Err(e)) => {
            let path = track.path().to_string();
            Err(E::custom(match path.as_str() {
                "." | "" => e.to_string(),
                _ => nest_path(&path, &e.to_string()),
            }))
        }
    }
}

/// The visitor of a surface object.
struct SpecVisitor;

impl<'de> Visitor<'de> for SpecVisitor {
    type Value = SurfaceSpec;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a surface: an object whose \"type\" names its family")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<SurfaceSpec, A::Error> {
        let Some(first) = map.next_key::<String>()? else {
            return Err(A::Error::missing_field("type"));
        };
        if first == "type" {
            let name: String = map.next_value()?;
            return family(&name, MapAccessDeserializer::new(map))
                .unwrap_or_else(|| Err(A::Error::unknown_variant(&name, FAMILIES)));
        }
        let mut object = Map::new();
        object.insert(first, map.next_value()?);
        while let Some((key, value)) = map.next_entry()? {
            object.insert(key, value);
        }
        buffered(object)
    }
}

impl<'de> Deserialize<'de> for SurfaceSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_map(SpecVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_family_name_reads_back_what_serde_writes() {
        // The tag serde writes for each variant (rename_all = snake_case) is a name read here.
        for name in FAMILIES {
            let e = serde_json::from_str::<SurfaceSpec>(&format!(r#"{{"type":"{name}"}}"#));
            // Every family has a required field (or, for pal, none): either it reads, or the
            // error is about a field, never about the family.
            if let Err(e) = e {
                assert!(!e.to_string().contains("unknown variant"), "{name}: {e}");
            }
        }
        let e = serde_json::from_str::<SurfaceSpec>(r#"{"type":"torus"}"#).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("unknown variant `torus`, expected one of `asphere`")
        );
        let e = serde_json::from_str::<SurfaceSpec>(r#"{"radius_mm":2}"#).unwrap_err();
        assert!(e.to_string().starts_with("missing field `type`"), "{e}");
        let e = serde_json::from_str::<SurfaceSpec>(r#"{"type":3}"#).unwrap_err();
        assert!(e.to_string().contains("expected a string"), "{e}");
        let e = serde_json::from_str::<SurfaceSpec>(r#"{"radius_mm":2,"type":3}"#).unwrap_err();
        assert!(e.to_string().contains("must name a surface family"), "{e}");
    }
}

//! Zygo `.datx` files (Mx, MetroPro 9 and later): HDF5 files holding the surface map as a 2-D
//! dataset with its units and calibration as attributes. Read with the pure-Rust `hdf5-reader`
//! crate (no C library; it also builds for wasm32, so the page reads the same files).
//!
//! **Layout**, as the public readers expect it (no Zygo specification is public):
//! - *Which dataset.* The `/MetaData` table (a compound dataset of `Source`, `Link`,
//!   `Destination` strings) maps `Root` → `Measurement` → `Surface` → `Path`, the surface's
//!   HDF5 path (SurfaceTopography `IO/DATX.py`; Superflat-PCP's `ZygoDatx.py`); without it,
//!   `/Measurement/Surface` (prysm 0.20 `read_zygo_datx`, "new style" and NX2 files), else the
//!   one dataset in `/Data/Surface` (prysm's current `read_zygo_datx`). The one used is named
//!   in [`MeasuredMap::source`].
//! - *Heights.* The surface's `Unit` attribute (a string array of one): `NanoMeters`,
//!   `MicroMeters`, `MilliMeters`, `Meters` (SurfaceTopography's unit table) or `Fringes`,
//!   converted as prysm does: `z = v · S · O · λ` with `Interferometric Scale Factor` S,
//!   `Obliquity Factor` O (1 when the attribute is absent, as prysm 0.20 took it) and
//!   `Wavelength` λ in metres. Values at or above the `No Data` attribute (prysm's test) or not
//!   finite have no value; without `No Data` only non-finite values are masked.
//! - *Lateral spacing.* The `X Converter` and `Y Converter` attributes (a compound of
//!   `Category`, `BaseUnit`, `Parameters[4]`; category `LateralCat`, `Parameters[1]` metres
//!   per pixel: SurfaceTopography, prysm 0.20's NX2 branch); when they are absent or zero, the
//!   attribute group's `Data Context.Lateral Resolution:Value` (metres: prysm 0.20,
//!   Superflat-PCP; a name ending so, as `Surface Data Context.…` in sro_sto_plume's
//!   `microscopy.py`), looked for in `/MetaData`'s `Measurement` → `Attributes` → `Path`,
//!   `/Measurement/Attributes` and the groups under `/Attributes`.
//! - *Orientation.* The dataset's rows are image rows, the first at the top (prysm flips the
//!   array "so their y coordinates increase upward"): the first row becomes the highest y,
//!   columns run along +x, and the origin is the array's centre.
//!
//! Element types: 8-, 16-, 32- and 64-bit integers and 32- and 64-bit floats. Limits: the file
//! ([`super::MAX_FILE_BYTES`]), the surface's nodes ([`super::MAX_GRID_NODES`], checked from
//! its shape before it is read) and the `/MetaData` table ([`MAX_METADATA_ROWS`] rows); the
//! HDF5 reader is opened with a decoded-read limit of the largest grid of 64-bit values and a
//! 16 MiB chunk cache.

use super::{
    HeightGrid, MAX_FILE_BYTES, MAX_GRID_NODES, MeasuredData, MeasuredError, MeasuredMap,
    check_limit,
};
use hdf5_reader::error::Error as H5Error;
use hdf5_reader::messages::datatype::StringSize;
use hdf5_reader::{Attribute, ByteOrder, Dataset, Datatype, Hdf5File, OpenOptions};

/// The most rows of the `/MetaData` table read.
pub const MAX_METADATA_ROWS: u64 = 100_000;

/// A surface map's unit and millimetres per unit.
const UNITS: [(&str, f64); 4] = [
    ("NanoMeters", 1e-6),
    ("MicroMeters", 1e-3),
    ("MilliMeters", 1.0),
    ("Meters", 1e3),
];

/// Where the reader found things and how it converted them, for [`MeasuredMap::source`].
struct Found {
    surface: String,
    how: &'static str,
    attributes: Option<String>,
}

/// An HDF5 error about `object` of `file`.
fn h5_error(file: &str, object: &str, e: H5Error) -> MeasuredError {
    MeasuredError::object(file, object, e.to_string())
}

/// Whether an HDF5 error only says that an object is absent.
fn absent(e: &H5Error) -> bool {
    match e {
        H5Error::Context { source, .. } => absent(source),
        H5Error::GroupNotFound(_) | H5Error::DatasetNotFound(_) | H5Error::AttributeNotFound(_) => {
            true
        }
        _ => false,
    }
}

/// `Ok(None)` for an absent object, the object, or the error.
fn optional<T>(file: &str, object: &str, r: hdf5_reader::error::Result<T>) -> ResultOpt<T> {
    match r {
        Ok(v) => Ok(Some(v)),
        Err(e) if absent(&e) => Ok(None),
        Err(e) => Err(h5_error(file, object, e)),
    }
}

type ResultOpt<T> = Result<Option<T>, MeasuredError>;

/// One number of type `dt` from `b` (floats and integers of any width and byte order).
fn number(dt: &Datatype, b: &[u8]) -> Option<f64> {
    let (size, order) = match dt {
        Datatype::FloatingPoint { size, byte_order } => (*size, *byte_order),
        Datatype::FixedPoint {
            size, byte_order, ..
        } => (*size, *byte_order),
        _ => return None,
    };
    let mut w = [0u8; 8];
    let n = usize::from(size);
    if n == 0 || n > 8 || b.len() < n {
        return None;
    }
    w[..n].copy_from_slice(&b[..n]);
    if order == ByteOrder::BigEndian {
        w[..n].reverse();
    }
    Some(match dt {
        Datatype::FloatingPoint { size: 4, .. } => {
            f64::from(f32::from_le_bytes([w[0], w[1], w[2], w[3]]))
        }
        Datatype::FloatingPoint { size: 8, .. } => f64::from_le_bytes(w),
        Datatype::FixedPoint { signed: true, .. } => {
            let shift = 64 - 8 * n as u32;
            ((i64::from_le_bytes(w) << shift) >> shift) as f64
        }
        Datatype::FixedPoint { signed: false, .. } => u64::from_le_bytes(w) as f64,
        _ => return None,
    })
}

/// The byte size of one element of `dt` as stored in a record (vlen: a heap reference).
fn stored_size(dt: &Datatype, vlen_ref: usize) -> Option<usize> {
    Some(match dt {
        Datatype::FloatingPoint { size, .. } | Datatype::FixedPoint { size, .. } => {
            usize::from(*size)
        }
        Datatype::String {
            size: StringSize::Fixed(n),
            ..
        } => *n as usize,
        Datatype::VarLen { .. }
        | Datatype::String {
            size: StringSize::Variable,
            ..
        } => vlen_ref,
        Datatype::Compound { size, .. } => *size as usize,
        Datatype::Array { base, dims } => {
            let n = dims
                .iter()
                .try_fold(1usize, |a, d| a.checked_mul(*d as usize))?;
            stored_size(base, vlen_ref)?.checked_mul(n)?
        }
        _ => return None,
    })
}

/// The text of a string field stored as `b` (fixed-length or a heap reference).
fn field_text(ds: &Dataset, dt: &Datatype, b: &[u8]) -> Option<String> {
    let bytes = match dt {
        Datatype::String {
            size: StringSize::Fixed(_),
            ..
        } => b.to_vec(),
        Datatype::VarLen { .. }
        | Datatype::String {
            size: StringSize::Variable,
            ..
        } => ds.resolve_vlen_reference_bytes(b, 1).ok()?,
        _ => return None,
    };
    let s = String::from_utf8_lossy(&bytes);
    Some(s.trim_end_matches(['\0', ' ']).trim().to_string())
}

/// A compound record's fields, by name: the string or the numbers of each.
enum Field {
    Text(String),
    Numbers(Vec<f64>),
}

/// The fields of the compound record `b` of type `dt`.
fn record(ds: &Dataset, dt: &Datatype, b: &[u8]) -> Option<Vec<(String, Field)>> {
    let Datatype::Compound { fields, .. } = dt else {
        return None;
    };
    let vlen_ref = ds.vlen_reference_size();
    let mut out = Vec::with_capacity(fields.len());
    for f in fields {
        let at = f.byte_offset as usize;
        let bytes = b.get(at..at.checked_add(stored_size(&f.datatype, vlen_ref)?)?)?;
        let value = match &f.datatype {
            Datatype::Array { base, .. } => {
                let step = stored_size(base, vlen_ref)?;
                if step == 0 {
                    return None;
                }
                let v: Option<Vec<f64>> =
                    bytes.chunks_exact(step).map(|c| number(base, c)).collect();
                Field::Numbers(v?)
            }
            Datatype::FloatingPoint { .. } | Datatype::FixedPoint { .. } => {
                Field::Numbers(vec![number(&f.datatype, bytes)?])
            }
            other => Field::Text(field_text(ds, other, bytes)?),
        };
        out.push((f.name.clone(), value));
    }
    Some(out)
}

/// The numbers of a numeric attribute.
fn attr_numbers(a: &Attribute) -> Option<Vec<f64>> {
    let step = stored_size(&a.datatype, 0).filter(|s| *s > 0)?;
    a.raw_data
        .chunks_exact(step)
        .map(|c| number(&a.datatype, c))
        .collect()
}

/// The first number of the attribute `name` of `ds`, if it exists.
fn attr_number(file: &str, object: &str, ds: &Dataset, name: &str) -> ResultOpt<f64> {
    let Some(a) = optional(file, object, ds.attribute(name))? else {
        return Ok(None);
    };
    match attr_numbers(&a).as_deref() {
        Some([v, ..]) => Ok(Some(*v)),
        _ => Err(MeasuredError::object(
            file,
            &format!("{object}:{name}"),
            format!("expected a number, found {:?}", a.datatype),
        )),
    }
}

/// The `/MetaData` table as (source, link, destination) rows, if there is one.
fn metadata(file: &str, h5: &Hdf5File) -> ResultOpt<Vec<[String; 3]>> {
    const OBJECT: &str = "/MetaData";
    let Some(ds) = optional(file, OBJECT, h5.dataset(OBJECT))? else {
        return Ok(None);
    };
    let rows = ds.shape().iter().product::<u64>();
    check_limit(file, "/MetaData rows", rows, MAX_METADATA_ROWS)?;
    let bad = |what: &str| MeasuredError::object(file, OBJECT, what.to_string());
    let size = stored_size(ds.dtype(), ds.vlen_reference_size())
        .filter(|s| *s > 0)
        .ok_or_else(|| bad("expected a table of Source, Link, Destination strings"))?;
    let raw = ds.read_raw_bytes().map_err(|e| h5_error(file, OBJECT, e))?;
    let mut out = Vec::with_capacity(rows as usize);
    for b in raw.chunks_exact(size) {
        let fields = record(&ds, ds.dtype(), b)
            .ok_or_else(|| bad("expected a table of Source, Link, Destination strings"))?;
        let text = |name: &str| {
            fields.iter().find_map(|(n, f)| match f {
                Field::Text(t) if n == name => Some(t.clone()),
                _ => None,
            })
        };
        match (text("Source"), text("Link"), text("Destination")) {
            (Some(s), Some(l), Some(d)) => out.push([s, l, d]),
            _ => return Err(bad("a row lacks Source, Link or Destination")),
        }
    }
    Ok(Some(out))
}

/// Follows `links` from `Root` through the `/MetaData` rows.
fn follow(rows: &[[String; 3]], links: &[&str]) -> Option<String> {
    let mut node = "Root".to_string();
    for link in links {
        node = rows
            .iter()
            .find(|r| r[0] == node && r[1] == *link)
            .map(|r| r[2].clone())?;
    }
    Some(node)
}

/// The surface dataset's path, how it was found, and the attribute group `/MetaData` names.
fn locate(file: &str, h5: &Hdf5File) -> Result<Found, MeasuredError> {
    let rows = metadata(file, h5)?.unwrap_or_default();
    let attributes = follow(&rows, &["Measurement", "Attributes", "Path"]);
    if let Some(surface) = follow(&rows, &["Measurement", "Surface", "Path"]) {
        return Ok(Found {
            surface,
            how: "named by /MetaData",
            attributes,
        });
    }
    if optional(
        file,
        "/Measurement/Surface",
        h5.dataset("/Measurement/Surface"),
    )?
    .is_some()
    {
        return Ok(Found {
            surface: "/Measurement/Surface".into(),
            how: "/Measurement/Surface",
            attributes,
        });
    }
    if let Some(g) = optional(file, "/Data/Surface", h5.group("/Data/Surface"))? {
        let (_, names) = g
            .member_names()
            .map_err(|e| h5_error(file, "/Data/Surface", e))?;
        return match names.as_slice() {
            [one] => Ok(Found {
                surface: format!("/Data/Surface/{one}"),
                how: "the one dataset in /Data/Surface",
                attributes,
            }),
            _ => Err(MeasuredError::object(
                file,
                "/Data/Surface",
                format!(
                    "{} datasets ({}) and no /MetaData naming the measured one",
                    names.len(),
                    names.join(", ")
                ),
            )),
        };
    }
    Err(MeasuredError::object(
        file,
        "/",
        "no surface map: expected /MetaData naming Measurement → Surface → Path, a \
         /Measurement/Surface dataset or one dataset in /Data/Surface (a Zygo .datx layout)",
    ))
}

/// The surface's values, row by row as stored, after checking its shape against the limits.
fn values(file: &str, path: &str, ds: &Dataset) -> Result<(usize, usize, Vec<f64>), MeasuredError> {
    let &[ny, nx] = ds.shape() else {
        return Err(MeasuredError::object(
            file,
            path,
            format!("shape {:?}: expected a 2-D map", ds.shape()),
        ));
    };
    if nx == 0 || ny == 0 {
        return Err(MeasuredError::object(
            file,
            path,
            format!("shape {ny} × {nx}: empty"),
        ));
    }
    check_limit(file, "surface nodes", ny.saturating_mul(nx), MAX_GRID_NODES)?;
    let dt = ds.dtype();
    let size = match dt {
        Datatype::FloatingPoint { size: 4 | 8, .. } | Datatype::FixedPoint { size: 1..=8, .. } => {
            stored_size(dt, 0).unwrap_or(1)
        }
        other => {
            return Err(MeasuredError::object(
                file,
                path,
                format!("element type {other:?}: expected integers or floats"),
            ));
        }
    };
    let raw = ds.read_raw_bytes().map_err(|e| h5_error(file, path, e))?;
    let v: Vec<f64> = raw
        .chunks_exact(size.max(1))
        .map(|b| number(dt, b).unwrap_or(f64::NAN))
        .collect();
    if v.len() as u64 != nx * ny {
        return Err(MeasuredError::object(
            file,
            path,
            format!("{} values for a {ny} × {nx} map", v.len()),
        ));
    }
    Ok((nx as usize, ny as usize, v))
}

/// Millimetres per stored unit, and its description.
fn height_scale(file: &str, path: &str, ds: &Dataset) -> Result<(f64, String), MeasuredError> {
    let object = format!("{path}:Unit");
    let unit = optional(file, &object, ds.attribute("Unit"))?
        .and_then(|a| a.read_strings().ok())
        .and_then(|s| s.into_iter().next())
        .ok_or_else(|| {
            MeasuredError::object(file, &object, "missing: the surface's unit is required")
        })?;
    let unit = unit.trim_end_matches('\0').trim().to_string();
    if let Some((_, mm)) = UNITS.iter().find(|(u, _)| *u == unit) {
        return Ok((*mm, unit));
    }
    if unit != "Fringes" {
        return Err(MeasuredError::object(
            file,
            &object,
            format!("{unit:?}: expected Fringes, NanoMeters, MicroMeters, MilliMeters or Meters"),
        ));
    }
    let required = |name: &str| -> Result<f64, MeasuredError> {
        match attr_number(file, path, ds, name)? {
            Some(v) if v.is_finite() && v > 0.0 => Ok(v),
            v => Err(MeasuredError::object(
                file,
                &format!("{path}:{name}"),
                format!(
                    "{}: a map in fringes needs a finite value > 0",
                    v.map_or("missing".into(), |v| format!("{v:e}"))
                ),
            )),
        }
    };
    let s = required("Interferometric Scale Factor")?;
    let lambda = required("Wavelength")?;
    let o = match attr_number(file, path, ds, "Obliquity Factor")? {
        None => 1.0,
        Some(_) => required("Obliquity Factor")?,
    };
    let how = format!("Fringes × S {s} × O {o} × λ {:.4} nm", lambda * 1e9);
    Ok((s * o * lambda * 1e3, how))
}

/// Metres per pixel from a lateral converter attribute, if it has one.
fn converter(file: &str, path: &str, ds: &Dataset, name: &str) -> ResultOpt<f64> {
    let object = format!("{path}:{name}");
    let Some(a) = optional(file, &object, ds.attribute(name))? else {
        return Ok(None);
    };
    let fields = a
        .raw_data
        .get(..stored_size(&a.datatype, ds.vlen_reference_size()).unwrap_or(usize::MAX))
        .and_then(|b| record(ds, &a.datatype, b))
        .ok_or_else(|| {
            MeasuredError::object(
                file,
                &object,
                "expected a compound of Category, BaseUnit and Parameters",
            )
        })?;
    let category = fields.iter().find_map(|(n, f)| match f {
        Field::Text(t) if n == "Category" => Some(t.as_str()),
        _ => None,
    });
    let per_pixel = fields.iter().find_map(|(n, f)| match f {
        Field::Numbers(v) if n == "Parameters" => v.get(1).copied(),
        _ => None,
    });
    Ok(match (category, per_pixel) {
        (Some("LateralCat"), Some(m)) if m.is_finite() && m > 0.0 => Some(m),
        _ => None,
    })
}

/// The attribute groups that may hold `Data Context.Lateral Resolution:Value`.
fn attribute_groups(
    file: &str,
    h5: &Hdf5File,
    named: Option<&str>,
) -> Result<Vec<String>, MeasuredError> {
    let mut out: Vec<String> = named.into_iter().map(str::to_string).collect();
    out.push("/Measurement/Attributes".into());
    if let Some(g) = optional(file, "/Attributes", h5.group("/Attributes"))? {
        let (groups, _) = g
            .member_names()
            .map_err(|e| h5_error(file, "/Attributes", e))?;
        out.extend(groups.iter().rev().map(|n| format!("/Attributes/{n}")));
    }
    Ok(out)
}

/// Metres per pixel along x and y, and where they came from.
fn lateral(
    file: &str,
    h5: &Hdf5File,
    found: &Found,
    ds: &Dataset,
) -> Result<(f64, f64, String), MeasuredError> {
    let path = found.surface.as_str();
    if let Some(dx) = converter(file, path, ds, "X Converter")? {
        let dy = converter(file, path, ds, "Y Converter")?.unwrap_or(dx);
        return Ok((dx, dy, "X/Y Converter".into()));
    }
    const NAME: &str = "Data Context.Lateral Resolution:Value";
    for g in attribute_groups(file, h5, found.attributes.as_deref())? {
        let Some(group) = optional(file, &g, h5.group(&g))? else {
            continue;
        };
        let attrs = group.attributes().map_err(|e| h5_error(file, &g, e))?;
        if let Some(a) = attrs.iter().find(|a| a.name.ends_with(NAME)) {
            let object = format!("{g}:{}", a.name);
            return match attr_numbers(a).as_deref() {
                Some([m, ..]) if m.is_finite() && *m > 0.0 => Ok((*m, *m, object)),
                _ => Err(MeasuredError::object(
                    file,
                    &object,
                    "expected metres per pixel > 0 (the file has no lateral calibration)",
                )),
            };
        }
    }
    Err(MeasuredError::object(
        file,
        path,
        format!(
            "no lateral calibration: expected an X Converter (LateralCat, metres per pixel) or \
             {NAME} in the attribute group"
        ),
    ))
}

/// Opens `bytes` as HDF5 with the reader's limits.
fn open(file: &str, bytes: Vec<u8>) -> Result<Hdf5File, MeasuredError> {
    let options = OpenOptions::default()
        .with_chunk_cache_bytes(16 << 20)
        .with_max_chunk_bytes(64 << 20)
        .with_max_read_bytes((MAX_GRID_NODES * 8) as usize);
    Hdf5File::from_vec_with_options(bytes, options).map_err(|e| h5_error(file, "HDF5 file", e))
}

/// Reads a Zygo `.datx` (see the module docs) from the file `file`'s bytes.
pub fn read(file: &str, bytes: Vec<u8>) -> Result<MeasuredMap, MeasuredError> {
    check_limit(file, "size (bytes)", bytes.len() as u64, MAX_FILE_BYTES)?;
    let h5 = open(file, bytes)?;
    let found = locate(file, &h5)?;
    let path = found.surface.as_str();
    let ds = h5.dataset(path).map_err(|e| h5_error(file, path, e))?;
    let (nx, ny, raw) = values(file, path, &ds)?;
    let (mm_per_unit, unit) = height_scale(file, path, &ds)?;
    let no_data = attr_number(file, path, &ds, "No Data")?;
    let (dx, dy, lateral_from) = lateral(file, &h5, &found, &ds)?;
    let mut z = vec![0.0; nx * ny];
    let mut valid = vec![false; nx * ny];
    for (k, v) in raw.iter().enumerate() {
        let at = (ny - 1 - k / nx) * nx + k % nx;
        if v.is_finite() && no_data.is_none_or(|n| *v < n) {
            z[at] = v * mm_per_unit;
            valid[at] = true;
            if !z[at].is_finite() {
                return Err(MeasuredError::object(
                    file,
                    path,
                    format!(
                        "row {}, column {}: {v:e} {unit} is beyond the range of heights",
                        k / nx,
                        k % nx
                    ),
                ));
            }
        }
    }
    let source = format!(
        "Zygo .datx {file}, surface {path} ({}), {nx} × {ny}, {unit}, {:.6} × {:.6} µm per \
         pixel from {lateral_from}{}",
        found.how,
        dx * 1e6,
        dy * 1e6,
        no_data.map_or(String::new(), |n| format!(", No Data {n:e}")),
    );
    Ok(MeasuredMap::new(
        MeasuredData::Grid(HeightGrid::centred(nx, ny, dx * 1e3, dy * 1e3, z, valid)),
        source,
    ))
}

//! The length unit of a STEP file (ISO 10303-41 units as AP203/AP214 files write them): the
//! `LENGTH_UNIT` that a `GLOBAL_UNIT_ASSIGNED_CONTEXT` names, either an `SI_UNIT` with an
//! optional prefix (`(LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.))`) or a
//! `CONVERSION_BASED_UNIT` (`'INCH'`) whose `LENGTH_MEASURE_WITH_UNIT` gives its size in another
//! length unit (25.4 mm, or 0.0254 m). Files without any length unit are read as millimetres.

use super::part21::{Exchange, Instance, Param};

/// Conversion chains longer than this are refused (a unit defined by itself).
const MAX_CHAIN: usize = 8;

/// A length unit: its size in millimetres and a name for messages.
#[derive(Debug, Clone, PartialEq)]
pub struct LengthUnit {
    /// Millimetres per unit.
    pub mm: f64,
    /// E.g. `mm`, `INCH (25.4 mm)`.
    pub name: String,
}

/// The file's length unit; `None` where it states none. Several different ones are an error.
pub fn file_length_unit(ex: &Exchange) -> Result<Option<LengthUnit>, String> {
    let mut found: Vec<(u64, LengthUnit)> = Vec::new();
    for id in context_units(ex) {
        let Some(unit) = ex.get(id).filter(|i| i.record("LENGTH_UNIT").is_some()) else {
            continue;
        };
        let length = size(ex, unit, 0)?;
        if !found.iter().any(|(_, f)| same(f.mm, length.mm)) {
            found.push((id, length));
        }
    }
    match found.len() {
        0 => Ok(None),
        1 => Ok(found.pop().map(|(_, u)| u)),
        _ => {
            let list: Vec<String> = found
                .iter()
                .map(|(id, u)| format!("#{id} {}", u.name))
                .collect();
            Err(format!(
                "the file assigns several length units ({}); set \"units\"",
                list.join(", ")
            ))
        }
    }
}

/// Every unit a `GLOBAL_UNIT_ASSIGNED_CONTEXT` lists, in file order.
fn context_units(ex: &Exchange) -> Vec<u64> {
    let mut out = Vec::new();
    for instance in &ex.instances {
        if let Some(r) = instance.record("GLOBAL_UNIT_ASSIGNED_CONTEXT")
            && let Some(units) = r.params.first().and_then(Param::list)
        {
            out.extend(units.iter().filter_map(Param::reference));
        }
    }
    out
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs())
}

/// The size of the length unit `unit` in millimetres.
fn size(ex: &Exchange, unit: &Instance, depth: usize) -> Result<LengthUnit, String> {
    if depth > MAX_CHAIN {
        return Err(format!(
            "#{}: the length unit's conversion chain is longer than {MAX_CHAIN}",
            unit.id
        ));
    }
    if let Some(si) = unit.record("SI_UNIT") {
        return si_unit(unit.id, &si.params);
    }
    if let Some(conversion) = unit.record("CONVERSION_BASED_UNIT") {
        return converted(ex, unit.id, &conversion.params, depth);
    }
    Err(format!(
        "#{} {}: only SI_UNIT and CONVERSION_BASED_UNIT length units are read",
        unit.id,
        unit.names()
    ))
}

/// `SI_UNIT(prefix, name)` (in a complex instance; a simple one has the dimensions first).
fn si_unit(id: u64, params: &[Param]) -> Result<LengthUnit, String> {
    let [prefix, name] = match params {
        [.., p, n] => [p, n],
        _ => return Err(format!("#{id}: SI_UNIT needs a prefix and a name")),
    };
    if name.enumeration() != Some("METRE") {
        return Err(format!("#{id}: a length unit must be METRE, not {name:?}"));
    }
    let (factor, label) = match prefix {
        Param::Unset => (1000.0, "m"),
        Param::Enum(p) => match p.as_str() {
            "KILO" => (1e6, "km"),
            "DECI" => (100.0, "dm"),
            "CENTI" => (10.0, "cm"),
            "MILLI" => (1.0, "mm"),
            "MICRO" => (1e-3, "µm"),
            "NANO" => (1e-6, "nm"),
            other => return Err(format!("#{id}: the SI prefix .{other}. is not read")),
        },
        other => return Err(format!("#{id}: bad SI prefix {other:?}")),
    };
    Ok(LengthUnit {
        mm: factor,
        name: label.into(),
    })
}

/// `CONVERSION_BASED_UNIT(name, #measure)`, the measure `(LENGTH_)MEASURE_WITH_UNIT(value,
/// #unit)`.
fn converted(ex: &Exchange, id: u64, params: &[Param], depth: usize) -> Result<LengthUnit, String> {
    let name = params.first().and_then(Param::string).unwrap_or("unnamed");
    let measure_id = params
        .get(1)
        .and_then(Param::reference)
        .ok_or_else(|| format!("#{id}: CONVERSION_BASED_UNIT needs a conversion factor #ref"))?;
    let measure = ex
        .get(measure_id)
        .ok_or_else(|| format!("#{id} refers to #{measure_id}, which is not in the file"))?;
    let record = measure
        .records
        .iter()
        .find(|r| r.name.ends_with("MEASURE_WITH_UNIT") && r.params.len() == 2)
        .ok_or_else(|| format!("#{measure_id}: expected a LENGTH_MEASURE_WITH_UNIT"))?;
    let value = record.params[0]
        .number()
        .filter(|v| v.is_finite() && *v > 0.0)
        .ok_or_else(|| format!("#{measure_id}: the conversion factor must be a number > 0"))?;
    let base_id = record.params[1]
        .reference()
        .ok_or_else(|| format!("#{measure_id}: the conversion needs a unit #ref"))?;
    let base = ex
        .get(base_id)
        .ok_or_else(|| format!("#{measure_id} refers to #{base_id}, which is not in the file"))?;
    let base = size(ex, base, depth + 1)?;
    Ok(LengthUnit {
        mm: value * base.mm,
        name: format!("{name} ({} mm)", value * base.mm),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(data: &str) -> Exchange {
        let text =
            format!("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n{data}\nENDSEC;\nEND-ISO-10303-21;\n");
        Exchange::parse(&text).unwrap()
    }

    fn context(units: &str) -> String {
        format!(
            "#100 = ( GEOMETRIC_REPRESENTATION_CONTEXT(3) \
             GLOBAL_UNIT_ASSIGNED_CONTEXT(({units})) REPRESENTATION_CONTEXT('','') );"
        )
    }

    #[test]
    fn si_prefixes_and_inches() {
        let mm = file(&format!(
            "#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n\
             #2 = ( NAMED_UNIT(*) PLANE_ANGLE_UNIT() SI_UNIT($,.RADIAN.) );\n{}",
            context("#1,#2")
        ));
        assert_eq!(file_length_unit(&mm).unwrap().unwrap().mm, 1.0);
        let m = file(&format!(
            "#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );\n{}",
            context("#1")
        ));
        assert_eq!(file_length_unit(&m).unwrap().unwrap().mm, 1000.0);
        let inch = file(&format!(
            "#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT($,.METRE.) );\n\
             #2 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(0.0254),#1);\n\
             #3 = DIMENSIONAL_EXPONENTS(1.,0.,0.,0.,0.,0.,0.);\n\
             #4 = ( CONVERSION_BASED_UNIT('INCH',#2) LENGTH_UNIT() NAMED_UNIT(#3) );\n{}",
            context("#4")
        ));
        let u = file_length_unit(&inch).unwrap().unwrap();
        assert!((u.mm - 25.4).abs() < 1e-13, "{u:?}");
        assert!(u.name.starts_with("INCH"), "{u:?}");
        assert_eq!(file_length_unit(&file("#1 = X();")).unwrap(), None);
    }

    #[test]
    fn conflicting_and_unreadable_units_are_errors() {
        let two = file(&format!(
            "#1 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) );\n\
             #2 = ( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.CENTI.,.METRE.) );\n{}",
            context("#1,#2")
        ));
        let e = file_length_unit(&two).unwrap_err();
        assert!(e.contains("#1 mm, #2 cm"), "{e}");
        let looped = file(&format!(
            "#2 = LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(2.),#4);\n\
             #4 = ( CONVERSION_BASED_UNIT('LOOP',#2) LENGTH_UNIT() NAMED_UNIT(*) );\n{}",
            context("#4")
        ));
        assert!(file_length_unit(&looped).unwrap_err().contains("chain"));
        let missing = file(&format!(
            "#4 = ( CONVERSION_BASED_UNIT('FOOT',#9) LENGTH_UNIT() NAMED_UNIT(*) );\n{}",
            context("#4")
        ));
        assert_eq!(
            file_length_unit(&missing).unwrap_err(),
            "#4 refers to #9, which is not in the file"
        );
    }
}

//! The syntax of FST argument cells: numbers, numeric TLPs (`17,0,2`) and
//! text TLPs (`AIN 3-1,EU`, `DIN4-1,STATUS`, `DOU 4-1`), and resolving a
//! TLP against a database. ROCLINK writes TLPs either way depending on an
//! option, so a table may hold both.

use linc_format::db::Tlp;
use linc_format::Database;
use std::collections::HashMap;

/// What an argument cell says, before anything is looked up.
#[derive(Clone, Debug, PartialEq)]
pub enum Syntax<'a> {
    Number(f32),
    Numeric(Tlp),
    /// A point name and, if written, a parameter name (both trimmed).
    Text {
        point: &'a str,
        param: Option<&'a str>,
    },
}

/// Why a cell is not an argument.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum SyntaxError {
    /// Looks like a number but is outside the f32 range (or not finite).
    NumberRange,
    /// Not readable as anything; the text says why.
    Malformed(&'static str),
}

/// Reads an argument cell. Numbers win over TLPs: `12` is the constant 12.
pub fn parse(text: &str) -> Result<Syntax<'_>, SyntaxError> {
    let text = text.trim();
    if text.is_empty() {
        return Err(SyntaxError::Malformed("empty argument"));
    }
    if looks_numeric(text) && !text.contains(',') {
        return number(text).map(Syntax::Number);
    }
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if parts.len() == 3 && parts.iter().all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit())) {
        let n = |s: &str| s.parse::<u16>().map_err(|_| SyntaxError::Malformed("TLP number above 65535"));
        return Ok(Syntax::Numeric(Tlp { t: n(parts[0])?, l: n(parts[1])?, p: n(parts[2])? }));
    }
    match parts.as_slice() {
        [point] => Ok(Syntax::Text { point, param: None }),
        ["", _] => Err(SyntaxError::Malformed("no point before the comma")),
        [_, ""] => Err(SyntaxError::Malformed("no parameter after the comma")),
        [_, param] if param.contains(char::is_whitespace) => {
            Err(SyntaxError::Malformed("a parameter name has no spaces"))
        }
        [point, param] => Ok(Syntax::Text { point, param: Some(param) }),
        _ => Err(SyntaxError::Malformed("too many commas for a TLP")),
    }
}

/// Whether a cell is meant as a number: a sign, a digit or a point first.
fn looks_numeric(text: &str) -> bool {
    let t = text.strip_prefix(['-', '+']).unwrap_or(text);
    let t = t.strip_prefix('.').unwrap_or(t);
    t.starts_with(|c: char| c.is_ascii_digit())
}

/// A decimal number as the device holds it (single precision). Rust would
/// also read `inf` and `NaN`; those never get here ([`looks_numeric`]).
pub fn number(text: &str) -> Result<f32, SyntaxError> {
    let wide: f64 = text.trim().parse().map_err(|_| SyntaxError::Malformed("not a number"))?;
    if !wide.is_finite() || wide.abs() > f64::from(f32::MAX) {
        return Err(SyntaxError::NumberRange);
    }
    Ok(wide as f32)
}

/// Why a TLP names nothing in the database.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ResolveError {
    /// No such point; the closest name is [`suggest`]'s to find, when the
    /// error is shown (it reads every block).
    UnknownPoint,
    UnknownParam {
        block: usize,
    },
    NeedsParam {
        block: usize,
    },
    NoType {
        t: u16,
    },
    NoLogical {
        template: usize,
        count: usize,
    },
    NoParam {
        template: usize,
    },
}

/// The parameter a point means when none is written (B.1.4: `DOU 4-1`).
pub fn default_param(template: &str) -> Option<&'static str> {
    match template.to_ascii_uppercase().as_str() {
        "AIN" | "AOU" => Some("EU"),
        "DIN" | "DOU" => Some("STATUS"),
        _ => None,
    }
}

/// The database's points indexed once per table, so that resolving a cell
/// costs the same however many blocks the database has (a search through
/// the blocks for every cell made checking a large table against a large
/// database quadratic).
pub struct Points<'a> {
    pub db: &'a Database,
    /// Block by name as [`squeeze`] writes it; the first of equal names.
    by_name: HashMap<String, usize>,
    /// Each template's blocks in database order: logical number → block.
    by_template: Vec<Vec<usize>>,
    /// Template by point type number on the database's device family.
    by_type: HashMap<u16, usize>,
}

impl<'a> Points<'a> {
    pub fn new(db: &'a Database) -> Points<'a> {
        let mut by_name = HashMap::with_capacity(db.blocks.len());
        let mut by_template = vec![Vec::new(); db.templates.len()];
        for (i, b) in db.blocks.iter().enumerate() {
            by_name.entry(squeeze(&b.name)).or_insert(i);
            if let Some(list) = by_template.get_mut(b.template) {
                list.push(i);
            }
        }
        let mut by_type = HashMap::new();
        for (i, t) in db.templates.iter().enumerate() {
            if let Some(n) = t.point_type(db.device) {
                by_type.entry(n).or_insert(i);
            }
        }
        Points { db, by_name, by_template, by_type }
    }

    /// The block a point name names, as `Database::point` finds it.
    pub fn point(&self, name: &str) -> Option<usize> {
        self.by_name.get(&squeeze(name)).copied()
    }
}

/// A point name as compared: upper case, no spaces (`DIN4-1` is `DIN 4-1`).
fn squeeze(s: &str) -> String {
    s.chars().filter(|c| !c.is_whitespace()).map(|c| c.to_ascii_uppercase()).collect()
}

/// The block and field a parsed TLP names.
pub fn resolve(points: &Points<'_>, syntax: &Syntax<'_>) -> Result<(usize, usize), ResolveError> {
    match syntax {
        Syntax::Number(_) => Err(ResolveError::UnknownPoint),
        Syntax::Numeric(tlp) => resolve_numeric(points, *tlp),
        Syntax::Text { point, param } => {
            let block = points.point(point).ok_or(ResolveError::UnknownPoint)?;
            let template = points.db.block_template(block);
            let name = match param {
                Some(p) => *p,
                None => default_param(&template.name).ok_or(ResolveError::NeedsParam { block })?,
            };
            let field = template.field(name).ok_or(ResolveError::UnknownParam { block })?;
            Ok((block, field))
        }
    }
}

/// The block and field of a numeric TLP, or which part of it is missing
/// (type, logical, parameter).
fn resolve_numeric(points: &Points<'_>, tlp: Tlp) -> Result<(usize, usize), ResolveError> {
    let template = *points.by_type.get(&tlp.t).ok_or(ResolveError::NoType { t: tlp.t })?;
    let blocks = points.by_template.get(template).map_or(&[][..], Vec::as_slice);
    let Some(&block) = blocks.get(usize::from(tlp.l)) else {
        return Err(ResolveError::NoLogical { template, count: blocks.len() });
    };
    let fields = points.db.templates.get(template).map_or(0, |t| t.fields.len());
    if usize::from(tlp.p) < fields {
        return Ok((block, usize::from(tlp.p)));
    }
    Err(ResolveError::NoParam { template })
}

/// The ROC point closest to `point` (at most two letters off).
pub fn suggest(db: &Database, point: &str) -> Option<String> {
    if point.len() > 64 {
        return None;
    }
    let want = squeeze(point);
    db.blocks
        .iter()
        .map(|b| (distance(&want, &squeeze(&b.name)), &b.name))
        .filter(|(d, _)| *d <= 2)
        .min_by_key(|(d, _)| *d)
        .map(|(_, n)| n.clone())
}

/// Edit distance, for "did you mean" (the ST checker's).
pub(super) use crate::st::check::distance;

#[cfg(test)]
mod tests {
    use super::*;

    fn text<'a>(point: &'a str, param: Option<&'a str>) -> Result<Syntax<'a>, SyntaxError> {
        Ok(Syntax::Text { point, param })
    }

    #[test]
    fn numbers() {
        assert_eq!(parse("12"), Ok(Syntax::Number(12.0)));
        assert_eq!(parse("-3.5"), Ok(Syntax::Number(-3.5)));
        assert_eq!(parse("1e3"), Ok(Syntax::Number(1000.0)));
        assert_eq!(parse(" 0.1 "), Ok(Syntax::Number(0.1)));
        assert_eq!(parse(".5"), Ok(Syntax::Number(0.5)));
        assert_eq!(parse("1e39"), Err(SyntaxError::NumberRange));
        assert_eq!(parse("-1e400"), Err(SyntaxError::NumberRange));
        assert_eq!(parse("12abc"), Err(SyntaxError::Malformed("not a number")));
        // `inf` and `NaN` are names, not numbers.
        assert_eq!(parse("inf"), text("inf", None));
        assert_eq!(parse("NaN"), text("NaN", None));
    }

    #[test]
    fn numeric_tlps() {
        assert_eq!(parse("17,0,2"), Ok(Syntax::Numeric(Tlp { t: 17, l: 0, p: 2 })));
        assert_eq!(parse(" 98 , 1 , 20 "), Ok(Syntax::Numeric(Tlp { t: 98, l: 1, p: 20 })));
        assert_eq!(parse("70000,0,1"), Err(SyntaxError::Malformed("TLP number above 65535")));
        assert_eq!(parse("1,2,3,4"), Err(SyntaxError::Malformed("too many commas for a TLP")));
    }

    #[test]
    fn text_tlps() {
        assert_eq!(parse("AIN 3-1,EU"), text("AIN 3-1", Some("EU")));
        assert_eq!(parse("DIN4-1,STATUS"), text("DIN4-1", Some("STATUS")));
        assert_eq!(parse("DOU 4-1"), text("DOU 4-1", None));
        assert_eq!(parse("SFP 3,DATA3"), text("SFP 3", Some("DATA3")));
        assert_eq!(parse("FST 1, CMPFLG"), text("FST 1", Some("CMPFLG")));
        assert_eq!(parse("FST 1,R1"), text("FST 1", Some("R1")));
        assert_eq!(parse("SFP 3,"), Err(SyntaxError::Malformed("no parameter after the comma")));
        assert_eq!(parse(",DATA3"), Err(SyntaxError::Malformed("no point before the comma")));
    }

    fn db() -> Database {
        Database::from_json(
            r#"{"device": "ROC800", "blocks": {"FST 1": {"type": "FST"}, "SFP 3": {"type": "SFP"},
                "AIN 3-1": {"type": "AIN"}, "DIN 4-1": {"type": "DIN"}, "DOU 4-1": {"type": "DOU"}}}"#,
        )
        .unwrap()
    }

    fn names(db: &Database, cell: &str) -> Result<(String, String), ResolveError> {
        let (b, f) = resolve(&Points::new(db), &parse(cell).unwrap())?;
        Ok((db.blocks[b].name.clone(), db.block_template(b).fields[f].name.clone()))
    }

    #[test]
    fn text_tlps_resolve_ignoring_case_and_spaces() {
        let db = db();
        let pair = |b: &str, f: &str| Ok((b.to_string(), f.to_string()));
        assert_eq!(names(&db, "DIN4-1,STATUS"), pair("DIN 4-1", "STATUS"));
        assert_eq!(names(&db, "ain 3-1,hial"), pair("AIN 3-1", "HIAL"));
        assert_eq!(names(&db, "AIN 3-1"), pair("AIN 3-1", "EU"));
        assert_eq!(names(&db, "DOU 4-1"), pair("DOU 4-1", "STATUS"));
        assert_eq!(names(&db, "SFP 3,DATA3"), pair("SFP 3", "DATA3"));
        assert_eq!(names(&db, "FST 1,CMPFLG"), pair("FST 1", "CMPFLG"));
        let sfp = db.block("SFP 3").unwrap();
        assert_eq!(names(&db, "SFP 3"), Err(ResolveError::NeedsParam { block: sfp }));
        assert_eq!(names(&db, "SFP 3,DATA30"), Err(ResolveError::UnknownParam { block: sfp }));
        assert_eq!(names(&db, "SFP 4,DATA3"), Err(ResolveError::UnknownPoint));
        assert_eq!(suggest(&db, "SFP 4"), Some("SFP 3".into()));
    }

    #[test]
    fn numeric_tlps_say_which_part_is_missing() {
        let db = db();
        assert_eq!(names(&db, "98,0,3"), Ok(("SFP 3".to_string(), "DATA2".to_string())));
        assert_eq!(names(&db, "7,0,3"), Err(ResolveError::NoType { t: 7 }));
        let sfp = db.template("SFP").unwrap();
        assert_eq!(names(&db, "98,1,3"), Err(ResolveError::NoLogical { template: sfp, count: 1 }));
        assert_eq!(names(&db, "98,0,99"), Err(ResolveError::NoParam { template: sfp }));
    }
}

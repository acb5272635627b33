//! Field types of templates and initial values of blocks.

use super::json::{check_name, code, object, DbError};
use super::schema::{FieldDef, FieldType, InitValue, Template};
use super::tree::{get, Json, Member, Node};
use super::RocType;
use crate::code::Code;
use std::collections::HashSet;

/// Most values an ENUM may have: the store keeps the index in a u16.
pub const MAX_ENUM_VALUES: usize = 1 << 16;

/// A template's field from `"Name": <type spec>`.
pub(super) fn field_spec(template: &str, m: &Member) -> Result<FieldDef, DbError> {
    let (ty, readonly, wire) = type_spec(template, &m.key, &m.value)?;
    Ok(FieldDef { name: m.key.clone(), ty, readonly, wire })
}

fn unknown_type(template: &str, field: &str, node: &Node) -> DbError {
    DbError::at(
        code::FIELD_TYPE,
        format!("field `{template}.{field}` has an unknown type (expected REAL, INT, BOOL, BITS8, BITS16, STRING, DATE, TIME, BSEQ, WSTR, {{\"ENUM\": [...]}}, {{\"ALARMS\": [...]}} or {{\"type\": ..., \"readonly\": true}})"),
        node.span,
    )
}

/// A field's type, whether it is read-only, and the ROC type it travels as
/// if the template names one.
fn type_spec(template: &str, field: &str, node: &Node) -> Result<(FieldType, bool, Option<RocType>), DbError> {
    let bad = || unknown_type(template, field, node);
    match &node.v {
        Json::Str(s) => {
            let ty = match s.to_ascii_uppercase().as_str() {
                "REAL" => FieldType::Real,
                "INT" => FieldType::Int,
                "BOOL" => FieldType::Bool,
                "BITS8" => FieldType::Bits { width: 8, names: vec![] },
                "BITS16" => FieldType::Bits { width: 16, names: vec![] },
                "STRING" => FieldType::String,
                "DATE" => FieldType::Date,
                "TIME" => FieldType::Time,
                "BSEQ" => FieldType::Bseq,
                "WSTR" => FieldType::Wstr,
                _ => return Err(bad()),
            };
            Ok((ty, false, None))
        }
        Json::Obj(m) if get(m, "type").is_some() => {
            let mut ty = None;
            let mut readonly = false;
            let mut wire = None;
            for member in m {
                match (member.key.as_str(), &member.value.v) {
                    ("type", _) => ty = Some(type_spec(template, field, &member.value)?.0),
                    ("wire", Json::Str(w)) => wire = Some((RocType::parse(w), member.value.span)),
                    ("wire", _) => wire = Some((None, member.value.span)),
                    ("readonly", Json::Bool(b)) => readonly = *b,
                    ("readonly", _) => {
                        let message = format!(
                            "`readonly` of field `{template}.{field}` must be true or false, not {}",
                            member.value.kind()
                        );
                        return Err(DbError::at(code::READONLY, message, member.value.span));
                    }
                    (key, _) => {
                        let message = format!(
                            "unknown key `{key}` in the type of field `{template}.{field}` (expected type, readonly, wire)"
                        );
                        return Err(DbError::at(code::FIELD_TYPE, message, member.key_span));
                    }
                }
            }
            let ty = ty.ok_or_else(bad)?;
            let wire = match wire {
                None => None,
                Some((Some(w), _)) if w.fits(&ty) => Some(w),
                Some((_, span)) => {
                    let message = format!(
                        "`wire` of field `{template}.{field}` must name a ROC type that carries its type: AC1…AC255 for STRING; FL or an integer type for REAL; BIN, INT8, INT16, INT32, UINT8, UINT16 or UINT32 for whole numbers"
                    );
                    return Err(DbError::at(code::FIELD_TYPE, message, span));
                }
            };
            Ok((ty, readonly, wire))
        }
        Json::Obj(m) if m.len() == 1 => {
            let kind = m[0].key.to_ascii_uppercase();
            let Json::Arr(items) = &m[0].value.v else { return Err(bad()) };
            if !matches!(kind.as_str(), "ENUM" | "ALARMS" | "BITS8" | "BITS16") {
                return Err(bad());
            }
            let names = name_list(template, field, &kind, items)?;
            let ty = match kind.as_str() {
                "ENUM" if names.is_empty() => return Err(bad()),
                "ENUM" if names.len() > MAX_ENUM_VALUES => {
                    let message = format!(
                        "ENUM field `{template}.{field}` has {} values; an ENUM has at most {MAX_ENUM_VALUES}",
                        names.len()
                    );
                    return Err(DbError::at(code::ENUM_TOO_BIG, message, m[0].value.span));
                }
                "ENUM" => FieldType::Enum(names),
                "ALARMS" => FieldType::Alarms(names),
                "BITS8" if names.len() <= 8 => FieldType::Bits { width: 8, names },
                "BITS16" if names.len() <= 16 => FieldType::Bits { width: 16, names },
                _ => return Err(bad()),
            };
            Ok((ty, false, None))
        }
        _ => Err(bad()),
    }
}

/// The names of an ENUM, ALARMS or bit list: strings, each a valid name,
/// none twice (ignoring case).
fn name_list(template: &str, field: &str, kind: &str, items: &[Node]) -> Result<Vec<String>, DbError> {
    let what = match kind {
        "ENUM" => "an ENUM value",
        "ALARMS" => "an alarm",
        _ => "a bit",
    };
    let mut seen = HashSet::new();
    let mut names = Vec::with_capacity(items.len());
    for item in items {
        let name = item.as_str().ok_or_else(|| unknown_type(template, field, item))?;
        check_name(what, name, item.span)?;
        if !seen.insert(name.to_ascii_uppercase()) {
            let message = format!("{kind} list of field `{template}.{field}` names `{name}` twice (names ignore case)");
            return Err(DbError::at(code::TWICE, message, item.span));
        }
        names.push(name.to_string());
    }
    Ok(names)
}

/// A block's `"values"`, checked against its template.
pub(super) fn init_values(block: &str, t: &Template, node: &Node) -> Result<Vec<(usize, InitValue)>, DbError> {
    let mut values: Vec<(usize, InitValue)> = Vec::new();
    for m in object(node, &format!("`values` of block `{block}`"))? {
        let fname = &m.key;
        let fi = t.field(fname).ok_or_else(|| {
            let message = format!("block `{block}` of type `{}` has no field `{fname}`", t.name);
            DbError::at(code::INIT_VALUE, message, m.key_span)
        })?;
        let field = &t.fields[fi];
        if values.iter().any(|(i, _)| *i == fi) {
            let message =
                format!("block `{block}` gives field `{}` two initial values (names ignore case)", field.name);
            return Err(DbError::at(code::TWICE, message, m.key_span));
        }
        let value = init_value(&field.ty, &m.value).map_err(|(code, why)| {
            DbError::at(code, format!("initial value of `{block}.{}`: {why}", field.name), m.value.span)
        })?;
        values.push((fi, value));
    }
    Ok(values)
}

type ValueError = (Code, String);

fn wrong(why: String) -> ValueError {
    (code::INIT_VALUE, why)
}

/// Checks an initial value against its field type. Numbers must survive
/// the trip into the store and back out to `--out` unchanged in meaning.
fn init_value(ty: &FieldType, node: &Node) -> Result<InitValue, ValueError> {
    match (ty, &node.v) {
        (FieldType::Real | FieldType::Int | FieldType::Bits { .. }, Json::Num(x)) => number(ty, *x).map(InitValue::Num),
        (FieldType::Bool, Json::Bool(b)) => Ok(InitValue::Bool(*b)),
        (FieldType::Bool, Json::Num(x)) => Ok(InitValue::Bool(*x != 0.0)),
        (FieldType::Enum(names), Json::Str(s)) => {
            if names.iter().any(|n| n.eq_ignore_ascii_case(s)) {
                Ok(InitValue::Text(s.clone()))
            } else {
                Err(wrong(format!("`{s}` is not one of {}", names.join(", "))))
            }
        }
        (FieldType::String | FieldType::Date | FieldType::Time | FieldType::Bseq | FieldType::Wstr, Json::Str(s)) => {
            // The VM's limit on a string, so that no program starts with a
            // value it could not have written itself.
            if s.len() > crate::MAX_STRING {
                let why =
                    format!("the text is {} bytes long; a string field holds at most {}", s.len(), crate::MAX_STRING);
                return Err((code::OUT_OF_RANGE, why));
            }
            Ok(InitValue::Text(s.clone()))
        }
        (FieldType::Alarms(names), Json::Obj(m)) => {
            let mut active: Vec<String> = Vec::new();
            let mut seen = HashSet::new();
            for alarm in m {
                let k = &alarm.key;
                if !names.iter().any(|n| n.eq_ignore_ascii_case(k)) {
                    return Err(wrong(format!("`{k}` is not one of the alarms {}", names.join(", "))));
                }
                if !seen.insert(k.to_ascii_uppercase()) {
                    return Err((code::TWICE, format!("alarm `{k}` is given twice (names ignore case)")));
                }
                match alarm.value.v {
                    Json::Bool(true) => active.push(k.clone()),
                    Json::Bool(false) => {}
                    _ => return Err(wrong(format!("the state of alarm `{k}` must be true or false"))),
                }
            }
            Ok(InitValue::Active(active))
        }
        (ty, _) => Err(wrong(format!("expected a value for a {} field, not {}", ty.keyword(), node.kind()))),
    }
}

/// A number for a REAL, INT or bitfield, refused (E0815) if the store
/// could not hold it: REAL beyond the f32 range, INT not a whole number in
/// the i32 range, a bitfield not a whole number in its range.
fn number(ty: &FieldType, x: f64) -> Result<f64, ValueError> {
    let (ok, range) = match ty {
        FieldType::Real => ((x as f32).is_finite(), "from -3.4028235e38 to 3.4028235e38"),
        FieldType::Int => {
            (whole_in(x, i32::MIN.into(), i32::MAX.into()), "a whole number from -2147483648 to 2147483647")
        }
        FieldType::Bits { width: 8, .. } => (whole_in(x, 0.0, 255.0), "a whole number from 0 to 255"),
        _ => (whole_in(x, -32_768.0, 65_535.0), "a whole number from -32768 to 65535"),
    };
    if ok {
        Ok(x)
    } else {
        Err((code::OUT_OF_RANGE, format!("{} does not fit a {} field (expected {range})", show(x), ty.keyword())))
    }
}

/// A number as the message shows it: `1e300`, not three hundred digits.
fn show(x: f64) -> String {
    if x.is_infinite() {
        "a number this large".to_string()
    } else if x != 0.0 && !(1e-4..1e16).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

fn whole_in(x: f64, lo: f64, hi: f64) -> bool {
    x.fract() == 0.0 && (lo..=hi).contains(&x)
}

//! Loading a database from the JSON contract.
//!
//! Errors carry a code and a byte range into the JSON text so that the CLI
//! can render them like any other diagnostic.

use super::schema::{Alias, Block, Database, FieldDef, FieldType, InitValue, Template};
use serde_json::{Map, Value};
use std::fmt;

/// Something wrong with a database file.
#[derive(Clone, Debug, PartialEq)]
pub struct DbError {
    pub code: &'static str,
    pub message: String,
    /// Byte range in the database text, when it can be located.
    pub span: Option<(usize, usize)>,
}

impl fmt::Display for DbError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "error[{}]: {}", self.code, self.message)
    }
}

impl std::error::Error for DbError {}

const BUILTIN: &str = include_str!("builtin.json");

impl Database {
    /// The built-in template library with no blocks.
    pub fn builtin() -> Database {
        let mut db = Database::default();
        // The built-in library is tested to load; an empty library is the
        // only possible fallback and keeps this path free of panics.
        let _ = Loader { text: BUILTIN, db: &mut db }.load();
        db
    }

    /// Loads a database file over the built-in library.
    pub fn from_json(text: &str) -> Result<Database, DbError> {
        let mut db = Database::builtin();
        Loader { text, db: &mut db }.load()?;
        Ok(db)
    }
}

struct Loader<'a> {
    text: &'a str,
    db: &'a mut Database,
}

impl Loader<'_> {
    fn load(&mut self) -> Result<(), DbError> {
        let root: Value = serde_json::from_str(self.text).map_err(|e| {
            let at = offset_of(self.text, e.line(), e.column());
            DbError { code: "E0800", message: format!("the database is not valid JSON: {e}"), span: Some((at, at)) }
        })?;
        let root = self.object(&root, "the database")?;
        for key in root.keys() {
            if !matches!(key.as_str(), "templates" | "blocks" | "aliases") {
                return Err(self.err(
                    "E0801",
                    format!("unknown top-level key `{key}` (expected templates, blocks, aliases)"),
                    key,
                ));
            }
        }
        if let Some(t) = root.get("templates") {
            for (name, spec) in self.object(t, "`templates`")? {
                self.template(name, spec)?;
            }
        }
        if let Some(b) = root.get("blocks") {
            for (name, spec) in self.object(b, "`blocks`")? {
                self.block(name, spec)?;
            }
        }
        if let Some(a) = root.get("aliases") {
            for (name, target) in self.object(a, "`aliases`")? {
                self.alias(name, target)?;
            }
        }
        Ok(())
    }

    fn err(&self, code: &'static str, message: String, near: &str) -> DbError {
        DbError { code, message, span: locate(self.text, near) }
    }

    fn object<'v>(&self, v: &'v Value, what: &str) -> Result<&'v Map<String, Value>, DbError> {
        v.as_object().ok_or_else(|| DbError {
            code: "E0801",
            message: format!("{what} must be a JSON object"),
            span: None,
        })
    }

    fn template(&mut self, name: &str, spec: &Value) -> Result<(), DbError> {
        let spec = spec
            .as_object()
            .ok_or_else(|| self.err("E0801", format!("template `{name}` must be an object with `fields`"), name))?;
        let doc = spec.get("doc").and_then(Value::as_str).unwrap_or_default().to_string();
        let mut fields = Vec::new();
        if let Some(fs) = spec.get("fields") {
            let fs = fs
                .as_object()
                .ok_or_else(|| self.err("E0801", format!("`fields` of template `{name}` must be an object"), name))?;
            for (fname, fspec) in fs {
                if fields.iter().any(|f: &FieldDef| f.name.eq_ignore_ascii_case(fname)) {
                    return Err(self.err("E0806", format!("template `{name}` declares field `{fname}` twice"), fname));
                }
                let (ty, readonly) = self.field_spec(name, fname, fspec)?;
                fields.push(FieldDef { name: fname.clone(), ty, readonly });
            }
        }
        self.db.put_template(Template::new(name.to_string(), doc, fields));
        Ok(())
    }

    fn field_spec(&self, tname: &str, fname: &str, spec: &Value) -> Result<(FieldType, bool), DbError> {
        let bad = || {
            self.err(
                "E0802",
                format!("field `{tname}.{fname}` has an unknown type (expected REAL, INT, BOOL, BITS8, BITS16, STRING, DATE, TIME, BSEQ, WSTR, {{\"ENUM\": [...]}}, {{\"ALARMS\": [...]}} or {{\"type\": ..., \"readonly\": true}})"),
                fname,
            )
        };
        match spec {
            Value::String(s) => {
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
                Ok((ty, false))
            }
            Value::Object(m) if m.contains_key("type") => {
                let (ty, _) = self.field_spec(tname, fname, &m["type"])?;
                let readonly = m.get("readonly").and_then(Value::as_bool).unwrap_or(false);
                Ok((ty, readonly))
            }
            Value::Object(m) if m.len() == 1 => {
                let (kind, list) = m.iter().next().ok_or_else(bad)?;
                let names: Vec<String> = list
                    .as_array()
                    .ok_or_else(bad)?
                    .iter()
                    .map(|v| v.as_str().map(str::to_string).ok_or_else(bad))
                    .collect::<Result<_, _>>()?;
                let ty = match kind.to_ascii_uppercase().as_str() {
                    "ENUM" if !names.is_empty() => FieldType::Enum(names),
                    "ALARMS" => FieldType::Alarms(names),
                    "BITS8" if names.len() <= 8 => FieldType::Bits { width: 8, names },
                    "BITS16" if names.len() <= 16 => FieldType::Bits { width: 16, names },
                    _ => return Err(bad()),
                };
                Ok((ty, false))
            }
            _ => Err(bad()),
        }
    }

    fn block(&mut self, name: &str, spec: &Value) -> Result<(), DbError> {
        let spec = spec
            .as_object()
            .ok_or_else(|| self.err("E0801", format!("block `{name}` must be an object with `type`"), name))?;
        let tname = spec
            .get("type")
            .and_then(Value::as_str)
            .ok_or_else(|| self.err("E0801", format!("block `{name}` has no `type`"), name))?;
        let template = self
            .db
            .template(tname)
            .ok_or_else(|| self.err("E0803", format!("block `{name}` has unknown type `{tname}`"), tname))?;
        let mut values = Vec::new();
        if let Some(vs) = spec.get("values") {
            let vs = vs
                .as_object()
                .ok_or_else(|| self.err("E0801", format!("`values` of block `{name}` must be an object"), name))?;
            for (fname, v) in vs {
                let t = &self.db.templates[template];
                let fi = t.field(fname).ok_or_else(|| {
                    self.err("E0804", format!("block `{name}` of type `{}` has no field `{fname}`", t.name), fname)
                })?;
                let value = init_value(&t.fields[fi].ty, v)
                    .map_err(|why| self.err("E0804", format!("initial value of `{name}.{fname}`: {why}"), fname))?;
                values.push((fi, value));
            }
        }
        if !self.db.add_block(Block { name: name.to_string(), template, values }) {
            return Err(self.err("E0806", format!("block `{name}` is declared twice (names ignore case)"), name));
        }
        Ok(())
    }

    fn alias(&mut self, name: &str, target: &Value) -> Result<(), DbError> {
        let t = target.as_str().filter(|t| !t.is_empty() && t.split('.').all(|s| !s.is_empty())).ok_or_else(|| {
            self.err("E0805", format!("alias `{name}` must name a reference like \"BLOCK.FIELD\""), name)
        })?;
        let alias = Alias { name: name.to_string(), target: t.split('.').map(str::to_string).collect() };
        if !self.db.add_alias(alias) {
            return Err(self.err("E0806", format!("alias `{name}` is declared twice (names ignore case)"), name));
        }
        Ok(())
    }
}

/// Checks an initial value against its field type.
fn init_value(ty: &FieldType, v: &Value) -> Result<InitValue, String> {
    match (ty, v) {
        (FieldType::Real | FieldType::Int | FieldType::Bits { .. }, Value::Number(n)) => {
            let x = n.as_f64().ok_or("not a representable number")?;
            Ok(InitValue::Num(x))
        }
        (FieldType::Bool, Value::Bool(b)) => Ok(InitValue::Bool(*b)),
        (FieldType::Bool, Value::Number(n)) => Ok(InitValue::Bool(n.as_f64().unwrap_or(0.0) != 0.0)),
        (FieldType::Enum(names), Value::String(s)) => {
            if names.iter().any(|n| n.eq_ignore_ascii_case(s)) {
                Ok(InitValue::Text(s.clone()))
            } else {
                Err(format!("`{s}` is not one of {}", names.join(", ")))
            }
        }
        (
            FieldType::String | FieldType::Date | FieldType::Time | FieldType::Bseq | FieldType::Wstr,
            Value::String(s),
        ) => Ok(InitValue::Text(s.clone())),
        (FieldType::Alarms(names), Value::Object(m)) => {
            let mut active = Vec::new();
            for (k, v) in m {
                if !names.iter().any(|n| n.eq_ignore_ascii_case(k)) {
                    return Err(format!("`{k}` is not one of the alarms {}", names.join(", ")));
                }
                if v.as_bool().ok_or("alarm states are true or false")? {
                    active.push(k.clone());
                }
            }
            Ok(InitValue::Active(active))
        }
        (ty, _) => Err(format!("expected a value for a {} field", ty.keyword())),
    }
}

/// Byte offset of a 1-based line and column.
fn offset_of(text: &str, line: usize, column: usize) -> usize {
    let start: usize = text.split_inclusive('\n').take(line.saturating_sub(1)).map(str::len).sum();
    (start + column.saturating_sub(1)).min(text.len())
}

/// Finds the first occurrence of a quoted key, to point an error at it.
fn locate(text: &str, key: &str) -> Option<(usize, usize)> {
    let quoted = format!("\"{key}\"");
    text.find(&quoted).map(|at| (at, at + quoted.len()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_library_loads() {
        let mut db = Database::default();
        let r = Loader { text: BUILTIN, db: &mut db }.load();
        assert_eq!(r, Ok(()));
        for t in ["ACTION", "DIGACT", "SFC_CON", "RAW_COM", "PID", "AN_CONN", "DG_CONN"] {
            assert!(db.template(t).is_some(), "{t}");
        }
    }

    #[test]
    fn contract_example_loads() {
        let text = r#"{ "templates": { "RECIPE": { "fields": { "A0": "REAL", "N0": "INT", "Flags": "BITS16",
            "Mode": { "ENUM": ["MANUAL", "AUTO"] }, "Alarms": { "ALARMS": ["HighAbs", "LowAbs"] } } } },
            "blocks": { "REC1": { "type": "RECIPE", "values": { "A0": 12.5, "Mode": "AUTO" } } },
            "aliases": { "avg": "REC1.A0" } }"#;
        let db = Database::from_json(text).expect("loads");
        let b = db.block("rec1").expect("block");
        let t = db.block_template(b);
        assert_eq!(
            t.fields.iter().map(|f| f.name.as_str()).collect::<Vec<_>>(),
            ["A0", "N0", "Flags", "Mode", "Alarms"]
        );
        assert_eq!(db.alias("AVG").map(|a| a.target.clone()), Some(vec!["REC1".to_string(), "A0".to_string()]));
    }

    #[test]
    fn errors_are_coded_and_located() {
        let e = Database::from_json("{ \"blocks\": { \"B\": { \"type\": \"NOPE\" } } }").expect_err("fails");
        assert_eq!(e.code, "E0803");
        assert_eq!(e.span, Some((29, 35)));
        let e = Database::from_json("{ \"blocks\": ").expect_err("fails");
        assert_eq!(e.code, "E0800");
        let e = Database::from_json(
            r#"{"templates":{"T":{"fields":{"M":{"ENUM":["A"]}}}},"blocks":{"B":{"type":"T","values":{"M":"Z"}}}}"#,
        )
        .expect_err("fails");
        assert_eq!(e.code, "E0804");
    }

    #[test]
    fn bit_names() {
        let t = FieldType::Bits { width: 8, names: vec!["Run".into()] };
        assert_eq!(t.bit_index("BIT7"), Some(7));
        assert_eq!(t.bit_index("Bit8"), None);
        assert_eq!(t.bit_index("run"), Some(0));
        assert_eq!(t.bit_index("Bitx"), None);
    }
}

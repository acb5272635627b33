//! The Modbus register map of a database (`"modbus"`, docs/modbus.md):
//! which field each coil, discrete input, holding and input register
//! stands for. Checked when the database loads, each error at its place in
//! the JSON: unknown fields, types that do not fit, overlapping addresses.

use super::json::{code, DbError};
use super::schema::{Database, FieldType};
use super::tree::{get, Json, Member, Node};

/// The four Modbus tables.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Table {
    Coil,
    Discrete,
    Holding,
    Input,
}

impl Table {
    pub const ALL: [Table; 4] = [Table::Coil, Table::Discrete, Table::Holding, Table::Input];

    pub fn name(self) -> &'static str {
        match self {
            Table::Coil => "coil",
            Table::Discrete => "discrete",
            Table::Holding => "holding",
            Table::Input => "input",
        }
    }

    /// Whether the table holds bits (coils, discrete inputs), not registers.
    pub fn bits(self) -> bool {
        matches!(self, Table::Coil | Table::Discrete)
    }

    /// Whether clients may write it (coils and holding registers).
    pub fn writable(self) -> bool {
        matches!(self, Table::Coil | Table::Holding)
    }
}

/// How a field sits in its table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MbType {
    /// IEEE-754 float32 in two registers.
    Real,
    /// One register, two's complement.
    Int,
    /// One bit.
    Bool,
}

/// One mapped field.
#[derive(Clone, Debug, PartialEq)]
pub struct MbEntry {
    pub table: Table,
    pub address: u16,
    pub block: usize,
    pub field: usize,
    /// A bit of a bitfield, for a coil or discrete input.
    pub bit: Option<u8>,
    pub ty: MbType,
    /// A REAL's low word at `address`, high word after (`"words": "low-first"`).
    pub low_first: bool,
}

impl MbEntry {
    /// Registers or bits it takes.
    pub fn width(&self) -> u32 {
        if self.ty == MbType::Real {
            2
        } else {
            1
        }
    }
}

/// A database's map: the unit it answers as and the entries, each table's
/// sorted by address.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModbusMap {
    pub unit: u8,
    pub entries: Vec<MbEntry>,
}

impl ModbusMap {
    /// The entry covering `address` of `table`, and the offset of the
    /// address in it (1 for a REAL's second register).
    pub fn at(&self, table: Table, address: u16) -> Option<(&MbEntry, u32)> {
        let of_table = |e: &&MbEntry| e.table == table;
        let i = self.entries.partition_point(|e| (e.table as u8, e.address) <= (table as u8, address));
        let e = self.entries[..i].iter().rev().find(of_table)?;
        let off = u32::from(address) - u32::from(e.address);
        (off < e.width()).then_some((e, off))
    }
}

fn bad(c: crate::code::Code, message: impl Into<String>, node: &Node) -> DbError {
    DbError::at(c, message.into(), node.span)
}

/// Reads `"modbus": {"unit": 1, "map": [...]}` against the database's
/// blocks and aliases (so it is read after them).
pub(super) fn load(db: &Database, node: &Node) -> Result<ModbusMap, DbError> {
    let Json::Obj(members) = &node.v else {
        return Err(bad(code::MODBUS_SHAPE, "`modbus` is an object with `unit` and `map`", node));
    };
    let mut map = ModbusMap { unit: 1, entries: Vec::new() };
    for m in members {
        match m.key.as_str() {
            "unit" => {
                map.unit = m
                    .value
                    .whole(0.0, 255.0)
                    .ok_or_else(|| bad(code::MODBUS_SHAPE, "`unit` is a whole number from 0 to 255", &m.value))?
                    as u8
            }
            "map" => {
                let Json::Arr(items) = &m.value.v else {
                    return Err(bad(code::MODBUS_SHAPE, "`map` is an array of entries", &m.value));
                };
                for item in items {
                    let e = entry(db, item)?;
                    overlap(&map.entries, &e, item)?;
                    map.entries.push(e);
                }
            }
            other => {
                let message = format!("unknown key `{other}` in `modbus` (expected unit, map)");
                return Err(DbError::at(code::MODBUS_SHAPE, message, m.key_span));
            }
        }
    }
    map.entries.sort_by_key(|e| (e.table as u8, e.address));
    Ok(map)
}

fn text<'a>(spec: &'a [Member], key: &str, entry: &Node) -> Result<Option<(&'a str, &'a Node)>, DbError> {
    match get(spec, key) {
        None => Ok(None),
        Some(m) => match &m.value.v {
            Json::Str(s) => Ok(Some((s.as_str(), &m.value))),
            _ => Err(bad(code::MODBUS_SHAPE, format!("`{key}` of a map entry is a string"), entry)),
        },
    }
}

/// One entry: its table, address, field, type and word order.
fn entry(db: &Database, item: &Node) -> Result<MbEntry, DbError> {
    let Json::Obj(spec) = &item.v else {
        return Err(bad(code::MODBUS_SHAPE, "a map entry is an object: table, address, field, type", item));
    };
    if let Some(m) = spec.iter().find(|m| !["table", "address", "field", "type", "words"].contains(&m.key.as_str())) {
        let message = format!("unknown key `{}` in a map entry (expected table, address, field, type, words)", m.key);
        return Err(DbError::at(code::MODBUS_SHAPE, message, m.key_span));
    }
    let (tname, tnode) =
        text(spec, "table", item)?.ok_or_else(|| bad(code::MODBUS_SHAPE, "a map entry needs `table`", item))?;
    let table = Table::ALL.into_iter().find(|t| t.name().eq_ignore_ascii_case(tname)).ok_or_else(|| {
        bad(code::MODBUS_SHAPE, format!("`{tname}` is not a table: coil, discrete, holding or input"), tnode)
    })?;
    let anode =
        &get(spec, "address").ok_or_else(|| bad(code::MODBUS_SHAPE, "a map entry needs `address`", item))?.value;
    let address = anode
        .whole(0.0, 65535.0)
        .ok_or_else(|| bad(code::MODBUS_SHAPE, "`address` is a whole number from 0 to 65535", anode))?
        as u16;
    let (path, pnode) = text(spec, "field", item)?
        .ok_or_else(|| bad(code::MODBUS_SHAPE, "a map entry needs `field` (BLOCK.FIELD)", item))?;
    let (block, field, bit) = db.field_path(path).map_err(|why| bad(code::MODBUS_FIELD, why, pnode))?;
    let fty = &db.block_template(block).fields[field].ty;
    let ty = match text(spec, "type", item)? {
        None if table.bits() => MbType::Bool,
        None => return Err(bad(code::MODBUS_SHAPE, "a register needs `type`: REAL or INT", item)),
        Some((t, tn)) => match t.to_ascii_uppercase().as_str() {
            "REAL" => MbType::Real,
            "INT" => MbType::Int,
            "BOOL" => MbType::Bool,
            _ => return Err(bad(code::MODBUS_SHAPE, format!("`{t}` is not a Modbus type: REAL, INT or BOOL"), tn)),
        },
    };
    fits(table, ty, fty, bit).map_err(|why| bad(code::MODBUS_TYPE, format!("`{path}`: {why}"), item))?;
    let low_first = match text(spec, "words", item)? {
        None => false,
        Some((w, _)) if w.eq_ignore_ascii_case("high-first") => false,
        Some((w, _)) if w.eq_ignore_ascii_case("low-first") => true,
        Some((w, wn)) => {
            return Err(bad(code::MODBUS_SHAPE, format!("`words` is high-first or low-first, not `{w}`"), wn))
        }
    };
    let e = MbEntry { table, address, block, field, bit, ty, low_first };
    if u32::from(address) + e.width() > 65536 {
        return Err(bad(code::MODBUS_SHAPE, "a REAL at 65535 would pass the last register", anode));
    }
    Ok(e)
}

/// Whether a field of `fty` can sit in `table` as `ty`.
fn fits(table: Table, ty: MbType, fty: &FieldType, bit: Option<u8>) -> Result<(), String> {
    let whole = matches!(fty, FieldType::Int | FieldType::Bits { .. } | FieldType::Enum(_));
    match (table.bits(), ty) {
        (true, MbType::Bool) if bit.is_some() || matches!(fty, FieldType::Bool | FieldType::Int) => Ok(()),
        (true, MbType::Bool) => Err("a coil or discrete input is a BOOL field, an INT (0/1) or a bit".into()),
        (true, _) => Err("coils and discrete inputs hold bits: leave out `type` or write BOOL".into()),
        (false, _) if bit.is_some() => Err("a single bit belongs in a coil or discrete input".into()),
        (false, MbType::Real) if matches!(fty, FieldType::Real) => Ok(()),
        (false, MbType::Int) if whole => Ok(()),
        (false, MbType::Bool) => Err("a register holds REAL or INT".into()),
        (false, _) => Err("REAL registers hold a REAL field, INT registers an INT, BITS or ENUM field".into()),
    }
}

/// Two entries of one table may not share an address.
fn overlap(entries: &[MbEntry], e: &MbEntry, item: &Node) -> Result<(), DbError> {
    let (a0, a1) = (u32::from(e.address), u32::from(e.address) + e.width());
    if let Some(o) = entries
        .iter()
        .find(|o| o.table == e.table && u32::from(o.address) < a1 && a0 < u32::from(o.address) + o.width())
    {
        let message = format!("{} {} overlaps the entry at {} of the same table", e.table.name(), e.address, o.address);
        return Err(bad(code::MODBUS_OVERLAP, message, item));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const BLOCKS: &str = r#""templates": {"TANK": {"fields": {"Level": "REAL", "HighCnt": "INT", "Valve": "BOOL",
        "Flags": "BITS8", "Name": "STRING"}}},
        "blocks": {"TANK1": {"type": "TANK"}}, "aliases": {"Lvl": "TANK1.Level"}"#;

    fn db(map: &str) -> Result<Database, DbError> {
        Database::from_json(&format!("{{{BLOCKS}, \"modbus\": {map}}}"))
    }

    #[test]
    fn the_issues_map_loads_and_finds_each_address() {
        let d = db(r#"{ "unit": 1, "map": [
            { "table": "holding", "address": 0, "field": "TANK1.Level",   "type": "REAL" },
            { "table": "holding", "address": 2, "field": "TANK1.HighCnt", "type": "INT" },
            { "table": "input",   "address": 0, "field": "Lvl",           "type": "REAL", "words": "low-first" },
            { "table": "coil",    "address": 0, "field": "TANK1.Valve" },
            { "table": "discrete", "address": 7, "field": "TANK1.Flags.Bit3" } ] }"#)
        .unwrap();
        let m = d.modbus.as_ref().unwrap();
        assert_eq!(m.unit, 1);
        let (e, off) = m.at(Table::Holding, 1).unwrap();
        assert_eq!((e.ty, e.address, off, e.low_first), (MbType::Real, 0, 1, false));
        assert_eq!(m.at(Table::Holding, 2).unwrap().0.ty, MbType::Int);
        assert!(m.at(Table::Holding, 3).is_none());
        assert!(m.at(Table::Input, 1).unwrap().0.low_first);
        assert_eq!(m.at(Table::Discrete, 7).unwrap().0.bit, Some(3));
        assert!(m.at(Table::Coil, 1).is_none() && m.at(Table::Discrete, 0).is_none());
    }

    #[test]
    fn every_mistake_is_coded_and_located() {
        for (map, c, at) in [
            (r#"{"map": [{"table": "holding", "address": 0, "field": "TANK1.Level"}]}"#, code::MODBUS_SHAPE, "{"),
            (
                r#"{"map": [{"table": "hold", "address": 0, "field": "TANK1.Level", "type": "REAL"}]}"#,
                code::MODBUS_SHAPE,
                "\"hold\"",
            ),
            (r#"{"map": [{"table": "coil", "address": 70000, "field": "TANK1.Valve"}]}"#, code::MODBUS_SHAPE, "70000"),
            (
                r#"{"map": [{"table": "coil", "address": 0, "field": "TANK1.Valv"}]}"#,
                code::MODBUS_FIELD,
                "\"TANK1.Valv\"",
            ),
            (
                r#"{"map": [{"table": "coil", "address": 0, "field": "TANK1.Flags.Bit9"}]}"#,
                code::MODBUS_FIELD,
                "\"TANK1.Flags.Bit9\"",
            ),
            (
                r#"{"map": [{"table": "holding", "address": 0, "field": "TANK1.Level", "type": "INT"}]}"#,
                code::MODBUS_TYPE,
                "{",
            ),
            (r#"{"map": [{"table": "coil", "address": 0, "field": "TANK1.Level"}]}"#, code::MODBUS_TYPE, "{"),
            (
                r#"{"map": [{"table": "holding", "address": 0, "field": "TANK1.Name", "type": "INT"}]}"#,
                code::MODBUS_TYPE,
                "{",
            ),
            (
                r#"{"map": [{"table": "holding", "address": 65535, "field": "TANK1.Level", "type": "REAL"}]}"#,
                code::MODBUS_SHAPE,
                "65535",
            ),
            (
                r#"{"map": [{"table": "holding", "address": 0, "field": "TANK1.Level", "type": "REAL"},
                         {"table": "holding", "address": 1, "field": "TANK1.HighCnt", "type": "INT"}]}"#,
                code::MODBUS_OVERLAP,
                "{",
            ),
            (r#"{"unit": 300, "map": []}"#, code::MODBUS_SHAPE, "300"),
            (r#"{"units": 1}"#, code::MODBUS_SHAPE, "\"units\""),
        ] {
            let text = format!("{{{BLOCKS}, \"modbus\": {map}}}");
            let e = Database::from_json(&text).unwrap_err();
            assert_eq!(e.code, c, "{map}: {}", e.message);
            let (s, _) = e.span.expect("located");
            assert!(text[s..].starts_with(at), "{map}: error at `{}`", &text[s..(s + 12).min(text.len())]);
        }
        // Different tables may share addresses.
        assert!(db(r#"{"map": [{"table": "coil", "address": 0, "field": "TANK1.Valve"},
                               {"table": "discrete", "address": 0, "field": "TANK1.Valve"}]}"#)
        .is_ok());
    }
}

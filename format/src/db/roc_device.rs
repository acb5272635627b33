//! What a ROC-protocol device keeps beside its points
//! (docs/roc-protocol.md): the configurable opcode tables hosts read with
//! opcode 10 and write with 11 (`"opcode_tables"`), and the links store and
//! forward (opcode 24) passes frames on (`"roc": {"forward": …}`).

use super::json::{code, DbError};
use super::schema::Database;
use super::tree::{Json, Member, Node};

/// Tables a device has (0–15) and locations in each (0–43).
pub const TABLES: u8 = 16;
pub const LOCATIONS: u8 = 44;

/// One configurable opcode table: its version and, by location, the field
/// it holds (block and field index).
#[derive(Clone, Debug, PartialEq)]
pub struct OpcodeTable {
    pub version: f32,
    pub slots: [Option<(usize, usize)>; LOCATIONS as usize],
}

impl Default for OpcodeTable {
    fn default() -> OpcodeTable {
        OpcodeTable { version: 0.0, slots: [None; LOCATIONS as usize] }
    }
}

/// A unit and group, as the forward links name devices.
pub type UnitGroup = (u8, u8);

fn bad(c: crate::code::Code, message: impl Into<String>, span: (usize, usize)) -> DbError {
    DbError::at(c, message.into(), span)
}

/// A number key from 0 to `below - 1`.
fn index_key(m: &Member, what: &str, below: u8) -> Result<u8, DbError> {
    m.key.parse::<u8>().ok().filter(|&n| n < below).ok_or_else(|| {
        let message = format!("`{}` is not {what}: a whole number from 0 to {}", m.key, below - 1);
        bad(code::OPCODE_TABLE, message, m.key_span)
    })
}

/// `"opcode_tables": {"1": {"version": 1.0, "slots": {"0": "SFP 1.DATA1"}}}`:
/// each location names a field with a ROC form (it travels at that size),
/// so a host reading the table gets a value for every location it maps.
pub(super) fn opcode_tables(db: &Database, node: &Node) -> Result<Vec<(u8, OpcodeTable)>, DbError> {
    let Json::Obj(tables) = &node.v else {
        return Err(bad(code::OPCODE_TABLE, "`opcode_tables` is an object of table numbers", node.span));
    };
    let mut out = Vec::new();
    for t in tables {
        let number = index_key(t, "a table number", TABLES)?;
        let Json::Obj(spec) = &t.value.v else {
            return Err(bad(
                code::OPCODE_TABLE,
                "a table is an object with `slots` and optionally `version`",
                t.value.span,
            ));
        };
        let mut table = OpcodeTable::default();
        for m in spec {
            match m.key.as_str() {
                "version" => {
                    let Json::Num(v) = m.value.v else {
                        return Err(bad(code::OPCODE_TABLE, "`version` is a number", m.value.span));
                    };
                    table.version = v as f32;
                }
                "slots" => slots(db, &m.value, &mut table)?,
                other => {
                    let message = format!("unknown key `{other}` in an opcode table (expected version, slots)");
                    return Err(bad(code::OPCODE_TABLE, message, m.key_span));
                }
            }
        }
        out.push((number, table));
    }
    Ok(out)
}

fn slots(db: &Database, node: &Node, table: &mut OpcodeTable) -> Result<(), DbError> {
    let Json::Obj(slots) = &node.v else {
        return Err(bad(code::OPCODE_TABLE, "`slots` is an object of locations and fields", node.span));
    };
    for s in slots {
        let at = index_key(s, "a location", LOCATIONS)?;
        let Json::Str(path) = &s.value.v else {
            return Err(bad(code::OPCODE_TABLE, "a location holds a field, `BLOCK.FIELD`", s.value.span));
        };
        let (block, field, bit) = db.field_path(path).map_err(|why| bad(code::OPCODE_TABLE, why, s.value.span))?;
        if bit.is_some() || db.roc_type(block, field).is_none() {
            let message = format!("`{path}` has no ROC form: a location holds a whole field that travels in 180/181");
            return Err(bad(code::OPCODE_TABLE, message, s.value.span));
        }
        table.slots[usize::from(at)] = Some((block, field));
    }
    Ok(())
}

/// A `UNIT,GROUP` key.
fn unit_group(m: &Member) -> Result<UnitGroup, DbError> {
    let mut parts = m.key.split(',').map(|p| p.trim().parse::<u8>().ok());
    match (parts.next().flatten(), parts.next().flatten(), parts.next()) {
        (Some(u), Some(g), None) if u != 0 => Ok((u, g)),
        _ => {
            let message = format!("`{}` is not a device: UNIT,GROUP, each 0–255, the unit not 0", m.key);
            Err(bad(code::FORWARD, message, m.key_span))
        }
    }
}

/// `"roc": {"forward": {"3,1": "127.0.0.1:4001"}}`: where store and
/// forward reaches each device. An address is written out (an IP address
/// and a port): a device does not look names up. The rest of `"roc"` is
/// what a run wrote with `--out` (the logs and archives), which loading
/// skips.
pub(super) fn forward(node: &Node) -> Result<Vec<(UnitGroup, std::net::SocketAddr)>, DbError> {
    let Json::Obj(members) = &node.v else { return Ok(Vec::new()) };
    let Some(f) = members.iter().find(|m| m.key == "forward") else { return Ok(Vec::new()) };
    let Json::Obj(links) = &f.value.v else {
        return Err(bad(code::FORWARD, "`forward` is an object: {\"UNIT,GROUP\": \"ADDR:PORT\"}", f.value.span));
    };
    let mut out: Vec<(UnitGroup, std::net::SocketAddr)> = Vec::new();
    for m in links {
        let device = unit_group(m)?;
        let addr = match &m.value.v {
            Json::Str(s) => s.parse().ok(),
            _ => None,
        };
        let Some(addr) = addr else {
            return Err(bad(code::FORWARD, "a link is an address and port, such as \"127.0.0.1:4001\"", m.value.span));
        };
        if out.iter().any(|(d, _)| *d == device) {
            return Err(bad(code::FORWARD, format!("device {},{} has two links", device.0, device.1), m.key_span));
        }
        out.push((device, addr));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::super::Database;
    use crate::code::Code;

    const BLOCKS: &str = r#""device": "FB107", "blocks": {"SFP 1": {"type": "SFP"}, "AIN 1": {"type": "AIN"}}"#;

    #[test]
    fn tables_and_links_load() {
        let text = format!(
            r#"{{{BLOCKS}, "opcode_tables": {{"1": {{"version": 2.5, "slots": {{"0": "SFP 1.DATA1", "43": "AIN 1.EU"}}}}}},
               "roc": {{"forward": {{"5,2": "127.0.0.1:4001"}}, "alarms": {{}}}}}}"#
        );
        let d = Database::from_json(&text).unwrap();
        let (n, t) = &d.opcode_tables[0];
        assert_eq!((*n, t.version), (1, 2.5));
        let sfp = d.block("SFP 1").unwrap();
        assert_eq!(t.slots[0].map(|s| s.0), Some(sfp));
        assert!(t.slots[1].is_none() && t.slots[43].is_some());
        assert_eq!(d.roc_forward, vec![((5, 2), "127.0.0.1:4001".parse().unwrap())]);
    }

    #[test]
    fn mistakes_are_located() {
        for (extra, code, at) in [
            (r#""opcode_tables": {"16": {"slots": {}}}"#, Code::E0855, "\"16\""),
            (r#""opcode_tables": {"1": {"slots": {"44": "SFP 1.DATA1"}}}"#, Code::E0855, "\"44\""),
            (r#""opcode_tables": {"1": {"slots": {"0": "SFP 9.DATA1"}}}"#, Code::E0855, "\"SFP 9.DATA1\""),
            (r#""opcode_tables": {"1": {"slots": {"0": 3}}}"#, Code::E0855, "3"),
            (r#""opcode_tables": {"1": {"version": "x", "slots": {}}}"#, Code::E0855, "\"x\""),
            (r#""opcode_tables": {"1": {"rows": {}}}"#, Code::E0855, "\"rows\""),
            (r#""roc": {"forward": {"0,1": "127.0.0.1:1"}}"#, Code::E0856, "\"0,1\""),
            (r#""roc": {"forward": {"3,1": "localhost:1"}}"#, Code::E0856, "\"localhost:1\""),
            (r#""roc": {"forward": {"3,1,2": "127.0.0.1:1"}}"#, Code::E0856, "\"3,1,2\""),
            (r#""roc": {"forward": []}"#, Code::E0856, "[]"),
        ] {
            let text = format!("{{{BLOCKS}, {extra}}}");
            let e = Database::from_json(&text).unwrap_err();
            assert_eq!(e.code, code, "{extra}: {}", e.message);
            let (s, t) = e.span.expect("located");
            assert_eq!(&text[s..t], at, "{extra}: {}", e.message);
        }
    }
}

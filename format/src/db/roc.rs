//! ROC point addressing: device families and numeric TLPs (`docs/roc-points.md`).
//!
//! A ROC point is a block whose template carries point type numbers (the
//! `"roc"` key of a template). Its parameters are its fields, numbered by
//! position; its logical number is its position among the blocks of the same
//! template, in database order. So `T,L,P` names the `L`-th block of the
//! template whose type number on the database's device family is `T`, and
//! that block's field `P`.

use super::schema::{Database, FieldType};
use std::fmt;

/// A ROC device family: it decides which point type numbers a TLP uses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Device {
    #[default]
    Roc800,
    Fb107,
}

impl Device {
    pub const ALL: [Device; 2] = [Device::Roc800, Device::Fb107];

    /// The family's name as database files write it.
    pub fn name(self) -> &'static str {
        match self {
            Device::Roc800 => "ROC800",
            Device::Fb107 => "FB107",
        }
    }

    /// A family by name, ignoring case.
    pub fn parse(name: &str) -> Option<Device> {
        Device::ALL.into_iter().find(|d| d.name().eq_ignore_ascii_case(name))
    }
}

/// A numeric point reference: point type, logical number, parameter number.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Tlp {
    pub t: u16,
    pub l: u16,
    pub p: u16,
}

impl fmt::Display for Tlp {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{},{},{}", self.t, self.l, self.p)
    }
}

/// Which part of a numeric TLP names nothing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TlpFault {
    PointType,
    Logical,
    Parameter,
}

/// How a parameter's value travels in ROC Plus opcodes 180 and 181
/// (docs/roc-protocol.md): integers at their width little-endian, `FL` an
/// IEEE-754 float32 little-endian, `AC(n)` n bytes of ASCII padded with
/// spaces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum RocType {
    Bin,
    Int8,
    Int16,
    Int32,
    Uint8,
    Uint16,
    Uint32,
    Fl,
    Ac(u8),
}

impl RocType {
    /// Bytes on the wire.
    pub fn size(self) -> usize {
        match self {
            RocType::Bin | RocType::Int8 | RocType::Uint8 => 1,
            RocType::Int16 | RocType::Uint16 => 2,
            RocType::Int32 | RocType::Uint32 | RocType::Fl => 4,
            RocType::Ac(n) => usize::from(n),
        }
    }

    /// The range of whole numbers an integer type carries; `None` for FL
    /// and text.
    pub fn range(self) -> Option<(i64, i64)> {
        Some(match self {
            RocType::Bin => (0, 1),
            RocType::Int8 => (i8::MIN.into(), i8::MAX.into()),
            RocType::Int16 => (i16::MIN.into(), i16::MAX.into()),
            RocType::Int32 => (i32::MIN.into(), i32::MAX.into()),
            RocType::Uint8 => (0, u8::MAX.into()),
            RocType::Uint16 => (0, u16::MAX.into()),
            RocType::Uint32 => (0, u32::MAX.into()),
            RocType::Fl | RocType::Ac(_) => return None,
        })
    }

    /// The name as the protocol's documents write it (`UINT8`, `FL`, `AC10`).
    pub fn name(self) -> String {
        match self {
            RocType::Bin => "BIN".into(),
            RocType::Int8 => "INT8".into(),
            RocType::Int16 => "INT16".into(),
            RocType::Int32 => "INT32".into(),
            RocType::Uint8 => "UINT8".into(),
            RocType::Uint16 => "UINT16".into(),
            RocType::Uint32 => "UINT32".into(),
            RocType::Fl => "FL".into(),
            RocType::Ac(n) => format!("AC{n}"),
        }
    }

    /// A type by name, ignoring case; `AC1`…`AC255`.
    pub fn parse(name: &str) -> Option<RocType> {
        let up = name.to_ascii_uppercase();
        if let Some(n) = up.strip_prefix("AC") {
            return n.parse::<u8>().ok().filter(|&n| n > 0).map(RocType::Ac);
        }
        [
            RocType::Bin,
            RocType::Int8,
            RocType::Int16,
            RocType::Int32,
            RocType::Uint8,
            RocType::Uint16,
            RocType::Uint32,
            RocType::Fl,
        ]
        .into_iter()
        .find(|t| t.name() == up)
    }

    /// The type a field of `ty` travels as unless its template says
    /// otherwise: REAL as FL, INT as INT32 (linc's INT is 32 bits), BOOL as
    /// BIN, BITS8 and ENUM (its index) as UINT8, BITS16 as UINT16, text as
    /// AC10 (a ROC tag). Other types have no ROC form.
    pub fn default_for(ty: &FieldType) -> Option<RocType> {
        Some(match ty {
            FieldType::Real => RocType::Fl,
            FieldType::Int => RocType::Int32,
            FieldType::Bool => RocType::Bin,
            FieldType::Bits { width: 8, .. } | FieldType::Enum(_) => RocType::Uint8,
            FieldType::Bits { .. } => RocType::Uint16,
            FieldType::String => RocType::Ac(10),
            _ => return None,
        })
    }

    /// Whether a field of `ty` may travel as this type: text as `AC`, REAL
    /// as FL or as a whole number (read rounded, as a device keeps a scan
    /// period in whole units), whole-number fields as any integer type.
    pub fn fits(self, ty: &FieldType) -> bool {
        match (self, ty) {
            (RocType::Ac(_), FieldType::String) | (RocType::Fl, FieldType::Real) => true,
            (RocType::Ac(_) | RocType::Fl, _) => false,
            (_, FieldType::Int | FieldType::Real | FieldType::Bool | FieldType::Bits { .. } | FieldType::Enum(_)) => {
                true
            }
            _ => false,
        }
    }
}

/// Whether two ROC point names are the same the way ROCLINK writes them,
/// ignoring case and spaces (`DIN4-1` is `DIN 4-1`).
pub fn same_point(a: &str, b: &str) -> bool {
    fn squeeze(s: &str) -> impl Iterator<Item = char> + '_ {
        s.chars().filter(|c| !c.is_whitespace()).map(|c| c.to_ascii_uppercase())
    }
    squeeze(a).eq(squeeze(b))
}

impl Database {
    /// The block a ROC point name names (see [`same_point`]).
    pub fn point(&self, name: &str) -> Option<usize> {
        self.blocks.iter().position(|b| same_point(&b.name, name))
    }

    /// The template whose point type number on this database's family is `t`.
    pub fn point_template(&self, t: u16) -> Option<usize> {
        self.templates.iter().position(|tp| tp.point_type(self.device) == Some(t))
    }

    /// A block's logical number: its position among the blocks of its template.
    pub fn logical(&self, block: usize) -> Option<u16> {
        let template = self.blocks.get(block)?.template;
        let n = self.blocks[..block].iter().filter(|b| b.template == template).count();
        u16::try_from(n).ok()
    }

    /// The block and field a numeric TLP names, if the database has them.
    pub fn tlp_target(&self, tlp: Tlp) -> Option<(usize, usize)> {
        self.tlp_parts(tlp).ok()
    }

    /// The block and field a numeric TLP names, or which part of it names
    /// nothing (a ROC device answers each with its own error code).
    pub fn tlp_parts(&self, tlp: Tlp) -> Result<(usize, usize), TlpFault> {
        let template = self.point_template(tlp.t).ok_or(TlpFault::PointType)?;
        let block = self
            .blocks
            .iter()
            .enumerate()
            .filter(|(_, b)| b.template == template)
            .nth(usize::from(tlp.l))
            .map(|(i, _)| i)
            .ok_or(TlpFault::Logical)?;
        let field = usize::from(tlp.p);
        (field < self.templates[template].fields.len()).then_some((block, field)).ok_or(TlpFault::Parameter)
    }

    /// How ROC Plus carries a field of a ROC point: its template's `wire`,
    /// else [`RocType::default_for`] its type; `None` for a field of a type
    /// with no ROC form.
    pub fn roc_type(&self, block: usize, field: usize) -> Option<RocType> {
        let f = self.block_template(block).fields.get(field)?;
        f.wire.or_else(|| RocType::default_for(&f.ty))
    }

    /// The numeric TLP of a block's field, if the block is a ROC point.
    pub fn tlp_of(&self, block: usize, field: usize) -> Option<Tlp> {
        let t = self.block_template(block).point_type(self.device)?;
        Some(Tlp { t, l: self.logical(block)?, p: u16::try_from(field).ok()? })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn db(device: &str) -> Database {
        let text = format!(
            r#"{{"device": "{device}", "blocks": {{
                "SFP 1": {{"type": "SFP"}}, "FST 1": {{"type": "FST"}}, "SFP 2": {{"type": "SFP"}}
            }}}}"#
        );
        Database::from_json(&text).unwrap()
    }

    #[test]
    fn numeric_tlps_follow_the_device_family() {
        let roc = db("ROC800");
        let b = roc.block("SFP 2").unwrap();
        let data1 = roc.block_template(b).field("DATA1").unwrap();
        assert_eq!(roc.tlp_target(Tlp { t: 98, l: 1, p: 2 }), Some((b, data1)));
        assert_eq!(roc.tlp_of(b, data1), Some(Tlp { t: 98, l: 1, p: 2 }));
        let fb = db("fb107");
        assert_eq!(fb.device, Device::Fb107);
        let b = fb.block("SFP 1").unwrap();
        assert_eq!(fb.tlp_target(Tlp { t: 17, l: 0, p: 2 }), Some((b, data1)));
        assert_eq!(fb.tlp_target(Tlp { t: 98, l: 0, p: 2 }), None, "ROC800 numbers mean nothing on an FB107");
        let f = fb.block("FST 1").unwrap();
        let r1 = fb.block_template(f).field("R1").unwrap();
        assert_eq!(fb.tlp_target(Tlp { t: 16, l: 0, p: 2 }), Some((f, r1)));
    }

    #[test]
    fn missing_points_and_parameters_are_none() {
        let roc = db("ROC800");
        assert_eq!(roc.tlp_target(Tlp { t: 98, l: 2, p: 2 }), None, "only two soft points");
        assert_eq!(roc.tlp_target(Tlp { t: 98, l: 0, p: 200 }), None);
        assert_eq!(roc.tlp_target(Tlp { t: 7, l: 0, p: 0 }), None);
        let act = Database::from_json(r#"{"blocks": {"A": {"type": "ACTION"}}}"#).unwrap();
        assert_eq!(act.tlp_of(0, 0), None, "an ACTION block is not a ROC point");
    }

    #[test]
    fn roc_types_by_name_size_and_what_they_carry() {
        for t in ["BIN", "INT8", "INT16", "INT32", "UINT8", "UINT16", "UINT32", "FL", "AC1", "AC30", "AC255"] {
            assert_eq!(RocType::parse(t).map(RocType::name).as_deref(), Some(t));
        }
        assert_eq!(RocType::parse("ac10"), Some(RocType::Ac(10)));
        for bad in ["AC0", "AC256", "AC", "FLOAT", "", "INT64"] {
            assert_eq!(RocType::parse(bad), None, "{bad}");
        }
        assert_eq!(RocType::Ac(30).size(), 30);
        assert_eq!(RocType::Uint32.range(), Some((0, 4_294_967_295)));
        assert!(RocType::Uint8.fits(&FieldType::Int) && !RocType::Fl.fits(&FieldType::Int));
        assert!(!RocType::Ac(4).fits(&FieldType::Real) && RocType::Ac(4).fits(&FieldType::String));
        assert!(RocType::Uint16.fits(&FieldType::Real), "a REAL may travel as a whole number");
    }

    #[test]
    fn a_field_travels_as_its_template_says_or_as_its_type() {
        let roc = db("ROC800");
        let f = roc.block("FST 1").unwrap();
        let field = |n: &str| roc.block_template(f).field(n).unwrap();
        assert_eq!(roc.roc_type(f, field("RR")), Some(RocType::Fl));
        assert_eq!(roc.roc_type(f, field("TAG")), Some(RocType::Ac(10)));
        assert_eq!(roc.roc_type(f, field("MSG1")), Some(RocType::Ac(30)));
        assert_eq!(roc.roc_type(f, field("RUNFLG")), Some(RocType::Uint8));
        assert_eq!(roc.roc_type(f, field("CMPFLG")), Some(RocType::Uint8));
        assert_eq!(roc.roc_type(f, 999), None);
    }

    /// docs/roc-points.md lists every ROC template's parameters with the
    /// type each travels as; the page must say what the code does.
    #[test]
    fn the_pages_wire_types_are_the_templates() {
        let page = include_str!("../../../docs/roc-points.md");
        let section = page.split("## Wire types").nth(1).expect("the section");
        let section = section.split("## TLPs in a table").next().unwrap();
        let db = Database::from_json(r#"{"blocks": {}}"#).unwrap();
        let mut checked = 0;
        for part in section.split("### ").skip(1) {
            let name = part.split_whitespace().next().unwrap();
            let t = db.templates.iter().position(|t| t.name == name).expect(name);
            let b = Database::from_json(&format!(r#"{{"blocks": {{"X": {{"type": "{name}"}}}}}}"#)).unwrap();
            let rows: Vec<Vec<&str>> = part
                .lines()
                .filter(|l| l.starts_with("| ") && !l.starts_with("| P "))
                .map(|l| l.trim_matches('|').split('|').map(str::trim).collect())
                .collect();
            assert_eq!(rows.len(), db.templates[t].fields.len(), "{name}: every parameter is listed");
            for (p, row) in rows.iter().enumerate() {
                assert_eq!(row[0], p.to_string(), "{name}");
                assert_eq!(row[1].trim_matches('`'), db.templates[t].fields[p].name, "{name} P {p}");
                assert_eq!(Some(row[2].to_string()), b.roc_type(0, p).map(RocType::name), "{name} P {p}");
                checked += 1;
            }
        }
        assert!(checked > 60, "{checked} rows");
    }

    #[test]
    fn a_wire_type_that_cannot_carry_the_field_is_refused_where_it_is_written() {
        for (spec, ok) in [(r#""wire": "UINT8""#, true), (r#""wire": "AC8""#, false), (r#""wire": 8"#, false)] {
            let text = format!(
                r#"{{"templates": {{"T": {{"fields": {{"N": {{"type": "INT", {spec}}}}}}}}}, "blocks": {{}}}}"#
            );
            match Database::from_json(&text) {
                Ok(_) => assert!(ok, "{spec} accepted"),
                Err(e) => {
                    assert!(!ok, "{spec}: {e:?}");
                    let d = format!("{e:?}");
                    assert!(d.contains("E0802") && d.contains("wire"), "{d}");
                }
            }
        }
    }

    #[test]
    fn unknown_families_are_refused() {
        let e = Database::from_json(r#"{"device": "ROC300"}"#).unwrap_err();
        assert_eq!(e.code, "E0818");
        assert!(e.message.contains("ROC800, FB107"), "{}", e.message);
    }
}

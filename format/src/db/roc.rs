//! ROC point addressing: device families and numeric TLPs (`docs/roc-points.md`).
//!
//! A ROC point is a block whose template carries point type numbers (the
//! `"roc"` key of a template). Its parameters are its fields, numbered by
//! position; its logical number is its position among the blocks of the same
//! template, in database order. So `T,L,P` names the `L`-th block of the
//! template whose type number on the database's device family is `T`, and
//! that block's field `P`.

use super::schema::Database;
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
        let template = self.point_template(tlp.t)?;
        let block = self
            .blocks
            .iter()
            .enumerate()
            .filter(|(_, b)| b.template == template)
            .nth(usize::from(tlp.l))
            .map(|(i, _)| i)?;
        let field = usize::from(tlp.p);
        (field < self.templates[template].fields.len()).then_some((block, field))
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
    fn unknown_families_are_refused() {
        let e = Database::from_json(r#"{"device": "ROC300"}"#).unwrap_err();
        assert_eq!(e.code, "E0818");
        assert!(e.message.contains("ROC800, FB107"), "{}", e.message);
    }
}

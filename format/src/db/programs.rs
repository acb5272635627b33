//! Which blocks of a database run programs, and which: the one rule every
//! reader of a database shares — the strategy engine over its live values,
//! a language server or a formatter over the values in the file.
//!
//! An action-type block (a template with `FileName` and `ActName`: ACTION,
//! DIGACT, RAW_COM) runs the action `ActName` of its file; an SFC_CON block
//! runs the sequence its file holds; a ROC FST block the table its file
//! holds.

use super::schema::{Database, InitValue, Template};

/// A block of the strategy that runs a program, and the program it names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Want {
    pub block: usize,
    /// `FileName`, as written (relative to the database file).
    pub file: String,
    /// `ActName`; empty for a sequence or an FST table.
    pub action: String,
    pub kind: WantKind,
}

/// What kind of program a block runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WantKind {
    /// An action-type block: the action `ActName` of its file.
    Action,
    /// An SFC_CON block: the sequence its file holds.
    Sequence,
    /// A ROC FST block: the table its file holds.
    Fst,
}

impl WantKind {
    /// How the console and the monitor name it.
    pub fn name(self) -> &'static str {
        match self {
            WantKind::Action => "action",
            WantKind::Sequence => "sequence",
            WantKind::Fst => "fst",
        }
    }
}

impl Want {
    /// The field a block that names a program leaves empty (`FileName`, or
    /// `ActName` unless it runs a sequence or table): it can't run (E0830).
    pub fn missing(&self) -> Option<&'static str> {
        match (self.file.is_empty(), self.action.is_empty() && self.kind == WantKind::Action) {
            (true, _) => Some("FileName"),
            (_, true) => Some("ActName"),
            _ => None,
        }
    }
}

/// Whether blocks of `t` are sequence controllers (SFC_CON).
pub fn is_sfc_con(t: &Template) -> bool {
    ["FileName", "Run", "Hold", "Stop", "Reset", "Status"].iter().all(|f| t.field(f).is_some())
        && t.field("ActName").is_none()
}

/// Whether blocks of `t` run FST tables.
pub fn is_fst(t: &Template) -> bool {
    ["FileName", "RR", "CMPFLG", "RUNFLG", "IP", "BRK"].iter().all(|f| t.field(f).is_some())
}

/// The blocks that name a program, in database order; `text(block, field)`
/// reads a string field's value (`None` when the block's template has no
/// such field). A block with neither `FileName` nor `ActName` runs
/// nothing; one with only one of them is listed, to be refused
/// ([`Want::missing`]).
pub fn wanted(db: &Database, text: &dyn Fn(usize, &str) -> Option<String>) -> Vec<Want> {
    (0..db.blocks.len())
        .filter_map(|b| {
            let file = text(b, "FileName")?;
            let t = db.block_template(b);
            let whole =
                |kind| (!file.is_empty()).then(|| Want { block: b, file: file.clone(), action: String::new(), kind });
            if is_sfc_con(t) {
                return whole(WantKind::Sequence);
            }
            if is_fst(t) {
                return whole(WantKind::Fst);
            }
            let action = text(b, "ActName")?;
            let named = !file.is_empty() || !action.is_empty();
            named.then_some(Want { block: b, file, action, kind: WantKind::Action })
        })
        .collect()
}

impl Database {
    /// The programs the blocks name, by the values in the database (what a
    /// strategy built from it runs before any `--set`).
    pub fn programs(&self) -> Vec<Want> {
        let text = |b: usize, field: &str| {
            let f = self.block_template(b).field(field)?;
            Some(match self.blocks[b].values.iter().find(|(i, _)| *i == f) {
                Some((_, InitValue::Text(t))) => t.clone(),
                _ => String::new(),
            })
        };
        wanted(self, &text)
    }
}

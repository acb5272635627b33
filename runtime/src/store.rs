//! The live database: typed field values the VM reads and writes.
//!
//! Every field of every block is one cell, blocks laid out one after the
//! other in template order, so `X{n}` is "n cells further" and a run of
//! same-typed fields is a contiguous range of cells.

use crate::db::{Database, FieldDef, FieldType, InitValue};
use crate::text::{encode_dollar, format_value};
use linc_stdlib::value::decode_dollar;
use linc_stdlib::Value;

/// Longest suppression, 90 days (§18.3.1).
pub const MAX_SUPPRESS: f64 = 7_776_000.0;

/// Alarm states and their suppression deadlines (POSIX seconds; 0 none,
/// infinity indefinite).
#[derive(Clone, Debug, PartialEq)]
pub struct Alarms {
    pub names: Vec<String>,
    pub active: Vec<bool>,
    pub until: Vec<f64>,
    pub all_until: f64,
}

/// One field's value.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    Real(f32),
    Int(i32),
    Bool(bool),
    Bits {
        v: u16,
        width: u8,
    },
    Enum {
        idx: u16,
    },
    /// STRING, DATE and TIME: text kept as written.
    Text(Vec<u8>),
    Bseq(Vec<u8>),
    Wstr(Vec<u8>),
    Alarms(Box<Alarms>),
}

pub use crate::object::class_of;

/// The database with values, and the clock suppression timers run on.
#[derive(Clone, Debug)]
pub struct Store {
    pub db: Database,
    pub cells: Vec<Cell>,
    /// First cell of each block.
    pub first: Vec<u32>,
    /// For each cell, the last cell of its run of same-typed fields.
    pub run_end: Vec<u32>,
    /// For each cell, whether programs may not write it (the block computes it).
    readonly: Vec<bool>,
    /// Current time, POSIX seconds.
    pub now: f64,
    /// The ROC device's logs and history archives, which FST tables write.
    pub roc: crate::roc::RocState,
    /// For each cell, whether the console forced it: writes by programs
    /// and the engine are dropped. Never retentive.
    forced: Vec<bool>,
    /// Writes dropped because their cell was forced, since the start.
    pub ignored_writes: u64,
    /// Cells of dropped writes not yet traced (at most [`MAX_PENDING_IGNORED`]).
    ignored: Vec<u32>,
}

/// Dropped writes kept for the trace between two drains; more are only counted.
pub const MAX_PENDING_IGNORED: usize = 1024;

impl Store {
    /// Lays out every block with its initial values.
    pub fn new(db: Database) -> Store {
        let mut cells = Vec::new();
        let mut first = Vec::new();
        let mut run_end = Vec::new();
        let mut readonly = Vec::new();
        for b in &db.blocks {
            let t = &db.templates[b.template];
            let start = cells.len() as u32;
            first.push(start);
            for (fi, f) in t.fields.iter().enumerate() {
                let init = b.values.iter().find(|(i, _)| *i == fi).map(|(_, v)| v);
                cells.push(initial(&f.ty, init));
                readonly.push(f.readonly);
            }
            let n = t.fields.len();
            let mut ends = vec![0u32; n];
            for i in (0..n).rev() {
                let same_next = i + 1 < n && t.fields[i + 1].ty.same_kind(&t.fields[i].ty);
                ends[i] = if same_next { ends[i + 1] } else { start + i as u32 };
            }
            run_end.extend(ends);
        }
        let roc = crate::roc::RocState::new(&db);
        let forced = vec![false; cells.len()];
        Store { db, cells, first, run_end, readonly, now: 0.0, roc, forced, ignored_writes: 0, ignored: Vec::new() }
    }

    /// Whether a write to `cell` must be dropped because the cell is forced
    /// (and then counts it). Every write path of the VM and the engine asks
    /// this: one byte lookup, so forcing costs nothing on reads.
    #[inline]
    pub fn refuse_forced(&mut self, cell: u32) -> bool {
        if !self.forced.get(cell as usize).copied().unwrap_or(false) {
            return false;
        }
        self.ignored_writes += 1;
        if self.ignored.len() < MAX_PENDING_IGNORED {
            self.ignored.push(cell);
        }
        true
    }

    /// Whether the console forced this cell.
    pub fn is_forced(&self, cell: u32) -> bool {
        self.forced.get(cell as usize).copied().unwrap_or(false)
    }

    /// Forces a cell (its value is set by the caller first) or releases it.
    pub fn set_forced(&mut self, cell: u32, on: bool) {
        if let Some(f) = self.forced.get_mut(cell as usize) {
            *f = on;
        }
    }

    /// Every forced cell, in cell order.
    pub fn forced_cells(&self) -> Vec<u32> {
        (0..self.forced.len() as u32).filter(|&c| self.is_forced(c)).collect()
    }

    /// The cells of the writes dropped since the last call, for the trace.
    pub fn take_ignored(&mut self) -> Vec<u32> {
        std::mem::take(&mut self.ignored)
    }

    /// Whether programs may not write this cell.
    pub fn is_readonly(&self, cell: u32) -> bool {
        self.readonly.get(cell as usize).copied().unwrap_or(true)
    }

    /// The cell of `block.field`, by names (ignoring case).
    pub fn cell_of(&self, block: usize, field: &str) -> Option<u32> {
        let t = self.db.block_template(block);
        t.field(field).map(|f| self.first[block] + f as u32)
    }

    /// The block and field definition a cell holds.
    fn field_at(&self, cell: u32) -> Option<(usize, &FieldDef)> {
        let b = self.first.partition_point(|&f| f <= cell).checked_sub(1)?;
        let block = self.db.blocks.get(b)?;
        let field = self.db.templates[block.template].fields.get((cell - self.first[b]) as usize)?;
        Some((b, field))
    }

    /// `BLOCK.Field` for a cell, for traces and messages.
    pub fn describe(&self, cell: u32) -> String {
        match self.field_at(cell) {
            Some((block, field)) => format!("{}.{}", self.db.blocks[block].name, field.name),
            None => format!("cell {cell}"),
        }
    }

    /// Enumeration names of an ENUM cell's field.
    pub fn enum_names(&self, cell: u32) -> &[String] {
        match self.field_at(cell).map(|(_, f)| &f.ty) {
            Some(FieldType::Enum(names)) => names,
            _ => &[],
        }
    }

    /// A cell's value as ST would print it.
    pub fn show(&self, cell: u32) -> String {
        self.cells.get(cell as usize).map(|v| self.show_as(cell, v)).unwrap_or_default()
    }

    /// `value` as ST would print it were it `cell`'s (whose field gives an
    /// ENUM its names): a trace shows the value a cell had before a write.
    pub fn show_as(&self, cell: u32, value: &Cell) -> String {
        match value {
            Cell::Real(r) => format_value(&Value::Real(*r)),
            Cell::Int(i) => i.to_string(),
            Cell::Bool(b) => format_value(&Value::Bool(*b)),
            Cell::Bits { v, width } => bits_value(*v, *width).to_string(),
            Cell::Enum { idx } => {
                let name = self.enum_names(cell).get(usize::from(*idx)).cloned().unwrap_or_default();
                format_value(&Value::Bytes(name.into_bytes()))
            }
            Cell::Text(t) | Cell::Bseq(t) | Cell::Wstr(t) => format_value(&Value::Bytes(t.clone())),
            Cell::Alarms(a) => {
                let on: Vec<&str> =
                    a.names.iter().zip(&a.active).filter(|(_, on)| **on).map(|(n, _)| n.as_str()).collect();
                format!("[{}]", on.join(", "))
            }
        }
    }

    /// Remaining suppression in whole seconds (-1 indefinite).
    pub fn suppress_remaining(&self, until: f64) -> i32 {
        if until.is_infinite() {
            -1
        } else {
            (until - self.now).max(0.0).ceil().min(MAX_SUPPRESS) as i32
        }
    }

    /// The deadline a written suppression time gives, or `None` to ignore
    /// the write (negative values other than -1).
    pub fn suppress_deadline(&self, seconds: i32) -> Option<f64> {
        match seconds {
            -1 => Some(f64::INFINITY),
            s if s < 0 => None,
            0 => Some(0.0),
            s => Some(self.now + f64::from(s).min(MAX_SUPPRESS)),
        }
    }

    /// The block values in the database file's shape (`{"BLOCK": {"FIELD": v}}`).
    pub fn values_json(&self) -> serde_json::Map<String, serde_json::Value> {
        use serde_json::{json, Value as J};
        let mut out = serde_json::Map::new();
        for (bi, b) in self.db.blocks.iter().enumerate() {
            let t = &self.db.templates[b.template];
            let mut vals = serde_json::Map::new();
            for (fi, f) in t.fields.iter().enumerate() {
                let cell = &self.cells[self.first[bi] as usize + fi];
                let v = match cell {
                    // The shortest text that reads back to the same f32.
                    Cell::Real(r) => json!(crate::text::format_real(*r).parse::<f64>().unwrap_or(0.0)),
                    Cell::Int(i) => json!(i),
                    Cell::Bool(b) => json!(b),
                    Cell::Bits { v, width } => json!(bits_value(*v, *width)),
                    Cell::Enum { idx } => match &f.ty {
                        FieldType::Enum(names) => {
                            json!(names.get(usize::from(*idx)).cloned().unwrap_or_default())
                        }
                        _ => J::Null,
                    },
                    Cell::Text(t) => json!(String::from_utf8_lossy(t)),
                    Cell::Bseq(t) | Cell::Wstr(t) => json!(encode_dollar(t)),
                    Cell::Alarms(a) => {
                        let m: serde_json::Map<String, J> =
                            a.names.iter().zip(&a.active).map(|(n, on)| (n.clone(), J::Bool(*on))).collect();
                        J::Object(m)
                    }
                };
                vals.insert(f.name.clone(), v);
            }
            out.insert(b.name.clone(), J::Object(vals));
        }
        out
    }
}

/// A bitfield as ST reads it: 8-bit fields 0..255, 16-bit fields
/// -32768..32767 (§12.7.2).
pub fn bits_value(v: u16, width: u8) -> i32 {
    if width == 8 {
        i32::from(v & 0xFF)
    } else {
        i32::from(v as i16)
    }
}

fn initial(ty: &FieldType, init: Option<&InitValue>) -> Cell {
    let num = match init {
        Some(InitValue::Num(x)) => *x,
        Some(InitValue::Bool(b)) => f64::from(u8::from(*b)),
        _ => 0.0,
    };
    let text = match init {
        Some(InitValue::Text(t)) => t.as_bytes().to_vec(),
        _ => Vec::new(),
    };
    match ty {
        FieldType::Real => Cell::Real(num as f32),
        // The loader only accepts whole numbers in the i32 range, which
        // f64 holds exactly (going through f32 would round 16777217).
        FieldType::Int => Cell::Int(num.round() as i32),
        FieldType::Bool => Cell::Bool(num != 0.0),
        FieldType::Bits { width, .. } => Cell::Bits { v: (num as i64) as u16, width: *width },
        FieldType::Enum(names) => {
            let idx = names.iter().position(|n| n.as_bytes().eq_ignore_ascii_case(&text)).unwrap_or(0);
            Cell::Enum { idx: idx as u16 }
        }
        FieldType::String | FieldType::Date | FieldType::Time => Cell::Text(text),
        FieldType::Bseq => Cell::Bseq(decode_dollar(&text)),
        FieldType::Wstr => Cell::Wstr(decode_dollar(&text)),
        FieldType::Alarms(names) => {
            let active = names
                .iter()
                .map(|n| matches!(init, Some(InitValue::Active(a)) if a.iter().any(|x| x.eq_ignore_ascii_case(n))))
                .collect();
            Cell::Alarms(Box::new(Alarms {
                names: names.clone(),
                active,
                until: vec![0.0; names.len()],
                all_until: 0.0,
            }))
        }
    }
}

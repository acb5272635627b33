//! The `.sto` object file: compiled programs, independent of any database.
//!
//! Layout (all integers little-endian; names are u16 length + UTF-8; every
//! table is a u32 count and its records, as declared below with `records!`):
//!
//! ```text
//! magic "LINCSTO\x1a" | version u16 (3) | flags u16 | crc32 u32 | length u32
//! object: source name, symbols, constant pool, units
//! unit:   kind u8, name, source file, block type, retained u16, code blocks,
//!         charts (sequences), step listing (FST tables)
//! block:  name, locals u8, u32 code length + code, labels (u32 each),
//!         line table (op, line, col), loop table (start, end, line, col)
//! ```
//!
//! The CRC-32 (ISO-HDLC, the zip/PNG one) covers the whole file with its own
//! field zeroed. Symbols name database references by text (guide §10.1: one
//! compiled action runs against any database that has those fields); they
//! become cells when the object is linked to a store. See ADR 0004.

use crate::errors::LoadError;
use crate::records;
use crate::wire::{Bytes, Code, Reader, Wire};

pub const MAGIC: &[u8; 8] = b"LINCSTO\x1a";
pub const VERSION: u16 = 3;
const HEADER: usize = 8 + 2 + 2 + 4 + 4;

/// The storage class of a field, as the compiler assumed it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    Real = 1,
    Int = 2,
    Bool = 3,
    Bits8 = 4,
    Bits16 = 5,
    Enum = 6,
    String = 7,
    Date = 8,
    Time = 9,
    Bseq = 10,
    Wstr = 11,
    Alarms = 12,
}

impl Class {
    pub fn from_u8(b: u8) -> Option<Class> {
        use Class::*;
        Some(match b {
            1 => Real,
            2 => Int,
            3 => Bool,
            4 => Bits8,
            5 => Bits16,
            6 => Enum,
            7 => String,
            8 => Date,
            9 => Time,
            10 => Bseq,
            11 => Wstr,
            12 => Alarms,
            _ => return None,
        })
    }

    /// Loaded and stored through the numeric stack as INT.
    pub fn is_int(self) -> bool {
        matches!(self, Class::Int | Class::Bool | Class::Bits8 | Class::Bits16)
    }

    /// Loaded and stored through the string stack.
    pub fn is_string(self) -> bool {
        matches!(self, Class::Enum | Class::String | Class::Date | Class::Time | Class::Bseq | Class::Wstr)
    }

    /// Number of bits of a bitfield.
    pub fn bits(self) -> Option<u8> {
        match self {
            Class::Bits8 => Some(8),
            Class::Bits16 => Some(16),
            _ => None,
        }
    }
}

/// What part of a field a symbol names.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Sub {
    /// The field itself (or, with bit operands, one of its bits).
    Field,
    /// One alarm's In_Alarm state.
    Alarm(String),
    /// Suppression of one alarm, or (`None`) of the whole block.
    Suppress(Option<String>),
}

/// A database reference by text. An empty `block` is the block that runs
/// the action (`ACTION name : TYPE`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Symbol {
    pub block: String,
    pub field: String,
    pub sub: Sub,
    pub class: Class,
}

impl Symbol {
    /// `BLOCK.Field[.Alarm][.Suppress]` as an engineer would write it.
    pub fn text(&self) -> String {
        let base = if self.block.is_empty() { self.field.clone() } else { format!("{}.{}", self.block, self.field) };
        match &self.sub {
            Sub::Field => base,
            Sub::Alarm(a) => format!("{base}.{a}"),
            Sub::Suppress(Some(a)) => format!("{base}.{a}.Suppress"),
            Sub::Suppress(None) => format!("{base}.Suppress"),
        }
    }
}

records! {
    /// Where a statement starts, for error positions.
    LineEntry "line table" { op: u32, line: u32, col: u32 }

    /// The instructions of a loop and where its statement is, so a watchdog
    /// error can name the loop.
    LoopEntry "loop table" { start: u32, end: u32, line: u32, col: u32 }

    /// A straight piece of code with its own labels, locals and tables: an
    /// action body, and later a transition or a step's action of a chart.
    /// Jumps name labels of the same block; a label is an instruction index.
    /// Charts name a unit's blocks by a `u16`, so a unit has at most 65,536.
    CodeBlock "code block" at most 65536 {
        name: String,
        locals: u8,
        ops: Code,
        labels: Vec<u32>,
        lines: Vec<LineEntry>,
        loops: Vec<LoopEntry>,
    }

    /// A program: what one block of a strategy runs. `retained` numeric slots
    /// keep their value from one run to the next (edge memory, timers).
    Unit "unit" {
        kind: UnitKind,
        name: String,
        /// The source file the unit was compiled from.
        file: String,
        /// Block type of `ACTION name : TYPE`, or empty.
        block_type: String,
        retained: u16,
        blocks: Vec<CodeBlock>,
        /// A sequence's charts: the ROOT chart first, then the charts of its
        /// chart actions (empty for other units).
        charts: Vec<ChartRec>,
        /// An FST table's steps as listed (`CMD ARG1 ARG2`), for traces and
        /// run-time messages (empty for other units).
        steps: Vec<String>,
    }

    /// A chart of a sequence unit (see `sequence::chart`).
    ChartRec "chart" {
        steps: Vec<StepRec>,
        transitions: Vec<TransitionRec>,
        actions: Vec<ActionRec>,
    }

    /// A step: its name, whether it is initial (1), its retained slot pair
    /// (`.X` at `2 × slot`, `.T` in seconds as REAL bits at `2 × slot + 1`),
    /// its associations and its source line (for coverage reports).
    StepRec "step" { name: String, initial: u8, slot: u16, assocs: Vec<AssocRec>, line: u32 }

    /// `Action(Q, time)`: an action of the same chart, a qualifier (the
    /// letter's byte: b'P', b'N', ...), and the time of L, D and E in µs.
    AssocRec "association" { action: u16, qualifier: u8, time_us: u64 }

    /// A transition: source and target steps of the same chart, priority
    /// (`u32::MAX` for none), the code block computing its condition and
    /// its source line (for coverage reports).
    TransitionRec "transition" { name: String, from: Vec<u16>, to: Vec<u16>, priority: u32, block: u16, line: u32 }

    /// An action: a code block (`kind` 0) or a chart of this unit (`kind` 1).
    ActionRec "action" { name: String, kind: u8, index: u16 }

    /// A whole object file in memory (without its header).
    ObjectFile "object" {
        /// The first source file (objects may hold units of several).
        source: String,
        symbols: Vec<Symbol>,
        strings: Vec<Bytes>,
        units: Vec<Unit>,
    }
}

/// What kind of program a unit is. Today every unit is an ST action; the
/// engines for sequences, ladder and FST tables add theirs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum UnitKind {
    #[default]
    Action = 1,
    /// A sequence: charts whose conditions and actions are code blocks.
    Sequence = 2,
    /// A ROC Function Sequence Table: one code block whose label `n` is
    /// step `n`, run by the FST engine (`docs/fst.md`).
    Fst = 3,
}

impl Wire for UnitKind {
    const MIN: usize = 1;
    fn put(&self, out: &mut Vec<u8>) {
        (*self as u8).put(out);
    }
    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
        match u8::get(r, what)? {
            1 => Ok(UnitKind::Action),
            2 => Ok(UnitKind::Sequence),
            3 => Ok(UnitKind::Fst),
            k => Err(LoadError::Malformed { what: format!("{what}: unknown unit kind {k}") }),
        }
    }
}

/// Instructions name a symbol by a `u16`, so an object has at most 65,536.
impl Wire for Symbol {
    const MIN: usize = 2 + 2 + 1 + 1;
    const MAX_COUNT: usize = 1 << 16;
    fn put(&self, out: &mut Vec<u8>) {
        self.block.put(out);
        self.field.put(out);
        (self.class as u8).put(out);
        match &self.sub {
            Sub::Field => 0u8.put(out),
            Sub::Alarm(a) => {
                1u8.put(out);
                a.put(out);
            }
            Sub::Suppress(Some(a)) => {
                2u8.put(out);
                a.put(out);
            }
            Sub::Suppress(None) => 3u8.put(out),
        }
    }

    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
        let block = String::get(r, what)?;
        let field = String::get(r, what)?;
        let class_byte = u8::get(r, what)?;
        let class = Class::from_u8(class_byte)
            .ok_or_else(|| LoadError::Malformed { what: format!("symbol `{block}.{field}` has class {class_byte}") })?;
        let sub = match u8::get(r, what)? {
            0 => Sub::Field,
            1 => Sub::Alarm(String::get(r, what)?),
            2 => Sub::Suppress(Some(String::get(r, what)?)),
            3 => Sub::Suppress(None),
            k => return Err(LoadError::Malformed { what: format!("symbol `{block}.{field}` has sub-kind {k}") }),
        };
        Ok(Symbol { block, field, sub, class })
    }
}

impl Unit {
    /// The unit's main block (an action's body).
    pub fn main(&self) -> Option<&CodeBlock> {
        self.blocks.first()
    }
}

fn crc_table() -> &'static [u32; 256] {
    static TABLE: std::sync::OnceLock<[u32; 256]> = std::sync::OnceLock::new();
    TABLE.get_or_init(|| {
        let mut t = [0u32; 256];
        for (i, e) in t.iter_mut().enumerate() {
            let mut c = i as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            }
            *e = c;
        }
        t
    })
}

/// Feeds bytes into a running (not yet inverted) CRC-32 state.
fn crc32_update(state: u32, data: &[u8]) -> u32 {
    let table = crc_table();
    data.iter().fold(state, |c, &b| table[((c ^ u32::from(b)) & 0xFF) as usize] ^ (c >> 8))
}

/// CRC-32/ISO-HDLC (reflected, polynomial 0x04C11DB7, init and xor-out all ones).
pub fn crc32(data: &[u8]) -> u32 {
    !crc32_update(!0, data)
}

impl ObjectFile {
    /// The object with every source position (line and column of the line
    /// and loop tables, the lines of steps and transitions) set to zero: what a change of layout alone leaves
    /// the same, so `linc fmt` can be proved to keep a program's meaning.
    pub fn without_positions(&self) -> ObjectFile {
        let mut o = self.clone();
        for block in o.units.iter_mut().flat_map(|u| u.blocks.iter_mut()) {
            for l in &mut block.lines {
                (l.line, l.col) = (0, 0);
            }
            for l in &mut block.loops {
                (l.line, l.col) = (0, 0);
            }
        }
        for chart in o.units.iter_mut().flat_map(|u| u.charts.iter_mut()) {
            chart.steps.iter_mut().for_each(|s| s.line = 0);
            chart.transitions.iter_mut().for_each(|t| t.line = 0);
        }
        o
    }

    /// Encodes the object, header and checksum included.
    pub fn to_bytes(&self) -> Vec<u8> {
        encode(|out| self.put(out))
    }

    /// The bytes [`Self::to_bytes`] gives for this object with its source
    /// file names (the object's and each unit's) empty, without copying the
    /// object: a strategy's fingerprint sums what its programs are, not
    /// where they were read from, and a copy of a large object took 8 bytes
    /// per byte of its file.
    pub fn to_bytes_without_files(&self) -> Vec<u8> {
        encode(|out| {
            String::new().put(out);
            self.symbols.put(out);
            self.strings.put(out);
            (self.units.len() as u32).put(out);
            for u in &self.units {
                let Unit { kind, name, file: _, block_type, retained, blocks, charts, steps } = u;
                kind.put(out);
                name.put(out);
                String::new().put(out);
                block_type.put(out);
                retained.put(out);
                blocks.put(out);
                charts.put(out);
                steps.put(out);
            }
        })
    }

    /// Decodes an object, checking magic, version, length and checksum and
    /// that every table is complete. Instructions are decoded but not yet
    /// verified (see [`crate::verify`]).
    pub fn from_bytes(data: &[u8]) -> Result<ObjectFile, LoadError> {
        if data.len() < 8 || &data[..8] != MAGIC {
            return Err(LoadError::BadMagic);
        }
        if data.len() < HEADER {
            return Err(LoadError::Truncated { what: "header".into() });
        }
        let version = u16::from_le_bytes([data[8], data[9]]);
        if version != VERSION {
            return Err(LoadError::BadVersion { found: version, supported: VERSION });
        }
        let stored_crc = u32::from_le_bytes([data[12], data[13], data[14], data[15]]);
        let len = u32::from_le_bytes([data[16], data[17], data[18], data[19]]) as usize;
        if len != data.len() {
            return Err(if len > data.len() {
                LoadError::Truncated { what: format!("file ({} of {len} bytes)", data.len()) }
            } else {
                LoadError::Malformed { what: format!("{} bytes after the end of the object", data.len() - len) }
            });
        }
        let actual = crc32_zeroed(data);
        if actual != stored_crc {
            return Err(LoadError::BadChecksum { stored: stored_crc, actual });
        }
        let mut r = Reader { data, at: HEADER };
        let obj = ObjectFile::get(&mut r, "object")?;
        if r.at != data.len() {
            return Err(LoadError::Malformed { what: format!("{} unread bytes at the end", data.len() - r.at) });
        }
        Ok(obj)
    }
}

/// An object file: the header, the body `put` writes, then the length and
/// the CRC filled in.
fn encode(put: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut out = Vec::with_capacity(256);
    out.extend_from_slice(MAGIC);
    VERSION.put(&mut out);
    0u16.put(&mut out);
    0u32.put(&mut out);
    0u32.put(&mut out);
    put(&mut out);
    let len = out.len() as u32;
    out[16..20].copy_from_slice(&len.to_le_bytes());
    let crc = crc32(&out);
    out[12..16].copy_from_slice(&crc.to_le_bytes());
    out
}

/// The CRC of a file with its own CRC field taken as zero, without copying it.
fn crc32_zeroed(data: &[u8]) -> u32 {
    let state = crc32_update(!0, &data[..12]);
    let state = crc32_update(state, &[0; 4]);
    !crc32_update(state, &data[16..])
}
/// The storage class of a template field: the database schema's type as
/// the object format and the verifier see it.
pub fn class_of(ty: &crate::db::FieldType) -> Class {
    use crate::db::FieldType;
    match ty {
        FieldType::Real => Class::Real,
        FieldType::Int => Class::Int,
        FieldType::Bool => Class::Bool,
        FieldType::Bits { width: 8, .. } => Class::Bits8,
        FieldType::Bits { .. } => Class::Bits16,
        FieldType::Enum(_) => Class::Enum,
        FieldType::String => Class::String,
        FieldType::Date => Class::Date,
        FieldType::Time => Class::Time,
        FieldType::Bseq => Class::Bseq,
        FieldType::Wstr => Class::Wstr,
        FieldType::Alarms(_) => Class::Alarms,
    }
}

/// Deepest nesting of chart actions an object may have.
pub const MAX_CHART_DEPTH: usize = 32;

/// The action qualifiers a chart's association may hold, as stored (one
/// letter each, IEC 61131-3's N, P, L, D, E, F, S and R).
pub const QUALIFIERS: &[u8] = b"NPLDEFSR";

/// Whether `letter` is a stored qualifier (either case).
pub fn is_qualifier(letter: u8) -> bool {
    QUALIFIERS.contains(&letter.to_ascii_uppercase())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::isa::Op;

    /// Without files, the bytes are those of a copy with its file names
    /// cleared, every field of a unit in its place.
    #[test]
    fn bytes_without_files_are_those_of_a_cleared_copy() {
        let block = CodeBlock {
            name: "b".into(),
            locals: 2,
            ops: Code(vec![Op::PushI { v: 7 }, Op::Jump { to: 0 }, Op::Ret {}]),
            labels: vec![1],
            lines: vec![LineEntry { op: 0, line: 3, col: 4 }],
            loops: vec![LoopEntry { start: 0, end: 1, line: 3, col: 4 }],
        };
        let unit = Unit {
            kind: UnitKind::Fst,
            name: "U".into(),
            file: "u.fst".into(),
            block_type: "FST".into(),
            retained: 5,
            blocks: vec![block],
            charts: vec![ChartRec::default()],
            steps: vec!["ST R1".into()],
        };
        let symbols = vec![Symbol { block: "B".into(), field: "F".into(), sub: Sub::Field, class: Class::Real }];
        let obj = ObjectFile { source: "x.st".into(), symbols, strings: vec![Bytes(b"k".to_vec())], units: vec![unit] };
        let mut cleared = obj.clone();
        cleared.source.clear();
        cleared.units.iter_mut().for_each(|u| u.file.clear());
        assert_eq!(obj.to_bytes_without_files(), cleared.to_bytes());
        assert_ne!(obj.to_bytes_without_files(), obj.to_bytes());
    }
}

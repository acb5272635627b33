//! The `.sto` object file: compiled actions, independent of any database.
//!
//! Layout (all integers little-endian, strings as u16 length + UTF-8):
//!
//! ```text
//! magic "LINCSTO\x1a" | version u16 | flags u16 | crc32 u32 | length u32
//! source file name
//! symbols:  u32 count, each: block, field, class u8, sub u8 [, alarm name]
//! strings:  u32 count, each: u32 length + bytes          (constant pool)
//! actions:  u32 count, each: name, source file, block type, locals u8,
//!           u32 code length + code, u32 n + n × (op, line, col),
//!           u32 n + n × (start, end, line, col)          (loops)
//! ```
//!
//! The CRC-32 (ISO-HDLC, the zip/PNG one) covers the whole file with its own
//! field zeroed. Symbols name database references by text (guide §10.1: one
//! compiled action runs against any database that has those fields); they
//! become slot indices when the object is loaded against a database.

use crate::errors::LoadError;
use crate::isa::Op;

pub const MAGIC: &[u8; 8] = b"LINCSTO\x1a";
pub const VERSION: u16 = 1;
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

/// Where a statement starts, for error positions.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LineEntry {
    pub op: u32,
    pub line: u32,
    pub col: u32,
}

/// The instructions of a loop and where its statement is, so a watchdog
/// error can name the loop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LoopEntry {
    pub start: u32,
    pub end: u32,
    pub line: u32,
    pub col: u32,
}

/// One compiled action.
#[derive(Clone, Debug, PartialEq)]
pub struct ActionCode {
    pub name: String,
    /// The source file the action was compiled from.
    pub file: String,
    /// Block type of `ACTION name : TYPE`, or empty.
    pub block_type: String,
    pub locals: u8,
    pub ops: Vec<Op>,
    pub lines: Vec<LineEntry>,
    pub loops: Vec<LoopEntry>,
}

/// A whole object file in memory.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjectFile {
    pub source: String,
    pub symbols: Vec<Symbol>,
    pub strings: Vec<Vec<u8>>,
    pub actions: Vec<ActionCode>,
}

/// CRC-32/ISO-HDLC (reflected, polynomial 0x04C11DB7, init and xor-out all ones).
pub fn crc32(data: &[u8]) -> u32 {
    static TABLE: std::sync::OnceLock<[u32; 256]> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        let mut t = [0u32; 256];
        for (i, e) in t.iter_mut().enumerate() {
            let mut c = i as u32;
            for _ in 0..8 {
                c = if c & 1 != 0 { 0xEDB8_8320 ^ (c >> 1) } else { c >> 1 };
            }
            *e = c;
        }
        t
    });
    !data.iter().fold(!0u32, |c, &b| table[((c ^ u32::from(b)) & 0xFF) as usize] ^ (c >> 8))
}

fn put_str(out: &mut Vec<u8>, s: &str) {
    let b = s.as_bytes();
    let n = b.len().min(u16::MAX as usize);
    out.extend_from_slice(&(n as u16).to_le_bytes());
    out.extend_from_slice(&b[..n]);
}

fn put_u32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

impl ObjectFile {
    /// Encodes the object, checksum included.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(256);
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&VERSION.to_le_bytes());
        out.extend_from_slice(&0u16.to_le_bytes());
        put_u32(&mut out, 0);
        put_u32(&mut out, 0);
        put_str(&mut out, &self.source);
        put_u32(&mut out, self.symbols.len() as u32);
        for s in &self.symbols {
            put_str(&mut out, &s.block);
            put_str(&mut out, &s.field);
            out.push(s.class as u8);
            match &s.sub {
                Sub::Field => out.push(0),
                Sub::Alarm(a) => {
                    out.push(1);
                    put_str(&mut out, a);
                }
                Sub::Suppress(Some(a)) => {
                    out.push(2);
                    put_str(&mut out, a);
                }
                Sub::Suppress(None) => out.push(3),
            }
        }
        put_u32(&mut out, self.strings.len() as u32);
        for s in &self.strings {
            put_u32(&mut out, s.len() as u32);
            out.extend_from_slice(s);
        }
        put_u32(&mut out, self.actions.len() as u32);
        for a in &self.actions {
            put_str(&mut out, &a.name);
            put_str(&mut out, &a.file);
            put_str(&mut out, &a.block_type);
            out.push(a.locals);
            let mut code = Vec::new();
            for op in &a.ops {
                op.encode(&mut code);
            }
            put_u32(&mut out, code.len() as u32);
            out.extend_from_slice(&code);
            put_u32(&mut out, a.lines.len() as u32);
            for l in &a.lines {
                for v in [l.op, l.line, l.col] {
                    put_u32(&mut out, v);
                }
            }
            put_u32(&mut out, a.loops.len() as u32);
            for l in &a.loops {
                for v in [l.start, l.end, l.line, l.col] {
                    put_u32(&mut out, v);
                }
            }
        }
        let len = out.len() as u32;
        out[16..20].copy_from_slice(&len.to_le_bytes());
        let crc = crc32(&out);
        out[12..16].copy_from_slice(&crc.to_le_bytes());
        out
    }

    /// Decodes an object, checking magic, version, length and checksum and
    /// that every section is complete. Instructions are decoded but not yet
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
        let mut zeroed = data.to_vec();
        zeroed[12..16].fill(0);
        let actual = crc32(&zeroed);
        if actual != stored_crc {
            return Err(LoadError::BadChecksum { stored: stored_crc, actual });
        }
        let mut r = Reader { data, at: HEADER };
        let source = r.string("source name")?;
        let mut symbols = Vec::new();
        for _ in 0..r.count("symbol table")? {
            let block = r.string("symbol")?;
            let field = r.string("symbol")?;
            let class_byte = r.u8("symbol")?;
            let class = Class::from_u8(class_byte).ok_or_else(|| LoadError::Malformed {
                what: format!("symbol `{block}.{field}` has class {class_byte}"),
            })?;
            let sub = match r.u8("symbol")? {
                0 => Sub::Field,
                1 => Sub::Alarm(r.string("symbol")?),
                2 => Sub::Suppress(Some(r.string("symbol")?)),
                3 => Sub::Suppress(None),
                k => return Err(LoadError::Malformed { what: format!("symbol `{block}.{field}` has sub-kind {k}") }),
            };
            symbols.push(Symbol { block, field, sub, class });
        }
        let mut strings = Vec::new();
        for _ in 0..r.count("constant pool")? {
            let n = r.u32("constant pool")? as usize;
            strings.push(r.bytes(n, "constant pool")?.to_vec());
        }
        let mut actions = Vec::new();
        for _ in 0..r.count("action table")? {
            let name = r.string("action")?;
            let file = r.string("action")?;
            let block_type = r.string("action")?;
            let locals = r.u8("action")?;
            let n = r.u32("action code")? as usize;
            let code = r.bytes(n, "action code")?;
            let mut ops = Vec::new();
            let mut at = 0;
            while at < code.len() {
                let start = at;
                let op = Op::decode(code, &mut at).ok_or_else(|| LoadError::BadInstruction {
                    action: name.clone(),
                    offset: start,
                    opcode: code[start],
                })?;
                ops.push(op);
            }
            let mut lines = Vec::new();
            for _ in 0..r.count("line table")? {
                lines.push(LineEntry {
                    op: r.u32("line table")?,
                    line: r.u32("line table")?,
                    col: r.u32("line table")?,
                });
            }
            let mut loops = Vec::new();
            for _ in 0..r.count("loop table")? {
                loops.push(LoopEntry {
                    start: r.u32("loop table")?,
                    end: r.u32("loop table")?,
                    line: r.u32("loop table")?,
                    col: r.u32("loop table")?,
                });
            }
            actions.push(ActionCode { name, file, block_type, locals, ops, lines, loops });
        }
        if r.at != data.len() {
            return Err(LoadError::Malformed { what: format!("{} unread bytes at the end", data.len() - r.at) });
        }
        Ok(ObjectFile { source, symbols, strings, actions })
    }
}

/// A bounds-checked cursor; every read names the section it is in.
struct Reader<'a> {
    data: &'a [u8],
    at: usize,
}

impl<'a> Reader<'a> {
    fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], LoadError> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.data.len());
        let end = end.ok_or_else(|| LoadError::Truncated { what: what.to_string() })?;
        let s = &self.data[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn u8(&mut self, what: &str) -> Result<u8, LoadError> {
        Ok(self.bytes(1, what)?[0])
    }

    fn u32(&mut self, what: &str) -> Result<u32, LoadError> {
        let b = self.bytes(4, what)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }

    /// An element count; it cannot exceed the bytes left (each element takes
    /// at least one), which keeps a damaged count from allocating wildly.
    fn count(&mut self, what: &str) -> Result<u32, LoadError> {
        let n = self.u32(what)?;
        if n as usize > self.data.len() - self.at {
            return Err(LoadError::Truncated { what: what.to_string() });
        }
        Ok(n)
    }

    fn string(&mut self, what: &str) -> Result<String, LoadError> {
        let b = self.bytes(2, what)?;
        let n = usize::from(u16::from_le_bytes([b[0], b[1]]));
        let s = self.bytes(n, what)?;
        String::from_utf8(s.to_vec()).map_err(|_| LoadError::Malformed { what: format!("{what}: text is not UTF-8") })
    }
}

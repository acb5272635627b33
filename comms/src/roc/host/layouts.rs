//! How each command's bytes come out of words and go back into them
//! (`003_…` §6.1.2: "Byte data will be placed in the Least Significant
//! byte of a word. Word data will be presented as words. Floating point
//! data will be presented as two consecutive words.").
//!
//! Every opcode's request and reply is described as a list of fields of
//! the manual's kinds (BIN, INT, FL, AC), and one pair of functions moves
//! bytes through any list: [`gather`] builds request bytes from words,
//! [`place`] turns reply bytes into words. An opcode is then a row of
//! data — its fields and the header bytes its reply echoes — rather than
//! a function of its own, and the parse-time range checks read the same
//! rows as running does, so they cannot disagree. The byte layouts are
//! those of docs/roc-protocol.md, "The ROC protocol".

use super::commands::Command;
use super::poll::status;
use crate::roc::ops;

/// The ROC protocol's opcodes the module's command list names, by the
/// host's names for them (ROC Plus shares 8, 180 and 181, in [`ops`]).
pub mod op {
    pub use crate::roc::rocp::{
        DAY as DAY_HOURS, FORWARD as STORE_FORWARD, FROM_POINTER as HISTORY, POINTERS as LOG_POINTERS,
        TABLE_READ as TABLE,
    };
}

/// One field kind of the manual's layouts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// One byte, in the low byte of one word.
    Bin,
    /// Two bytes, little-endian, in one word.
    Int,
    /// Four bytes (a float, or any 4-byte value) in two words, low word
    /// first: the order of the little-endian wire value split in two.
    Fl,
    /// Text of `n` bytes, a byte in the low byte of each of `n` words.
    Ac(usize),
    /// `n` bytes the reply carries but the module does not store (a 180's
    /// count, and its TLPs when TYPE strips them).
    Skip(usize),
}

use Kind::{Ac, Bin, Fl, Int, Skip};

impl Kind {
    /// Its bytes on the wire.
    pub fn bytes(self) -> usize {
        match self {
            Bin => 1,
            Int => 2,
            Fl => 4,
            Ac(n) | Skip(n) => n,
        }
    }

    /// The words it takes in the table.
    pub fn words(self) -> usize {
        match self {
            Bin | Int => 1,
            Fl => 2,
            Ac(n) => n,
            Skip(_) => 0,
        }
    }

    /// The kind of a value `size` bytes wide: a 181's or a 10's TYPE, or
    /// a 180 reply's value. A width with no number kind is text.
    pub fn of_size(size: usize) -> Kind {
        match size {
            1 => Bin,
            2 => Int,
            4 => Fl,
            n => Ac(n),
        }
    }
}

/// `n` fields of one kind in a row.
pub type Field = (Kind, usize);

/// The bytes a layout takes on the wire.
pub fn byte_len(layout: &[Field]) -> usize {
    layout.iter().map(|&(k, n)| k.bytes() * n).sum()
}

/// The words a layout takes in the table.
pub fn word_len(layout: &[Field]) -> usize {
    layout.iter().map(|&(k, n)| k.words() * n).sum()
}

/// 120's 26 reply bytes in 18 words, as the manual's §6.1.2 example
/// places them: the alarm, event and three hourly pointers and 2 reserved
/// bytes as six INT; the three daily pointers and a reserved byte as four
/// BIN; the most alarms and events as two INT; the three days of daily
/// history, a reserved byte and the audit pointer's two bytes as six BIN
/// (the example's last six fields are bytes).
pub const LOG_POINTERS: &[Field] = &[(Int, 6), (Bin, 4), (Int, 2), (Bin, 6)];

/// 128's 134 reply bytes in 75 words: point, month, day, hour, minute;
/// the day's first periodic index; 24 hourly values, the daily value, the
/// least and greatest; the two times (5 bytes each) and the point type;
/// the 8 reserved bytes as two 4-byte fields.
pub const DAY_HOURS: &[Field] = &[(Bin, 5), (Int, 1), (Fl, 27), (Bin, 11), (Fl, 2)];

/// The fields of a 10 reply before its values: table, first location,
/// locations, the table's version.
const TABLE_HEAD: &[Field] = &[(Bin, 3), (Fl, 1)];

/// The fields of a 130 reply before its values: type, point, values sent.
const HISTORY_HEAD: &[Field] = &[(Bin, 3)];

/// What a command sends from its SRC ADDR words, for every opcode but 181
/// (whose values come from DEST ADDR): 8 the clock's CNT bytes; 10 and
/// 128 three bytes; 130 three bytes and the starting pointer; 180 the
/// TLPs (after the count byte, which is CNT, not a word).
pub fn request_layout(opcode: u8, count: u16) -> Vec<Field> {
    match opcode {
        ops::CLOCK_SET => vec![(Bin, usize::from(count))],
        op::TABLE | op::DAY_HOURS => vec![(Bin, 3)],
        op::HISTORY => vec![(Bin, 3), (Int, 1)],
        ops::READ | ops::WRITE => vec![(Bin, 3 * usize::from(count))],
        _ => vec![],
    }
}

/// The words a command's reply surely takes from DEST ADDR, checked when
/// the list is read; 181's values to send are checked there too. The rest
/// of a 10, 130 or 180 reply depends on what the device sends and is
/// checked when it arrives (status 2).
pub fn dest_words(opcode: u8, count: u16, ty: u16) -> usize {
    match opcode {
        op::TABLE => word_len(TABLE_HEAD),
        op::LOG_POINTERS => word_len(LOG_POINTERS),
        op::DAY_HOURS => word_len(DAY_HOURS),
        op::HISTORY => word_len(HISTORY_HEAD),
        ops::WRITE => usize::from(count) * Kind::of_size(usize::from(ty)).words(),
        _ => 0,
    }
}

/// The bytes of `layout` from `words` (exactly the layout's words); a
/// word sent as a byte but over 255 is status 3.
pub fn gather(layout: &[Field], words: &[u16]) -> Result<Vec<u8>, u16> {
    let mut out = Vec::with_capacity(byte_len(layout));
    let mut w = words.iter().copied();
    let mut next = || w.next().unwrap_or(0);
    for &(kind, n) in layout {
        for _ in 0..n {
            match kind {
                Bin | Ac(_) => {
                    for _ in 0..kind.bytes() {
                        out.push(u8::try_from(next()).map_err(|_| status::BAD_VALUE)?);
                    }
                }
                Int => out.extend(next().to_le_bytes()),
                Fl => {
                    let (lo, hi) = (next(), next());
                    out.extend(lo.to_le_bytes().into_iter().chain(hi.to_le_bytes()));
                }
                Skip(k) => out.resize(out.len() + k, 0),
            }
        }
    }
    Ok(out)
}

/// The words of `data` by `layout`; `None` when the data is not exactly
/// the layout's length.
pub fn place(layout: &[Field], data: &[u8]) -> Option<Vec<u16>> {
    if data.len() != byte_len(layout) {
        return None;
    }
    let mut out = Vec::with_capacity(word_len(layout));
    let mut at = 0;
    for &(kind, n) in layout {
        for _ in 0..n {
            let b = &data[at..at + kind.bytes()];
            match kind {
                Bin | Ac(_) => out.extend(b.iter().map(|&x| u16::from(x))),
                Int => out.push(u16::from_le_bytes([b[0], b[1]])),
                Fl => out.extend([u16::from_le_bytes([b[0], b[1]]), u16::from_le_bytes([b[2], b[3]])]),
                Skip(_) => {}
            }
            at += kind.bytes();
        }
    }
    Some(out)
}

/// The data of a command's request, from the word table (`words`, all
/// 4,000: the list's parse checked every range this reads). 180 and 181
/// start with the count; a 181 follows each TLP with its value from DEST
/// ADDR at TYPE's size.
pub fn request(c: &Command, words: &[u16]) -> Result<Vec<u8>, u16> {
    let from = |at: u16, layout: &[Field]| {
        let at = usize::from(at);
        gather(layout, &words[at..at + word_len(layout)])
    };
    match c.opcode {
        ops::READ => Ok([vec![c.count as u8], from(c.src, &request_layout(c.opcode, c.count))?].concat()),
        ops::WRITE => {
            let value = Kind::of_size(usize::from(c.ty));
            let mut out = vec![c.count as u8];
            for i in 0..c.count {
                out.extend(from(c.src + 3 * i, &[(Bin, 3)])?);
                out.extend(from(c.dest + i * value.words() as u16, &[(value, 1)])?);
            }
            Ok(out)
        }
        _ => from(c.src, &request_layout(c.opcode, c.count)),
    }
}

/// The layout of a reply's data (`data`) to a request (`sent`), after
/// checking the header bytes the reply echoes: a reply that echoes
/// another table, point, day or TLP answers another question, status 4.
/// Whether the data's length fits the layout is [`place`]'s to say.
pub fn reply_layout(c: &Command, sent: &[u8], data: &[u8]) -> Result<Vec<Field>, u16> {
    // Pairs of (reply byte, request byte) that must be equal.
    let echoes =
        |pairs: &[(usize, usize)]| pairs.iter().all(|&(r, s)| data.get(r).is_some_and(|b| sent.get(s) == Some(b)));
    let incomplete = Err(status::INCOMPLETE);
    match c.opcode {
        op::TABLE => {
            if !echoes(&[(0, 0), (1, 1), (2, 2)]) {
                return incomplete;
            }
            Ok(table_layout(c.ty, usize::from(sent[2]), data.len()))
        }
        op::LOG_POINTERS => Ok(LOG_POINTERS.to_vec()),
        // The request says point, day, month; the reply point, month, day.
        op::DAY_HOURS if echoes(&[(0, 0), (1, 2), (2, 1)]) => Ok(DAY_HOURS.to_vec()),
        // The device may send fewer values than asked (the archive's
        // end), never more.
        op::HISTORY if echoes(&[(0, 0), (1, 1)]) && data.get(2).is_some_and(|&n| n <= sent[2]) => {
            Ok([HISTORY_HEAD, &[(Fl, usize::from(data[2]))]].concat())
        }
        ops::READ => read_layout(c, sent, data),
        ops::CLOCK_SET | ops::WRITE => Ok(vec![]),
        _ => incomplete,
    }
}

/// A 10 reply's layout: its head, then `n` values at TYPE's size (1, 2
/// or 4 bytes, so the length follows the count); TYPE 0 takes the values'
/// bytes two to a word (an odd last byte in a word's low byte), and as a
/// value is 1 to 4 bytes they are from `n` to `4n` bytes.
fn table_layout(ty: u16, n: usize, len: usize) -> Vec<Field> {
    let head = TABLE_HEAD.to_vec();
    if ty != 0 {
        return [head, vec![(Kind::of_size(usize::from(ty)), n)]].concat();
    }
    let values = len.saturating_sub(byte_len(TABLE_HEAD));
    if values < n || values > 4 * n {
        // No layout of n values fits: one that place refuses.
        return [head, vec![(Bin, n)]].concat();
    }
    [head, vec![(Int, values / 2), (Bin, values % 2)]].concat()
}

/// A 180 reply's layout: the count, then each TLP and its value. The
/// reply carries no types, so the module's rule applies: every value of
/// one command has the same size, and the reply splits by it. Each TLP
/// must be the one asked for; TYPE 1 keeps them in the words, TYPE 0
/// strips them.
fn read_layout(c: &Command, sent: &[u8], data: &[u8]) -> Result<Vec<Field>, u16> {
    let n = usize::from(c.count);
    let body = data.len().saturating_sub(1 + 3 * n);
    if data.first() != sent.first() || body == 0 || !body.is_multiple_of(n) {
        return Err(status::INCOMPLETE);
    }
    let size = body / n;
    let tlps = data[1..].chunks_exact(3 + size).map(|v| &v[..3]);
    if !tlps.eq(sent[1..].chunks_exact(3)) {
        return Err(status::INCOMPLETE);
    }
    let tlp = if c.ty == 1 { (Bin, 3) } else { (Skip(3), 1) };
    let mut layout = vec![(Skip(1), 1)];
    for _ in 0..n {
        layout.extend([tlp, (Kind::of_size(size), 1)]);
    }
    Ok(layout)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_manuals_layouts_have_their_sizes() {
        assert_eq!((byte_len(LOG_POINTERS), word_len(LOG_POINTERS)), (26, 18));
        assert_eq!((byte_len(DAY_HOURS), word_len(DAY_HOURS)), (134, 75));
        assert_eq!(word_len(&request_layout(op::HISTORY, 4)), 4);
        assert_eq!(byte_len(&request_layout(op::HISTORY, 4)), 5);
    }

    #[test]
    fn gather_and_place_are_inverse() {
        let layout = [(Bin, 2), (Int, 1), (Fl, 1), (Ac(3), 1)];
        let words = [7, 255, 0x1234, 0x5678, 0x9ABC, 65, 66, 67];
        let bytes = gather(&layout, &words).unwrap();
        assert_eq!(bytes, [7, 255, 0x34, 0x12, 0x78, 0x56, 0xBC, 0x9A, 65, 66, 67]);
        assert_eq!(place(&layout, &bytes).unwrap(), words);
        assert_eq!(place(&layout, &bytes[1..]), None, "one byte short");
        assert_eq!(gather(&[(Bin, 1)], &[256]), Err(status::BAD_VALUE));
        assert_eq!(place(&[(Skip(2), 1), (Bin, 1)], &[1, 2, 3]).unwrap(), [3]);
    }
}

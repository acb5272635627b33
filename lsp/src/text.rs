//! Positions and a light scan of the text that works on incomplete code:
//! the protocol speaks in lines and UTF-16 columns, the compiler in byte
//! offsets; hover, completion and highlighting need to know whether the
//! cursor is in a comment, a string or a dotted name even where the parser
//! gave up.

use lsp_types::{Position, Range};

/// Where each line starts, for converting offsets and positions.
#[derive(Clone, Debug)]
pub struct LineIndex {
    starts: Vec<usize>,
}

impl LineIndex {
    pub fn new(text: &str) -> LineIndex {
        let mut starts = vec![0];
        starts.extend(text.match_indices('\n').map(|(i, _)| i + 1));
        LineIndex { starts }
    }

    /// The position of byte `offset` (clamped to the text, and to a
    /// character boundary).
    pub fn position(&self, text: &str, offset: usize) -> Position {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        let col: usize = text[self.starts[line]..offset].chars().map(char::len_utf16).sum();
        Position::new(line as u32, col as u32)
    }

    /// The byte offset of a position; a line or column past the end is
    /// clamped (a client may send anything).
    pub fn offset(&self, text: &str, pos: Position) -> usize {
        let Some(&start) = self.starts.get(pos.line as usize) else { return text.len() };
        let end = self.starts.get(pos.line as usize + 1).map_or(text.len(), |&e| e.saturating_sub(1));
        let mut units = 0usize;
        for (i, c) in text[start..end].char_indices() {
            if units >= pos.character as usize {
                return start + i;
            }
            units += c.len_utf16();
        }
        end
    }

    pub fn range(&self, text: &str, start: usize, end: usize) -> Range {
        Range::new(self.position(text, start), self.position(text, end))
    }
}

/// Positions of offsets visited in increasing order, each found from the
/// last: [`LineIndex::position`] counts from the line's start, which for
/// every token of one very long line would be quadratic.
pub struct Cursor<'t> {
    text: &'t str,
    index: &'t LineIndex,
    offset: usize,
    pos: Position,
}

impl<'t> Cursor<'t> {
    pub fn new(text: &'t str, index: &'t LineIndex) -> Cursor<'t> {
        Cursor { text, index, offset: 0, pos: Position::new(0, 0) }
    }

    pub fn position(&mut self, offset: usize) -> Position {
        let same_line = offset >= self.offset && !self.text[self.offset..offset.min(self.text.len())].contains('\n');
        if same_line && self.text.is_char_boundary(offset.min(self.text.len())) {
            let more: usize = self.text[self.offset..offset.min(self.text.len())].chars().map(char::len_utf16).sum();
            self.pos.character += more as u32;
        } else {
            self.pos = self.index.position(self.text, offset);
        }
        self.offset = offset.min(self.text.len());
        self.pos
    }
}

/// What a piece of text is, to the scan.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Comment,
    Str,
    Number,
    /// A possibly dotted name: `TIC_100.PV`, `Dig_A.Out.Bit3`.
    Word,
    Punct,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Piece {
    pub kind: Kind,
    pub start: usize,
    pub end: usize,
}

/// The pieces of an ST, sequence or ladder text, blanks left out. It never
/// fails: an unclosed comment or string runs to the end (of the text, or of
/// the line).
pub fn pieces(text: &str) -> Vec<Piece> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let start = i;
        let kind = if c.is_ascii_whitespace() {
            i += 1;
            continue;
        } else if c == b'(' && b.get(i + 1) == Some(&b'*') {
            i = text[i + 2..].find("*)").map_or(b.len(), |k| i + 2 + k + 2);
            Kind::Comment
        } else if c == b'\'' || c == b'"' {
            i += 1;
            while i < b.len() && b[i] != c && b[i] != b'\n' {
                i += if b[i] == b'$' { 2 } else { 1 };
            }
            i = (i + 1).min(b.len());
            Kind::Str
        } else if c.is_ascii_digit() || ((c == b'T' || c == b't') && b.get(i + 1) == Some(&b'#')) {
            i += 1;
            while i < b.len() && (b[i].is_ascii_alphanumeric() || matches!(b[i], b'#' | b'_' | b'.')) {
                if b[i] == b'.' && !b.get(i + 1).is_some_and(u8::is_ascii_digit) {
                    break;
                }
                i += 1;
            }
            Kind::Number
        } else if c.is_ascii_alphabetic() || c == b'_' {
            i += 1;
            while i < b.len()
                && (b[i].is_ascii_alphanumeric()
                    || b[i] == b'_'
                    || (b[i] == b'.' && b.get(i + 1).is_some_and(|n| n.is_ascii_alphanumeric() || *n == b'_')))
            {
                i += 1;
            }
            Kind::Word
        } else {
            i += text[i..].chars().next().map_or(1, char::len_utf8);
            Kind::Punct
        };
        out.push(Piece { kind, start, end: i.min(b.len()) });
    }
    out
}

/// The piece that holds `offset` (a cursor just after a word is on it).
pub fn piece_at(pieces: &[Piece], offset: usize) -> Option<Piece> {
    let i = pieces.partition_point(|p| p.end < offset);
    pieces.get(i).copied().filter(|p| p.start <= offset && offset <= p.end)
}

/// A dotted name split at its dots, with the index of the part holding
/// `offset` and the byte range of each part.
pub fn parts(text: &str, word: Piece, offset: usize) -> (Vec<(usize, usize)>, usize) {
    let mut parts = Vec::new();
    let mut start = word.start;
    for (i, c) in text[word.start..word.end].char_indices() {
        if c == '.' {
            parts.push((start, word.start + i));
            start = word.start + i + 1;
        }
    }
    parts.push((start, word.end));
    let at = parts.iter().position(|&(s, e)| s <= offset && offset <= e).unwrap_or(parts.len() - 1);
    (parts, at)
}

/// The cells of a CSV line as byte ranges (quotes included), for FST tables.
pub fn cells(line: &str, delim: u8) -> Vec<(usize, usize)> {
    let b = line.as_bytes();
    let mut out = Vec::new();
    let (mut start, mut quoted) = (0, false);
    for (i, &c) in b.iter().enumerate() {
        if c == b'"' {
            quoted = !quoted;
        } else if c == delim && !quoted {
            out.push((start, i));
            start = i + 1;
        }
    }
    out.push((start, b.len()));
    out
}

/// The cell of an FST table that holds `offset`: its column (0 STEP …
/// 5 COMMENT) and its byte range in the text, quotes included.
pub fn fst_cell(text: &str, offset: usize) -> Option<(usize, usize, usize)> {
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line_end = text[offset..].find('\n').map_or(text.len(), |i| offset + i);
    let cs = cells(&text[line_start..line_end], linc_compiler::fst::reader::delimiter(text));
    let col = cs.iter().position(|&(s, e)| line_start + s <= offset && offset <= line_start + e)?;
    Some((col, line_start + cs[col].0, line_start + cs[col].1))
}

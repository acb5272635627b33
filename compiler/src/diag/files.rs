//! The file map of a session: each file's name, decoded text and line index.
//!
//! The session adds sources to it and the renderer reads it, so a diagnostic
//! (which names its file by [`FileId`]) is always shown against its own file.

use crate::diag::span::FileId;
use std::cell::OnceCell;

/// The byte order mark some editors put at the start of UTF-8 files.
pub const BOM: char = '\u{FEFF}';

/// What stands in the text for a byte of the file that was not UTF-8 (ASCII
/// SUB, "substitute"): one byte for one byte, so offsets stay those of the file.
pub const SUBSTITUTE: char = '\u{1A}';

/// One file: its name as given, its text and the bytes that were not UTF-8.
#[derive(Debug)]
pub struct SourceFile {
    name: String,
    text: String,
    invalid: Vec<(usize, u8)>,
    line_starts: OnceCell<Vec<usize>>,
    /// Each character of more than one byte: its offset, and how many bytes
    /// beyond one all such characters up to it have. Columns are counted in
    /// characters, and this counts them without walking the line.
    wide: OnceCell<Vec<(usize, usize)>>,
}

impl SourceFile {
    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn text(&self) -> &str {
        &self.text
    }

    /// The text, as codespan's files call it.
    pub fn source(&self) -> &String {
        &self.text
    }

    /// Offsets (sorted) and values of the file's bytes that were not UTF-8;
    /// the text holds [`SUBSTITUTE`] at each of them.
    pub fn invalid_bytes(&self) -> &[(usize, u8)] {
        &self.invalid
    }

    /// The original byte at `at` if it was replaced because it was not UTF-8.
    pub fn invalid_byte_at(&self, at: usize) -> Option<u8> {
        self.invalid.binary_search_by_key(&at, |p| p.0).ok().map(|i| self.invalid[i].1)
    }

    /// Byte offsets where lines start; computed when first needed (a clean
    /// file never needs them).
    pub fn line_starts(&self) -> &[usize] {
        self.line_starts.get_or_init(|| {
            let mut starts = vec![0];
            starts.extend(self.text.bytes().enumerate().filter(|(_, b)| *b == b'\n').map(|(i, _)| i + 1));
            starts
        })
    }

    /// The 0-based line holding byte `at`.
    pub fn line_index(&self, at: usize) -> usize {
        self.line_starts().partition_point(|&s| s <= at).saturating_sub(1)
    }

    /// The bytes of line `line` without its terminator (`\n` or `\r\n`).
    pub fn line_range(&self, line: usize) -> std::ops::Range<usize> {
        let starts = self.line_starts();
        let start = starts.get(line).copied().unwrap_or(self.text.len());
        let mut end = starts.get(line + 1).map(|s| s - 1).unwrap_or(self.text.len());
        if end > start && self.text.as_bytes()[end - 1] == b'\r' && end < self.text.len() {
            end -= 1;
        }
        start..end
    }

    /// Bytes beyond the first of every character that starts before `at`.
    fn extra_bytes_before(&self, at: usize) -> usize {
        let wide = self.wide.get_or_init(|| {
            let mut total = 0;
            let mut out = Vec::new();
            for (i, c) in self.text.char_indices().filter(|(_, c)| !c.is_ascii()) {
                total += c.len_utf8() - 1;
                out.push((i, total));
            }
            out
        });
        let k = wide.partition_point(|w| w.0 < at);
        if k == 0 {
            0
        } else {
            wide[k - 1].1
        }
    }

    /// `at` moved into the text and back to a character boundary.
    pub fn clamp(&self, at: usize) -> usize {
        let mut at = at.min(self.text.len());
        while at > 0 && !self.text.is_char_boundary(at) {
            at -= 1;
        }
        at
    }

    /// `(line, column)` of byte `at`, both 1-based; columns count characters,
    /// and a byte order mark at the start of the file is not one.
    pub fn line_col(&self, at: usize) -> (usize, usize) {
        let at = self.clamp(at);
        let line = self.line_index(at);
        let start = self.line_starts()[line];
        let mut col = at - start - (self.extra_bytes_before(at) - self.extra_bytes_before(start)) + 1;
        if start == 0 && at > 0 && self.text.starts_with(BOM) {
            col -= 1;
        }
        (line + 1, col)
    }
}

/// The files diagnostics can point into (sources and database files).
#[derive(Debug, Default)]
pub struct SourceFiles {
    files: Vec<SourceFile>,
}

impl SourceFiles {
    pub fn new() -> SourceFiles {
        SourceFiles::default()
    }

    /// Adds a text that was valid UTF-8.
    pub fn add(&mut self, name: String, text: String) -> FileId {
        self.add_decoded(name, text, Vec::new())
    }

    /// Adds a decoded text with the offsets and values of the bytes that
    /// were replaced by [`SUBSTITUTE`].
    pub fn add_decoded(&mut self, name: String, text: String, invalid: Vec<(usize, u8)>) -> FileId {
        self.files.push(SourceFile { name, text, invalid, line_starts: OnceCell::new(), wide: OnceCell::new() });
        FileId((self.files.len() - 1) as u32)
    }

    pub fn file(&self, id: FileId) -> Option<&SourceFile> {
        self.files.get(id.index())
    }

    /// The file at `index` (the index of its [`FileId`]).
    pub fn get(&self, index: usize) -> Option<&SourceFile> {
        self.files.get(index)
    }

    pub fn len(&self) -> usize {
        self.files.len()
    }

    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Takes `other`'s files after these; the file `FileId(i)` of `other`
    /// is `FileId(self.len() + i)` here.
    pub fn append(&mut self, other: SourceFiles) {
        self.files.extend(other.files);
    }
}

/// Decodes a file's bytes: valid UTF-8 is taken as it is (no copy); a byte
/// that is not part of a valid sequence becomes [`SUBSTITUTE`] and is listed
/// with its offset, so that the error can point at it.
pub fn decode(bytes: Vec<u8>) -> (String, Vec<(usize, u8)>) {
    match String::from_utf8(bytes) {
        Ok(text) => (text, Vec::new()),
        Err(e) => {
            let mut bytes = e.into_bytes();
            let mut invalid = Vec::new();
            let mut at = 0;
            while at < bytes.len() {
                match std::str::from_utf8(&bytes[at..]) {
                    Ok(_) => break,
                    Err(e) => {
                        let bad = at + e.valid_up_to();
                        let n = e.error_len().unwrap_or(bytes.len() - bad);
                        for (i, b) in bytes[bad..bad + n].iter_mut().enumerate() {
                            invalid.push((bad + i, *b));
                            *b = SUBSTITUTE as u8;
                        }
                        at = bad + n;
                    }
                }
            }
            // Every invalid byte was replaced by an ASCII byte.
            let text = String::from_utf8(bytes).unwrap_or_default();
            (text, invalid)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_bytes_are_replaced_one_for_one() {
        let (text, invalid) = decode(b"a\xB0b\xE2\x82".to_vec());
        assert_eq!(text, "a\u{1A}b\u{1A}\u{1A}");
        assert_eq!(invalid, [(1, 0xB0), (3, 0xE2), (4, 0x82)]);
    }

    #[test]
    fn columns_do_not_count_a_byte_order_mark() {
        let mut files = SourceFiles::new();
        let id = files.add("a.st".into(), "\u{FEFF}ab\r\ncd".into());
        let f = files.file(id).unwrap();
        assert_eq!(f.line_col(3), (1, 1));
        assert_eq!(f.line_col(4), (1, 2));
        assert_eq!(f.line_col(7), (2, 1));
        assert_eq!(f.line_range(0), 0..5);
        let id = files.add("b.st".into(), "é°x\nü x".into());
        let f = files.file(id).unwrap();
        assert_eq!((f.line_col(4), f.line_col(5), f.line_col(9)), ((1, 3), (1, 4), (2, 3)));
    }
}

//! Byte ranges into one source file, and the ids of files in a session.

/// A half-open byte range `start..end` into one file.
///
/// Spans are file-local: every stage but the session works on one file at a
/// time, so the file is carried once per diagnostic ([`crate::Diagnostic::file`])
/// instead of once per span (ADR 0007).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Span {
    pub start: usize,
    pub end: usize,
}

impl Span {
    pub fn new(start: usize, end: usize) -> Span {
        Span { start, end }
    }

    /// The smallest span covering both.
    pub fn to(self, other: Span) -> Span {
        Span { start: self.start.min(other.start), end: self.end.max(other.end) }
    }
}

/// A file of a [`crate::session::Session`] or of a [`crate::diag::render::SourceFiles`]
/// map: an index in the order files were added.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct FileId(pub u32);

impl FileId {
    /// No file: a diagnostic about the command itself (an option value, a
    /// missing argument) rather than about a place in a file. It is printed
    /// without a location (`json`: `"file": null`).
    pub const NONE: FileId = FileId(u32::MAX);

    pub fn index(self) -> usize {
        self.0 as usize
    }
}

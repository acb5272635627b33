//! Diagnostics: the one shape every error of every stage is turned into,
//! the spans and source files they point into, and the one place they are
//! rendered as text.
//!
//! Each stage keeps its own error enum (plain data with file-local spans);
//! this module defines the common [`Diagnostic`] those enums convert into,
//! which also names the file ([`span`], [`files`]), and the renderers in
//! [`mod@render`] are the only place that formats them. The code registry is
//! [`codes`].

pub mod codes;
pub mod files;
mod problems;
pub mod render;
pub mod span;

pub use files::{decode, SourceFile, SourceFiles};
pub use linc_format::Code;
pub use problems::Problems;
pub use render::{escape, escape_text, line_col, render, Format};
pub use span::{FileId, Span};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
    /// What a command says besides what it was asked for (a summary, a
    /// server's log line): printed as its message alone, or in `json` as
    /// an object like a diagnostic's, with its code.
    Note,
}

/// A secondary label. `file` is `None` for the diagnostic's own file, or
/// names another file (an action defined twice, in two files).
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    pub file: Option<FileId>,
    pub span: Span,
    pub text: String,
}

/// A replacement that corrects a diagnostic's mistake (the closest field,
/// enumeration value, block or function name): offered by the language
/// server as a quick fix; `linc check` shows it as help text.
#[derive(Clone, Debug, PartialEq)]
pub struct Fix {
    pub span: Span,
    pub text: String,
}

/// A located, coded message with optional secondary labels and help notes.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub code: Code,
    pub message: String,
    /// The file `span` points into.
    pub file: FileId,
    pub span: Span,
    /// Text under the primary span.
    pub label: String,
    pub secondary: Vec<Label>,
    pub help: Vec<String>,
    pub fix: Option<Fix>,
}

impl Diagnostic {
    pub fn error(code: Code, message: impl Into<String>, span: Span) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            file: FileId::default(),
            span,
            label: String::new(),
            secondary: Vec::new(),
            help: Vec::new(),
            fix: None,
        }
    }

    /// An error about the command itself (an option, an argument), which
    /// belongs to no file: printed without a location.
    pub fn command(code: Code, message: impl Into<String>) -> Diagnostic {
        Diagnostic::error(code, message, Span::default()).in_file(FileId::NONE)
    }

    /// A note about the command, which points into no file.
    pub fn note(code: Code, message: impl Into<String>) -> Diagnostic {
        Diagnostic { severity: Severity::Note, ..Diagnostic::command(code, message) }
    }

    pub fn warning(code: Code, message: impl Into<String>, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, ..Diagnostic::error(code, message, span) }
    }

    /// Places the diagnostic in `file`.
    pub fn in_file(mut self, file: FileId) -> Diagnostic {
        self.file = file;
        self
    }

    /// The replacement of `span` by `text` that corrects the mistake.
    pub fn fix(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.fix = Some(Fix { span, text: text.into() });
        self
    }

    pub fn label(mut self, text: impl Into<String>) -> Diagnostic {
        self.label = text.into();
        self
    }

    /// A secondary label in the diagnostic's own file.
    pub fn with(mut self, span: Span, text: impl Into<String>) -> Diagnostic {
        self.secondary.push(Label { file: None, span, text: text.into() });
        self
    }

    /// A secondary label in another file.
    pub fn with_in(mut self, file: FileId, span: Span, text: impl Into<String>) -> Diagnostic {
        self.secondary.push(Label { file: Some(file), span, text: text.into() });
        self
    }

    pub fn help(mut self, text: impl Into<String>) -> Diagnostic {
        self.help.push(text.into());
        self
    }

    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

/// How many errors of one kind (lexical, syntax, checking, across files)
/// one file keeps. A file of junk must not become millions of diagnostics
/// held in memory; what is over is counted and reported once (E0023).
pub const MAX_ERRORS: usize = 1_000;

/// A list of errors that keeps the first [`MAX_ERRORS`] and counts the rest,
/// remembering the first one it did not keep (for where to point).
#[derive(Debug)]
pub struct Capped<T> {
    items: Vec<T>,
    dropped: usize,
    first_dropped: Option<T>,
}

impl<T> Default for Capped<T> {
    fn default() -> Self {
        Capped { items: Vec::new(), dropped: 0, first_dropped: None }
    }
}

impl<T> Capped<T> {
    pub fn push(&mut self, item: T) {
        if self.items.len() < MAX_ERRORS {
            self.items.push(item);
        } else {
            self.dropped += 1;
            if self.first_dropped.is_none() {
                self.first_dropped = Some(item);
            }
        }
    }

    /// How many were pushed, kept or not.
    pub fn total(&self) -> usize {
        self.items.len() + self.dropped
    }

    /// The last one kept, while nothing has been dropped (so that a run of
    /// bad characters can grow the error before it).
    pub fn last_mut(&mut self) -> Option<&mut T> {
        if self.dropped == 0 {
            self.items.last_mut()
        } else {
            None
        }
    }

    /// The kept items, how many were not kept, and the first of those.
    pub fn into_parts(self) -> (Vec<T>, usize, Option<T>) {
        (self.items, self.dropped, self.first_dropped)
    }
}

/// Errors a file had beyond those kept: how many, and where the first was.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Omitted {
    pub count: usize,
    pub first: Option<Span>,
}

impl Omitted {
    pub fn add(&mut self, count: usize, first: Option<Span>) {
        self.count += count;
        self.first = match (self.first, first) {
            (Some(a), Some(b)) => Some(if b.start < a.start { b } else { a }),
            (a, b) => a.or(b),
        };
    }
}

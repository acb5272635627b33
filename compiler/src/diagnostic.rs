//! The one shape every error of every stage is turned into.
//!
//! Each stage keeps its own error enum (plain data with file-local spans);
//! this module defines the common [`Diagnostic`] those enums convert into,
//! which also names the file, and the renderers in [`crate::render`] are the
//! only place that formats them.

use crate::span::{FileId, Span};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Severity {
    Error,
    Warning,
}

/// A secondary label. `file` is `None` for the diagnostic's own file, or
/// names another file (an action defined twice, in two files).
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    pub file: Option<FileId>,
    pub span: Span,
    pub text: String,
}

/// A located, coded message with optional secondary labels and help notes.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnostic {
    pub severity: Severity,
    pub code: &'static str,
    pub message: String,
    /// The file `span` points into.
    pub file: FileId,
    pub span: Span,
    /// Text under the primary span.
    pub label: String,
    pub secondary: Vec<Label>,
    pub help: Vec<String>,
}

impl Diagnostic {
    pub fn error(code: &'static str, message: impl Into<String>, span: Span) -> Diagnostic {
        Diagnostic {
            severity: Severity::Error,
            code,
            message: message.into(),
            file: FileId::default(),
            span,
            label: String::new(),
            secondary: Vec::new(),
            help: Vec::new(),
        }
    }

    pub fn warning(code: &'static str, message: impl Into<String>, span: Span) -> Diagnostic {
        Diagnostic { severity: Severity::Warning, ..Diagnostic::error(code, message, span) }
    }

    /// Places the diagnostic in `file`.
    pub fn in_file(mut self, file: FileId) -> Diagnostic {
        self.file = file;
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

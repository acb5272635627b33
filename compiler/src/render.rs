//! The one place diagnostics are turned into text.
//!
//! Three formats: `human` (codespan-reporting with source snippets, labels
//! and help notes), `short` (`FILE:LINE:COL: error[E0001]: message`, one line
//! each, for editors and grep) and `json` (one object per diagnostic per
//! line, for tools).

use crate::diagnostic::{Diagnostic, Severity};
use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::{Files, SimpleFiles};
use codespan_reporting::term;

/// The files diagnostics can point into (sources and database files).
pub type SourceFiles = SimpleFiles<String, String>;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Human,
    Short,
    Json,
}

/// Renders one diagnostic located in file `id`.
pub fn render(files: &SourceFiles, id: usize, d: &Diagnostic, format: Format) -> String {
    match format {
        Format::Human => human(files, id, d),
        Format::Short => short(files, id, d),
        Format::Json => json(files, id, d),
    }
}

fn clamp(files: &SourceFiles, id: usize, at: usize) -> usize {
    let len = files.source(id).map(|s| s.len()).unwrap_or(0);
    let mut at = at.min(len);
    if let Ok(src) = files.source(id) {
        while at > 0 && !src.is_char_boundary(at) {
            at -= 1;
        }
    }
    at
}

fn range(files: &SourceFiles, id: usize, span: crate::Span) -> std::ops::Range<usize> {
    let s = clamp(files, id, span.start);
    let e = clamp(files, id, span.end).max(s);
    s..e
}

fn human(files: &SourceFiles, id: usize, d: &Diagnostic) -> String {
    let base = match d.severity {
        Severity::Error => cs::Diagnostic::error(),
        Severity::Warning => cs::Diagnostic::warning(),
    };
    let mut labels = vec![cs::Label::primary(id, range(files, id, d.span)).with_message(d.label.clone())];
    for (span, text) in &d.secondary {
        labels.push(cs::Label::secondary(id, range(files, id, *span)).with_message(text.clone()));
    }
    let diag = base
        .with_code(d.code)
        .with_message(d.message.clone())
        .with_labels(labels)
        .with_notes(d.help.iter().map(|h| format!("help: {h}")).collect());
    let config = term::Config::default();
    term::emit_into_string(&config, files, &diag).unwrap_or_else(|_| short(files, id, d))
}

/// `(line, column)`, both 1-based.
pub fn line_col(files: &SourceFiles, id: usize, at: usize) -> (usize, usize) {
    match files.location(id, clamp(files, id, at)) {
        Ok(l) => (l.line_number, l.column_number),
        Err(_) => (1, 1),
    }
}

fn severity_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
    }
}

fn short(files: &SourceFiles, id: usize, d: &Diagnostic) -> String {
    let (line, col) = line_col(files, id, d.span.start);
    let name = files.name(id).map(|n| n.to_string()).unwrap_or_default();
    format!("{name}:{line}:{col}: {}[{}]: {}\n", severity_word(d.severity), d.code, d.message)
}

fn json(files: &SourceFiles, id: usize, d: &Diagnostic) -> String {
    let (line, column) = line_col(files, id, d.span.start);
    let (end_line, end_column) = line_col(files, id, d.span.end);
    let name = files.name(id).map(|n| n.to_string()).unwrap_or_default();
    let labels: Vec<serde_json::Value> = d
        .secondary
        .iter()
        .map(|(span, text)| {
            let (l, c) = line_col(files, id, span.start);
            serde_json::json!({ "line": l, "column": c, "start": span.start, "end": span.end, "message": text })
        })
        .collect();
    let v = serde_json::json!({
        "file": name,
        "line": line,
        "column": column,
        "end_line": end_line,
        "end_column": end_column,
        "start": d.span.start,
        "end": d.span.end,
        "severity": severity_word(d.severity),
        "code": d.code,
        "message": d.message,
        "label": d.label,
        "labels": labels,
        "help": d.help,
    });
    format!("{v}\n")
}

//! Diagnostics: exactly what `linc check` reports for the file (against the
//! database that names it), or, for a database JSON, why it does not load,
//! at its place in the JSON.

use crate::server::{Doc, Lang};
use crate::workspace::Workspace;
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_compiler::{Diagnostic, Severity};
use lsp_types::{DiagnosticRelatedInformation, DiagnosticSeverity, Location, NumberOrString};

pub fn diagnostics(ws: &Workspace, doc: &Doc) -> Vec<lsp_types::Diagnostic> {
    match doc.lang {
        Lang::Json => database(ws, doc),
        Lang::Other => Vec::new(),
        _ => check(ws, doc).iter().map(|d| convert(doc, d)).collect(),
    }
}

/// The file checked as `linc check --db` checks it.
pub fn check(ws: &Workspace, doc: &Doc) -> Vec<Diagnostic> {
    let db = ws.db_for(&doc.path).and_then(|d| d.database());
    let mut session = Session::new(Context::of(db));
    let id = session.add(doc.lang.file_name(&doc.path), doc.text.as_bytes().to_vec());
    session.check(id, CheckOptions::default()).diagnostics
}

fn database(ws: &Workspace, doc: &Doc) -> Vec<lsp_types::Diagnostic> {
    let Some(file) = ws.db_at(&doc.path) else { return Vec::new() };
    let Err(e) = &file.db else { return Vec::new() };
    let (start, end) = e.span.unwrap_or((0, 0));
    vec![lsp_types::Diagnostic {
        range: doc.index.range(&doc.text, start, end),
        severity: Some(DiagnosticSeverity::ERROR),
        code: Some(NumberOrString::String(e.code.as_str().to_string())),
        source: Some("linc".into()),
        message: e.message.clone(),
        ..lsp_types::Diagnostic::default()
    }]
}

/// A compiler diagnostic as the protocol's: help notes become lines of the
/// message, secondary labels related locations.
pub fn convert(doc: &Doc, d: &Diagnostic) -> lsp_types::Diagnostic {
    let mut message = d.message.clone();
    for h in &d.help {
        message.push_str("\nhelp: ");
        message.push_str(h);
    }
    let related: Vec<DiagnosticRelatedInformation> = d
        .secondary
        .iter()
        .filter(|l| l.file.is_none())
        .map(|l| DiagnosticRelatedInformation {
            location: Location::new(doc.uri.clone(), doc.index.range(&doc.text, l.span.start, l.span.end)),
            message: l.text.to_string(),
        })
        .collect();
    lsp_types::Diagnostic {
        range: doc.index.range(&doc.text, d.span.start, d.span.end),
        severity: Some(match d.severity {
            Severity::Error => DiagnosticSeverity::ERROR,
            Severity::Warning => DiagnosticSeverity::WARNING,
            Severity::Note => DiagnosticSeverity::INFORMATION,
        }),
        code: Some(NumberOrString::String(d.code.as_str().to_string())),
        source: Some("linc".into()),
        message,
        related_information: (!related.is_empty()).then_some(related),
        data: d.fix.as_ref().map(|f| serde_json::json!({ "fix": f.text, "start": f.span.start, "end": f.span.end })),
        ..lsp_types::Diagnostic::default()
    }
}

//! Formatting (`linc fmt`) and quick fixes for diagnostics that carry one.

use crate::server::{Lang, Server};
use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, CodeActionParams, DocumentFormattingParams, TextEdit,
    WorkspaceEdit,
};
use std::collections::HashMap;

/// The whole document in the canonical layout, as one edit; nothing when
/// it is already formatted or does not parse.
pub fn format(server: &Server, p: &DocumentFormattingParams) -> Option<Vec<TextEdit>> {
    let doc = server.doc(&p.text_document.uri)?;
    let kind = linc_compiler::source_kind::SourceKind::of_name(&doc.lang.file_name(&doc.path));
    if matches!(doc.lang, Lang::Json | Lang::Other) {
        return None;
    }
    let formatted = linc_compiler::fmt::format(kind, &doc.text).ok()?;
    if formatted == doc.text {
        return Some(Vec::new());
    }
    let range = doc.index.range(&doc.text, 0, doc.text.len());
    Some(vec![TextEdit::new(range, formatted)])
}

/// A quick fix for each diagnostic in the request that carries a
/// replacement (the closest field, enumeration value or name).
pub fn code_actions(server: &Server, p: &CodeActionParams) -> Option<Vec<CodeActionOrCommand>> {
    let doc = server.doc(&p.text_document.uri)?;
    let mut out = Vec::new();
    for d in &p.context.diagnostics {
        let Some(data) = &d.data else { continue };
        let (Some(fix), Some(start), Some(end)) = (data["fix"].as_str(), data["start"].as_u64(), data["end"].as_u64())
        else {
            continue;
        };
        if data["version"].as_i64() != Some(i64::from(doc.version)) {
            continue; // the text changed since: the offsets no longer hold
        }
        let (start, end) = (start as usize, end as usize);
        if end > doc.text.len() || start > end || !doc.text.is_char_boundary(start) || !doc.text.is_char_boundary(end) {
            continue;
        }
        let edit = TextEdit::new(doc.index.range(&doc.text, start, end), fix.to_string());
        out.push(CodeActionOrCommand::CodeAction(CodeAction {
            title: format!("Replace with `{fix}`"),
            kind: Some(CodeActionKind::QUICKFIX),
            diagnostics: Some(vec![d.clone()]),
            edit: Some(WorkspaceEdit {
                changes: Some(HashMap::from([(doc.uri.clone(), vec![edit])])),
                ..WorkspaceEdit::default()
            }),
            is_preferred: Some(true),
            ..CodeAction::default()
        }));
    }
    Some(out)
}

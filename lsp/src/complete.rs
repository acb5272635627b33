//! Completion: block names, fields after `.`, enumeration values inside a
//! string assigned to an enumerated field, functions with their arguments
//! as a snippet, steps and actions of a sequence, FST commands and points.

use crate::resolve::{Ctx, Sym};
use crate::server::{Lang, Server};
use crate::text::{cells, piece_at, Kind};
use linc_compiler::fst::commands::Cmd;
use linc_format::{Database, FieldType};
use lsp_types::{CompletionItem, CompletionItemKind, CompletionParams, CompletionResponse, InsertTextFormat, TextEdit};

pub fn complete(server: &Server, p: &CompletionParams) -> Option<CompletionResponse> {
    let pos = &p.text_document_position;
    let doc = server.doc(&pos.text_document.uri)?;
    let offset = doc.index.offset(&doc.text, pos.position);
    let ctx = Ctx::new(server, doc);
    let items = match doc.lang {
        Lang::Fst => fst(&ctx, offset),
        Lang::Json | Lang::Other => return None,
        _ => source(&ctx, offset),
    };
    Some(CompletionResponse::Array(items))
}

fn item(label: &str, kind: CompletionItemKind, detail: Option<String>) -> CompletionItem {
    CompletionItem { label: label.to_string(), kind: Some(kind), detail, ..CompletionItem::default() }
}

fn source(ctx: &Ctx, offset: usize) -> Vec<CompletionItem> {
    if let Some(p) = piece_at(&ctx.pieces, offset).filter(|p| p.kind == Kind::Str && p.start < offset) {
        return enum_values(ctx, p.start, p.end, offset);
    }
    if piece_at(&ctx.pieces, offset).is_some_and(|p| p.kind == Kind::Comment && p.start < offset) {
        return Vec::new();
    }
    let before = &ctx.doc.text[..offset];
    let word_start = before
        .char_indices()
        .rev()
        .find(|&(_, c)| !(c.is_ascii_alphanumeric() || c == '_' || c == '.'))
        .map_or(0, |(i, c)| i + c.len_utf8());
    let typed = &before[word_start..];
    match typed.rfind('.') {
        Some(dot) => members(ctx, word_start, &typed[..dot]),
        None => names(ctx, offset),
    }
}

/// After `prefix.`: the fields of a block (or alias, or step variables),
/// the bits or alarms of a field.
fn members(ctx: &Ctx, word_start: usize, prefix: &str) -> Vec<CompletionItem> {
    let local = ctx.local_names();
    if !prefix.contains('.') && local.steps.iter().any(|s| s.0.eq_ignore_ascii_case(prefix)) {
        return vec![
            item("X", CompletionItemKind::FIELD, Some("BOOL: the step is active".into())),
            item("T", CompletionItemKind::FIELD, Some("REAL: seconds since it activated".into())),
        ];
    }
    let Some(db) = ctx.db() else { return Vec::new() };
    // Resolve the prefix as the name it is, at its last part.
    match ctx.symbol_at(word_start + prefix.len()) {
        Some((Sym::Block(b), _, _)) => fields(db, db.blocks[b].template),
        Some((Sym::Alias(i), _, _)) => {
            let a = &db.aliases[i];
            let Some(b) = a.target.first().and_then(|n| db.block(n)) else { return Vec::new() };
            let t = db.blocks[b].template;
            match a.target.get(1).and_then(|f| db.templates[t].field(f)) {
                Some(f) => subs(&db.templates[t].fields[f].ty),
                None => fields(db, t),
            }
        }
        Some((Sym::Field { template, field, sub: None, .. }, _, _)) => subs(&db.templates[template].fields[field].ty),
        _ => Vec::new(),
    }
}

fn fields(db: &Database, template: usize) -> Vec<CompletionItem> {
    db.templates[template]
        .fields
        .iter()
        .map(|f| {
            let ro = if f.readonly { " (read-only)" } else { "" };
            item(&f.name, CompletionItemKind::FIELD, Some(format!("{}{ro}", f.ty.keyword())))
        })
        .collect()
}

fn subs(ty: &FieldType) -> Vec<CompletionItem> {
    match ty {
        FieldType::Bits { width, names } => (0..*width)
            .map(|i| item(&format!("Bit{i}"), CompletionItemKind::FIELD, Some("BOOL".into())))
            .chain(names.iter().map(|n| item(n, CompletionItemKind::FIELD, Some("BOOL".into()))))
            .collect(),
        FieldType::Alarms(names) => names
            .iter()
            .map(|n| item(n, CompletionItemKind::FIELD, Some("alarm".into())))
            .chain([item("Suppress", CompletionItemKind::FIELD, Some("TIME".into()))])
            .collect(),
        _ => Vec::new(),
    }
}

/// Every name that may start here: blocks, aliases, the own block's fields,
/// functions, and a sequence's steps and actions.
fn names(ctx: &Ctx, offset: usize) -> Vec<CompletionItem> {
    let mut out = Vec::new();
    let local = ctx.local_names();
    for (n, _, _) in &local.steps {
        out.push(item(n, CompletionItemKind::CLASS, Some("step".into())));
    }
    for (n, _, _) in &local.actions {
        out.push(item(n, CompletionItemKind::METHOD, Some("action".into())));
    }
    if let Some(db) = ctx.db() {
        for b in &db.blocks {
            out.push(item(&b.name, CompletionItemKind::VARIABLE, Some(db.templates[b.template].name.clone())));
        }
        for a in &db.aliases {
            out.push(item(&a.name, CompletionItemKind::VARIABLE, Some(format!("alias for {}", a.target.join(".")))));
        }
        if let Some(t) = ctx.own_type(offset) {
            out.extend(fields(db, t));
        }
    }
    for sig in linc_compiler::functions::SIGNATURES {
        let args: Vec<String> = sig.params[..sig.required.max(1).min(sig.params.len())]
            .iter()
            .enumerate()
            .map(|(i, p)| format!("${{{}:{}}}", i + 1, p.name()))
            .collect();
        out.push(CompletionItem {
            insert_text: Some(format!("{}({})", sig.name, args.join(", "))),
            insert_text_format: Some(InsertTextFormat::SNIPPET),
            ..item(sig.name, CompletionItemKind::FUNCTION, Some(sig.to_string()))
        });
    }
    out
}

/// Inside the string `src[start..end]`: the values of the enumerated field
/// it is compared with or assigned to.
fn enum_values(ctx: &Ctx, start: usize, end: usize, offset: usize) -> Vec<CompletionItem> {
    let Some(db) = ctx.db() else { return Vec::new() };
    let i = ctx.pieces.partition_point(|p| p.end <= start);
    let before: Vec<_> = ctx.pieces[..i].iter().rev().filter(|p| p.kind != Kind::Comment).take(3).collect();
    let t = |p: &crate::text::Piece| ctx.text((p.start, p.end));
    // `f := '…'`, `f <> '…'` and `f = '…'` (the scan splits `:=` and `<>`).
    let target = match before.as_slice() {
        [a, b, w, ..] if (t(b), t(a)) == (":", "=") || (t(b), t(a)) == ("<", ">") => *w,
        [eq, w, ..] if t(eq) == "=" => *w,
        _ => return Vec::new(),
    };
    let Some((Sym::Field { template, field, .. }, _, _)) = ctx.symbol_at(target.end) else { return Vec::new() };
    let FieldType::Enum(values) = &db.templates[template].fields[field].ty else { return Vec::new() };
    let text = &ctx.doc.text;
    let quote = text[start..].chars().next().unwrap_or('"');
    let inner_end = if end > start + 1 && text[..end].ends_with(quote) { end - 1 } else { end };
    let range = ctx.doc.index.range(text, start + 1, inner_end.max(offset.min(inner_end)));
    values
        .iter()
        .map(|v| CompletionItem {
            text_edit: Some(lsp_types::CompletionTextEdit::Edit(TextEdit::new(range, v.clone()))),
            ..item(v, CompletionItemKind::ENUM_MEMBER, Some(db.templates[template].fields[field].name.clone()))
        })
        .collect()
}

/// FST: commands in the CMD column, points (and a point's parameters after
/// its `,`) in the argument columns.
fn fst(ctx: &Ctx, offset: usize) -> Vec<CompletionItem> {
    let text = &ctx.doc.text;
    let line_start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = &text[line_start..offset];
    let cs = cells(line, linc_compiler::fst::reader::delimiter(text));
    match cs.len() - 1 {
        2 => Cmd::ALL
            .iter()
            .map(|c| item(c.text(), CompletionItemKind::KEYWORD, Some(format!("{}: {}", c.category(), c.doc()))))
            .collect(),
        3 | 4 => {
            let Some(db) = ctx.db() else { return Vec::new() };
            let (s, _) = cs[cs.len() - 1];
            let cell = line[s..].trim_start().trim_start_matches('"');
            match cell.split_once(',') {
                Some((point, _)) => match db.block(point.trim()) {
                    Some(b) => fields(db, db.blocks[b].template),
                    None => Vec::new(),
                },
                None => db
                    .blocks
                    .iter()
                    .filter(|b| db.templates[b.template].point_type(db.device).is_some())
                    .map(|b| item(&b.name, CompletionItemKind::VARIABLE, Some(db.templates[b.template].name.clone())))
                    .collect(),
            }
        }
        _ => Vec::new(),
    }
}

//! Go to definition, find references and rename.

use crate::resolve::{Ctx, Sym};
use crate::server::{Lang, Server};
use crate::text::{cells, pieces, Kind, LineIndex};
use linc_format::db::tree::{self, Member, Node};
use lsp_types::{
    GotoDefinitionParams, GotoDefinitionResponse, Location, PrepareRenameResponse, ReferenceParams, RenameParams,
    TextDocumentPositionParams, TextEdit, Url, WorkspaceEdit,
};
use std::collections::HashMap;
use std::path::Path;

pub fn definition(server: &Server, p: &GotoDefinitionParams) -> Option<GotoDefinitionResponse> {
    let pos = &p.text_document_position_params;
    let doc = server.doc(&pos.text_document.uri)?;
    let offset = doc.index.offset(&doc.text, pos.position);
    let ctx = Ctx::new(server, doc);
    let loc = match doc.lang {
        Lang::Json => json_definition(server, &ctx, offset),
        Lang::Fst => fst_definition(&ctx, offset),
        Lang::Other => None,
        _ => {
            let (sym, _, _) = ctx.symbol_at(offset)?;
            sym_location(&ctx, &sym)
        }
    }?;
    Some(GotoDefinitionResponse::Scalar(loc))
}

/// Where a symbol is defined: in the file (steps, actions, labels) or in
/// the database JSON (blocks, fields, aliases).
pub fn sym_location(ctx: &Ctx, sym: &Sym) -> Option<Location> {
    let local = |list: &[(String, usize, usize)], name: &str| {
        let (_, s, e) = list.iter().find(|n| n.0.eq_ignore_ascii_case(name))?;
        Some(Location::new(ctx.doc.uri.clone(), ctx.doc.index.range(&ctx.doc.text, *s, *e)))
    };
    let names = ctx.local_names();
    match sym {
        Sym::Step(n) => local(&names.steps, n),
        Sym::Action(n) => local(&names.actions, n),
        Sym::Label(n) => local(&names.labels, n),
        Sym::Function(_) => None,
        _ => {
            let file = ctx.file?;
            let db = ctx.db()?;
            let root = tree::parse(&file.text).ok()?;
            let top = root.as_object()?;
            let span = match sym {
                Sym::Block(b) => member(top, &["blocks", &db.blocks[*b].name]).map(|m| m.key_span),
                Sym::Alias(i) => member(top, &["aliases", &db.aliases[*i].name]).map(|m| m.key_span),
                Sym::Field { block, template, field, .. } => {
                    let t = &db.templates[*template];
                    let f = &t.fields[*field].name;
                    member(top, &["templates", &t.name, "fields", f])
                        .or_else(|| block.and_then(|b| member(top, &["blocks", &db.blocks[b].name, "values", f])))
                        .or_else(|| block.and_then(|b| member(top, &["blocks", &db.blocks[b].name])))
                        .map(|m| m.key_span)
                }
                _ => None,
            }?;
            let index = LineIndex::new(&file.text);
            Some(Location::new(Url::from_file_path(&file.path).ok()?, index.range(&file.text, span.0, span.1)))
        }
    }
}

/// The member at a path of keys (case-insensitive, as names are).
fn member<'a>(members: &'a [Member], path: &[&str]) -> Option<&'a Member> {
    let m = members.iter().find(|m| m.key.eq_ignore_ascii_case(path[0]))?;
    match path.len() {
        1 => Some(m),
        _ => member(m.value.as_object()?, &path[1..]),
    }
}

/// In a database: a block's `FileName` goes to the file, its `ActName` to
/// the action in that file.
fn json_definition(server: &Server, ctx: &Ctx, offset: usize) -> Option<Location> {
    let root: Node = tree::parse(&ctx.doc.text).ok()?;
    let blocks = member(root.as_object()?, &["blocks"])?.value.as_object()?;
    for b in blocks {
        let Some(values) = b.value.as_object().and_then(|o| member(o, &["values"])) else { continue };
        let Some(values) = values.value.as_object() else { continue };
        let file = member(values, &["FileName"]).and_then(|m| m.value.as_str().map(|s| (m, s)));
        let act = member(values, &["ActName"]).and_then(|m| m.value.as_str().map(|s| (m, s)));
        let inside = |m: &Member| m.value.span.0 <= offset && offset <= m.value.span.1;
        let Some((fm, file)) = file else { continue };
        let path = ctx.doc.path.parent().unwrap_or(Path::new(".")).join(file);
        let uri = Url::from_file_path(&path).ok()?;
        if inside(fm) {
            return Some(Location::new(uri, Default::default()));
        }
        if let Some((am, action)) = act.filter(|(m, _)| inside(m)) {
            let _ = am;
            let text = read(server, &uri, &path)?;
            let (s, e) = find_action(&text, action)?;
            let index = LineIndex::new(&text);
            return Some(Location::new(uri, index.range(&text, s, e)));
        }
    }
    None
}

/// The name of `ACTION name` in an action file.
fn find_action(text: &str, action: &str) -> Option<(usize, usize)> {
    let ps = pieces(text);
    let words: Vec<_> = ps.iter().filter(|p| p.kind != Kind::Comment).collect();
    words.windows(2).find_map(|w| {
        let header = text[w[0].start..w[0].end].eq_ignore_ascii_case("ACTION");
        (header && text[w[1].start..w[1].end].eq_ignore_ascii_case(action)).then_some((w[1].start, w[1].end))
    })
}

/// The text of a file: the editor's when it is open, else the disk's.
fn read(server: &Server, uri: &Url, path: &Path) -> Option<String> {
    match server.doc(uri) {
        Some(d) => Some(d.text.to_string()),
        None => crate::workspace::read(path),
    }
}

/// FST: a branch's label goes to the row that has it.
fn fst_definition(ctx: &Ctx, offset: usize) -> Option<Location> {
    let text = &ctx.doc.text;
    let delim = linc_compiler::fst::reader::delimiter(text);
    let (_, s, e) = crate::text::fst_cell(text, offset)?;
    let label = text[s..e].trim().trim_matches('"').trim();
    let mut at = 0;
    for row in text.split_inclusive('\n') {
        let rc = cells(row.trim_end_matches(['\r', '\n']), delim);
        if let Some(&(ls, le)) = rc.get(1) {
            if !label.is_empty() && row[ls..le].trim().eq_ignore_ascii_case(label) {
                let range = ctx.doc.index.range(text, at + ls, at + le);
                return Some(Location::new(ctx.doc.uri.clone(), range));
            }
        }
        at += row.len();
    }
    None
}

/// Every use of a block or field (and of a step, action or label in its
/// file) across the workspace's source files, as the checker resolves each
/// file's names (against the database that names it).
pub fn references(server: &Server, p: &ReferenceParams) -> Option<Vec<Location>> {
    let pos = &p.text_document_position;
    let doc = server.doc(&pos.text_document.uri)?;
    let offset = doc.index.offset(&doc.text, pos.position);
    let ctx = Ctx::new(server, doc);
    let (sym, _, _) = ctx.symbol_at(offset)?;
    let db = ctx.db();
    let (block, field) = match &sym {
        Sym::Block(b) => (db?.blocks[*b].name.clone(), None),
        Sym::Field { block: Some(b), template, field, .. } => {
            let db = db?;
            (db.blocks[*b].name.clone(), Some(db.templates[*template].fields[*field].name.clone()))
        }
        Sym::Step(_) | Sym::Action(_) | Sym::Label(_) => {
            let locs = same_names(&ctx, &sym).into_iter();
            return Some(locs.map(|(s, e)| Location::new(doc.uri.clone(), doc.index.range(&doc.text, s, e))).collect());
        }
        _ => return None,
    };
    let mut out = Vec::new();
    for (uri, path) in workspace_sources(server) {
        let Some(text) = read(server, &uri, &path) else { continue };
        let index = LineIndex::new(&text);
        let found = uses(server, &path, &text, (&block, field.as_deref()));
        out.extend(found.into_iter().map(|(start, end)| Location::new(uri.clone(), index.range(&text, start, end))));
    }
    if p.context.include_declaration {
        out.extend(sym_location(&ctx, &sym));
    }
    Some(out)
}

/// The open documents and the files the databases name, in URI order
/// (sources only).
fn workspace_sources(server: &Server) -> Vec<(Url, std::path::PathBuf)> {
    let mut files: Vec<(Url, std::path::PathBuf)> =
        server.docs.values().map(|d| (d.uri.clone(), d.path.clone())).collect();
    for f in server.ws.source_files() {
        if let Ok(uri) = Url::from_file_path(&f) {
            if !files.iter().any(|(u, _)| *u == uri) {
                files.push((uri, f));
            }
        }
    }
    files.retain(|(_, p)| !matches!(Lang::of(p, ""), Lang::Json | Lang::Other | Lang::Fst));
    files.sort_by(|a, b| a.0.as_str().cmp(b.0.as_str()));
    files
}

/// Where `text` (the file `path`) names `block` (or its `field`), as the
/// checker resolves the file's names against its database: a field's use
/// spans `BLOCK.FIELD` as written.
fn uses(server: &Server, path: &Path, text: &str, (block, field): (&str, Option<&str>)) -> Vec<(usize, usize)> {
    let Some(db) = server.ws.db_for(path).and_then(|d| d.database()) else { return Vec::new() };
    let file_name = Lang::of(path, "").file_name(path);
    let names = linc_compiler::names::of_source(text, &file_name, linc_compiler::Context::of(Some(db)));
    let is_block = |b: usize| db.blocks[b].name.eq_ignore_ascii_case(block);
    let mut out = Vec::new();
    let mut last_block: Option<(usize, usize)> = None;
    for n in names.iter() {
        match (&n.meaning, field) {
            (Sym::Block(b), None) if is_block(*b) => out.push((n.span.start, n.span.end)),
            (Sym::Field { block: Some(b), template, field: f, sub: None }, Some(want))
                if is_block(*b) && db.templates[*template].fields[*f].name.eq_ignore_ascii_case(want) =>
            {
                let dotted = last_block.filter(|(_, e)| text.get(*e..n.span.start).is_some_and(|g| g.trim() == "."));
                out.push((dotted.map_or(n.span.start, |(s, _)| s), n.span.end));
            }
            _ => {}
        }
        last_block = matches!(n.meaning, Sym::Block(_)).then_some((n.span.start, n.span.end));
    }
    out
}

/// Where the file names the step, action or label `sym` (declarations
/// included), as the checker resolves its names.
fn same_names(ctx: &Ctx, sym: &Sym) -> Vec<(usize, usize)> {
    ctx.resolved().iter().filter(|n| n.meaning == *sym).map(|n| (n.span.start, n.span.end)).collect()
}

pub fn prepare_rename(server: &Server, p: &TextDocumentPositionParams) -> Option<PrepareRenameResponse> {
    let doc = server.doc(&p.text_document.uri)?;
    let offset = doc.index.offset(&doc.text, p.position);
    let ctx = Ctx::new(server, doc);
    match ctx.symbol_at(offset)? {
        (Sym::Step(_) | Sym::Action(_), s, e) => Some(PrepareRenameResponse::Range(doc.index.range(&doc.text, s, e))),
        _ => None,
    }
}

/// Renames a step or an action of a sequence everywhere in its file; a
/// new name that is not an ST identifier of at most 8 characters (§12.8) is
/// refused with the reason.
pub fn rename(server: &Server, p: &RenameParams) -> Result<Option<WorkspaceEdit>, String> {
    let pos = &p.text_document_position;
    let Some(doc) = server.doc(&pos.text_document.uri) else { return Ok(None) };
    let offset = doc.index.offset(&doc.text, pos.position);
    let ctx = Ctx::new(server, doc);
    let sym = match ctx.symbol_at(offset) {
        Some((sym @ (Sym::Step(_) | Sym::Action(_)), _, _)) => sym,
        _ => return Ok(None),
    };
    let new = &p.new_name;
    let valid = new.chars().next().is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && new.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
        && new.len() <= 8;
    if !valid {
        return Err(format!(
            "`{new}` is not a step or action name: a letter or `_`, then letters, digits or `_`, at most 8 characters"
        ));
    }
    if crate::symbols::KEYWORDS.iter().any(|k| k.eq_ignore_ascii_case(new)) {
        return Err(format!("`{new}` is a keyword"));
    }
    // Only where the name means this step or action, as the checker
    // resolves it: `Fill.PV` is a block's field even in a sequence with a
    // step Fill.
    let edits: Vec<TextEdit> = same_names(&ctx, &sym)
        .into_iter()
        .map(|(s, e)| TextEdit::new(doc.index.range(&doc.text, s, e), new.clone()))
        .collect();
    Ok(Some(WorkspaceEdit { changes: Some(HashMap::from([(doc.uri.clone(), edits)])), ..WorkspaceEdit::default() }))
}

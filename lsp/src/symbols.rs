//! Document and workspace symbols (actions, steps, transitions, labelled
//! rungs, FST labels) and semantic tokens.

use crate::resolve::Ctx;
use crate::server::{Doc, Lang, Server};
use crate::text::{cells, parts, Kind, LineIndex};
use lsp_types::{
    DocumentSymbol, DocumentSymbolParams, DocumentSymbolResponse, Location, SemanticToken, SemanticTokenType,
    SemanticTokens, SemanticTokensLegend, SemanticTokensParams, SemanticTokensResult, SymbolInformation, SymbolKind,
    Url, WorkspaceSymbolParams,
};

/// The token types, in the legend's order.
const TYPES: [SemanticTokenType; 12] = [
    SemanticTokenType::KEYWORD,
    SemanticTokenType::COMMENT,
    SemanticTokenType::STRING,
    SemanticTokenType::NUMBER,
    SemanticTokenType::OPERATOR,
    SemanticTokenType::VARIABLE,
    SemanticTokenType::PROPERTY,
    SemanticTokenType::FUNCTION,
    SemanticTokenType::ENUM_MEMBER,
    SemanticTokenType::new("label"),
    SemanticTokenType::CLASS,
    SemanticTokenType::METHOD,
];

#[derive(Clone, Copy)]
enum T {
    Keyword = 0,
    Comment = 1,
    Str = 2,
    Number = 3,
    Variable = 5,
    Property = 6,
    Function = 7,
    Label = 9,
    Step = 10,
    Action = 11,
}

pub fn legend() -> SemanticTokensLegend {
    SemanticTokensLegend { token_types: TYPES.to_vec(), token_modifiers: Vec::new() }
}

/// The words of the languages: ST's keywords, the chart's and the rungs'.
pub const KEYWORDS: [&str; 35] = [
    "IF",
    "THEN",
    "ELSIF",
    "ELSE",
    "END_IF",
    "FOR",
    "TO",
    "BY",
    "DO",
    "END_FOR",
    "WHILE",
    "END_WHILE",
    "REPEAT",
    "UNTIL",
    "END_REPEAT",
    "EXIT",
    "ACTION",
    "END_ACTION",
    "AND",
    "OR",
    "XOR",
    "NOT",
    "MOD",
    "TRUE",
    "FALSE",
    "STEP",
    "INITIAL_STEP",
    "END_STEP",
    "TRANSITION",
    "FROM",
    "END_TRANSITION",
    "PRIORITY",
    "CHART",
    "LADDER",
    "JUMP",
];

fn is_keyword(w: &str, lang: Lang) -> bool {
    let i = KEYWORDS.iter().position(|k| k.eq_ignore_ascii_case(w));
    match i {
        Some(i) if i < 25 => true,
        Some(34) => lang == Lang::Ladder || lang == Lang::Sfc,
        None => false,
        Some(_) => lang == Lang::Sfc,
    }
}

pub fn document(server: &Server, p: &DocumentSymbolParams) -> Option<DocumentSymbolResponse> {
    let doc = server.doc(&p.text_document.uri)?;
    Some(DocumentSymbolResponse::Nested(symbols_of(server, doc)))
}

#[allow(deprecated)]
fn symbol(doc: &Doc, name: &str, detail: &str, kind: SymbolKind, s: usize, e: usize) -> DocumentSymbol {
    let range = doc.index.range(&doc.text, s, e);
    DocumentSymbol {
        name: name.to_string(),
        detail: (!detail.is_empty()).then(|| detail.to_string()),
        kind,
        tags: None,
        deprecated: None,
        range,
        selection_range: range,
        children: None,
    }
}

/// The symbols of one document, in text order.
pub fn symbols_of(server: &Server, doc: &Doc) -> Vec<DocumentSymbol> {
    let ctx = Ctx::new(server, doc);
    let mut out = Vec::new();
    match doc.lang {
        Lang::Sfc => {
            let names = ctx.local_names();
            let lists =
                [(&names.steps, "step", SymbolKind::CLASS), (&names.transitions, "transition", SymbolKind::EVENT)];
            for (list, detail, kind) in lists {
                out.extend(list.iter().map(|(n, s, e)| symbol(doc, n, detail, kind, *s, *e)));
            }
            out.extend(names.actions.iter().map(|(n, s, e)| symbol(doc, n, "action", SymbolKind::FUNCTION, *s, *e)));
        }
        Lang::St | Lang::Ladder => {
            let words: Vec<_> = ctx.pieces.iter().filter(|p| p.kind != Kind::Comment).collect();
            for (k, w) in words.iter().enumerate() {
                let after_colon = k > 0 && ctx.text((words[k - 1].start, words[k - 1].end)) == ":";
                if ctx.text((w.start, w.end)).eq_ignore_ascii_case("ACTION") && !after_colon {
                    if let Some(n) = words.get(k + 1).filter(|n| n.kind == Kind::Word) {
                        out.push(symbol(
                            doc,
                            ctx.text((n.start, n.end)),
                            "action",
                            SymbolKind::FUNCTION,
                            n.start,
                            n.end,
                        ));
                    }
                }
            }
            for (n, s, e) in &ctx.local_names().labels {
                out.push(symbol(doc, n, "rung label", SymbolKind::KEY, *s, *e));
            }
        }
        Lang::Fst => {
            let mut at = 0;
            let delim = linc_compiler::fst::reader::delimiter(&doc.text);
            for row in doc.text.split_inclusive('\n') {
                let cs = cells(row.trim_end_matches(['\r', '\n']), delim);
                if let (Some(&(s, e)), true) = (cs.get(1), at > 0) {
                    let label = row[s..e].trim().trim_matches('"');
                    if !label.is_empty() {
                        out.push(symbol(doc, label, "FST label", SymbolKind::KEY, at + s, at + e));
                    }
                }
                at += row.len();
            }
        }
        Lang::Json | Lang::Other => {}
    }
    out.sort_by_key(|s| (s.range.start.line, s.range.start.character));
    out
}

/// Symbols of every source file of the workspace whose name holds the query.
#[allow(deprecated)]
pub fn workspace(server: &Server, p: &WorkspaceSymbolParams) -> Option<Vec<SymbolInformation>> {
    let query = p.query.to_ascii_lowercase();
    let mut uris: Vec<Url> = server.docs.keys().cloned().collect();
    let mut disk = Vec::new();
    for f in server.ws.source_files() {
        if let Ok(uri) = Url::from_file_path(&f) {
            if !uris.contains(&uri) {
                if let Some(text) = crate::workspace::read(&f) {
                    disk.push(Doc::new(uri.clone(), text, 0, ""));
                    uris.push(uri);
                }
            }
        }
    }
    let mut docs: Vec<&Doc> = server.docs.values().chain(disk.iter()).collect();
    docs.sort_by(|a, b| a.uri.as_str().cmp(b.uri.as_str()));
    let mut out = Vec::new();
    for doc in docs {
        for s in symbols_of(server, doc) {
            if s.name.to_ascii_lowercase().contains(&query) {
                out.push(SymbolInformation {
                    name: s.name,
                    kind: s.kind,
                    tags: None,
                    deprecated: None,
                    location: Location::new(doc.uri.clone(), s.range),
                    container_name: doc.path.file_name().and_then(|n| n.to_str()).map(str::to_string),
                });
            }
        }
    }
    Some(out)
}

pub fn semantic(server: &Server, p: &SemanticTokensParams) -> Option<SemanticTokensResult> {
    let doc = server.doc(&p.text_document.uri)?;
    let ctx = Ctx::new(server, doc);
    let mut spans: Vec<(usize, usize, T)> = Vec::new();
    if doc.lang == Lang::Fst {
        fst_spans(doc, &mut spans);
    } else if doc.lang != Lang::Json && doc.lang != Lang::Other {
        let names = ctx.local_names();
        let db = ctx.db();
        let has = |list: &[(String, usize, usize)], w: &str| list.iter().any(|n| n.0.eq_ignore_ascii_case(w));
        for piece in &ctx.pieces {
            let t = match piece.kind {
                Kind::Comment => T::Comment,
                Kind::Str => T::Str,
                Kind::Number => T::Number,
                Kind::Punct => continue,
                Kind::Word => {
                    let (ps, _) = parts(&doc.text, *piece, piece.start);
                    let first = ctx.text(ps[0]);
                    let t = if ps.len() == 1 && is_keyword(first, doc.lang) {
                        T::Keyword
                    } else if has(&names.steps, first) {
                        T::Step
                    } else if has(&names.actions, first) {
                        T::Action
                    } else if has(&names.labels, first) {
                        T::Label
                    } else if ctx.next_char(piece.end) == Some('(') && linc_compiler::functions::lookup(first).is_some()
                    {
                        T::Function
                    } else {
                        T::Variable
                    };
                    spans.push((ps[0].0, ps[0].1, t));
                    for &(s, e) in &ps[1..] {
                        spans.push((s, e, if db.is_some() { T::Property } else { T::Variable }));
                    }
                    continue;
                }
            };
            spans.push((piece.start, piece.end, t));
        }
    }
    Some(SemanticTokensResult::Tokens(SemanticTokens { result_id: None, data: encode(doc, &spans) }))
}

fn fst_spans(doc: &Doc, spans: &mut Vec<(usize, usize, T)>) {
    let mut at = 0;
    let delim = linc_compiler::fst::reader::delimiter(&doc.text);
    for (row_no, row) in doc.text.split_inclusive('\n').enumerate() {
        let line = row.trim_end_matches(['\r', '\n']);
        for (col, &(s, e)) in cells(line, delim).iter().enumerate() {
            let t = match (row_no, col) {
                (0, _) => T::Keyword,
                (_, 0) => T::Number,
                (_, 1) => T::Label,
                (_, 2) => T::Keyword,
                (_, 3 | 4) => T::Variable,
                _ => T::Comment,
            };
            if e > s && !line[s..e].trim().is_empty() {
                spans.push((at + s, at + e, t));
            }
        }
        at += row.len();
    }
}

/// The protocol's relative encoding; a token over several lines is cut at
/// each line end (clients draw tokens line by line).
fn encode(doc: &Doc, spans: &[(usize, usize, T)]) -> Vec<SemanticToken> {
    let index: &LineIndex = &doc.index;
    let mut cursor = crate::text::Cursor::new(&doc.text, index);
    let mut out = Vec::new();
    let (mut line, mut col) = (0u32, 0u32);
    for &(s, e, t) in spans {
        let mut start = s;
        while start < e {
            let stop = doc.text[start..e].find('\n').map_or(e, |i| start + i);
            let (a, b) = (cursor.position(start), cursor.position(stop));
            if b.character > a.character {
                let delta_start = if a.line == line { a.character - col } else { a.character };
                out.push(SemanticToken {
                    delta_line: a.line - line,
                    delta_start,
                    length: b.character - a.character,
                    token_type: t as u32,
                    token_modifiers_bitset: 0,
                });
                (line, col) = (a.line, a.character);
            }
            start = stop + 1;
        }
    }
    out
}

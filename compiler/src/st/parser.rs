//! Drives the lalrpop parser over the cooked tokens and turns its errors
//! (recovered or fatal) into [`SyntaxError`]s.

use crate::diag::span::Span;
use crate::diag::{Capped, Omitted, MAX_ERRORS};
use crate::st::ast::{Action, Expr, Ident, SourceFile, Stmt};
use crate::st::depth_guard::DepthGuard;
use crate::st::errors::{LexError, SyntaxError};
use crate::st::lexer::{Lexer, Spanned, Tok};
use crate::st::parse_support::{Item, Never, Parsed, Recovered};
use lalrpop_util::{lalrpop_mod, ParseError};
use std::cell::Cell;

lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications, unused_parens)]
    grammar,
    "/st/grammar.rs"
);

/// Everything the front end found wrong in a text, in source order per stage.
#[derive(Debug, Default)]
pub struct ParseErrors {
    pub lex: Vec<LexError>,
    pub syntax: Vec<SyntaxError>,
    /// Errors over [`crate::diag::MAX_ERRORS`] of one kind, not kept.
    pub omitted: Omitted,
}

/// Parses an action file, handing each statement before the first `ACTION`
/// header and each action to `sink` as soon as it is read. Statements before
/// a header are an error (E0016) if the file has headers; in a file without
/// any, they are its one action, named after the file. Returns false if the
/// parser could not recover (what was read before that has been handed over).
pub fn parse_actions(src: &str, sink: &mut dyn FnMut(Item)) -> (bool, ParseErrors) {
    let mut file = FileItems::default();
    let (parsed, errors) = run(src, Tok::StartFile, &mut |item| {
        file.see(&item);
        sink(item)
    });
    file.finish(matches!(parsed, Some(Parsed::File)), errors)
}

/// What a file's items say about it as a whole: whether statements stand
/// before its first header (E0016 once it has headers).
#[derive(Default)]
pub(crate) struct FileItems {
    first_stmt: Option<Span>,
    actions: usize,
}

impl FileItems {
    pub(crate) fn see(&mut self, item: &Item) {
        match item {
            Item::Stmt(s) => {
                self.first_stmt.get_or_insert(s.span());
            }
            Item::Action(_) => self.actions += 1,
        }
    }

    pub(crate) fn finish(self, ok: bool, mut errors: ParseErrors) -> (bool, ParseErrors) {
        if let (Some(span), 1..) = (self.first_stmt, self.actions) {
            errors.syntax.push(SyntaxError::StatementOutsideAction { span });
            errors.syntax.sort_by_key(|e| syntax_span(e).start);
        }
        (ok, errors)
    }
}

/// Files at least this long are parsed on a second thread while the
/// caller's sink (the checker) works on what was read before. Parsing and
/// checking then overlap on two cores; below this size starting a thread
/// costs more than it saves.
pub const PIPELINE_MIN: usize = 128 * 1024;

/// Items handed from the parsing thread to the sink at a time: a channel
/// operation per statement of a file without headers would cost more than
/// the statement.
pub(crate) const BATCH: usize = 32;

/// [`parse_actions`], with the parser on its own thread for long texts.
/// The sink sees the same items in the same order and the result is the
/// same; only the time differs. At most four batches wait at once, so
/// memory stays bounded however far the parser runs ahead. A file whose
/// actions can be split is parsed on two threads at once
/// ([`crate::st::split`]).
pub fn parse_actions_pipelined(src: &str, sink: &mut dyn FnMut(Item)) -> (bool, ParseErrors) {
    parse_actions_giving(src, &mut |item| {
        sink(item);
        None
    })
}

/// [`parse_actions_pipelined`] with a sink that gives back the items it
/// does not keep, to be freed on the thread that parsed them.
pub fn parse_actions_giving(src: &str, sink: &mut crate::st::split::Giving) -> (bool, ParseErrors) {
    if src.len() < PIPELINE_MIN {
        return parse_actions(src, &mut |item| drop(sink(item)));
    }
    crate::st::split::parse_actions_split_giving(src, sink)
}

/// Parses `src` from `start` (the start of the file, or of an `ACTION`
/// header where the text before parsed without a fault) to its end on a
/// second thread, handing `sink` every item after the first `skip`: they
/// were handed over already.
pub(crate) fn parse_rest_pipelined(
    src: &str,
    start: usize,
    mut skip: usize,
    sink: &mut dyn FnMut(Item),
) -> (Option<Parsed>, ParseErrors) {
    let (tx, rx) = std::sync::mpsc::sync_channel::<Vec<Item>>(4);
    std::thread::scope(|scope| {
        let parser = scope.spawn(move || {
            let mut batch = Vec::with_capacity(BATCH);
            let part = Part { start, end: usize::MAX };
            let result = run_part(src, Tok::StartFile, part, &Cell::new(None), &mut |item| {
                if skip > 0 {
                    skip -= 1;
                    return;
                }
                batch.push(item);
                if batch.len() == BATCH {
                    // A closed channel means the sink panicked; the panic
                    // is the caller's to see, not this thread's.
                    let _ = tx.send(std::mem::replace(&mut batch, Vec::with_capacity(BATCH)));
                }
            });
            if !batch.is_empty() {
                let _ = tx.send(batch);
            }
            result
        });
        for item in rx.into_iter().flatten() {
            sink(item);
        }
        parser.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}

/// The one action of a file without `ACTION` headers: named `stem`,
/// spanning the whole text.
pub fn headerless(src: &str, stem: &str, body: Vec<Stmt>) -> Action {
    let name = Ident { text: stem.into(), span: Span::new(0, 0) };
    Action { name, block_type: None, body, header: None, span: Span::new(0, src.len()) }
}

/// Parses an action file into one tree. `None` only when the parser could
/// not recover.
pub fn parse_file(src: &str, stem: &str) -> (Option<SourceFile>, ParseErrors) {
    let (mut body, mut actions) = (Vec::new(), Vec::new());
    let (ok, errors) = parse_actions(src, &mut |item| match item {
        Item::Stmt(s) => body.push(s),
        Item::Action(a) => actions.push(a),
    });
    if actions.is_empty() {
        actions.push(headerless(src, stem, body));
    }
    (ok.then_some(SourceFile { actions }), errors)
}

/// Parses one expression, as a transition is (§12.11).
pub fn parse_expr(src: &str) -> (Option<Expr>, ParseErrors) {
    let (parsed, errors) = run(src, Tok::StartExpr, &mut |_| {});
    let expr = parsed.and_then(|p| match p {
        Parsed::Expr(e) => Some(e),
        Parsed::File => None,
    });
    (expr, errors)
}

fn run(src: &str, start: Tok<'static>, sink: &mut dyn FnMut(Item)) -> (Option<Parsed>, ParseErrors) {
    run_part(src, start, Part { start: 0, end: usize::MAX }, &Cell::new(None), sink)
}

/// The part of a text a parse reads: from `start` (a token's start), up to
/// the first token at or after `end`, which is not read but left in `cut`.
/// A parse of the whole text has no `end` (`usize::MAX`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Part {
    pub start: usize,
    pub end: usize,
}

/// Parses `part` of `src`: the parser meets the end of input at the part's
/// end. The token found there, if any, is put in `cut` as soon as it is met
/// (the sink can tell the items reduced before it from those after).
pub(crate) fn run_part<'s>(
    src: &'s str,
    start: Tok<'static>,
    part: Part,
    cut: &Cell<Option<Spanned<'s>>>,
    sink: &mut dyn FnMut(Item),
) -> (Option<Parsed>, ParseErrors) {
    let mut lexer = Lexer::starting_at(src, part.start);
    let mut recovered = Recovered::default();
    let mut syntax = Capped::default();
    let parser = grammar::StartParser::new();
    let mut guard = DepthGuard::new(lexer.by_ref());
    // Once as many syntax errors are reported as are shown, the rest of the
    // file is not read: each recovery costs the parser a search of its
    // states, and a file of a million errors would take seconds to report
    // a thousand.
    let (count, stopped) = (recovered.count.clone(), Cell::new(None));
    let feed = guard.by_ref().map_while(|t| {
        if t.0 >= part.end {
            cut.set(Some(t));
            return None;
        }
        if count.get() < MAX_ERRORS {
            return Some(t);
        }
        stopped.set(Some(Span::new(t.0, t.2)));
        None
    });
    let tokens = std::iter::once((0, start, 0)).chain(feed).map(Ok::<Spanned, Never>);
    let result = parser.parse(&mut recovered, &mut syntax, sink, tokens);
    let mut omitted = Omitted::default();
    let (too_deep, n, first) = guard.errors.into_parts();
    omitted.add(n, first.as_ref().map(syntax_span));
    let (recovered, n, first) = recovered.kept.into_parts();
    omitted.add(n, first.map(|r| syntax_span(&convert(&lexer.glued, r.error, src.len()))));
    let mut found: Vec<SyntaxError> =
        recovered.into_iter().map(|r| convert(&lexer.glued, r.error, src.len())).collect();
    let parsed = match (result, stopped.get()) {
        (Ok(p), None) => Some(p),
        // The end the parser met is not the file's: say where reading stopped.
        (_, Some(span)) => {
            found.push(SyntaxError::Stopped { span });
            None
        }
        (Err(e), None) => {
            found.push(convert(&lexer.glued, e, src.len()));
            None
        }
    };
    // Merge grammar-reported name errors with parse errors in source order,
    // dropping a parse error that repeats one already at the same place.
    let (syntax, n, first) = syntax.into_parts();
    omitted.add(n, first.as_ref().map(syntax_span));
    found.extend(syntax);
    found.extend(too_deep);
    found.sort_by_key(|e| syntax_span(e).start);
    found.dedup_by(|b, a| syntax_span(a) == syntax_span(b));
    let (lex, n, first) = lexer.errors.into_parts();
    omitted.add(n, first.map(|e| e.to_diagnostic().span));
    (parsed, ParseErrors { lex, syntax: found, omitted })
}

/// The primary span of a syntax error.
pub fn syntax_span(e: &SyntaxError) -> Span {
    match e {
        SyntaxError::Unexpected { span, .. }
        | SyntaxError::UnexpectedEof { span, .. }
        | SyntaxError::NameTooLong { span, .. }
        | SyntaxError::InvalidName { span, .. }
        | SyntaxError::GluedWordOperator { span, .. }
        | SyntaxError::BadActionName { span, .. }
        | SyntaxError::DoubleOffset { span }
        | SyntaxError::StatementOutsideAction { span }
        | SyntaxError::MissingFinalSemicolon { span }
        | SyntaxError::NestedTooDeep { span, .. }
        | SyntaxError::ExprTooDeep { span }
        | SyntaxError::Stopped { span } => *span,
    }
}

fn convert(glued: &[(usize, &'static str)], e: ParseError<usize, Tok, Never>, len: usize) -> SyntaxError {
    match e {
        ParseError::UnrecognizedToken { token: (l, tok, r), expected } => {
            let span = Span::new(l, r);
            if let Some(&(_, op)) = glued.iter().find(|g| g.0 == l) {
                return SyntaxError::GluedWordOperator { span, op, name: tok.describe_name() };
            }
            SyntaxError::Unexpected { span, found: tok.describe(), expected: readable(&expected) }
        }
        ParseError::UnrecognizedEof { location, expected } => {
            let at = location.min(len);
            SyntaxError::UnexpectedEof { span: Span::new(at, at), expected: readable(&expected) }
        }
        ParseError::ExtraToken { token: (l, tok, r) } => {
            SyntaxError::Unexpected { span: Span::new(l, r), found: tok.describe(), expected: Vec::new() }
        }
        ParseError::InvalidToken { location } => {
            SyntaxError::Unexpected { span: Span::new(location, location), found: "token".into(), expected: Vec::new() }
        }
        ParseError::User { error } => match error {},
    }
}

/// Turns lalrpop's terminal names into what an engineer reads.
fn readable(expected: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for e in expected {
        let text = match e.trim_matches('"') {
            "Name" | "Bracketed" => "a name".to_string(),
            "Int" | "Real" => "a number".to_string(),
            "Time" | "Str" | "TRUE" | "FALSE" => "a constant".to_string(),
            "DotName" => "`.name`".to_string(),
            "StartFile" | "StartExpr" | "Skipped" | "SkippedPrefix" | "SkippedStatement" => continue,
            other => format!("`{}`", other.replace("\\\"", "\"")),
        };
        if !out.contains(&text) {
            out.push(text);
        }
    }
    let rank = |t: &String| match t.as_str() {
        "a name" => 0,
        "a number" => 1,
        "a constant" => 2,
        _ => 3,
    };
    out.sort_by(|a, b| rank(a).cmp(&rank(b)).then_with(|| a.cmp(b)));
    // At the end of an action's statements, where another statement could
    // also follow, the useful hint is the closing keyword.
    if out.iter().any(|t| t == "`END_ACTION`") && out.iter().any(|t| t == "`EXIT`") {
        return vec!["`END_ACTION`".to_string()];
    }
    out
}

impl Tok<'_> {
    fn describe_name(&self) -> String {
        match self {
            Tok::Name(n) => n.trim().to_string(),
            other => other.describe(),
        }
    }
}

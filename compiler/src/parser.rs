//! Drives the lalrpop parser over the cooked tokens and turns its errors
//! (recovered or fatal) into [`SyntaxError`]s.

use crate::ast::{Action, Expr, Ident, SourceFile};
use crate::errors::{LexError, SyntaxError};
use crate::lexer::{self, Spanned, Tok};
use crate::parse_support::{Never, Parsed};
use crate::span::Span;
use lalrpop_util::{lalrpop_mod, ErrorRecovery, ParseError};

lalrpop_mod!(
    #[allow(clippy::all, clippy::pedantic, unused_qualifications, unused_parens)]
    grammar
);

/// Everything the front end found wrong in a text, in source order per stage.
#[derive(Debug, Default)]
pub struct ParseErrors {
    pub lex: Vec<LexError>,
    pub syntax: Vec<SyntaxError>,
}

/// Parses an action file. `stem` names the action of a file without
/// `ACTION` headers. Returns `None` only when the parser could not recover.
pub fn parse_file(src: &str, stem: &str) -> (Option<SourceFile>, ParseErrors) {
    let (parsed, mut errors) = run(src, Tok::StartFile);
    let file = parsed.and_then(|p| match p {
        Parsed::File(body, actions) => {
            if let (Some(first), false) = (body.first(), actions.is_empty()) {
                errors.syntax.push(SyntaxError::StatementOutsideAction { span: first.span() });
            }
            Some(file_from(src, stem, body, actions.into_iter().map(|a| a.0).collect()))
        }
        Parsed::Expr(_) => None,
    });
    (file, errors)
}

/// Parses one expression, as a transition is (§12.11).
pub fn parse_expr(src: &str) -> (Option<Expr>, ParseErrors) {
    let (parsed, errors) = run(src, Tok::StartExpr);
    let expr = parsed.and_then(|p| match p {
        Parsed::Expr(e) => Some(e),
        Parsed::File(..) => None,
    });
    (expr, errors)
}

fn file_from(src: &str, stem: &str, body: Vec<crate::ast::Stmt>, actions: Vec<Action>) -> SourceFile {
    if actions.is_empty() {
        let span = Span::new(0, src.len());
        let name = Ident { text: stem.to_string(), span: Span::new(0, 0) };
        return SourceFile { actions: vec![Action { name, block_type: None, body, header: None, span }] };
    }
    SourceFile { actions }
}

fn run(src: &str, start: Tok<'static>) -> (Option<Parsed>, ParseErrors) {
    let (mut tokens, lex) = lexer::lex(src);
    tokens.insert(0, (0, start, 0));
    let mut recovered: Vec<ErrorRecovery<usize, Tok, Never>> = Vec::new();
    let mut syntax = Vec::new();
    let parser = grammar::StartParser::new();
    let result = parser.parse(&mut recovered, &mut syntax, tokens.iter().cloned().map(Ok::<Spanned, Never>));
    let mut found: Vec<SyntaxError> = Vec::new();
    for r in recovered {
        found.push(convert(&tokens, r.error, src.len()));
    }
    let parsed = match result {
        Ok(p) => Some(p),
        Err(e) => {
            found.push(convert(&tokens, e, src.len()));
            None
        }
    };
    // Merge grammar-reported name errors with parse errors in source order,
    // dropping a parse error that repeats one already at the same place.
    found.extend(syntax);
    found.sort_by_key(|e| syntax_span(e).start);
    found.dedup_by(|b, a| syntax_span(a) == syntax_span(b));
    (parsed, ParseErrors { lex, syntax: found })
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
        | SyntaxError::MissingFinalSemicolon { span } => *span,
    }
}

fn convert(tokens: &[Spanned], e: ParseError<usize, Tok, Never>, len: usize) -> SyntaxError {
    match e {
        ParseError::UnrecognizedToken { token: (l, tok, r), expected } => {
            let span = Span::new(l, r);
            let at = tokens.partition_point(|t| t.0 < l);
            let prev = at.checked_sub(1).and_then(|i| tokens.get(i)).map(|t| &t.1);
            if let Some(op) = lexer::glued_word_operator(prev, &tok) {
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
            "StartFile" | "StartExpr" => continue,
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

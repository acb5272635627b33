//! Tree-building helpers called from the grammar's actions.
//!
//! Keeping them here keeps the grammar readable and lets the name rules
//! (§12.8: at most 8 characters, no leading digit) live in plain Rust.

use crate::ast::{Action, BinOp, Expr, ExprKind, Ident, Seg, Stmt, UnOp, Var};
use crate::errors::SyntaxError;
use crate::span::Span;

/// The parser's user error type: the lexer reports its own errors, so the
/// parser never receives one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Never {}

/// What the grammar's start rule produced.
#[derive(Debug)]
pub enum Parsed {
    /// Statements before any `ACTION` header, then the actions.
    File(Vec<Stmt>, Vec<RawAction>),
    Expr(Expr),
}

/// An action as parsed, before the file's stem names a header-less one.
#[derive(Debug)]
pub struct RawAction(pub Action);

/// A part after a variable's first name: `{offset}` or `.Name`.
#[derive(Debug)]
pub enum Suffix {
    Offset(Box<Expr>, Span),
    Field(String, Span),
}

/// Saturates an integer constant's magnitude at 2^31, so that a following
/// sign can still make `-2147483648`; [`Expr::int_value`] clips the rest.
pub fn clip(v: i64) -> i64 {
    v.min(1 << 31)
}

pub fn leaf(kind: ExprKind, l: usize, r: usize) -> Box<Expr> {
    Box::new(Expr { kind, span: Span::new(l, r) })
}

pub fn binary(op: BinOp, a: Box<Expr>, b: Box<Expr>) -> Box<Expr> {
    let span = a.span.to(b.span);
    Box::new(Expr { kind: ExprKind::Binary(op, a, b), span })
}

pub fn unary(op: UnOp, e: Box<Expr>, span: Span) -> Box<Expr> {
    Box::new(Expr { kind: ExprKind::Unary(op, e), span })
}

/// Unary minus; a negated numeric constant is folded so that `-12345` and
/// `BY -2` are constants, and `-2147483648` fits.
pub fn negate(e: Box<Expr>, span: Span) -> Box<Expr> {
    match e.kind {
        ExprKind::Int(v) if e.span.start == span.start + 1 => Box::new(Expr { kind: ExprKind::Int(-v), span }),
        ExprKind::Real(x) if e.span.start == span.start + 1 => Box::new(Expr { kind: ExprKind::Real(-x), span }),
        _ => unary(UnOp::Neg, e, span),
    }
}

/// Parentheses only widen the span.
pub fn paren(mut e: Box<Expr>, span: Span) -> Box<Expr> {
    e.span = span;
    e
}

pub fn call(name: &str, l: usize, nr: usize, args: Vec<Box<Expr>>, span: Span) -> Box<Expr> {
    let name = Ident { text: name.to_string(), span: Span::new(l, nr) };
    Box::new(Expr { kind: ExprKind::Call { name, args: args.into_iter().map(|a| *a).collect() }, span })
}

/// Checks one identifier against §12.8.
fn check_ident(syntax: &mut Vec<SyntaxError>, text: &str, span: Span) {
    let first = text.chars().next();
    if first.map(|c| c.is_ascii_digit()).unwrap_or(true) {
        let why = if text.is_empty() { "empty name part" } else { "starts with a digit" };
        syntax.push(SyntaxError::InvalidName { span, name: text.to_string(), why });
    } else if text.chars().count() > 8 {
        syntax.push(SyntaxError::NameTooLong { span, name: text.to_string() });
    }
}

/// Removes spaces and comments around a name part: a reported illegal
/// space such as `TIC_100 (*c*) .SL` leaves them inside the joined token.
fn strip_spaces(mut part: &str) -> &str {
    loop {
        let before = part.len();
        part = part.trim();
        if part.starts_with("(*") {
            if let Some(end) = part.find("*)") {
                part = &part[end + 2..];
            }
        }
        if part.ends_with("*)") {
            if let Some(start) = part.rfind("(*") {
                part = &part[..start];
            }
        }
        if part.len() == before {
            return part;
        }
    }
}

/// Splits `text` (starting at byte `at`) at dots into identifiers with spans.
fn split(syntax: &mut Vec<SyntaxError>, text: &str, at: usize, bracketed: bool) -> Vec<Seg> {
    let mut segs = Vec::new();
    let mut start = at;
    for part in text.split('.') {
        let name = if bracketed { part } else { strip_spaces(part) };
        let lead = if bracketed { 0 } else { name.as_ptr() as usize - part.as_ptr() as usize };
        let s = if bracketed { start } else { start + lead };
        let span = Span::new(s, s + name.len());
        if !bracketed {
            check_ident(syntax, name, span);
        }
        segs.push(Seg { name: Ident { text: name.to_string(), span }, offset: None });
        start += part.len() + 1;
    }
    segs
}

/// Builds a variable from its first token and suffixes.
pub fn var(
    syntax: &mut Vec<SyntaxError>,
    text: &str,
    (l, r): (usize, usize),
    bracketed: bool,
    suffixes: Vec<Suffix>,
) -> Var {
    let first = if bracketed { l + 1 } else { l };
    let before = syntax.len();
    let mut segs = split(syntax, text, first, bracketed);
    let mut end = r;
    for s in suffixes {
        match s {
            Suffix::Offset(e, span) => {
                end = span.end;
                if let Some(last) = segs.last_mut() {
                    if last.offset.is_some() {
                        syntax.push(SyntaxError::DoubleOffset { span });
                    }
                    last.offset = Some(e);
                }
            }
            Suffix::Field(name, span) => {
                end = span.end;
                let nspan = Span::new(span.start + 1, span.end);
                check_ident(syntax, &name, nspan);
                segs.push(Seg { name: Ident { text: name, span: nspan }, offset: None });
            }
        }
    }
    Var { segs, bracketed, span: Span::new(l, end), malformed: syntax.len() > before }
}

/// Validates an action header (§10.2.1) and builds the action.
pub fn action(
    syntax: &mut Vec<SyntaxError>,
    (nl, name, nr): (usize, &str, usize),
    block_type: Option<(usize, &str, usize)>,
    body: Vec<Stmt>,
    header: Span,
    span: Span,
) -> RawAction {
    let name_span = Span::new(nl, nr);
    if name.contains('.') || name.len() > 8 || name.starts_with(|c: char| c.is_ascii_digit()) {
        syntax.push(SyntaxError::BadActionName { span: name_span, name: name.to_string() });
    }
    let block_type = block_type.map(|(l, t, r)| Ident { text: t.to_string(), span: Span::new(l, r) });
    RawAction(Action {
        name: Ident { text: name.to_string(), span: name_span },
        block_type,
        body,
        header: Some(header),
        span,
    })
}

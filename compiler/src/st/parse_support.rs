//! Tree-building helpers called from the grammar's actions.
//!
//! Keeping them here keeps the grammar readable and lets the name rules
//! (§12.8: at most 8 characters, no leading digit) live in plain Rust.

use crate::diag::span::Span;
use crate::diag::Capped;
use crate::st::ast::{Action, BinOp, Expr, ExprKind, Ident, Name, Seg, Stmt, UnOp, Var};
use crate::st::errors::SyntaxError;
use crate::st::lexer::Tok;
use lalrpop_util::ErrorRecovery;
use std::cell::Cell;
use std::rc::Rc;

/// The errors the grammar recovered from (`!`), with a count the parser's
/// feed of tokens can read while the grammar holds the list: reading stops
/// once [`crate::diag::MAX_ERRORS`] are reported (`parser::run`).
#[derive(Debug, Default)]
pub struct Recovered<'s> {
    pub kept: Capped<ErrorRecovery<usize, Tok<'s>, Never>>,
    pub count: Rc<Cell<usize>>,
}

impl<'s> Recovered<'s> {
    pub fn push(&mut self, e: ErrorRecovery<usize, Tok<'s>, Never>) {
        self.count.set(self.count.get() + 1);
        self.kept.push(e);
    }
}

/// The parser's user error type: the lexer reports its own errors, so the
/// parser never receives one.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Never {}

/// What the grammar's start rule produced. An action file is not here: the
/// grammar hands its parts to the parser's sink as soon as each is read.
#[derive(Debug)]
pub enum Parsed {
    File,
    Expr(Expr),
}

/// A part of an action file, as the grammar hands it over.
#[derive(Debug)]
pub enum Item {
    /// A statement before any `ACTION` header: the body of a file without
    /// headers, or a statement outside an action (E0016).
    Stmt(Stmt),
    Action(Action),
}

/// How deep statements may nest: IF, FOR, WHILE and REPEAT inside one
/// another. Every later stage walks the tree recursively, so the limit keeps
/// them (and dropping the tree) inside a thread's stack; see ADR 0007.
pub const MAX_NESTING: u16 = 100;

/// How deep an expression may be: operators, calls and offsets inside one
/// another. `1+1+...+1` is as deep as it has terms (operators associate to
/// the left); brackets alone add nothing.
pub const MAX_EXPR_DEPTH: u16 = 200;

/// Depth of a part that was too deep: it is already reported and cut off,
/// and every part around it is cut off silently.
const CUT: u16 = u16::MAX;

/// An expression with its depth, as the grammar builds it.
#[derive(Debug)]
pub struct Node {
    pub e: Box<Expr>,
    pub depth: u16,
}

/// A statement with its nesting depth (0 for a simple statement).
#[derive(Debug)]
pub struct SNode {
    pub s: Stmt,
    pub depth: u16,
}

/// A statement list with the deepest nesting in it.
#[derive(Debug, Default)]
pub struct Block {
    pub stmts: Vec<Stmt>,
    pub depth: u16,
}

impl Block {
    pub fn push(mut self, s: SNode) -> Block {
        self.depth = self.depth.max(s.depth);
        self.stmts.push(s.s);
        self
    }
}

/// A variable with the depth of its offsets.
#[derive(Debug)]
pub struct VarNode {
    pub v: Var,
    pub depth: u16,
}

/// A part after a variable's first name: `{offset}` or `.Name`.
#[derive(Debug)]
pub enum Suffix {
    Offset(Node, Span),
    Field(Name, Span),
}

/// Saturates an integer constant's magnitude at 2^31, so that a following
/// sign can still make `-2147483648`; [`Expr::int_value`] clips the rest.
pub fn clip(v: i64) -> i64 {
    v.min(1 << 31)
}

fn cut(span: Span) -> Node {
    Node { e: Box::new(Expr { kind: ExprKind::Error, span }), depth: CUT }
}

/// `Some(cut node)` when a node over children as deep as `deepest` would be
/// too deep; the first such node is reported. The children are dropped
/// here, and they are within the limit, so dropping them is bounded.
fn too_deep(syntax: &mut Capped<SyntaxError>, deepest: u16, span: Span) -> Option<Node> {
    if deepest == CUT {
        return Some(cut(span));
    }
    if deepest >= MAX_EXPR_DEPTH {
        syntax.push(SyntaxError::ExprTooDeep { span });
        return Some(cut(span));
    }
    None
}

/// A part the depth guard skipped (and reported): every part around it is
/// cut off silently.
pub fn skipped(span: Span) -> Node {
    cut(span)
}

/// Statements the depth guard skipped (and reported).
pub fn skipped_stmt(span: Span) -> SNode {
    SNode { s: Stmt::Error { span }, depth: CUT }
}

pub fn leaf(kind: ExprKind, l: usize, r: usize) -> Node {
    Node { e: Box::new(Expr { kind, span: Span::new(l, r) }), depth: 1 }
}

pub fn binary(syntax: &mut Capped<SyntaxError>, op: BinOp, a: Node, b: Node) -> Node {
    let span = a.e.span.to(b.e.span);
    let deepest = a.depth.max(b.depth);
    if let Some(c) = too_deep(syntax, deepest, span) {
        return c;
    }
    Node { e: Box::new(Expr { kind: ExprKind::Binary(op, a.e, b.e), span }), depth: deepest + 1 }
}

/// A chain of operands and binary operators being bound by precedence
/// (operator-precedence parsing inside the LR grammar). `pending` holds the
/// operators still waiting for their right operand, each with its left
/// one, binding more loosely towards the bottom; `last` is the latest
/// operand. A pending operator binds as soon as an operator of its own or a
/// looser level follows, so `pending` never holds more than one operator
/// per level (eight) and memory stays constant along any chain.
#[derive(Debug)]
pub struct Climb {
    pending: Vec<(BinOp, Node)>,
    last: Node,
}

impl Climb {
    pub fn new(first: Node) -> Climb {
        Climb { pending: Vec::new(), last: first }
    }

    pub fn push(self, syntax: &mut Capped<SyntaxError>, op: BinOp, operand: Node) -> Climb {
        let Climb { mut pending, last } = self.bind_while(syntax, |top| level(top) <= level(op));
        pending.push((op, last));
        Climb { pending, last: operand }
    }

    pub fn finish(self, syntax: &mut Capped<SyntaxError>) -> Node {
        self.bind_while(syntax, |_| true).last
    }

    fn bind_while(self, syntax: &mut Capped<SyntaxError>, binds: impl Fn(BinOp) -> bool) -> Climb {
        let Climb { mut pending, mut last } = self;
        while let Some((op, left)) = pending.pop_if(|(top, _)| binds(*top)) {
            last = binary(syntax, op, left, last);
        }
        Climb { pending, last }
    }
}

/// How loosely an operator binds: `**` tightest, OR loosest (§12.6).
fn level(op: BinOp) -> u8 {
    match op {
        BinOp::Pow => 2,
        BinOp::Mul | BinOp::Div | BinOp::Mod => 3,
        BinOp::Add | BinOp::Sub => 4,
        BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Gt | BinOp::Le | BinOp::Ge => 5,
        BinOp::And => 6,
        BinOp::Xor => 7,
        BinOp::Or => 8,
    }
}

pub fn unary(syntax: &mut Capped<SyntaxError>, op: UnOp, e: Node, span: Span) -> Node {
    if let Some(c) = too_deep(syntax, e.depth, span) {
        return c;
    }
    Node { e: Box::new(Expr { kind: ExprKind::Unary(op, e.e), span }), depth: e.depth + 1 }
}

/// Unary minus; a negated numeric constant is folded so that `-12345` and
/// `BY -2` are constants, and `-2147483648` fits.
pub fn negate(syntax: &mut Capped<SyntaxError>, e: Node, span: Span) -> Node {
    let folded = e.e.span.start == span.start + 1;
    match e.e.kind {
        ExprKind::Int(v) if folded => Node { e: Box::new(Expr { kind: ExprKind::Int(-v), span }), depth: 1 },
        ExprKind::Real(x) if folded => Node { e: Box::new(Expr { kind: ExprKind::Real(-x), span }), depth: 1 },
        _ => unary(syntax, UnOp::Neg, e, span),
    }
}

/// Parentheses only widen the span.
pub fn paren(mut e: Node, span: Span) -> Node {
    e.e.span = span;
    e
}

pub fn call(syntax: &mut Capped<SyntaxError>, name: &str, l: usize, nr: usize, args: Vec<Node>, span: Span) -> Node {
    let deepest = args.iter().map(|a| a.depth).max().unwrap_or(0);
    if let Some(c) = too_deep(syntax, deepest, span) {
        return c;
    }
    let name = Ident { text: name.into(), span: Span::new(l, nr) };
    let args = args.into_iter().map(|a| *a.e).collect();
    Node { e: Box::new(Expr { kind: ExprKind::Call { name, args }, span }), depth: deepest + 1 }
}

/// A variable as an operand.
pub fn var_leaf(v: VarNode, l: usize, r: usize) -> Node {
    Node { e: Box::new(Expr { kind: ExprKind::Var(v.v), span: Span::new(l, r) }), depth: v.depth }
}

/// A statement that holds statement lists as deep as `deepest` (IF, FOR,
/// WHILE, REPEAT), or a cut-off error statement if that is too deep.
pub fn compound(
    syntax: &mut Capped<SyntaxError>,
    keyword: (&'static str, Span),
    deepest: u16,
    span: Span,
    make: impl FnOnce() -> Stmt,
) -> SNode {
    if deepest == CUT {
        return SNode { s: Stmt::Error { span }, depth: CUT };
    }
    if deepest >= MAX_NESTING {
        syntax.push(SyntaxError::NestedTooDeep { span: keyword.1, keyword: keyword.0 });
        return SNode { s: Stmt::Error { span }, depth: CUT };
    }
    SNode { s: make(), depth: deepest + 1 }
}

/// A simple statement (assignment, EXIT, error).
pub fn simple(s: Stmt) -> SNode {
    SNode { s, depth: 0 }
}

/// Checks one identifier against §12.8.
fn check_ident(syntax: &mut Capped<SyntaxError>, text: &str, span: Span) {
    let first = text.chars().next();
    if first.map(|c| c.is_ascii_digit()).unwrap_or(true) {
        let why = if text.is_empty() { "empty name part" } else { "starts with a digit" };
        syntax.push(SyntaxError::InvalidName { span, name: text.to_string(), why });
    } else if text.len() > 8 && text.chars().count() > 8 {
        syntax.push(SyntaxError::NameTooLong { span, name: text.to_string() });
    }
}

/// Removes spaces and comments around a name part: a reported illegal
/// space such as `TIC_100 (*c*) .SL` leaves them inside the joined token.
fn strip_spaces(mut part: &str) -> &str {
    // Nearly every part is a plain identifier: nothing to strip.
    if part.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
        return part;
    }
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
fn split(syntax: &mut Capped<SyntaxError>, text: &str, at: usize, bracketed: bool) -> Vec<Seg> {
    let mut segs = Vec::with_capacity(1 + text.bytes().filter(|&b| b == b'.').count());
    let mut start = at;
    // Split on the byte: `str::split` with a char pattern costs more than
    // the rest of building the reference.
    for part in text.as_bytes().split(|&b| b == b'.') {
        // Cut at an ASCII dot, so each part is a whole UTF-8 sequence.
        let part = &text[part.as_ptr() as usize - text.as_ptr() as usize..][..part.len()];
        let name = if bracketed { part } else { strip_spaces(part) };
        let lead = if bracketed { 0 } else { name.as_ptr() as usize - part.as_ptr() as usize };
        let s = if bracketed { start } else { start + lead };
        let span = Span::new(s, s + name.len());
        if !bracketed {
            check_ident(syntax, name, span);
        }
        segs.push(Seg { name: Ident { text: name.into(), span }, offset: None });
        start += part.len() + 1;
    }
    segs
}

/// Builds a variable from its first token and suffixes.
pub fn var(
    syntax: &mut Capped<SyntaxError>,
    text: &str,
    (l, r): (usize, usize),
    bracketed: bool,
    suffixes: Vec<Suffix>,
) -> VarNode {
    let first = if bracketed { l + 1 } else { l };
    let before = syntax.total();
    let mut segs = split(syntax, text, first, bracketed);
    let mut end = r;
    let mut deepest = 0;
    for s in suffixes {
        match s {
            Suffix::Offset(e, span) => {
                end = span.end;
                deepest = deepest.max(e.depth);
                if let Some(last) = segs.last_mut() {
                    if last.offset.is_some() {
                        syntax.push(SyntaxError::DoubleOffset { span });
                    }
                    last.offset = Some(e.e);
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
    let span = Span::new(l, end);
    let mut depth = deepest.saturating_add(1);
    if deepest == CUT || deepest >= MAX_EXPR_DEPTH {
        if deepest != CUT {
            syntax.push(SyntaxError::ExprTooDeep { span });
        }
        for seg in &mut segs {
            if let Some(o) = &mut seg.offset {
                **o = Expr { kind: ExprKind::Error, span: o.span };
            }
        }
        depth = CUT;
    }
    VarNode { v: Var { segs, bracketed, span, malformed: syntax.total() > before || depth == CUT }, depth }
}

/// Validates an action header (§10.2.1) and builds the action.
pub fn action(
    syntax: &mut Capped<SyntaxError>,
    (nl, name, nr): (usize, &str, usize),
    block_type: Option<(usize, &str, usize)>,
    body: Vec<Stmt>,
    header: Span,
    span: Span,
) -> Action {
    let name_span = Span::new(nl, nr);
    if name.contains('.') || name.len() > 8 || name.starts_with(|c: char| c.is_ascii_digit()) {
        syntax.push(SyntaxError::BadActionName { span: name_span, name: name.to_string() });
    }
    let block_type = block_type.map(|(l, t, r)| Ident { text: t.into(), span: Span::new(l, r) });
    Action { name: Ident { text: name.into(), span: name_span }, block_type, body, header: Some(header), span }
}

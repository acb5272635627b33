//! The syntax tree of a ladder file: actions made of rungs. Contacts,
//! coil targets and variable outputs hold ST syntax trees (the ST parser
//! reads them), with spans in the `.ld` file.

use crate::diag::span::Span;
use crate::st::ast::{Expr, Ident, Stmt};

/// A `.ld` file: its actions (one, named after the file, without headers).
#[derive(Clone, Debug, PartialEq)]
pub struct File {
    pub actions: Vec<Action>,
}

/// `ACTION name [: BLOCKTYPE] rungs END_ACTION`, or a whole file of rungs.
#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub name: Ident,
    pub block_type: Option<Ident>,
    pub rungs: Vec<Rung>,
    pub header: Option<Span>,
    pub span: Span,
}

/// `[label:] [condition] -> output;`
#[derive(Clone, Debug, PartialEq)]
pub struct Rung {
    pub label: Option<Ident>,
    /// `None`: the output is wired straight to the left rail (always TRUE).
    pub cond: Option<Cond>,
    pub output: Output,
    pub span: Span,
}

/// The condition of a rung.
#[derive(Clone, Debug, PartialEq)]
pub enum Cond {
    /// `[x]` or `[/x]`; `expr` is the ST expression between the brackets.
    Contact { negated: bool, expr: Expr, span: Span },
    /// Juxtaposed elements: wired AND.
    Series(Vec<Cond>),
    /// `( a | b | … )`: wired OR (one branch is a plain group).
    Parallel(Vec<Cond>, Span),
    /// `AND(…)`, `OR(…)`, `XOR(…)`, `NOT(…)`.
    Box { op: BoxOp, args: Vec<Cond>, span: Span },
}

impl Cond {
    pub fn span(&self) -> Span {
        match self {
            Cond::Contact { span, .. } | Cond::Parallel(_, span) | Cond::Box { span, .. } => *span,
            Cond::Series(v) => match (v.first(), v.last()) {
                (Some(a), Some(b)) => a.span().to(b.span()),
                _ => Span::default(),
            },
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BoxOp {
    And,
    Or,
    Xor,
    Not,
}

impl BoxOp {
    pub fn name(self) -> &'static str {
        match self {
            BoxOp::And => "AND",
            BoxOp::Or => "OR",
            BoxOp::Xor => "XOR",
            BoxOp::Not => "NOT",
        }
    }
}

/// The four coils of §11.1.1.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoilKind {
    /// `(x)`: writes the rung's value.
    Normal,
    /// `(/x)`: writes its negation.
    Negated,
    /// `(S x)`: writes TRUE when the rung is TRUE.
    Set,
    /// `(R x)`: writes FALSE when the rung is TRUE.
    Reset,
}

/// What a rung does.
#[derive(Clone, Debug, PartialEq)]
pub enum Output {
    /// `target` is an ST expression, a variable once checked (E0309).
    Coil {
        kind: CoilKind,
        target: Expr,
        span: Span,
    },
    Jump {
        label: Ident,
        span: Span,
    },
    /// `target := expression`, an ST assignment.
    Assign(Stmt),
}

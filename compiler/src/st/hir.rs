//! The checked program: the syntax tree with every name resolved and every
//! expression typed. The checker builds it; the lowering to instructions
//! reads only this, never the syntax tree.

use crate::diag::span::Span;
use crate::st::ast::{BinOp, Name};
use linc_format::object::Class;
use linc_stdlib::Ty;

#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    pub actions: Vec<Action>,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub name: String,
    pub block_type: Option<String>,
    pub body: Vec<Stmt>,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    Assign {
        place: Place,
        value: Expr,
        span: Span,
    },
    If {
        arms: Vec<(Expr, Vec<Stmt>)>,
        otherwise: Vec<Stmt>,
        span: Span,
    },
    For {
        place: Place,
        from: Expr,
        to: Expr,
        by: Option<Expr>,
        body: Vec<Stmt>,
        span: Span,
    },
    While {
        cond: Expr,
        body: Vec<Stmt>,
        span: Span,
    },
    Repeat {
        body: Vec<Stmt>,
        until: Expr,
        span: Span,
    },
    Exit {
        span: Span,
    },
    /// Something already reported; a program holding one is not lowered.
    Error {
        span: Span,
    },
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub ty: Ty,
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    Int(i32),
    Real(f32),
    Bool(bool),
    /// A string constant, `$`-sequences as written.
    Str(Vec<u8>),
    Load(Box<Place>),
    Neg(Box<Expr>),
    Not(Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    /// A library function by its index in `linc_stdlib::SIGNATURES`.
    Call {
        index: usize,
        args: Vec<Expr>,
    },
    Error,
}

/// A resolved reference to something in the database.
#[derive(Clone, Debug, PartialEq)]
pub struct Place {
    pub ty: Ty,
    /// Storage class of the field (None for step variables and unknowns).
    pub class: Option<Class>,
    pub target: Target,
    /// Allowed values of an ENUM field.
    pub enum_values: Option<Vec<String>>,
    /// As written, for messages: set for step variables, unknown names and
    /// enumerated fields, the references a message may name; empty for
    /// the others, which saves an allocation per reference.
    pub path: String,
    pub span: Span,
}

/// Which cell (and which part of it). An empty `block` is the block that
/// runs the action.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    Field {
        block: Name,
        field: Name,
        offset: Option<Box<Expr>>,
    },
    Bit {
        block: Name,
        field: Name,
        offset: Option<Box<Expr>>,
        bit: u8,
        bit_offset: Option<Box<Expr>>,
    },
    Alarm {
        block: Name,
        field: Name,
        alarm: Name,
    },
    Suppress {
        block: Name,
        field: Name,
        alarm: Option<Name>,
    },
    Step {
        step: Name,
        x: bool,
    },
    /// Not resolved (no database was given).
    Unknown,
}

impl Expr {
    pub fn error(span: Span) -> Expr {
        Expr { ty: Ty::Any, kind: ExprKind::Error, span }
    }
}

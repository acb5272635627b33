//! The syntax tree of LIN Structured Text.
//!
//! The tree keeps every name as written, with its span, so that later stages
//! can point at any part of a reference. Nodes that failed to parse are kept
//! as `Error` so the checker can go on past them.

use crate::diag::span::Span;

/// A name as the tree and the checked program hold it: inline up to 24
/// bytes, so no allocation for any LIN name (eight characters at most).
pub type Name = compact_str::CompactString;

/// A source file: one or more named actions (§10.2.1).
#[derive(Clone, Debug, PartialEq)]
pub struct SourceFile {
    pub actions: Vec<Action>,
}

/// `ACTION name [: BLOCKTYPE] ... END_ACTION`, or the whole of a file that
/// has no headers (then `header` is `None` and the name is the file's stem).
#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub name: Ident,
    pub block_type: Option<Ident>,
    pub body: Vec<Stmt>,
    pub header: Option<Span>,
    pub span: Span,
}

/// A name as written, with its place.
#[derive(Clone, Debug, PartialEq)]
pub struct Ident {
    pub text: Name,
    pub span: Span,
}

/// A statement. Expressions and the FOR loop variable are boxed so that a
/// statement is small: the parser moves statements on its stack, and lists
/// of simple statements are the bulk of a file.
#[derive(Clone, Debug, PartialEq)]
pub enum Stmt {
    Assign {
        target: Var,
        value: Box<Expr>,
        span: Span,
    },
    If {
        arms: Vec<(Expr, Vec<Stmt>)>,
        otherwise: Option<Vec<Stmt>>,
        span: Span,
    },
    For {
        var: Box<Var>,
        from: Box<Expr>,
        to: Box<Expr>,
        by: Option<Box<Expr>>,
        body: Vec<Stmt>,
        span: Span,
    },
    While {
        cond: Box<Expr>,
        body: Vec<Stmt>,
        span: Span,
    },
    Repeat {
        body: Vec<Stmt>,
        until: Box<Expr>,
        span: Span,
    },
    Exit {
        span: Span,
    },
    /// A statement that did not parse; its error is already reported.
    Error {
        span: Span,
    },
}

impl Stmt {
    pub fn span(&self) -> Span {
        match self {
            Stmt::Assign { span, .. }
            | Stmt::If { span, .. }
            | Stmt::For { span, .. }
            | Stmt::While { span, .. }
            | Stmt::Repeat { span, .. }
            | Stmt::Exit { span }
            | Stmt::Error { span } => *span,
        }
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct Expr {
    pub kind: ExprKind,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ExprKind {
    /// An integer constant as written; `2147483648` without a sign is the
    /// one value outside 32 bits, and [`Expr::int_value`] clips it (§12.9).
    Int(i64),
    Real(f64),
    /// A time constant, in seconds.
    Time(f64),
    Bool(bool),
    /// String constant text between the quotes, `$`-sequences as written.
    Str(String),
    Var(Var),
    Unary(UnOp, Box<Expr>),
    Binary(BinOp, Box<Expr>, Box<Expr>),
    Call {
        name: Ident,
        args: Vec<Expr>,
    },
    Error,
}

impl Expr {
    /// The value of an integer constant, clipped to 32 bits.
    pub fn int_value(&self) -> Option<i32> {
        match self.kind {
            ExprKind::Int(v) => Some(v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32),
            _ => None,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnOp {
    Neg,
    Not,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinOp {
    Pow,
    Mul,
    Div,
    Mod,
    Add,
    Sub,
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
    And,
    Xor,
    Or,
}

impl BinOp {
    pub fn symbol(self) -> &'static str {
        match self {
            BinOp::Pow => "**",
            BinOp::Mul => "*",
            BinOp::Div => "/",
            BinOp::Mod => "MOD",
            BinOp::Add => "+",
            BinOp::Sub => "-",
            BinOp::Eq => "=",
            BinOp::Ne => "<>",
            BinOp::Lt => "<",
            BinOp::Gt => ">",
            BinOp::Le => "<=",
            BinOp::Ge => ">=",
            BinOp::And => "AND",
            BinOp::Xor => "XOR",
            BinOp::Or => "OR",
        }
    }

    pub fn is_comparison(self) -> bool {
        matches!(self, BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Gt | BinOp::Le | BinOp::Ge)
    }
}

/// A variable reference: dotted segments, each of which may carry an offset.
///
/// `Block.Field{e}.Bit0` is three segments with an offset on `Field`;
/// `[DG_CONN3.W Field2.Bit6]` is bracketed and its segments may hold any
/// characters but `.`.
#[derive(Clone, Debug, PartialEq)]
pub struct Var {
    pub segs: Vec<Seg>,
    pub bracketed: bool,
    pub span: Span,
    /// A name part broke the identifier rules; that is already reported, so
    /// later stages stay quiet about this reference.
    pub malformed: bool,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Seg {
    pub name: Ident,
    pub offset: Option<Box<Expr>>,
}

impl Var {
    /// The reference as written, without offsets: `PIC_004.PV`.
    pub fn path(&self) -> String {
        // Built in one allocation: the checker asks for every reference's path.
        let len = self.segs.iter().map(|s| s.name.text.len() + 1).sum();
        let mut out = String::with_capacity(len);
        for (i, s) in self.segs.iter().enumerate() {
            if i > 0 {
                out.push('.');
            }
            out.push_str(&s.name.text);
        }
        out
    }
}

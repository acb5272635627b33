//! Typing of expressions and function calls.

use super::errors::CheckError;
use super::Checker;
use crate::ast::{BinOp, Expr, ExprKind, UnOp};
use linc_stdlib::{lookup, Param, Ty, SIGNATURES};

impl Checker<'_> {
    /// The type of an expression; errors are reported and give `Any`.
    pub(super) fn expr(&mut self, e: &Expr) -> Ty {
        match &e.kind {
            ExprKind::Int(_) => Ty::Int,
            ExprKind::Real(_) | ExprKind::Time(_) => Ty::Real,
            ExprKind::Bool(_) => Ty::Bool,
            ExprKind::Str(_) => Ty::Text,
            ExprKind::Error => Ty::Any,
            ExprKind::Var(v) => self.resolve(v).map(|r| r.ty).unwrap_or(Ty::Any),
            ExprKind::Unary(op, a) => {
                let t = self.expr(a);
                match op {
                    UnOp::Neg if t.is_numeric() => {
                        if t == Ty::Bool {
                            Ty::Int
                        } else {
                            t
                        }
                    }
                    UnOp::Not if t.is_integral() => Ty::Bool,
                    _ => {
                        let (op, help) = match op {
                            UnOp::Neg => ("-", "only numbers can be negated"),
                            UnOp::Not => ("NOT", "NOT applies to BOOL or INT values"),
                        };
                        self.errors.push(CheckError::OperandTypes {
                            span: e.span,
                            op: op.into(),
                            left: t.name().into(),
                            right: None,
                            help,
                        });
                        Ty::Any
                    }
                }
            }
            ExprKind::Binary(op, a, b) => self.binary(*op, a, b, e),
            ExprKind::Call { name, args } => self.call(&name.text, name.span, args, e),
        }
    }

    fn binary(&mut self, op: BinOp, a: &Expr, b: &Expr, whole: &Expr) -> Ty {
        let ta = self.expr(a);
        let tb = self.expr(b);
        if ta == Ty::Any && tb == Ty::Any {
            return if op.is_comparison() {
                Ty::Bool
            } else {
                Ty::Any
            };
        }
        let mismatch = |help: &'static str| CheckError::OperandTypes {
            span: whole.span,
            op: op.symbol().into(),
            left: ta.name().into(),
            right: Some(tb.name().into()),
            help,
        };
        match op {
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div | BinOp::Pow => {
                if !(ta.is_numeric() && tb.is_numeric()) {
                    let help = if op == BinOp::Add && ta.is_stringy() && tb.is_stringy() {
                        "join strings with CONCAT(A, B)"
                    } else {
                        "arithmetic needs numbers; use SCAN to read a number from a string"
                    };
                    self.errors.push(mismatch(help));
                    return Ty::Any;
                }
                if op == BinOp::Pow || ta == Ty::Real || tb == Ty::Real {
                    Ty::Real
                } else if ta == Ty::Any || tb == Ty::Any {
                    Ty::Any
                } else {
                    Ty::Int
                }
            }
            BinOp::Mod => {
                for (t, e) in [(ta, a), (tb, b)] {
                    if !t.is_integral() {
                        self.errors.push(CheckError::ModNotInteger {
                            span: e.span,
                            found: t.name().into(),
                        });
                        return Ty::Any;
                    }
                }
                Ty::Int
            }
            BinOp::And | BinOp::Or | BinOp::Xor => {
                if !(ta.is_integral() && tb.is_integral()) {
                    self.errors.push(mismatch(
                        "AND, OR and XOR take BOOL values, or INT values bit by bit (16 bits)",
                    ));
                    return Ty::Any;
                }
                if ta == Ty::Bool && tb == Ty::Bool {
                    Ty::Bool
                } else if ta == Ty::Any || tb == Ty::Any {
                    Ty::Any
                } else {
                    Ty::Int
                }
            }
            _ => {
                let ok =
                    (ta.is_numeric() && tb.is_numeric()) || (ta.is_stringy() && tb.is_stringy());
                if !ok {
                    self.errors.push(mismatch(
                        "compare numbers with numbers and strings with strings",
                    ));
                } else {
                    self.enum_comparison(a, b);
                    self.enum_comparison(b, a);
                }
                Ty::Bool
            }
        }
    }

    /// `PIC_004.Mode = "CASCADE"`: the constant must be one of the values.
    fn enum_comparison(&mut self, field: &Expr, constant: &Expr) {
        let (ExprKind::Var(v), ExprKind::Str(s)) = (&field.kind, &constant.kind) else {
            return;
        };
        let before = self.errors.len();
        let r = self.resolve(v);
        // The variable was already resolved once; drop repeated errors.
        self.errors.truncate(before);
        if let Some(values) = r.and_then(|r| r.enum_values) {
            self.enum_literal(&values, s, constant.span, v.path());
        }
    }

    fn call(&mut self, name: &str, name_span: crate::Span, args: &[Expr], whole: &Expr) -> Ty {
        let types: Vec<Ty> = args.iter().map(|a| self.expr(a)).collect();
        let Some(sig) = lookup(name) else {
            let suggestion = suggest(name);
            self.errors.push(CheckError::UnknownFunction {
                span: name_span,
                name: name.to_string(),
                suggestion,
            });
            return Ty::Any;
        };
        if !sig.arity_ok(args.len()) {
            self.errors.push(CheckError::WrongArity {
                span: whole.span,
                name: sig.name.to_string(),
                found: args.len(),
                signature: sig.to_string(),
            });
            return sig.result(&types, None);
        }
        for (i, (a, t)) in args.iter().zip(&types).enumerate() {
            if let Some(p) = sig.param(i) {
                if !p.accepts(*t) {
                    let expected = match p {
                        Param::Bytes => "a string",
                        Param::Int => "an integer",
                        Param::Bool => "a boolean",
                        Param::Num => "a number",
                    };
                    self.errors.push(CheckError::WrongArgType {
                        span: a.span,
                        index: i,
                        found: t.name().into(),
                        expected: expected.into(),
                        signature: sig.to_string(),
                    });
                }
            }
        }
        let scan_format = match args.first().map(|a| &a.kind) {
            Some(ExprKind::Str(s)) => Some(s.as_bytes()),
            _ => None,
        };
        sig.result(&types, scan_format)
    }
}

/// The function whose name is closest to `name`, if close enough.
fn suggest(name: &str) -> Option<String> {
    let upper = name.to_ascii_uppercase();
    SIGNATURES
        .iter()
        .map(|s| (distance(&upper, s.name), s.name))
        .filter(|(d, n)| *d <= 2.max(n.len() / 4))
        .min_by_key(|(d, _)| *d)
        .map(|(_, n)| n.to_string())
}

/// Levenshtein distance over bytes.
fn distance(a: &str, b: &str) -> usize {
    let b = b.as_bytes();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.bytes().enumerate() {
        let mut prev = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let cur = row[j + 1];
            row[j + 1] = (prev + usize::from(ca != *cb)).min(row[j] + 1).min(cur + 1);
            prev = cur;
        }
    }
    row[b.len()]
}

//! Typing of expressions and function calls.

use super::errors::CheckError;
use super::Checker;
use crate::st::ast::{BinOp, Expr, ExprKind, UnOp};
use crate::st::hir;
use linc_stdlib::signatures::index_of;
use linc_stdlib::{Param, Ty, SIGNATURES};

impl Checker<'_> {
    /// Types an expression; errors are reported and give `Any`.
    ///
    /// The walk recurses through `expr` and `binary`/`unary`/`load`/`call`
    /// only; what happens after the recursion (typing, errors) is in other
    /// functions, so the frames on the recursion path stay small.
    pub(super) fn expr(&mut self, e: &Expr) -> hir::Expr {
        let (ty, kind) = match &e.kind {
            ExprKind::Int(_) => (Ty::Int, hir::ExprKind::Int(e.int_value().unwrap_or_default())),
            ExprKind::Real(x) => (Ty::Real, hir::ExprKind::Real(*x as f32)),
            ExprKind::Time(x) => (Ty::Real, hir::ExprKind::Real(*x as f32)),
            ExprKind::Bool(b) => (Ty::Bool, hir::ExprKind::Bool(*b)),
            ExprKind::Str(s) => (Ty::Text, hir::ExprKind::Str(s.as_bytes().to_vec())),
            ExprKind::Error => (Ty::Any, hir::ExprKind::Error),
            ExprKind::Var(v) => self.load(v),
            ExprKind::Unary(op, a) => self.unary(*op, a, e.span),
            ExprKind::Binary(op, a, b) => self.binary(*op, a, b, e),
            ExprKind::Call { name, args } => self.call(&name.text, name.span, args, e),
        };
        hir::Expr { ty, kind, span: e.span }
    }

    fn load(&mut self, v: &crate::st::ast::Var) -> (Ty, hir::ExprKind) {
        let checked = self.offsets(v);
        self.load_checked(v, checked)
    }

    fn load_checked(&mut self, v: &crate::st::ast::Var, checked: Vec<Option<hir::Expr>>) -> (Ty, hir::ExprKind) {
        match self.resolve_checked(v, checked) {
            Some(r) => (r.ty(), hir::ExprKind::Load(Box::new(r.place))),
            None => (Ty::Any, hir::ExprKind::Error),
        }
    }

    fn unary(&mut self, op: UnOp, a: &Expr, span: crate::Span) -> (Ty, hir::ExprKind) {
        let a = self.expr(a);
        self.unary_node(op, a, span)
    }

    fn unary_node(&mut self, op: UnOp, a: hir::Expr, span: crate::Span) -> (Ty, hir::ExprKind) {
        let t = a.ty;
        match op {
            UnOp::Neg if t.is_numeric() => {
                let ty = if t == Ty::Bool { Ty::Int } else { t };
                (ty, hir::ExprKind::Neg(Box::new(a)))
            }
            UnOp::Not if t.is_integral() => (Ty::Bool, hir::ExprKind::Not(Box::new(a))),
            _ => {
                let (op, help) = match op {
                    UnOp::Neg => ("-", "only numbers can be negated"),
                    UnOp::Not => ("NOT", "NOT applies to BOOL or INT values"),
                };
                let left = t.name().into();
                self.errors.push(CheckError::OperandTypes { span, op: op.into(), left, right: None, help });
                (Ty::Any, hir::ExprKind::Error)
            }
        }
    }

    fn binary(&mut self, op: BinOp, a: &Expr, b: &Expr, whole: &Expr) -> (Ty, hir::ExprKind) {
        let ha = self.expr(a);
        let hb = self.expr(b);
        self.binary_node(op, ha, hb, (a.span, b.span, whole.span))
    }

    /// Types `a op b` once both sides are checked.
    fn binary_node(
        &mut self,
        op: BinOp,
        ha: hir::Expr,
        hb: hir::Expr,
        (a_span, b_span, whole): (crate::Span, crate::Span, crate::Span),
    ) -> (Ty, hir::ExprKind) {
        let (ta, tb) = (ha.ty, hb.ty);
        let node = |ha, hb| hir::ExprKind::Binary(op, Box::new(ha), Box::new(hb));
        if ta == Ty::Any && tb == Ty::Any {
            let ty = if op.is_comparison() { Ty::Bool } else { Ty::Any };
            return (ty, node(ha, hb));
        }
        let mismatch = |help: &'static str| CheckError::OperandTypes {
            span: whole,
            op: op.symbol().into(),
            left: ta.name().into(),
            right: Some(tb.name().into()),
            help,
        };
        let ty = match op {
            BinOp::Add | BinOp::Sub | BinOp::Mul | BinOp::Div | BinOp::Pow => {
                if !(ta.is_numeric() && tb.is_numeric()) {
                    let help = if op == BinOp::Add && ta.is_stringy() && tb.is_stringy() {
                        "join strings with CONCAT(A, B)"
                    } else {
                        "arithmetic needs numbers; use SCAN to read a number from a string"
                    };
                    self.errors.push(mismatch(help));
                    return (Ty::Any, hir::ExprKind::Error);
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
                for (t, span) in [(ta, a_span), (tb, b_span)] {
                    if !t.is_integral() {
                        self.errors.push(CheckError::ModNotInteger { span, found: t.name().into() });
                        return (Ty::Any, hir::ExprKind::Error);
                    }
                }
                Ty::Int
            }
            BinOp::And | BinOp::Or | BinOp::Xor => {
                if !(ta.is_integral() && tb.is_integral()) {
                    self.errors.push(mismatch("AND, OR and XOR take BOOL values, or INT values bit by bit (16 bits)"));
                    return (Ty::Any, hir::ExprKind::Error);
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
                let ok = (ta.is_numeric() && tb.is_numeric()) || (ta.is_stringy() && tb.is_stringy());
                if !ok {
                    self.errors.push(mismatch("compare numbers with numbers and strings with strings"));
                    return (Ty::Bool, hir::ExprKind::Error);
                }
                self.enum_comparison(&ha, &hb);
                self.enum_comparison(&hb, &ha);
                Ty::Bool
            }
        };
        (ty, node(ha, hb))
    }

    /// `PIC_004.Mode = "CASCADE"`: the constant must be one of the values.
    fn enum_comparison(&mut self, field: &hir::Expr, constant: &hir::Expr) {
        if let (hir::ExprKind::Load(p), hir::ExprKind::Str(s)) = (&field.kind, &constant.kind) {
            if let Some(values) = &p.enum_values {
                self.enum_literal(values, s, constant.span, p.path.clone());
            }
        }
    }

    fn call(&mut self, name: &str, name_span: crate::Span, args: &[Expr], whole: &Expr) -> (Ty, hir::ExprKind) {
        let mut hargs: Vec<hir::Expr> = Vec::with_capacity(args.len());
        for a in args {
            hargs.push(self.expr(a));
        }
        self.call_node(name, name_span, args, hargs, whole)
    }

    /// Types a call once its arguments are checked.
    fn call_node(
        &mut self,
        name: &str,
        name_span: crate::Span,
        args: &[Expr],
        hargs: Vec<hir::Expr>,
        whole: &Expr,
    ) -> (Ty, hir::ExprKind) {
        let types: Vec<Ty> = hargs.iter().map(|a| a.ty).collect();
        let Some(index) = index_of(name) else {
            let suggestion = suggest(name);
            self.errors.push(CheckError::UnknownFunction { span: name_span, name: name.to_string(), suggestion });
            return (Ty::Any, hir::ExprKind::Error);
        };
        let sig = &SIGNATURES[index];
        self.ctx.note(name_span, || crate::names::Meaning::Function(sig));
        if !sig.arity_ok(args.len()) {
            self.errors.push(CheckError::WrongArity {
                span: whole.span,
                name: sig.name.to_string(),
                found: args.len(),
                signature: sig.to_string(),
            });
            return (sig.result(&types, None), hir::ExprKind::Error);
        }
        if args.len() > super::MAX_CALL_ARGS {
            let span = args[super::MAX_CALL_ARGS].span.to(args[args.len() - 1].span);
            self.count_call_args(args.len(), span);
            return (sig.result(&types, None), hir::ExprKind::Error);
        }
        let mut ok = true;
        for (i, (a, t)) in args.iter().zip(&types).enumerate() {
            if let Some(p) = sig.param(i) {
                if !p.accepts(*t) {
                    ok = false;
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
        let mut ty = sig.result(&types, scan_format);
        if ty == Ty::Any && sig.name == "SCAN" {
            // A format only known at run time: the value is read as REAL.
            ty = Ty::Real;
        }
        if !ok {
            return (ty, hir::ExprKind::Error);
        }
        (ty, hir::ExprKind::Call { index, args: hargs })
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
pub(crate) fn distance(a: &str, b: &str) -> usize {
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

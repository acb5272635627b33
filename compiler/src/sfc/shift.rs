//! Moves spans found in a slice of the file to their place in the file.
//!
//! The ST inside a sequence (action bodies, transition conditions) is read by
//! the ST parser from a slice of the text, so everything it reports is
//! relative to that slice; adding the slice's start makes every diagnostic
//! and every node point into the `.sfc` file.

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use crate::st::ast::{Action, Expr, ExprKind, Ident, Stmt, Var};

fn span(s: &mut Span, by: usize) {
    s.start += by;
    s.end += by;
}

fn ident(i: &mut Ident, by: usize) {
    span(&mut i.span, by);
}

pub fn diagnostic(d: &mut Diagnostic, by: usize) {
    span(&mut d.span, by);
    for l in &mut d.secondary {
        span(&mut l.span, by);
    }
}

pub fn action(a: &mut Action, by: usize) {
    ident(&mut a.name, by);
    if let Some(t) = &mut a.block_type {
        ident(t, by);
    }
    if let Some(h) = &mut a.header {
        span(h, by);
    }
    span(&mut a.span, by);
    stmts(&mut a.body, by);
}

fn stmts(list: &mut [Stmt], by: usize) {
    for s in list {
        stmt(s, by);
    }
}

fn stmt(s: &mut Stmt, by: usize) {
    match s {
        Stmt::Assign { target, value, span: sp } => {
            var(target, by);
            expr(value, by);
            span(sp, by);
        }
        Stmt::If { arms, otherwise, span: sp } => {
            for (c, b) in arms {
                expr(c, by);
                stmts(b, by);
            }
            if let Some(b) = otherwise {
                stmts(b, by);
            }
            span(sp, by);
        }
        Stmt::For { var: v, from, to, by: step, body, span: sp } => {
            var(v, by);
            expr(from, by);
            expr(to, by);
            if let Some(e) = step {
                expr(e, by);
            }
            stmts(body, by);
            span(sp, by);
        }
        Stmt::While { cond, body, span: sp } | Stmt::Repeat { until: cond, body, span: sp } => {
            expr(cond, by);
            stmts(body, by);
            span(sp, by);
        }
        Stmt::Exit { span: sp } | Stmt::Error { span: sp } => span(sp, by),
    }
}

/// Shifts an expression. Operands are walked with an explicit stack, as an
/// expression may be as deep as the parser allows.
pub fn expr(e: &mut Expr, by: usize) {
    let mut todo = vec![e];
    while let Some(e) = todo.pop() {
        span(&mut e.span, by);
        match &mut e.kind {
            ExprKind::Var(v) => var(v, by),
            ExprKind::Unary(_, a) => todo.push(a),
            ExprKind::Binary(_, a, b) => {
                todo.push(a);
                todo.push(b);
            }
            ExprKind::Call { name, args } => {
                ident(name, by);
                todo.extend(args.iter_mut());
            }
            _ => {}
        }
    }
}

fn var(v: &mut Var, by: usize) {
    span(&mut v.span, by);
    for s in &mut v.segs {
        ident(&mut s.name, by);
        if let Some(o) = &mut s.offset {
            expr(o, by);
        }
    }
}

//! Every variable reference of a sequence, in source order: what the
//! generic-name tools (`generic.rs`) read and rewrite.
//!
//! The sequence tree keeps file spans (see `shift.rs`), so a reference's
//! name parts point into the `.sfc` text and can be replaced there, leaving
//! comments and layout as they were.

use super::ast::{ActionBody, Sequence};
use crate::st::ast::{Expr, ExprKind, Stmt, Var};

/// The references of every ST action and transition condition (nested
/// charts included), offsets' references too, sorted by position.
pub fn references(seq: &Sequence) -> Vec<&Var> {
    let mut out = Vec::new();
    for a in &seq.actions {
        match &a.body {
            ActionBody::St(st) => stmts(&st.body, &mut out),
            ActionBody::Chart(c) => conditions(c, &mut out),
        }
    }
    conditions(&seq.chart, &mut out);
    out.sort_by_key(|v| (v.span.start, v.span.end));
    out
}

fn conditions<'a>(c: &'a super::ast::Chart, out: &mut Vec<&'a Var>) {
    for cond in c.transitions.iter().filter_map(|t| t.cond.as_ref()) {
        expr(cond, out);
    }
}

/// Statements, walked with an explicit stack (bodies nest as deep as the
/// parser allows).
fn stmts<'a>(list: &'a [Stmt], out: &mut Vec<&'a Var>) {
    let mut todo: Vec<&'a Stmt> = list.iter().rev().collect();
    while let Some(s) = todo.pop() {
        match s {
            Stmt::Assign { target, value, .. } => {
                var(target, out);
                expr(value, out);
            }
            Stmt::If { arms, otherwise, .. } => {
                for (c, b) in arms {
                    expr(c, out);
                    todo.extend(b.iter());
                }
                todo.extend(otherwise.iter().flatten());
            }
            Stmt::For { var: v, from, to, by, body, .. } => {
                var(v, out);
                expr(from, out);
                expr(to, out);
                if let Some(e) = by {
                    expr(e, out);
                }
                todo.extend(body.iter());
            }
            Stmt::While { cond, body, .. } | Stmt::Repeat { until: cond, body, .. } => {
                expr(cond, out);
                todo.extend(body.iter());
            }
            Stmt::Exit { .. } | Stmt::Error { .. } => {}
        }
    }
}

/// An expression's references, with an explicit stack.
fn expr<'a>(e: &'a Expr, out: &mut Vec<&'a Var>) {
    let mut todo = vec![e];
    while let Some(e) = todo.pop() {
        match &e.kind {
            ExprKind::Var(v) => {
                out.push(v);
                todo.extend(v.segs.iter().filter_map(|s| s.offset.as_deref()));
            }
            ExprKind::Unary(_, a) => todo.push(a),
            ExprKind::Binary(_, a, b) => {
                todo.push(a);
                todo.push(b);
            }
            ExprKind::Call { args, .. } => todo.extend(args.iter()),
            _ => {}
        }
    }
}

fn var<'a>(v: &'a Var, out: &mut Vec<&'a Var>) {
    out.push(v);
    for o in v.segs.iter().filter_map(|s| s.offset.as_deref()) {
        expr(o, out);
    }
}

/// Calls `f` on every reference, mutably (to clear `malformed` of one whose
/// only fault was a generic name's length). References in offsets come
/// after the reference holding them.
pub fn for_each_mut(seq: &mut Sequence, f: &mut dyn FnMut(&mut Var)) {
    let mut exprs: Vec<&mut Expr> = Vec::new();
    let mut todo: Vec<&mut Stmt> = Vec::new();
    for a in &mut seq.actions {
        match &mut a.body {
            ActionBody::St(st) => todo.extend(st.body.iter_mut()),
            ActionBody::Chart(c) => exprs.extend(c.transitions.iter_mut().filter_map(|t| t.cond.as_mut())),
        }
    }
    exprs.extend(seq.chart.transitions.iter_mut().filter_map(|t| t.cond.as_mut()));
    while let Some(s) = todo.pop() {
        match s {
            Stmt::Assign { target, value, .. } => {
                var_mut(target, f, &mut exprs);
                exprs.push(value);
            }
            Stmt::If { arms, otherwise, .. } => {
                for (c, b) in arms {
                    exprs.push(c);
                    todo.extend(b.iter_mut());
                }
                todo.extend(otherwise.iter_mut().flatten());
            }
            Stmt::For { var: v, from, to, by, body, .. } => {
                var_mut(v, f, &mut exprs);
                exprs.push(from);
                exprs.push(to);
                exprs.extend(by.as_deref_mut());
                todo.extend(body.iter_mut());
            }
            Stmt::While { cond, body, .. } | Stmt::Repeat { until: cond, body, .. } => {
                exprs.push(cond);
                todo.extend(body.iter_mut());
            }
            Stmt::Exit { .. } | Stmt::Error { .. } => {}
        }
    }
    while let Some(e) = exprs.pop() {
        match &mut e.kind {
            ExprKind::Var(v) => var_mut(v, f, &mut exprs),
            ExprKind::Unary(_, a) => exprs.push(a),
            ExprKind::Binary(_, a, b) => {
                exprs.push(a);
                exprs.push(b);
            }
            ExprKind::Call { args, .. } => exprs.extend(args.iter_mut()),
            _ => {}
        }
    }
}

fn var_mut<'a>(v: &'a mut Var, f: &mut dyn FnMut(&mut Var), exprs: &mut Vec<&'a mut Expr>) {
    f(v);
    exprs.extend(v.segs.iter_mut().filter_map(|s| s.offset.as_deref_mut()));
}

//! Every variable reference of a sequence, in source order: what the
//! generic-name tools (`generic.rs`) read and rewrite.
//!
//! The sequence tree keeps file spans (see `shift.rs`), so a reference's
//! name parts point into the `.sfc` text and can be replaced there, leaving
//! comments and layout as they were.

use super::ast::{ActionBody, Sequence};
use crate::ast::{Expr, ExprKind, Stmt, Var};

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

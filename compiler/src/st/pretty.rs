//! A compact S-expression view of the syntax tree.
//!
//! Conformance snapshots and `linc check --tree` use it: it shows exactly how
//! a text was grouped (precedence, offsets, ELSIF arms) without spans.
//! Control characters in strings and bracketed names are escaped (`\u{1b}`),
//! as in diagnostics, so the tree is safe to print to a terminal.

use crate::diag::render::escape;
use crate::st::ast::{Action, Expr, ExprKind, SourceFile, Stmt, UnOp, Var};
use std::fmt::Write;

pub fn file(f: &SourceFile) -> String {
    let mut out = String::new();
    for a in &f.actions {
        action(&mut out, a);
    }
    out
}

fn action(out: &mut String, a: &Action) {
    let _ = write!(out, "(action {}", escape(&a.name.text));
    if let Some(t) = &a.block_type {
        let _ = write!(out, " : {}", t.text);
    }
    out.push('\n');
    stmts(out, &a.body, 1);
    out.push_str(")\n");
}

fn indent(out: &mut String, depth: usize) {
    for _ in 0..depth {
        out.push_str("  ");
    }
}

fn stmts(out: &mut String, list: &[Stmt], depth: usize) {
    for s in list {
        stmt(out, s, depth);
    }
}

fn stmt(out: &mut String, s: &Stmt, depth: usize) {
    indent(out, depth);
    match s {
        Stmt::Assign { target, value, .. } => {
            let _ = writeln!(out, "(:= {} {})", var(target), expr(value));
        }
        Stmt::If { arms, otherwise, .. } => {
            out.push_str("(if\n");
            for (i, (cond, body)) in arms.iter().enumerate() {
                indent(out, depth + 1);
                let _ = writeln!(out, "({} {}", if i == 0 { "then" } else { "elsif" }, expr(cond));
                stmts(out, body, depth + 2);
                indent(out, depth + 1);
                out.push_str(")\n");
            }
            if let Some(body) = otherwise {
                indent(out, depth + 1);
                out.push_str("(else\n");
                stmts(out, body, depth + 2);
                indent(out, depth + 1);
                out.push_str(")\n");
            }
            indent(out, depth);
            out.push_str(")\n");
        }
        Stmt::For { var: v, from, to, by, body, .. } => {
            let _ = write!(out, "(for {} {} {}", var(v), expr(from), expr(to));
            if let Some(b) = by {
                let _ = write!(out, " by {}", expr(b));
            }
            out.push('\n');
            stmts(out, body, depth + 1);
            indent(out, depth);
            out.push_str(")\n");
        }
        Stmt::While { cond, body, .. } => {
            let _ = writeln!(out, "(while {}", expr(cond));
            stmts(out, body, depth + 1);
            indent(out, depth);
            out.push_str(")\n");
        }
        Stmt::Repeat { body, until, .. } => {
            out.push_str("(repeat\n");
            stmts(out, body, depth + 1);
            indent(out, depth + 1);
            let _ = writeln!(out, "(until {}))", expr(until));
        }
        Stmt::Exit { .. } => out.push_str("(exit)\n"),
        Stmt::Error { .. } => out.push_str("(error)\n"),
    }
}

/// One expression on one line.
pub fn expr(e: &Expr) -> String {
    match &e.kind {
        ExprKind::Int(_) => e.int_value().unwrap_or_default().to_string(),
        ExprKind::Real(x) => format!("{x:?}"),
        ExprKind::Time(x) => format!("(time {x:?}s)"),
        ExprKind::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        ExprKind::Str(s) => format!("'{}'", escape(s)),
        ExprKind::Var(v) => var(v),
        ExprKind::Unary(op, a) => {
            let name = match op {
                UnOp::Neg => "neg",
                UnOp::Not => "NOT",
            };
            format!("({name} {})", expr(a))
        }
        ExprKind::Binary(op, a, b) => format!("({} {} {})", op.symbol(), expr(a), expr(b)),
        ExprKind::Call { name, args } => {
            let mut s = format!("({}", name.text.as_str().to_ascii_uppercase());
            for a in args {
                s.push(' ');
                s.push_str(&expr(a));
            }
            s.push(')');
            s
        }
        ExprKind::Error => "(error)".to_string(),
    }
}

fn var(v: &Var) -> String {
    let mut s = String::new();
    if v.bracketed {
        s.push('[');
    }
    for (i, seg) in v.segs.iter().enumerate() {
        if i > 0 {
            s.push('.');
        }
        s.push_str(&escape(&seg.name.text));
        if let Some(o) = &seg.offset {
            let _ = write!(s, "{{{}}}", expr(o));
        }
    }
    if v.bracketed {
        s.push(']');
    }
    s
}

//! Prints desugared ladder (or any ST syntax tree) as ST source text, for
//! `linc ladder to-st`: the program that runs is exactly this ST.

use crate::ast::{Action, BinOp, Expr, ExprKind, SourceFile, Stmt, UnOp, Var};
use std::fmt::Write;

/// The actions as ST: each with its `ACTION` header, or, for a file
/// without headers, its statements alone (the ST file then has the ladder
/// file's stem, and so the same action name).
pub fn file(f: &SourceFile) -> String {
    let mut out = String::new();
    for a in &f.actions {
        action_into(&mut out, a);
    }
    out
}

/// One action as [`file`] prints it: the statements alone for the one
/// action of a file without headers.
pub fn action_into(out: &mut String, a: &Action) {
    match a.header {
        None => stmts(out, &a.body, 0),
        Some(_) => action(out, a),
    }
}

fn action(out: &mut String, a: &Action) {
    let _ = write!(out, "ACTION {}", a.name.text);
    if let Some(t) = &a.block_type {
        let _ = write!(out, " : {}", t.text);
    }
    out.push('\n');
    stmts(out, &a.body, 1);
    out.push_str("END_ACTION\n");
}

fn stmts(out: &mut String, list: &[Stmt], depth: usize) {
    for s in list {
        stmt(out, s, depth);
    }
}

fn stmt(out: &mut String, s: &Stmt, depth: usize) {
    let pad = "    ".repeat(depth);
    match s {
        Stmt::Assign { target, value, .. } => {
            let _ = writeln!(out, "{pad}{} := {};", var(target), expr(value));
        }
        Stmt::If { arms, otherwise, .. } => {
            for (i, (c, body)) in arms.iter().enumerate() {
                let kw = if i == 0 { "IF" } else { "ELSIF" };
                let _ = writeln!(out, "{pad}{kw} {} THEN", expr(c));
                stmts(out, body, depth + 1);
            }
            if let Some(body) = otherwise {
                let _ = writeln!(out, "{pad}ELSE");
                stmts(out, body, depth + 1);
            }
            let _ = writeln!(out, "{pad}END_IF;");
        }
        Stmt::For { var: v, from, to, by, body, .. } => {
            let by = by.as_ref().map(|b| format!(" BY {}", expr(b))).unwrap_or_default();
            let _ = writeln!(out, "{pad}FOR {} := {} TO {}{by} DO", var(v), expr(from), expr(to));
            stmts(out, body, depth + 1);
            let _ = writeln!(out, "{pad}END_FOR;");
        }
        Stmt::While { cond, body, .. } => {
            let _ = writeln!(out, "{pad}WHILE {} DO", expr(cond));
            stmts(out, body, depth + 1);
            let _ = writeln!(out, "{pad}END_WHILE;");
        }
        Stmt::Repeat { body, until, .. } => {
            let _ = writeln!(out, "{pad}REPEAT");
            stmts(out, body, depth + 1);
            let _ = writeln!(out, "{pad}UNTIL {} END_REPEAT;", expr(until));
        }
        Stmt::Exit { .. } => {
            let _ = writeln!(out, "{pad}EXIT;");
        }
        Stmt::Error { .. } => {
            let _ = writeln!(out, "{pad}(* error *)");
        }
    }
}

/// A variable as written: `Blk.Field{3}.Bit0`, `[DG CONN.W]`.
pub fn var(v: &Var) -> String {
    let mut s = String::new();
    for (i, seg) in v.segs.iter().enumerate() {
        if i > 0 {
            s.push('.');
        }
        s.push_str(&seg.name.text);
        if let Some(o) = &seg.offset {
            let _ = write!(s, "{{{}}}", expr(o));
        }
    }
    if v.bracketed {
        format!("[{s}]")
    } else {
        s
    }
}

/// Binding strength, higher binds tighter (§12.4).
fn strength(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Binary(op, ..) => match op {
            BinOp::Or => 1,
            BinOp::Xor => 2,
            BinOp::And => 3,
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Gt | BinOp::Le | BinOp::Ge => 4,
            BinOp::Add | BinOp::Sub => 5,
            BinOp::Mul | BinOp::Div | BinOp::Mod => 6,
            BinOp::Pow => 8,
        },
        ExprKind::Unary(..) => 7,
        _ => 9,
    }
}

/// An expression with the parentheses its tree needs.
pub fn expr(e: &Expr) -> String {
    let wrap = |inner: &Expr, min: u8| {
        let s = expr(inner);
        if strength(inner) < min {
            format!("({s})")
        } else {
            s
        }
    };
    match &e.kind {
        ExprKind::Int(i) => i.to_string(),
        ExprKind::Real(r) => {
            let s = format!("{r:?}");
            if s.contains(['.', 'e', 'E']) {
                s
            } else {
                s + ".0"
            }
        }
        ExprKind::Time(t) => format!("T#{t}s"),
        ExprKind::Bool(b) => (if *b { "TRUE" } else { "FALSE" }).to_string(),
        ExprKind::Str(s) => format!("'{s}'"),
        ExprKind::Var(v) => var(v),
        ExprKind::Unary(UnOp::Not, a) => format!("NOT {}", wrap(a, 7)),
        ExprKind::Unary(UnOp::Neg, a) => format!("-{}", wrap(a, 7)),
        ExprKind::Binary(op, a, b) => {
            let me = strength(e);
            // Left-associative: the right operand needs parentheses at equal
            // strength, unless it is the same associative operator.
            let same = matches!(&b.kind, ExprKind::Binary(o, ..) if o == op)
                && matches!(op, BinOp::And | BinOp::Or | BinOp::Xor);
            format!("{} {} {}", wrap(a, me), op.symbol(), wrap(b, if same { me } else { me + 1 }))
        }
        ExprKind::Call { name, args } => {
            let args: Vec<String> = args.iter().map(expr).collect();
            format!("{}({})", name.text, args.join(", "))
        }
        ExprKind::Error => "(* error *)".to_string(),
    }
}

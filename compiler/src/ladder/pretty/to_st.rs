//! Prints desugared ladder (or any ST syntax tree) as ST source text, for
//! `linc ladder to-st`: the program that runs is exactly this ST.

use crate::ladder::desugar::depth;
use crate::st::ast::{Action, BinOp, Expr, ExprKind, SourceFile, Stmt, UnOp, Var};
use crate::st::parse_support::MAX_EXPR_DEPTH;
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

/// A variable as written: `Blk.Field{3}.Bit0`, `[DG CONN.W]`. A bracketed
/// name closes before its offset (`[Word 1]{2}.Bit3`): the text inside
/// brackets is a name, and an offset there would be part of it.
pub fn var(v: &Var) -> String {
    let mut s = String::new();
    put_var(&mut s, v, usize::from(MAX_EXPR_DEPTH));
    s
}

fn put_var(out: &mut String, v: &Var, room: usize) {
    let mut open = v.bracketed;
    if open {
        out.push('[');
    }
    for (i, seg) in v.segs.iter().enumerate() {
        if i > 0 {
            out.push('.');
        }
        out.push_str(&seg.name.text);
        if let Some(o) = &seg.offset {
            if std::mem::take(&mut open) {
                out.push(']');
            }
            out.push('{');
            put(out, o, room.saturating_sub(1));
            out.push('}');
        }
    }
    if open {
        out.push(']');
    }
}

/// Binding strength, higher binds tighter (§12.4; the grammar binds a
/// prefix operator tighter than `**`: `-a ** b` is `(-a) ** b`).
fn strength(e: &Expr) -> u8 {
    match &e.kind {
        ExprKind::Binary(op, ..) => match op {
            BinOp::Or => 1,
            BinOp::Xor => 2,
            BinOp::And => 3,
            BinOp::Eq | BinOp::Ne | BinOp::Lt | BinOp::Gt | BinOp::Le | BinOp::Ge => 4,
            BinOp::Add | BinOp::Sub => 5,
            BinOp::Mul | BinOp::Div | BinOp::Mod => 6,
            BinOp::Pow => 7,
        },
        ExprKind::Unary(..) => 8,
        _ => 9,
    }
}

/// An expression with the parentheses its tree needs, no deeper than the
/// parser allows when its tree is not.
pub fn expr(e: &Expr) -> String {
    let mut s = String::new();
    put(&mut s, e, usize::from(MAX_EXPR_DEPTH));
    s
}

/// The operands of the chain of `op` at `e`, left to right.
fn chain<'e>(e: &'e Expr, op: BinOp, out: &mut Vec<&'e Expr>) {
    match &e.kind {
        ExprKind::Binary(o, a, b) if *o == op => {
            chain(a, op, out);
            chain(b, op, out);
        }
        _ => out.push(e),
    }
}

/// `inner`, in parentheses if it binds less tightly than `min`.
fn wrap(out: &mut String, inner: &Expr, min: u8, room: usize) {
    if strength(inner) < min {
        out.push('(');
        put(out, inner, room);
        out.push(')');
    } else {
        put(out, inner, room);
    }
}

/// Prints `e`, whose parsed depth may be at most `room`. The parser reads
/// `a AND b AND c` leaning left, one level per operator; a ladder series is
/// a balanced tree, so a chain of AND, OR or XOR is written flat when that
/// fits in `room`, and with the brackets of its tree when it does not (a
/// series of 300 contacts written flat would be 300 deep, E0022).
fn put(out: &mut String, e: &Expr, room: usize) {
    let below = room.saturating_sub(1);
    match &e.kind {
        ExprKind::Int(i) => {
            let _ = write!(out, "{i}");
        }
        ExprKind::Real(r) => {
            let s = format!("{r:?}");
            out.push_str(&s);
            if !s.contains(['.', 'e', 'E']) {
                out.push_str(".0");
            }
        }
        ExprKind::Time(t) => {
            let _ = write!(out, "T#{t}s");
        }
        ExprKind::Bool(b) => out.push_str(if *b { "TRUE" } else { "FALSE" }),
        ExprKind::Str(s) => string(out, s),
        ExprKind::Var(v) => put_var(out, v, room),
        ExprKind::Unary(op, a) => {
            out.push_str(if *op == UnOp::Not { "NOT " } else { "-" });
            wrap(out, a, 8, below);
        }
        ExprKind::Binary(op, a, b) if matches!(op, BinOp::And | BinOp::Or | BinOp::Xor) => {
            let me = strength(e);
            let mut ops = Vec::new();
            chain(e, *op, &mut ops);
            let flat = ops.iter().skip(1).fold(depth(ops[0]), |cur, o| 1 + cur.max(depth(o)));
            if flat <= room {
                for (i, o) in ops.iter().enumerate() {
                    if i > 0 {
                        let _ = write!(out, " {} ", op.symbol());
                    }
                    wrap(out, o, me, room.saturating_sub(ops.len() - i.max(1)));
                }
            } else {
                wrap(out, a, me, below);
                let _ = write!(out, " {} ", op.symbol());
                wrap(out, b, me + 1, below);
            }
        }
        ExprKind::Binary(op, a, b) => {
            // Left-associative: the right operand needs parentheses at equal strength.
            let me = strength(e);
            wrap(out, a, me, below);
            let _ = write!(out, " {} ", op.symbol());
            wrap(out, b, me + 1, below);
        }
        ExprKind::Call { name, args } => {
            out.push_str(&name.text);
            out.push('(');
            for (i, a) in args.iter().enumerate() {
                if i > 0 {
                    out.push_str(", ");
                }
                put(out, a, below);
            }
            out.push(')');
        }
        ExprKind::Error => out.push_str("(* error *)"),
    }
}

/// A string constant, its text as written (`$`-sequences kept). The lexer
/// does not say which quotes it had: a `'` that no `$` escapes can only
/// have stood between double quotes, so those are used for it.
fn string(out: &mut String, s: &str) {
    let mut chars = s.chars();
    let mut bare_single = false;
    while let Some(c) = chars.next() {
        match c {
            '$' => {
                chars.next();
            }
            '\'' => bare_single = true,
            _ => {}
        }
    }
    let q = if bare_single { '"' } else { '\'' };
    out.push(q);
    out.push_str(s);
    out.push(q);
}

//! Rungs to ST statements (ADR 0009): the checker and the lowering of ST
//! then do the rest, so a ladder action means exactly what its ST means.
//!
//! Series is `AND`, a parallel branch `OR`, the function boxes their ST
//! operators; `(x)` is `IF c THEN x := TRUE; ELSE x := FALSE; END_IF;` and
//! `(/x)` the same with the values swapped (a rung is energised or not: one
//! decision, which coverage counts, ADR 0020), `x := TRUE;` or `x := FALSE;`
//! on a rung without contacts; `(S x)` and
//! `(R x)` are `IF c THEN x := TRUE/FALSE; END_IF;`, a variable output is
//! `IF c THEN target := value; END_IF;`. A forward jump wraps the rungs it
//! skips in `IF NOT (c) THEN … END_IF;`; when two jumps cross, the rungs
//! between the first label and the furthest reach are written once for
//! each way in, so each condition is still evaluated once, where its rung is.

use super::ast::{Action, BoxOp, CoilKind, Cond, Output, Rung};
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use crate::st::ast::{self, BinOp, Expr, ExprKind, Stmt, UnOp};
use crate::st::parse_support::MAX_EXPR_DEPTH;
use linc_format::Code;
use std::collections::HashSet;

/// How deeply jumps may nest, and how many rungs crossing jumps may make
/// (rungs written again count): a bound on the work for any input.
const MAX_NESTING: usize = 48;
const MAX_EMITTED: usize = 100_000;

/// The ST action of a ladder action. `targets` are [`super::check::jumps`]'s;
/// `bad` are contacts and coils already reported (left out). An error comes
/// back when the jumps nest or cross too much to be written out.
pub fn action(a: &Action, targets: &[Option<usize>], bad: &HashSet<Span>) -> (ast::Action, Vec<Diagnostic>) {
    desugar(a, targets, bad, true)
}

/// [`action`] for the rung `cond -> (T);` of a ladder transition condition:
/// its coil is an assignment of the condition, the value wanted.
pub fn condition_rung(a: &Action, targets: &[Option<usize>]) -> (ast::Action, Vec<Diagnostic>) {
    desugar(a, targets, &HashSet::new(), false)
}

fn desugar(a: &Action, targets: &[Option<usize>], bad: &HashSet<Span>, decide: bool) -> (ast::Action, Vec<Diagnostic>) {
    let mut d = Desugar { rungs: &a.rungs, targets, bad, emitted: 0, stopped: false, errors: Vec::new(), decide };
    let body = d.block(0, a.rungs.len(), 0);
    let action =
        ast::Action { name: a.name.clone(), block_type: a.block_type.clone(), body, header: a.header, span: a.span };
    (action, d.errors)
}

struct Desugar<'r> {
    rungs: &'r [Rung],
    targets: &'r [Option<usize>],
    bad: &'r HashSet<Span>,
    emitted: usize,
    /// E0312 was reported: nothing more is written.
    stopped: bool,
    errors: Vec<Diagnostic>,
    /// Whether a normal or negated coil is a decision (an IF) or an
    /// assignment of the rung's value (a transition's condition).
    decide: bool,
}

impl Desugar<'_> {
    /// The statements that run from rung `from` until rung `stop`.
    fn block(&mut self, from: usize, stop: usize, depth: usize) -> Vec<Stmt> {
        let mut out = Vec::new();
        let mut i = from;
        while i < stop {
            let rung = &self.rungs[i];
            self.emitted += 1;
            if self.stopped {
                return out;
            }
            if depth > MAX_NESTING || self.emitted > MAX_EMITTED {
                self.stopped = true;
                self.errors.push(
                    Diagnostic::error(Code::E0312, "jumps nest or cross too deeply", rung.span)
                        .label("here the jumps around this rung are too many to compile")
                        .help(format!("at most {MAX_NESTING} jumps may skip one rung; split the action")),
                );
                return out;
            }
            let Some(t) = self.targets.get(i).copied().flatten() else {
                out.extend(self.rung(rung));
                i += 1;
                continue;
            };
            let reach = self.reach(i, t);
            let cond = self.cond_or_true(rung);
            let span = rung.span;
            if reach == t {
                let skipped = self.block(i + 1, t, depth + 1);
                let not = Expr { kind: ExprKind::Unary(UnOp::Not, Box::new(cond)), span };
                out.push(Stmt::If { arms: vec![(not, skipped)], otherwise: None, span });
            } else {
                let jumped = self.block(t, reach, depth + 1);
                let fell = self.block(i + 1, reach, depth + 1);
                out.push(Stmt::If { arms: vec![(cond, jumped)], otherwise: Some(fell), span });
            }
            i = reach;
        }
        out
    }

    /// Where control from the jump at `i` to `t` meets again: the furthest
    /// target of any jump between them, taken again over the rungs added.
    fn reach(&self, i: usize, t: usize) -> usize {
        let (mut r, mut k) = (t, i + 1);
        while k < r {
            if let Some(tk) = self.targets.get(k).copied().flatten() {
                r = r.max(tk);
            }
            k += 1;
        }
        r
    }

    fn cond_or_true(&mut self, rung: &Rung) -> Expr {
        match &rung.cond {
            Some(c) => self.top(c),
            None => Expr { kind: ExprKind::Bool(true), span: rung.span },
        }
    }

    /// A rung's whole condition; one that would be deeper than ST allows
    /// is an error (E0022), so that checking and lowering stay bounded. One
    /// level is kept for the NOT of a negated coil or a jump, so that the
    /// ST of every rung (`linc ladder to-st`) is within the limit too.
    fn top(&mut self, c: &Cond) -> Expr {
        let e = self.cond(c);
        if depth(&e) < usize::from(MAX_EXPR_DEPTH) {
            return e;
        }
        self.errors.push(
            Diagnostic::error(Code::E0022, format!("rung condition nested {MAX_EXPR_DEPTH} or more deep"), c.span())
                .label("too many branches and boxes inside each other")
                .help("split the rung: write part of the condition to a digital variable on an earlier rung"),
        );
        Expr { kind: ExprKind::Error, span: c.span() }
    }

    fn cond(&self, c: &Cond) -> Expr {
        match c {
            Cond::Contact { span, .. } if self.bad.contains(span) => Expr { kind: ExprKind::Error, span: *span },
            Cond::Contact { negated: false, expr, .. } => expr.clone(),
            Cond::Contact { negated: true, expr, span } => {
                Expr { kind: ExprKind::Unary(UnOp::Not, Box::new(expr.clone())), span: *span }
            }
            Cond::Series(v) => self.fold(v, BinOp::And, c.span()),
            Cond::Parallel(v, span) => self.fold(v, BinOp::Or, *span),
            Cond::Box { op: BoxOp::Not, args, span } => {
                let inner = self.fold(args, BinOp::And, *span);
                Expr { kind: ExprKind::Unary(UnOp::Not, Box::new(inner)), span: *span }
            }
            Cond::Box { op, args, span } => {
                let bin = match op {
                    BoxOp::Or => BinOp::Or,
                    BoxOp::Xor => BinOp::Xor,
                    _ => BinOp::And,
                };
                self.fold(args, bin, *span)
            }
        }
    }

    /// `v[0] op v[1] op …` as a balanced tree (the operators are
    /// associative and operands are still evaluated left to right), so a
    /// long series is only as deep as its logarithm.
    fn fold(&self, v: &[Cond], op: BinOp, span: Span) -> Expr {
        match v {
            [] => Expr { kind: ExprKind::Error, span },
            [one] => self.cond(one),
            _ => {
                let (l, r) = v.split_at(v.len() / 2);
                let (a, b) = (self.fold(l, op, span), self.fold(r, op, span));
                let span = a.span.to(b.span);
                Expr { kind: ExprKind::Binary(op, Box::new(a), Box::new(b)), span }
            }
        }
    }

    /// The statement of a rung that is not a valid jump. A jump whose label
    /// is wrong (reported, so nothing is lowered) keeps its condition in an
    /// empty IF, so the ST checker still checks the names in it.
    fn rung(&mut self, rung: &Rung) -> Option<Stmt> {
        let span = rung.span;
        match &rung.output {
            Output::Jump { .. } => {
                let c = rung.cond.as_ref()?;
                Some(Stmt::If { arms: vec![(self.top(c), Vec::new())], otherwise: None, span })
            }
            Output::Coil { span: s, .. } if self.bad.contains(s) => Some(Stmt::Error { span }),
            Output::Coil { kind, target, .. } => {
                let ExprKind::Var(v) = &target.kind else { return Some(Stmt::Error { span }) };
                let assign = |value: Expr| Stmt::Assign { target: v.clone(), value: Box::new(value), span };
                let value = |on: bool| Expr { kind: ExprKind::Bool(on), span: target.span };
                let energised = *kind == CoilKind::Normal;
                if self.decide && rung.cond.is_some() && matches!(kind, CoilKind::Normal | CoilKind::Negated) {
                    let cond = self.cond_or_true(rung);
                    let (on, off) = (vec![assign(value(energised))], vec![assign(value(!energised))]);
                    return Some(Stmt::If { arms: vec![(cond, on)], otherwise: Some(off), span });
                }
                let cond = self.cond_or_true(rung);
                Some(match kind {
                    CoilKind::Normal => assign(cond),
                    CoilKind::Negated => assign(Expr { kind: ExprKind::Unary(UnOp::Not, Box::new(cond)), span }),
                    CoilKind::Set | CoilKind::Reset => {
                        let value = Expr { kind: ExprKind::Bool(*kind == CoilKind::Set), span: target.span };
                        self.when(rung, assign(value))
                    }
                })
            }
            Output::Assign(s) => Some(self.when(rung, s.clone())),
        }
    }

    /// `s` when the rung has no condition, else `IF cond THEN s; END_IF;`.
    fn when(&mut self, rung: &Rung, s: Stmt) -> Stmt {
        match &rung.cond {
            None => s,
            Some(c) => Stmt::If { arms: vec![(self.top(c), vec![s])], otherwise: None, span: rung.span },
        }
    }
}

/// How deep an expression is, as the parser counts it: operators, calls
/// and offsets (its own recursion is bounded by the parser's nesting limit
/// and the balanced folds).
pub(crate) fn depth(e: &Expr) -> usize {
    1 + match &e.kind {
        ExprKind::Unary(_, a) => depth(a),
        ExprKind::Binary(_, a, b) => depth(a).max(depth(b)),
        ExprKind::Call { args, .. } => args.iter().map(depth).max().unwrap_or(0),
        ExprKind::Var(v) => v.segs.iter().filter_map(|s| s.offset.as_deref()).map(depth).max().unwrap_or(0),
        _ => 0,
    }
}

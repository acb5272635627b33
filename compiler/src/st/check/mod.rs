//! Semantic checks: names against the database, types, and the statement
//! rules of chapter 12. The checker reports every error it finds and keeps
//! going, treating a broken part as `Any` so that one mistake is reported once.

mod errors;
mod expr;
pub(crate) use expr::distance;
mod limits;
mod resolve;

pub use errors::CheckError;
pub use limits::{FastHash, Limits, MAX_CALL_ARGS};
pub use resolve::Resolved;

use crate::diag::{Capped, Omitted};
use crate::names::{Meaning, Recorder};
use crate::st::ast::{Action, Expr, ExprKind, Stmt};
use crate::st::hir;
use limits::ActionLimits;
use linc_format::Database;
use linc_stdlib::Ty;
use std::collections::HashMap;

/// What names are checked against.
#[derive(Clone, Copy, Debug)]
pub struct Context<'a> {
    pub db: &'a Database,
    /// When false (no database given) an unknown first name is accepted as a
    /// block that will exist at run time; fields of an action's own block
    /// type are still checked.
    pub resolve_blocks: bool,
    /// `Some` in sequence actions and transitions, where `step.X` and
    /// `step.T` exist. An empty list accepts any step name.
    pub steps: Option<&'a [String]>,
    /// Whether `steps` is every step there is even when it is empty (a
    /// scenario's expectations over a strategy without sequences), so an
    /// empty list accepts none.
    pub steps_known: bool,
    /// Where to record what each name resolves to (a language server's
    /// question, `crate::names`); `None` for a plain check.
    pub record: Option<&'a Recorder>,
}

impl<'a> Context<'a> {
    /// Checks against `db`; without one, against the built-in library's
    /// block types with block names left unresolved (any block may exist at
    /// run time), as `linc check` without `--db` does.
    pub fn of(db: Option<&'a Database>) -> Context<'a> {
        match db {
            Some(db) => Context { db, resolve_blocks: true, steps: None, steps_known: false, record: None },
            None => Context {
                db: Database::builtin_shared(),
                resolve_blocks: false,
                steps: None,
                steps_known: false,
                record: None,
            },
        }
    }

    /// The same context, in sequence actions and transitions with `steps`
    /// (an empty list accepts any step name).
    pub fn with_steps(self, steps: &'a [String]) -> Context<'a> {
        Context { steps: Some(steps), ..self }
    }

    /// The same context with every step there is: a name that is not one
    /// of `steps` is unknown, even when there are none.
    pub fn with_all_steps(self, steps: &'a [String]) -> Context<'a> {
        Context { steps: Some(steps), steps_known: true, ..self }
    }

    /// The same context, with block names taken on trust (checked when the
    /// program runs, as without `--db`).
    pub fn unresolved(self) -> Context<'a> {
        Context { resolve_blocks: false, ..self }
    }

    /// The same context, recording each name it resolves into `r`.
    pub fn recording(self, r: &'a Recorder) -> Context<'a> {
        Context { record: Some(r), ..self }
    }

    /// Records that `span` names `meaning`, when recording.
    pub(crate) fn note(&self, span: crate::diag::Span, meaning: impl FnOnce() -> Meaning) {
        if let Some(r) = self.record {
            r.push(span, meaning());
        }
    }
}

/// Checks actions one at a time, keeping what spans actions: the limits of
/// one object file and the errors found so far.
pub struct Checker<'a> {
    ctx: Context<'a>,
    errors: Capped<CheckError>,
    omitted: Omitted,
    loop_depth: usize,
    /// Template of the action's own block (`ACTION a : PID`).
    self_template: Option<usize>,
    limits: Limits,
    action_limits: ActionLimits,
    /// "Did you mean" answers for unknown names, by name.
    suggestions: HashMap<String, Option<String>>,
    /// Whether the checked program is kept (for compiling).
    keep: bool,
    /// The sequence's step names in upper case with the index of the first
    /// of each, made on first use, so a step variable is one hashed look-up
    /// however many steps there are.
    step_index: Option<HashMap<String, usize>>,
}

impl<'a> Checker<'a> {
    /// A checker that counts database references into `limits`, which the
    /// session carries from file to file.
    pub fn new(ctx: Context<'a>, limits: Limits) -> Checker<'a> {
        Checker {
            ctx,
            errors: Capped::default(),
            omitted: Omitted::default(),
            loop_depth: 0,
            self_template: None,
            limits,
            action_limits: ActionLimits::default(),
            suggestions: HashMap::new(),
            keep: true,
            step_index: None,
        }
    }

    /// A checker that only reports errors: the checked statements it builds
    /// are dropped as soon as they are checked, and its programs are empty.
    pub fn reporting_only(mut self) -> Checker<'a> {
        self.keep = false;
        self
    }

    /// The errors found since the last call (the first
    /// [`crate::diag::MAX_ERRORS`]; the rest are counted in
    /// [`Checker::omitted`]).
    pub fn take_errors(&mut self) -> Vec<CheckError> {
        let (kept, n, first) = std::mem::take(&mut self.errors).into_parts();
        self.omitted.add(n, first.map(|e| e.to_diagnostic().span));
        kept
    }

    /// Errors found but not kept.
    pub fn omitted(&self) -> Omitted {
        self.omitted
    }

    /// Gives back the limits, to be handed to the next file's checker.
    pub fn into_limits(self) -> Limits {
        self.limits
    }

    /// Checks a transition expression, which must be a truth value.
    pub fn transition(&mut self, e: &Expr) -> hir::Expr {
        self.action_limits = ActionLimits::default();
        self.condition(e)
    }

    /// Checks an expression of any type.
    pub fn expression(&mut self, e: &Expr) -> hir::Expr {
        self.action_limits = ActionLimits::default();
        self.expr(e)
    }

    /// Checks one action.
    pub fn action(&mut self, a: &Action) -> hir::Action {
        let block_type = self.begin_action(a.block_type.as_ref());
        let body = self.stmts(&a.body);
        hir::Action { name: a.name.text.to_string(), block_type, body, span: a.span }
    }

    /// Starts an action of block type `block_type` (`ACTION a : PID`), whose
    /// statements are then checked one by one with [`Checker::statement`];
    /// returns the block type's name as the database spells it.
    pub fn begin_action(&mut self, block_type: Option<&crate::st::ast::Ident>) -> Option<String> {
        self.self_template = None;
        self.action_limits = ActionLimits::default();
        let t = block_type?;
        match self.ctx.db.template(&t.text) {
            Some(i) => {
                self.self_template = Some(i);
                Some(self.ctx.db.templates[i].name.clone())
            }
            None => {
                self.errors.push(CheckError::UnknownBlockType { span: t.span, name: t.text.to_string() });
                Some(t.text.to_string())
            }
        }
    }

    /// Checks one statement of the action begun last.
    pub fn statement(&mut self, s: &Stmt) -> hir::Stmt {
        self.stmt(s)
    }

    // The statement and expression walks recurse as deep as the tree (at
    // most the parser's nesting limits). They are written with plain loops
    // and small dispatching frames, so that the deepest accepted tree fits a
    // test thread's stack even in a debug build (tests/deep.rs).

    /// Checks a statement list. When the checked program is not wanted
    /// (`linc check`), each checked statement is dropped at once, so the
    /// checked program of a long action is never held.
    fn stmts(&mut self, list: &[Stmt]) -> Vec<hir::Stmt> {
        let mut out = Vec::with_capacity(if self.keep { list.len() } else { 0 });
        for s in list {
            let h = self.stmt(s);
            if self.keep {
                out.push(h);
            }
        }
        out
    }

    fn stmt(&mut self, s: &Stmt) -> hir::Stmt {
        match s {
            Stmt::Assign { target, value, span } => self.assign(target, value, *span),
            Stmt::If { arms, otherwise, span } => self.if_stmt(arms, otherwise.as_deref(), *span),
            Stmt::For { var, from, to, by, body, span } => self.for_loop(var, from, to, by.as_deref(), body, *span),
            Stmt::While { cond, body, span } => self.while_loop(cond, body, *span),
            Stmt::Repeat { body, until, span } => self.repeat_loop(body, until, *span),
            Stmt::Exit { span } => {
                if self.loop_depth == 0 {
                    self.errors.push(CheckError::ExitOutsideLoop { span: *span });
                }
                hir::Stmt::Exit { span: *span }
            }
            Stmt::Error { span } => hir::Stmt::Error { span: *span },
        }
    }

    fn assign(&mut self, target: &crate::st::ast::Var, value: &Expr, span: crate::Span) -> hir::Stmt {
        let value = self.expr(value);
        let Some(r) = self.resolve(target) else {
            return hir::Stmt::Error { span };
        };
        if !r.writable {
            self.errors.push(CheckError::NotWritable { span: target.span, what: target.path(), why: r.why_readonly });
            return hir::Stmt::Error { span };
        }
        if !self.store(&r, &value, target) {
            return hir::Stmt::Error { span };
        }
        hir::Stmt::Assign { place: r.place, value, span }
    }

    fn if_stmt(&mut self, arms: &[(Expr, Vec<Stmt>)], otherwise: Option<&[Stmt]>, span: crate::Span) -> hir::Stmt {
        let mut checked = Vec::with_capacity(arms.len());
        for (cond, body) in arms {
            let c = self.condition(cond);
            checked.push((c, self.stmts(body)));
        }
        let otherwise = match otherwise {
            Some(b) => self.stmts(b),
            None => Vec::new(),
        };
        hir::Stmt::If { arms: checked, otherwise, span }
    }

    fn while_loop(&mut self, cond: &Expr, body: &[Stmt], span: crate::Span) -> hir::Stmt {
        let cond = self.condition(cond);
        let body = self.in_loop(body);
        hir::Stmt::While { cond, body, span }
    }

    fn repeat_loop(&mut self, body: &[Stmt], until: &Expr, span: crate::Span) -> hir::Stmt {
        let body = self.in_loop(body);
        let until = self.condition(until);
        hir::Stmt::Repeat { body, until, span }
    }

    fn for_loop(
        &mut self,
        var: &crate::st::ast::Var,
        from: &Expr,
        to: &Expr,
        by: Option<&Expr>,
        body: &[Stmt],
        span: crate::Span,
    ) -> hir::Stmt {
        self.count_for_loop(span);
        let place = match self.resolve(var) {
            Some(r) if !r.writable => {
                self.errors.push(CheckError::NotWritable { span: var.span, what: var.path(), why: r.why_readonly });
                None
            }
            Some(r) if !matches!(r.ty(), Ty::Int | Ty::Real | Ty::Any) => {
                self.errors.push(CheckError::OperandTypes {
                    span: var.span,
                    op: "FOR".into(),
                    left: r.ty().name().into(),
                    right: None,
                    help: "the loop variable must be a numeric (INT or REAL) field",
                });
                None
            }
            other => other.map(|r| r.place),
        };
        let mut bounds = Vec::with_capacity(3);
        for e in [Some(from), Some(to), by].into_iter().flatten() {
            let h = self.expr(e);
            if !h.ty.is_numeric() {
                self.errors.push(CheckError::OperandTypes {
                    span: e.span,
                    op: "FOR".into(),
                    left: h.ty.name().into(),
                    right: None,
                    help: "FOR bounds and step are numbers",
                });
            }
            bounds.push(h);
        }
        if let Some(b) = by {
            self.for_step(b, place.as_ref().map(|p| p.ty).unwrap_or(Ty::Any));
        }
        let body = self.in_loop(body);
        let mut bounds = bounds.into_iter();
        match (place, bounds.next(), bounds.next()) {
            (Some(place), Some(from), Some(to)) => hir::Stmt::For { place, from, to, by: bounds.next(), body, span },
            _ => hir::Stmt::Error { span },
        }
    }

    /// The step after `BY`: a constant (§12.4.3) that is not zero once
    /// converted to the loop variable's type, or the loop would never end.
    fn for_step(&mut self, by: &Expr, index: Ty) {
        let zero = match by.kind {
            ExprKind::Int(v) => v == 0,
            ExprKind::Real(x) => {
                let x = x as f32;
                x == 0.0 || (matches!(index, Ty::Int | Ty::Bool) && linc_stdlib::value::round_to_i32(x) == 0)
            }
            _ => {
                self.errors.push(CheckError::ForByNotLiteral { span: by.span });
                return;
            }
        };
        if zero {
            let rounded = !matches!(by.kind, ExprKind::Int(0)) && (by.kind != ExprKind::Real(0.0));
            self.errors.push(CheckError::ForStepZero { span: by.span, rounded });
        }
    }

    fn in_loop(&mut self, body: &[Stmt]) -> Vec<hir::Stmt> {
        self.loop_depth += 1;
        let b = self.stmts(body);
        self.loop_depth -= 1;
        b
    }

    fn condition(&mut self, e: &Expr) -> hir::Expr {
        let h = self.expr(e);
        if !matches!(h.ty, Ty::Bool | Ty::Int | Ty::Any) {
            self.errors.push(CheckError::ConditionType { span: e.span, found: h.ty.name().into() });
        }
        h
    }

    /// Checks a value stored into a resolved field; false if it can't be.
    fn store(&mut self, r: &Resolved, value: &hir::Expr, target: &crate::st::ast::Var) -> bool {
        let vt = value.ty;
        let fits = match r.ty() {
            Ty::Any => true,
            Ty::Bool | Ty::Int | Ty::Real => vt.is_numeric(),
            Ty::Text | Ty::Bytes | Ty::WStr => vt.is_stringy(),
        };
        if !fits {
            let expected = if r.place.enum_values.is_some() { "ENUM".to_string() } else { r.ty().name().to_string() };
            self.errors.push(CheckError::AssignType {
                span: value.span,
                target: target.span,
                expected,
                found: vt.name().into(),
            });
            return false;
        }
        if let (Some(values), hir::ExprKind::Str(s)) = (&r.place.enum_values, &value.kind) {
            return self.enum_literal(values, s, value.span, target.path());
        }
        true
    }

    fn enum_literal(&mut self, values: &[String], s: &[u8], span: crate::Span, field: String) -> bool {
        if values.iter().any(|v| v.as_bytes().eq_ignore_ascii_case(s)) {
            return true;
        }
        let value = String::from_utf8_lossy(s).into_owned();
        self.errors.push(CheckError::BadEnumValue { span, value, field, values: values.to_vec() });
        false
    }
}

//! Semantic checks: names against the database, types, and the statement
//! rules of chapter 12. The checker reports every error it finds and keeps
//! going, treating a broken part as `Any` so that one mistake is reported once.

mod errors;
mod expr;
mod resolve;

pub use errors::CheckError;
pub use resolve::Resolved;

use crate::ast::{Action, Expr, ExprKind, SourceFile, Stmt};
use crate::hir;
use linc_runtime::Database;
use linc_stdlib::Ty;

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
}

pub(crate) struct Checker<'a> {
    ctx: Context<'a>,
    errors: Vec<CheckError>,
    loop_depth: usize,
    /// Template of the action's own block (`ACTION a : PID`).
    self_template: Option<usize>,
}

/// Checks every action of a file and builds the checked program. The
/// program is complete only when there are no errors.
pub fn check_file(file: &SourceFile, ctx: Context) -> (Vec<CheckError>, hir::Program) {
    let mut c = Checker { ctx, errors: Vec::new(), loop_depth: 0, self_template: None };
    let mut actions = Vec::new();
    for (i, a) in file.actions.iter().enumerate() {
        if let Some(first) = file.actions[..i].iter().find(|b| b.name.text.eq_ignore_ascii_case(&a.name.text)) {
            c.errors.push(CheckError::DuplicateAction {
                span: a.name.span,
                first: first.name.span,
                name: a.name.text.clone(),
            });
        }
        actions.push(c.action(a));
    }
    (c.errors, hir::Program { actions })
}

/// Checks a transition: an expression that must be a truth value (§12.11).
pub fn check_transition(e: &Expr, ctx: Context) -> (Vec<CheckError>, hir::Expr) {
    let mut c = Checker { ctx, errors: Vec::new(), loop_depth: 0, self_template: None };
    let h = c.condition(e);
    (c.errors, h)
}

/// Checks a value expression of any type (for `linc eval`).
pub fn check_expression(e: &Expr, ctx: Context) -> (Vec<CheckError>, hir::Expr) {
    let mut c = Checker { ctx, errors: Vec::new(), loop_depth: 0, self_template: None };
    let h = c.expr(e);
    (c.errors, h)
}

impl Checker<'_> {
    fn action(&mut self, a: &Action) -> hir::Action {
        self.self_template = None;
        if let Some(t) = &a.block_type {
            match self.ctx.db.template(&t.text) {
                Some(i) => self.self_template = Some(i),
                None => self.errors.push(CheckError::UnknownBlockType { span: t.span, name: t.text.clone() }),
            }
        }
        let body = self.stmts(&a.body);
        let block_type = a.block_type.as_ref().map(|t| {
            self.self_template.map(|i| self.ctx.db.templates[i].name.clone()).unwrap_or_else(|| t.text.clone())
        });
        hir::Action { name: a.name.text.clone(), block_type, body, span: a.span }
    }

    fn stmts(&mut self, list: &[Stmt]) -> Vec<hir::Stmt> {
        list.iter().map(|s| self.stmt(s)).collect()
    }

    fn stmt(&mut self, s: &Stmt) -> hir::Stmt {
        match s {
            Stmt::Assign { target, value, span } => {
                let value = self.expr(value);
                let Some(r) = self.resolve(target) else {
                    return hir::Stmt::Error { span: *span };
                };
                if !r.writable {
                    self.errors.push(CheckError::NotWritable {
                        span: target.span,
                        what: target.path(),
                        why: r.why_readonly,
                    });
                    return hir::Stmt::Error { span: *span };
                }
                if !self.store(&r, &value, target) {
                    return hir::Stmt::Error { span: *span };
                }
                hir::Stmt::Assign { place: r.place, value, span: *span }
            }
            Stmt::If { arms, otherwise, span } => {
                let arms = arms.iter().map(|(cond, body)| (self.condition(cond), self.stmts(body))).collect();
                let otherwise = otherwise.as_ref().map(|b| self.stmts(b)).unwrap_or_default();
                hir::Stmt::If { arms, otherwise, span: *span }
            }
            Stmt::For { var, from, to, by, body, span } => self.for_loop(var, from, to, by.as_ref(), body, *span),
            Stmt::While { cond, body, span } => {
                let cond = self.condition(cond);
                let body = self.in_loop(body);
                hir::Stmt::While { cond, body, span: *span }
            }
            Stmt::Repeat { body, until, span } => {
                let body = self.in_loop(body);
                let until = self.condition(until);
                hir::Stmt::Repeat { body, until, span: *span }
            }
            Stmt::Exit { span } => {
                if self.loop_depth == 0 {
                    self.errors.push(CheckError::ExitOutsideLoop { span: *span });
                }
                hir::Stmt::Exit { span: *span }
            }
            Stmt::Error { span } => hir::Stmt::Error { span: *span },
        }
    }

    fn for_loop(
        &mut self,
        var: &crate::ast::Var,
        from: &Expr,
        to: &Expr,
        by: Option<&Expr>,
        body: &[Stmt],
        span: crate::Span,
    ) -> hir::Stmt {
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
            if !matches!(b.kind, ExprKind::Int(_) | ExprKind::Real(_)) {
                self.errors.push(CheckError::ForByNotLiteral { span: b.span });
            }
        }
        let body = self.in_loop(body);
        let mut bounds = bounds.into_iter();
        match (place, bounds.next(), bounds.next()) {
            (Some(place), Some(from), Some(to)) => hir::Stmt::For { place, from, to, by: bounds.next(), body, span },
            _ => hir::Stmt::Error { span },
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
    fn store(&mut self, r: &Resolved, value: &hir::Expr, target: &crate::ast::Var) -> bool {
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

//! Semantic checks: names against the database, types, and the statement
//! rules of chapter 12. The checker reports every error it finds and keeps
//! going, treating a broken part as `Any` so that one mistake is reported once.

mod errors;
mod expr;
mod resolve;

pub use errors::CheckError;
pub use resolve::Resolved;

use crate::ast::{Action, Expr, ExprKind, SourceFile, Stmt};
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

/// Checks every action of a file.
pub fn check_file(file: &SourceFile, ctx: Context) -> Vec<CheckError> {
    let mut c = Checker {
        ctx,
        errors: Vec::new(),
        loop_depth: 0,
        self_template: None,
    };
    for (i, a) in file.actions.iter().enumerate() {
        if let Some(first) = file.actions[..i]
            .iter()
            .find(|b| b.name.text.eq_ignore_ascii_case(&a.name.text))
        {
            c.errors.push(CheckError::DuplicateAction {
                span: a.name.span,
                first: first.name.span,
                name: a.name.text.clone(),
            });
        }
        c.action(a);
    }
    c.errors
}

/// Checks a transition: an expression that must be a truth value (§12.11).
pub fn check_transition(e: &Expr, ctx: Context) -> Vec<CheckError> {
    let mut c = Checker {
        ctx,
        errors: Vec::new(),
        loop_depth: 0,
        self_template: None,
    };
    c.condition(e);
    c.errors
}

impl Checker<'_> {
    fn action(&mut self, a: &Action) {
        self.self_template = None;
        if let Some(t) = &a.block_type {
            match self.ctx.db.template(&t.text) {
                Some(i) => self.self_template = Some(i),
                None => self.errors.push(CheckError::UnknownBlockType {
                    span: t.span,
                    name: t.text.clone(),
                }),
            }
        }
        self.stmts(&a.body);
    }

    fn stmts(&mut self, list: &[Stmt]) {
        for s in list {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match s {
            Stmt::Assign { target, value, .. } => {
                let vt = self.expr(value);
                let Some(r) = self.resolve(target) else {
                    return;
                };
                if !r.writable {
                    self.errors.push(CheckError::NotWritable {
                        span: target.span,
                        what: target.path(),
                        why: r.why_readonly,
                    });
                    return;
                }
                self.store(&r, value, vt, target);
            }
            Stmt::If {
                arms, otherwise, ..
            } => {
                for (cond, body) in arms {
                    self.condition(cond);
                    self.stmts(body);
                }
                if let Some(body) = otherwise {
                    self.stmts(body);
                }
            }
            Stmt::For {
                var,
                from,
                to,
                by,
                body,
                ..
            } => {
                if let Some(r) = self.resolve(var) {
                    if !r.writable {
                        self.errors.push(CheckError::NotWritable {
                            span: var.span,
                            what: var.path(),
                            why: r.why_readonly,
                        });
                    } else if !matches!(r.ty, Ty::Int | Ty::Real | Ty::Any) {
                        self.errors.push(CheckError::OperandTypes {
                            span: var.span,
                            op: "FOR".into(),
                            left: r.ty.name().into(),
                            right: None,
                            help: "the loop variable must be a numeric (INT or REAL) field",
                        });
                    }
                }
                for e in [Some(from), Some(to), by.as_ref()].into_iter().flatten() {
                    let t = self.expr(e);
                    if !t.is_numeric() {
                        self.errors.push(CheckError::OperandTypes {
                            span: e.span,
                            op: "FOR".into(),
                            left: t.name().into(),
                            right: None,
                            help: "FOR bounds and step are numbers",
                        });
                    }
                }
                if let Some(b) = by {
                    if !matches!(b.kind, ExprKind::Int(_) | ExprKind::Real(_)) {
                        self.errors
                            .push(CheckError::ForByNotLiteral { span: b.span });
                    }
                }
                self.in_loop(body);
            }
            Stmt::While { cond, body, .. } => {
                self.condition(cond);
                self.in_loop(body);
            }
            Stmt::Repeat { body, until, .. } => {
                self.in_loop(body);
                self.condition(until);
            }
            Stmt::Exit { span } => {
                if self.loop_depth == 0 {
                    self.errors
                        .push(CheckError::ExitOutsideLoop { span: *span });
                }
            }
            Stmt::Error { .. } => {}
        }
    }

    fn in_loop(&mut self, body: &[Stmt]) {
        self.loop_depth += 1;
        self.stmts(body);
        self.loop_depth -= 1;
    }

    fn condition(&mut self, e: &Expr) {
        let t = self.expr(e);
        if !matches!(t, Ty::Bool | Ty::Int | Ty::Any) {
            self.errors.push(CheckError::ConditionType {
                span: e.span,
                found: t.name().into(),
            });
        }
    }

    /// Checks a value of type `vt` stored into a resolved field.
    fn store(&mut self, r: &Resolved, value: &Expr, vt: Ty, target: &crate::ast::Var) {
        let fits = match r.ty {
            Ty::Any => true,
            Ty::Bool | Ty::Int | Ty::Real => vt.is_numeric(),
            Ty::Text | Ty::Bytes | Ty::WStr => vt.is_stringy(),
        };
        if !fits {
            let expected = if r.enum_values.is_some() {
                "ENUM".to_string()
            } else {
                r.ty.name().to_string()
            };
            self.errors.push(CheckError::AssignType {
                span: value.span,
                target: target.span,
                expected,
                found: vt.name().into(),
            });
            return;
        }
        if let (Some(values), ExprKind::Str(s)) = (&r.enum_values, &value.kind) {
            self.enum_literal(values, s, value.span, target.path());
        }
    }

    fn enum_literal(&mut self, values: &[String], s: &str, span: crate::Span, field: String) {
        if !values.iter().any(|v| v.eq_ignore_ascii_case(s)) {
            self.errors.push(CheckError::BadEnumValue {
                span,
                value: s.to_string(),
                field,
                values: values.to_vec(),
            });
        }
    }
}

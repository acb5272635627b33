//! The ladder-specific checks: labels and jumps (§11.1.3, §20.8.1), and the
//! types of contacts and coils, found with the ST checker's resolver so that
//! a name means in a rung what it means in ST. Everything else (unknown
//! names, read-only targets, the types of variable outputs) is left to the
//! ST checker, which sees the desugared rungs.

use super::ast::{Action, Cond, Output, Rung};
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use crate::st::check::{Checker, Context, Limits};
use linc_format::Code;
use linc_stdlib::Ty;
use std::collections::{HashMap, HashSet};

/// The most characters a label may have (§20.8.1).
pub const MAX_LABEL: usize = 16;

/// The label that stands after the last rung.
pub const END_LABEL: &str = "_End";

/// For each rung, the rung its jump continues at (`rungs.len()` for
/// `_End`), when it is a valid forward jump; and the label and jump errors.
pub fn jumps(rungs: &[Rung]) -> (Vec<Option<usize>>, Vec<Diagnostic>) {
    let mut diags = Vec::new();
    let mut labels: HashMap<String, (usize, Span)> = HashMap::new();
    for (i, r) in rungs.iter().enumerate() {
        let Some(l) = &r.label else { continue };
        if l.text.chars().count() > MAX_LABEL {
            diags.push(
                Diagnostic::error(
                    Code::E0302,
                    format!("label `{}` is longer than {MAX_LABEL} characters", l.text),
                    l.span,
                )
                .label(format!("{} characters", l.text.chars().count()))
                .help(format!("labels have up to {MAX_LABEL} characters 0-9, A-Z, a-z and _ (§20.8.1)")),
            );
        }
        let key = l.text.as_str().to_ascii_uppercase();
        if key == END_LABEL.to_ascii_uppercase() {
            diags.push(
                Diagnostic::error(Code::E0303, "label `_End` is defined twice", l.span)
                    .label("`_End` already stands after the last rung")
                    .help("choose another name; jump to `_End` to skip to the end"),
            );
            continue;
        }
        match labels.get(&key) {
            Some(&(_, first)) => diags.push(
                Diagnostic::error(Code::E0303, format!("label `{}` is defined twice", l.text), l.span)
                    .label("second definition")
                    .with(first, "first defined here")
                    .help("labels ignore case and are unique within an action"),
            ),
            None => {
                labels.insert(key, (i, l.span));
            }
        }
    }
    let targets = rungs
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let Output::Jump { label, .. } = &r.output else { return None };
            let key = label.text.as_str().to_ascii_uppercase();
            if key == END_LABEL.to_ascii_uppercase() {
                return Some(rungs.len());
            }
            match labels.get(key.as_str()) {
                None => {
                    diags.push(
                        Diagnostic::error(
                            Code::E0304,
                            format!("unresolved jump: no label `{}`", label.text),
                            label.span,
                        )
                        .label("no rung of this action has this label")
                        .help("a jump goes to a label of the same action, or to `_End` after the last rung"),
                    );
                    None
                }
                Some(&(t, at)) if t <= i => {
                    diags.push(
                        Diagnostic::error(Code::E0305, format!("backward jump to `{}`", label.text), label.span)
                            .label("this jump goes back")
                            .with(at, "the label is here, at or above the jump")
                            .help("jumps go only forwards (§11.1.3); a loop is not allowed in a ladder"),
                    );
                    None
                }
                Some(&(t, _)) => Some(t),
            }
        })
        .collect();
    (targets, diags)
}

/// Checks the types of contacts and coils. Returns the errors and the
/// spans of the contacts and coils found wrong (the desugaring leaves them
/// out, so the ST checker does not report them a second time).
pub fn types(action: &Action, ctx: Context) -> (Vec<Diagnostic>, HashSet<Span>) {
    let mut c = Checker::new(ctx, Limits::default());
    c.begin_action(action.block_type.as_ref());
    c.take_errors();
    let mut t = Types { c, diags: Vec::new(), bad: HashSet::new() };
    for r in &action.rungs {
        if let Some(cond) = &r.cond {
            t.cond(cond);
        }
        if let Output::Coil { target, span, .. } = &r.output {
            t.coil(target, *span);
        }
    }
    (t.diags, t.bad)
}

struct Types<'a> {
    c: Checker<'a>,
    diags: Vec<Diagnostic>,
    bad: HashSet<Span>,
}

impl Types<'_> {
    fn ty(&mut self, e: &crate::st::ast::Expr) -> Ty {
        let ty = self.c.expression(e).ty;
        // The ST checker reports these errors when it checks the rungs.
        self.c.take_errors();
        ty
    }

    fn cond(&mut self, cond: &Cond) {
        match cond {
            Cond::Contact { expr, span, .. } => {
                let ty = self.ty(expr);
                if matches!(ty, Ty::Bool | Ty::Any) {
                    return;
                }
                let d = Diagnostic::error(
                    Code::E0306,
                    format!("a contact needs a digital value, not {}", ty_name(ty)),
                    expr.span,
                )
                .label(format!("this is {}", ty_name(ty)));
                let d = if matches!(ty, Ty::Int | Ty::Real) {
                    let text = crate::ladder::pretty::to_st::expr(expr);
                    d.help(format!("to test its value, write a comparison contact such as `[{text} <> 0]`"))
                } else {
                    d.help("a contact reads a BOOL, a bit (`Blk.Field.Bit3`) or a condition")
                };
                self.diags.push(d);
                self.bad.insert(*span);
            }
            Cond::Series(v) | Cond::Parallel(v, _) | Cond::Box { args: v, .. } => {
                for c in v {
                    self.cond(c);
                }
            }
        }
    }

    fn coil(&mut self, target: &crate::st::ast::Expr, span: Span) {
        if !matches!(target.kind, crate::st::ast::ExprKind::Var(_)) {
            self.diags.push(
                Diagnostic::error(Code::E0308, "a coil's target is not a variable", target.span)
                    .label("a coil writes a digital variable")
                    .help("to write a value computed from an expression, use a variable output: `-> target := value;`"),
            );
            self.bad.insert(span);
            return;
        }
        let ty = self.ty(target);
        if !matches!(ty, Ty::Bool | Ty::Any) {
            self.diags.push(
                Diagnostic::error(
                    Code::E0307,
                    format!("a coil needs a digital variable, not {}", ty_name(ty)),
                    target.span,
                )
                .label(format!("this is {}", ty_name(ty)))
                .help("a coil writes TRUE or FALSE; to write a number, use a variable output: `-> target := value;`"),
            );
            self.bad.insert(span);
        }
    }
}

fn ty_name(ty: Ty) -> &'static str {
    match ty {
        Ty::Bool => "a BOOL",
        Ty::Int => "an integer",
        Ty::Real => "a REAL",
        Ty::Text | Ty::Bytes | Ty::WStr => "a string",
        Ty::Any => "a value",
    }
}

//! The linc compiler: every language of a strategy to the one instruction
//! set, against a function-block database.
//!
//! Each language is a room: Structured Text ([`st`]), which the others are
//! lowered through, sequences ([`sfc`]), ladder ([`ladder`]) and FST tables
//! ([`fst`]); [`fmt`] lays each out. Data flows one way: bytes → text
//! ([`diag::files`]) → tokens → syntax tree, one action at a time → checked
//! against a [`linc_format::Database`] into the checked program → lowered
//! to an object file. A [`session::Session`] drives this for the files of
//! one run. Every stage reports plain-data errors that become
//! [`Diagnostic`]s, rendered in one place ([`diag`]).

/// Diagnostics, spans, source files, problems and their rendering.
pub mod diag;
/// The one canonical layout of every language (`linc fmt`, ADR 0017).
pub mod fmt;
/// FST tables: CSV reader, TLPs, checks, lowering, listing, translation.
pub mod fst;
/// Ladder files: parser, checks, desugaring to ST (ADR 0009).
pub mod ladder;
/// What each name denotes, as the checker resolves it (language servers).
pub mod names;
/// One compile session over the files of one run (ADR 0007).
pub mod session;
/// Sequences: parser, chart checks, generic names, resources, lowering.
pub mod sfc;
/// What kind of source a file is, decided in one place.
pub mod source_kind;
/// Structured Text: lexer, LALR grammar, tree, checks, lowering.
pub mod st;

/// The function library (§12.6) the checker types calls against, for the
/// surfaces that describe functions (a language server's hover and
/// completion).
pub mod functions {
    pub use linc_stdlib::{lookup, Signature, SIGNATURES};
}

pub use diag::{Diagnostic, FileId, Severity, Span};
pub use st::check::Context;

use session::{CheckOptions, Input, Session, Tree};
use st::{ast, hir};

/// The result of checking one text: the tree (if the parser could build
/// one), the checked program (only when there are no errors) and every
/// diagnostic, ordered by position, all in file 0.
#[derive(Debug)]
pub struct Report<T, P> {
    pub tree: Option<T>,
    pub program: Option<P>,
    pub diagnostics: Vec<Diagnostic>,
}

impl<T, P> Report<T, P> {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

/// Checks an action file as a one-file session. `stem` names a file's only
/// action when it has no `ACTION` header.
pub fn check_source(src: &str, stem: &str, ctx: Context) -> Report<ast::SourceFile, hir::Program> {
    let mut s = Session::keeping(ctx);
    let id = s.add(format!("{stem}.st"), src.as_bytes().to_vec());
    let c = s.check(id, CheckOptions { input: Input::Actions, tree: true });
    let tree = match c.tree {
        Some(Tree::Actions(t)) => Some(t),
        _ => None,
    };
    Report { tree, program: s.take_program(id), diagnostics: c.diagnostics }
}

/// Lexes, parses and checks a transition expression (§12.11).
pub fn check_transition(src: &str, ctx: Context) -> Report<ast::Expr, hir::Expr> {
    expression(src, ctx, Input::Transition)
}

/// Lexes, parses and checks an expression of any type (`linc eval`).
pub fn check_expression(src: &str, ctx: Context) -> Report<ast::Expr, hir::Expr> {
    expression(src, ctx, Input::Expression)
}

fn expression(src: &str, ctx: Context, input: Input) -> Report<ast::Expr, hir::Expr> {
    let mut s = Session::new(ctx);
    let id = s.add("<expr>", src.as_bytes().to_vec());
    let c = s.check(id, CheckOptions { input, tree: true });
    let tree = match c.tree {
        Some(Tree::Expr(e)) => Some(e),
        _ => None,
    };
    Report { tree, program: c.expr, diagnostics: c.diagnostics }
}

/// Parses and checks a `.sfc` sequence (its chart, associations, actions and
/// transitions) against `ctx`; the sequence's step names are put in scope
/// for its ST, whatever `ctx.steps` says.
pub fn check_sequence(src: &str, ctx: Context) -> Report<sfc::ast::Sequence, ()> {
    sfc::check_sequence(src, ctx)
}

/// Checks a ladder file (`.ld`, ADR 0009) as a one-file session: its rungs
/// are desugared into ST and checked as ST actions. `stem` names its only
/// action when it has no `ACTION` header. The tree is the desugared ST.
pub fn check_ladder(src: &str, stem: &str, ctx: Context) -> Report<ast::SourceFile, hir::Program> {
    let mut s = Session::keeping(ctx);
    let id = s.add(format!("{stem}.ld"), src.as_bytes().to_vec());
    let c = s.check(id, CheckOptions { input: Input::Actions, tree: true });
    let tree = match c.tree {
        Some(Tree::Actions(t)) => Some(t),
        _ => None,
    };
    Report { tree, program: s.take_program(id), diagnostics: c.diagnostics }
}

/// Checks `expr` (an expectation of a scenario test) as a BOOL expression in which the step variables of
/// `steps` (slot order: `.X` at `2 × slot`, `.T` at `2 × slot + 1`) may be
/// read, and lowers it into a one-unit object whose retained slots are those
/// step variables. Diagnostics are located within `expr`.
pub fn compile_expectation(
    expr: &str,
    db: &linc_format::Database,
    steps: &[String],
) -> Result<linc_format::ObjectFile, Vec<Diagnostic>> {
    let ctx = Context::of(Some(db)).with_all_steps(steps);
    let report = check_transition(expr, ctx);
    let failed = report.has_errors();
    let Some(checked) = report.program.filter(|_| !failed) else {
        return Err(report.diagnostics);
    };
    st::lower::lower_expectation(&checked, &st::lower::Lines::new(expr), steps)
        .map_err(|errors| errors.iter().map(|e| e.to_diagnostic()).collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use linc_format::isa::Op;

    #[test]
    fn expectations_compile_with_step_variables() {
        let db = linc_format::Database::from_json(r#"{"blocks": {"R": {"type": "RECIPE"}}}"#).unwrap();
        let steps = vec!["Fill".to_string(), "Heat".to_string()];
        let obj = compile_expectation("Heat.X AND R.A0 > 1.0", &db, &steps).expect("compiles");
        let code = &obj.units[0].blocks[0].ops.0;
        assert!(code.contains(&Op::LoadRet { n: 2 }), "Heat is slot 1: .X at 2");
        assert_eq!(obj.units[0].retained, 4);
        // Two sequences with a step `Fill`: the first one's is meant.
        let twice = vec!["Fill".to_string(), "Heat".to_string(), "Fill".to_string()];
        let obj = compile_expectation("Fill.X", &db, &twice).expect("compiles");
        assert!(obj.units[0].blocks[0].ops.0.contains(&Op::LoadRet { n: 0 }), "slot 0, not 2");
        let e = compile_expectation("R.A0 + 1.0", &db, &steps).unwrap_err();
        assert!(!e.is_empty(), "not BOOL");
        let e = compile_expectation("Nope.X", &db, &steps).unwrap_err();
        assert!(!e.is_empty());
    }
}

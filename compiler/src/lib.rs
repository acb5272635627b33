//! The linc compiler front end for LIN Structured Text.
//!
//! Data flows one way: source → [`lexer`] tokens → [`parser`] syntax tree
//! ([`ast`]) → [`check`]ed against a [`linc_runtime::Database`]. Every stage
//! reports plain-data errors that become [`Diagnostic`]s, rendered in one
//! place ([`render`]).

pub mod ast;
pub mod check;
pub mod codes;
pub mod diagnostic;
pub mod errors;
pub mod hir;
pub mod lexer;
pub mod lower;
pub mod parse_support;
pub mod parser;
pub mod pretty;
pub mod render;
pub mod span;
pub mod token;

pub use diagnostic::{Diagnostic, Severity};
pub use span::Span;

use check::Context;

/// The result of checking one text: the tree (if the parser could build
/// one), the checked program (only when there are no errors) and every
/// diagnostic, ordered by position.
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

fn collect(errors: parser::ParseErrors, checked: &[check::CheckError]) -> Vec<Diagnostic> {
    let mut out: Vec<Diagnostic> = errors.lex.iter().map(errors::LexError::to_diagnostic).collect();
    out.extend(errors.syntax.iter().map(errors::SyntaxError::to_diagnostic));
    out.extend(checked.iter().map(check::CheckError::to_diagnostic));
    out.sort_by_key(|d| (d.span.start, d.span.end));
    out
}

/// Lexes, parses and checks an action file. `stem` names a file's only
/// action when it has no `ACTION` header.
pub fn check_source(src: &str, stem: &str, ctx: Context) -> Report<ast::SourceFile, hir::Program> {
    let (tree, errors) = parser::parse_file(src, stem);
    let (checked, program) = match &tree {
        Some(t) => {
            let (e, p) = check::check_file(t, ctx);
            (e, Some(p))
        }
        None => (Vec::new(), None),
    };
    let diagnostics = collect(errors, &checked);
    let program = program.filter(|_| !diagnostics.iter().any(Diagnostic::is_error));
    Report { tree, program, diagnostics }
}

/// Lexes, parses and checks a transition expression (§12.11).
pub fn check_transition(src: &str, ctx: Context) -> Report<ast::Expr, hir::Expr> {
    expression(src, ctx, check::check_transition)
}

/// Lexes, parses and checks an expression of any type (`linc eval`).
pub fn check_expression(src: &str, ctx: Context) -> Report<ast::Expr, hir::Expr> {
    expression(src, ctx, check::check_expression)
}

fn expression(
    src: &str,
    ctx: Context,
    check: fn(&ast::Expr, Context) -> (Vec<check::CheckError>, hir::Expr),
) -> Report<ast::Expr, hir::Expr> {
    let (tree, errors) = parser::parse_expr(src);
    let (checked, program) = match &tree {
        Some(t) => {
            let (e, p) = check(t, ctx);
            (e, Some(p))
        }
        None => (Vec::new(), None),
    };
    let diagnostics = collect(errors, &checked);
    let program = program.filter(|_| !diagnostics.iter().any(Diagnostic::is_error));
    Report { tree, program, diagnostics }
}

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
pub mod lexer;
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
/// one) and every diagnostic, ordered by position.
#[derive(Debug)]
pub struct Report<T> {
    pub tree: Option<T>,
    pub diagnostics: Vec<Diagnostic>,
}

impl<T> Report<T> {
    pub fn has_errors(&self) -> bool {
        self.diagnostics.iter().any(Diagnostic::is_error)
    }
}

fn collect(errors: parser::ParseErrors, checked: Vec<check::CheckError>) -> Vec<Diagnostic> {
    let mut out: Vec<Diagnostic> = errors
        .lex
        .iter()
        .map(errors::LexError::to_diagnostic)
        .collect();
    out.extend(errors.syntax.iter().map(errors::SyntaxError::to_diagnostic));
    out.extend(checked.iter().map(check::CheckError::to_diagnostic));
    out.sort_by_key(|d| (d.span.start, d.span.end));
    out
}

/// Lexes, parses and checks an action file. `stem` names a file's only
/// action when it has no `ACTION` header.
pub fn check_source(src: &str, stem: &str, ctx: Context) -> Report<ast::SourceFile> {
    let (tree, errors) = parser::parse_file(src, stem);
    let checked = tree
        .as_ref()
        .map(|t| check::check_file(t, ctx))
        .unwrap_or_default();
    Report {
        tree,
        diagnostics: collect(errors, checked),
    }
}

/// Lexes, parses and checks a transition expression (§12.11).
pub fn check_transition(src: &str, ctx: Context) -> Report<ast::Expr> {
    let (tree, errors) = parser::parse_expr(src);
    let checked = tree
        .as_ref()
        .map(|t| check::check_transition(t, ctx))
        .unwrap_or_default();
    Report {
        tree,
        diagnostics: collect(errors, checked),
    }
}

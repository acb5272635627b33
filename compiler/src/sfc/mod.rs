//! The front end of `.sfc` sequences (issue 8): a textual SFC with LIN
//! Structured Text inside and LIN's action qualifiers.
//!
//! [`parser`] reads the chart structure and hands the ST inside to the ST
//! parser; [`check`] checks the charts, the associations and, with the ST
//! checker, the actions and transition conditions. Lowering is elsewhere.

pub mod ast;
pub mod check;
pub mod errors;
pub mod generic;
pub mod lower;
pub mod parser;
pub mod pretty;
mod refs;
pub mod resources;
mod safety;
mod shift;

use crate::check::Context;
use crate::diagnostic::Diagnostic;
use crate::Report;

/// Parses and checks one sequence. The tree is always built (parts that did
/// not parse are left out, already reported); diagnostics come in source
/// order, each once.
pub fn check_sequence(src: &str, ctx: Context) -> Report<ast::Sequence, ()> {
    let (seq, mut diagnostics) = parser::parse(src);
    diagnostics.extend(check::check(&seq, ctx));
    let diagnostics = ordered(diagnostics);
    let ok = !diagnostics.iter().any(Diagnostic::is_error);
    Report { tree: Some(seq), program: ok.then_some(()), diagnostics }
}

/// Sorts by position and drops repeats: the text inside an action is lexed
/// once for the chart and once more by the ST parser.
fn ordered(mut d: Vec<Diagnostic>) -> Vec<Diagnostic> {
    d.sort_by_key(|d| (d.span.start, d.span.end, d.code));
    d.dedup_by(|b, a| a.code == b.code && a.span == b.span);
    d
}

/// Checks a sequence and, when it is clean, lowers it into an object with
/// one sequence unit called `name`; `file` names the source in the object.
pub fn compile_sequence(
    src: &str,
    name: &str,
    file: &str,
    ctx: Context,
) -> (Vec<Diagnostic>, Option<linc_runtime::ObjectFile>) {
    let report = check_sequence(src, ctx);
    let (Some(tree), Some(())) = (&report.tree, report.program) else {
        return (report.diagnostics, None);
    };
    match lower::lower(tree, name, file, src, ctx) {
        Ok(obj) => (report.diagnostics, Some(obj)),
        Err(errors) => {
            let mut d = report.diagnostics;
            d.extend(errors.iter().map(crate::lower::LowerError::to_diagnostic));
            (d, None)
        }
    }
}

/// Every step name of the sequence (nested charts included), upper case.
pub(crate) fn steps_of(seq: &ast::Sequence) -> std::collections::HashSet<String> {
    let charts = std::iter::once(&seq.chart).chain(seq.actions.iter().filter_map(|a| match &a.body {
        ast::ActionBody::Chart(c) => Some(c),
        ast::ActionBody::St(_) => None,
    }));
    charts.flat_map(|c| &c.steps).map(|s| s.name.text.to_ascii_uppercase()).collect()
}

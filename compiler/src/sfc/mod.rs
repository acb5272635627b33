//! The front end of `.sfc` sequences (issue 8): a textual SFC with LIN
//! Structured Text inside and LIN's action qualifiers.
//!
//! [`parser`] reads the chart structure and hands the ST inside to the ST
//! parser; `check` checks the charts, the associations and, with the ST
//! checker, the actions and transition conditions. Lowering is elsewhere.

pub mod ast;
pub(crate) mod check;
pub(crate) mod errors;
pub mod generic;
pub(crate) mod lower;
pub mod parser;
pub mod pretty;
mod refs;
pub mod resources;
mod safety;
pub(crate) mod shift;
pub(crate) mod size;

/// How many steps and code blocks one sequence may have (the object format's limits).
pub use lower::{MAX_BLOCKS, MAX_STEPS};

use crate::diag::Diagnostic;
use crate::st::check::Context;
use crate::Report;

/// Parses and checks one sequence. The tree is always built (parts that did
/// not parse are left out, already reported); diagnostics come in source
/// order, each once.
pub fn check_sequence(src: &str, ctx: Context) -> Report<ast::Sequence, ()> {
    let (seq, diagnostics) = parser::parse(src);
    check_parsed(seq, diagnostics, ctx)
}

/// Checks a parsed sequence; `diagnostics` are the parser's.
fn check_parsed(seq: ast::Sequence, mut diagnostics: Vec<Diagnostic>, ctx: Context) -> Report<ast::Sequence, ()> {
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
) -> (Vec<Diagnostic>, Option<linc_format::ObjectFile>) {
    lower_checked(check_sequence(src, ctx), src, (name, file), ctx)
}

/// Lowers a checked sequence when it is clean.
fn lower_checked(
    report: Report<ast::Sequence, ()>,
    src: &str,
    (name, file): (&str, &str),
    ctx: Context,
) -> (Vec<Diagnostic>, Option<linc_format::ObjectFile>) {
    let (Some(tree), Some(())) = (&report.tree, report.program) else {
        return (report.diagnostics, None);
    };
    match lower::lower(tree, name, file, src, ctx) {
        Ok(obj) => (report.diagnostics, Some(obj)),
        Err(errors) => {
            let mut d = report.diagnostics;
            d.extend(errors.iter().map(crate::st::lower::LowerError::to_diagnostic));
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
    charts.flat_map(|c| &c.steps).map(|s| s.name.text.as_str().to_ascii_uppercase()).collect()
}

/// [`check_sequence`] for a generic sequence: the map's entries are aliases
/// in `ctx.db` (see [`generic::bind`]); generic names may have 16
/// characters, and a name the map lacks is E0250 (W0250 when `allow`);
/// a step may not have a generic name of the map (E0255).
pub fn check_generic(src: &str, ctx: Context, map: &generic::Named, allow: bool) -> Report<ast::Sequence, ()> {
    let (mut seq, diagnostics) = parser::parse(src);
    let mut diagnostics = generic::lift_long_names(&mut seq, diagnostics);
    diagnostics.extend(generic::step_collisions(&seq, map));
    let map_file = map.file.as_str();
    let mut report = check_parsed(seq, diagnostics, ctx);
    report.diagnostics = generic::with_map(report.diagnostics, src, map_file, allow);
    let ok = !report.diagnostics.iter().any(Diagnostic::is_error);
    report.program = ok.then_some(());
    report
}

/// [`compile_sequence`] for a generic sequence (every name must be mapped).
pub fn compile_generic(
    src: &str,
    (name, file): (&str, &str),
    ctx: Context,
    map: &generic::Named,
) -> (Vec<Diagnostic>, Option<linc_format::ObjectFile>) {
    lower_checked(check_generic(src, ctx, map, false), src, (name, file), ctx)
}

/// Records the names a sequence declares and names in its structure: its
/// steps (declared, and in transitions) and its actions (declared, and in
/// associations), for [`crate::names`].
pub fn declared(seq: &ast::Sequence, r: &crate::names::Recorder) {
    use crate::names::Meaning;
    let mut charts = vec![&seq.chart];
    charts.extend(seq.actions.iter().filter_map(|a| match &a.body {
        ast::ActionBody::Chart(c) => Some(c),
        ast::ActionBody::St(_) => None,
    }));
    let step = |name: &str| charts.iter().flat_map(|c| &c.steps).find(|s| s.name.text.eq_ignore_ascii_case(name));
    let action = |name: &str| seq.actions.iter().find(|a| a.name.text.eq_ignore_ascii_case(name));
    for c in &charts {
        for s in &c.steps {
            r.push(s.name.span, Meaning::Step(s.name.text.to_string()));
            for a in s.assocs.iter().filter_map(|a| action(&a.action.text).map(|d| (a, d))) {
                r.push(a.0.action.span, Meaning::Action(a.1.name.text.to_string()));
            }
        }
        for t in &c.transitions {
            for name in t.from.iter().chain(&t.to) {
                if let Some(s) = step(&name.text) {
                    r.push(name.span, Meaning::Step(s.name.text.to_string()));
                }
            }
        }
    }
    for a in &seq.actions {
        r.push(a.name.span, Meaning::Action(a.name.text.to_string()));
    }
}

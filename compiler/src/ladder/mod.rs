//! The front end of ladder diagrams as text (`.ld` files, issue 9, guide
//! chapter 11 and §20.8).
//!
//! [`parser`] reads rungs by hand and hands the ST inside them (contacts,
//! coil targets, variable outputs) to the ST parser; [`check`] checks labels,
//! jumps, contacts and coils; [`desugar`] turns each rung into ST
//! statements, which the ST checker and lowering then compile (ADR 0009):
//! types, names and most errors of a ladder action are those of its ST.

pub mod ast;
pub mod check;
pub mod desugar;
pub mod parser;
pub mod pretty {
    pub mod draw;
    pub mod to_st;
}

use crate::check::Context;
use crate::diagnostic::Diagnostic;

/// Whether a file name is a ladder source (`.ld`, any case).
pub fn is_ladder(name: &str) -> bool {
    std::path::Path::new(name).extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("ld"))
}

/// What the ladder front end makes of a file.
#[derive(Debug)]
pub struct Desugared {
    /// The rungs as read.
    pub ladder: ast::File,
    /// The same actions as ST, for the ST checker.
    pub st: crate::ast::SourceFile,
    /// The ladder front end's diagnostics (the ST checker's come later), in
    /// source order.
    pub diagnostics: Vec<Diagnostic>,
}

/// Parses a ladder file, checks its labels, jumps, contacts and coils, and
/// desugars it into ST. `stem` names the action of a file without headers.
pub fn desugar(src: &str, stem: &str, ctx: Context) -> Desugared {
    let (ladder, mut diagnostics) = parser::parse(src, stem);
    let mut actions = Vec::with_capacity(ladder.actions.len());
    for a in &ladder.actions {
        let (targets, jump_errors) = check::jumps(&a.rungs);
        let (type_errors, bad) = check::types(a, ctx);
        diagnostics.extend(jump_errors);
        diagnostics.extend(type_errors);
        let (st, errors) = desugar::action(a, &targets, &bad);
        diagnostics.extend(errors);
        actions.push(st);
    }
    diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
    Desugared { ladder, st: crate::ast::SourceFile { actions }, diagnostics }
}

/// The equivalent ST of a ladder file, as text (`linc ladder to-st`), or
/// the diagnostics when it has errors of its own.
pub fn to_st(src: &str, stem: &str, ctx: Context) -> Result<String, Vec<Diagnostic>> {
    let d = desugar(src, stem, ctx);
    if d.diagnostics.iter().any(Diagnostic::is_error) {
        return Err(d.diagnostics);
    }
    Ok(pretty::to_st::file(&d.st))
}

/// The diagram of a ladder file (`linc ladder show`), or its syntax errors;
/// `values` gives the state of each element (contact operands and coil
/// targets, by span), for `--values`.
pub fn draw(src: &str, stem: &str, values: pretty::draw::Values) -> Result<String, Vec<Diagnostic>> {
    let (ladder, diagnostics) = parser::parse(src, stem);
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Err(diagnostics);
    }
    Ok(pretty::draw::file(src, &ladder, values))
}

/// The spans of the elements `--values` shows, for the caller to evaluate.
pub fn element_spans(src: &str, stem: &str) -> Vec<crate::span::Span> {
    pretty::draw::element_spans(&parser::parse(src, stem).0)
}

/// The rungs of a sequence's `ACTION name : LADDER` as one ST action named
/// `name` (spans relative to `body`), with the ladder's own diagnostics:
/// syntax, labels and jumps. Contacts and coils are typed by the ST
/// checker when the sequence is checked.
pub fn desugar_body(body: &str, name: &str) -> (crate::ast::Action, Vec<Diagnostic>) {
    let (ladder, mut diagnostics) = parser::parse(body, name);
    let Some(a) = ladder.actions.into_iter().next() else {
        let name = crate::ast::Ident { text: name.to_string(), span: crate::span::Span::default() };
        let span = crate::span::Span::new(0, body.len());
        return (crate::ast::Action { name, block_type: None, body: Vec::new(), header: None, span }, diagnostics);
    };
    let (targets, jump_errors) = check::jumps(&a.rungs);
    diagnostics.extend(jump_errors);
    let (st, errors) = desugar::action(&a, &targets, &std::collections::HashSet::new());
    diagnostics.extend(errors);
    (st, diagnostics)
}

/// A sequence's ladder transition condition (one rung without an output,
/// §20.5.7) as the ST expression it stands for (spans relative to `cond`),
/// with the ladder front end's diagnostics.
pub fn desugar_condition(cond: &str) -> (Option<crate::ast::Expr>, Vec<Diagnostic>) {
    // Read as a rung whose coil stands for the transition; its value is the condition.
    let rung = format!("{cond} -> (T);");
    let (st, diagnostics) = desugar_body(&rung, "T");
    let expr = st.body.into_iter().find_map(|s| match s {
        crate::ast::Stmt::Assign { value, .. } => Some(*value),
        _ => None,
    });
    (expr, diagnostics)
}

//! The front end of ladder diagrams as text (`.ld` files, issue 9, guide
//! chapter 11 and §20.8).
//!
//! [`parser`] reads rungs by hand and hands the ST inside them (contacts,
//! coil targets, variable outputs) to the ST parser; `check` checks labels,
//! jumps, contacts and coils; `desugar` turns each rung into ST
//! statements, which the ST checker and lowering then compile (ADR 0009):
//! types, names and most errors of a ladder action are those of its ST.

pub mod ast;
pub(crate) mod check;
pub(crate) mod desugar;
pub mod parser;
pub mod pretty {
    pub mod to_st;
}

use crate::diag::Diagnostic;
use crate::st::check::Context;

/// Whether a file name is a ladder source (`.ld`, any case).
pub fn is_ladder(name: &str) -> bool {
    std::path::Path::new(name).extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("ld"))
}

/// Parses a ladder file one action at a time, checks each action's labels,
/// jumps, contacts and coils, desugars it into ST and hands the ST action
/// to `each` before the next action is read: only one action is held.
/// `stem` names the action of a file without headers. Returns the ladder
/// front end's diagnostics (the ST checker's come later), in source order.
pub fn desugar_each(
    src: &str,
    stem: &str,
    ctx: Context,
    each: &mut dyn FnMut(crate::st::ast::Action),
) -> Vec<Diagnostic> {
    let mut diagnostics = Vec::new();
    let mut read = parser::parse_each(src, stem, &mut |a| {
        let (targets, jump_errors) = check::jumps(&a.rungs);
        let (type_errors, bad) = check::types(&a, ctx);
        diagnostics.extend(jump_errors);
        diagnostics.extend(type_errors);
        let (st, errors) = desugar::action(&a, &targets, &bad);
        drop(a);
        diagnostics.extend(errors);
        each(st);
    });
    diagnostics.append(&mut read);
    diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
    diagnostics
}

/// The equivalent ST of a ladder file, as text (`linc ladder to-st`), or
/// the diagnostics when it has errors of its own.
pub fn to_st(src: &str, stem: &str, ctx: Context) -> Result<String, Vec<Diagnostic>> {
    let mut out = String::new();
    let diagnostics = desugar_each(src, stem, ctx, &mut |a| pretty::to_st::action_into(&mut out, &a));
    if diagnostics.iter().any(Diagnostic::is_error) {
        return Err(diagnostics);
    }
    Ok(out)
}

/// The rungs of a sequence's `ACTION name : LADDER` as one ST action named
/// `name` (spans relative to `body`), with the ladder's own diagnostics:
/// syntax, labels and jumps. Contacts and coils are typed by the ST
/// checker when the sequence is checked.
pub fn desugar_body(body: &str, name: &str) -> (crate::st::ast::Action, Vec<Diagnostic>) {
    desugar_body_as(body, name, true)
}

/// [`desugar_body`], with coils as decisions (`decide`) or as assignments
/// of the rung's value (a transition's condition).
fn desugar_body_as(body: &str, name: &str, decide: bool) -> (crate::st::ast::Action, Vec<Diagnostic>) {
    let (ladder, mut diagnostics) = parser::parse(body, name);
    let Some(a) = ladder.actions.into_iter().next() else {
        let name = crate::st::ast::Ident { text: name.into(), span: crate::diag::span::Span::default() };
        let span = crate::diag::span::Span::new(0, body.len());
        return (crate::st::ast::Action { name, block_type: None, body: Vec::new(), header: None, span }, diagnostics);
    };
    let (targets, jump_errors) = check::jumps(&a.rungs);
    diagnostics.extend(jump_errors);
    let (st, errors) = match decide {
        true => desugar::action(&a, &targets, &std::collections::HashSet::new()),
        false => desugar::condition_rung(&a, &targets),
    };
    diagnostics.extend(errors);
    (st, diagnostics)
}

/// A sequence's ladder transition condition (one rung without an output,
/// §20.5.7) as the ST expression it stands for (spans relative to `cond`),
/// with the ladder front end's diagnostics.
pub fn desugar_condition(cond: &str) -> (Option<crate::st::ast::Expr>, Vec<Diagnostic>) {
    // Read as a rung whose coil stands for the transition; its value is the condition.
    let rung = format!("{cond} -> (T);");
    let (st, diagnostics) = desugar_body_as(&rung, "T", false);
    let expr = st.body.into_iter().find_map(|s| match s {
        crate::st::ast::Stmt::Assign { value, .. } => Some(*value),
        _ => None,
    });
    (expr, diagnostics)
}

/// Records the rung labels a ladder file declares and the jumps to them,
/// for [`crate::names`].
pub fn declared(src: &str, stem: &str, r: &crate::names::Recorder) {
    use crate::names::Meaning;
    let (file, _) = parser::parse(src, stem);
    for a in &file.actions {
        let label =
            |name: &str| a.rungs.iter().filter_map(|g| g.label.as_ref()).find(|l| l.text.eq_ignore_ascii_case(name));
        for rung in &a.rungs {
            if let Some(l) = &rung.label {
                r.push(l.span, Meaning::Label(l.text.to_string()));
            }
            if let ast::Output::Jump { label: to, .. } = &rung.output {
                if let Some(l) = label(&to.text) {
                    r.push(to.span, Meaning::Label(l.text.to_string()));
                }
            }
        }
    }
}

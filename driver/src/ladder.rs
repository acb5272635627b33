//! The values of a ladder drawing (`linc ladder show --values`): runs a ladder file's actions against a
//! database, then evaluates each element (contact operands, coil targets)
//! in the database as the run left it, for the drawing.

use crate::plant::{Choice, PlantSpec, Program, Running};
use linc_compiler::diag::Problems;
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
pub use linc_draw::ladder_text::Values;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Database, Linked, Program as Linking, Store};
use linc_stdlib::Value;
use std::collections::HashMap;
use std::path::Path;

/// The truth of each element of a ladder file, by the span of its operand.
pub type Truths = HashMap<(usize, usize), bool>;

/// What a run of a ladder file's actions left for a drawing.
pub struct AfterRun {
    /// The truth of each element, by span.
    pub truths: Truths,
    /// The lines of the file on which a statement started in the last
    /// cycle (every action's last run), as the runtime counted them, so a
    /// picture draws a rung a taken jump skipped as not run; `None` with
    /// no cycles (nothing ran).
    pub lines_ran: Option<Vec<u32>>,
}

/// The truth of each element after `cycles` runs of every action, by span,
/// what the last cycle ran, and the run's problems (warnings, runtime
/// faults). The actions run through the plant builder, on the database's
/// values with `set`, at the clock's zero with seed 1, so a picture does
/// not depend on the day.
pub fn after_run(file: &Path, db_path: &Path, set: &[String], cycles: u32) -> Result<(AfterRun, Problems), Problems> {
    let spec = PlantSpec {
        program: Program::Actions { file: file.to_path_buf(), action: Choice::Every, block: None },
        set: set.to_vec(),
        now: Some(0),
        seed: Some(1),
        ..PlantSpec::strategy(db_path)
    };
    let mut plant = crate::plant::build(&spec)?;
    let mut problems = std::mem::take(&mut plant.warnings);
    let lines_ran = cycle_watched(&mut plant, cycles, &mut problems)?;
    let Running::Actions(a) = &plant.running else { return Err(problems.refused()) };
    let text = crate::files::read_input_text(file).unwrap_or_default();
    let stem = crate::source::stem(file, "ladder");
    let mut known = HashMap::new();
    for span in linc_draw::ladder_text::element_spans(&text, stem) {
        if let Some(v) = text.get(span.start..span.end).and_then(|e| truth(e, &a.store.db, &a.store)) {
            known.insert((span.start, span.end), v);
        }
    }
    Ok((AfterRun { truths: known, lines_ran }, problems))
}

/// Runs every action `cycles` times, the last cycle counted (coverage
/// counters, ADR 0020): the lines on which a statement started in it.
fn cycle_watched(
    plant: &mut crate::plant::Plant,
    cycles: u32,
    problems: &mut Problems,
) -> Result<Option<Vec<u32>>, Problems> {
    use linc_runtime::cover::{lines_between, statement_counts};
    if let Running::Actions(a) = &mut plant.running {
        a.linked.enable_coverage();
    }
    let req = crate::run::RunRequest::default;
    let first = crate::run::actions(plant, cycles.saturating_sub(1), 0.0, req())?.problems;
    // A fault ends an action's cycles: its last cycle is not run after it,
    // and what ran is then not known.
    let faulted = first.has_errors();
    problems.append(first);
    let counts = |plant: &crate::plant::Plant| match &plant.running {
        Running::Actions(a) => (0..a.programs.len()).map(|i| statement_counts(&a.linked, i)).collect(),
        Running::Strategy(_) => Vec::new(),
    };
    let before: Vec<_> = counts(plant);
    if cycles == 0 || faulted {
        return Ok(None);
    }
    problems.append(crate::run::actions(plant, 1, 0.0, req())?.problems);
    let after: Vec<_> = counts(plant);
    let mut lines: Vec<u32> = before.iter().zip(&after).flat_map(|(b, a)| lines_between(b, a)).collect();
    lines.sort_unstable();
    lines.dedup();
    Ok(Some(lines))
}

/// The ST a ladder file compiles as (`linc ladder to-st`, ADR 0009),
/// checked against `db` when given; the file's own errors are errors
/// found in it.
pub fn to_st(file: &Path, db: Option<&Path>) -> Result<String, Problems> {
    let db = crate::database::load_opt(db)?;
    let ctx = Context::of(db.as_ref().map(|d| &d.db));
    let source = crate::source::read(file)?;
    let stem = crate::source::stem(file, "ladder");
    linc_compiler::ladder::to_st(&source.text, stem, ctx).map_err(|ds| source.problems(ds))
}

/// The rungs drawn in text (`linc ladder show`), handed to `write` one
/// action at a time; `values` gives each element's state and `ran` the
/// lines the last cycle ran ([`AfterRun::lines_ran`]: a rung not run is
/// drawn as such). The file's syntax errors and rungs too large to draw
/// are errors found in it.
pub fn show(file: &Path, values: Values, ran: Option<&[u32]>, write: &mut dyn FnMut(&str)) -> Result<(), Problems> {
    let bytes = crate::files::read_input(file).map_err(|e| Problems::unreadable(file, &e))?;
    let (text, _) = linc_compiler::diag::decode(bytes);
    let stem = crate::source::stem(file, "ladder");
    linc_draw::ladder_text::draw_to(&text, stem, (values, ran), write).map_err(|ds| {
        let mut files = linc_compiler::diag::SourceFiles::new();
        let id = files.add(file.display().to_string(), text.clone());
        Problems::of(files, ds.into_iter().map(|d| d.in_file(id)).collect())
    })
}

/// An expression's value in `store`, as a truth value (`None` if it is not
/// one or does not evaluate).
fn truth(expr: &str, db: &Database, store: &Store) -> Option<bool> {
    eval(&element(expr, db, store)?, &mut store.clone())
}

/// An element's expression compiled and linked to `store`.
fn element(expr: &str, db: &Database, store: &Store) -> Option<Linked> {
    let mut session = Session::new(Context::of(Some(db)));
    let id = session.add("<element>", expr.as_bytes().to_vec());
    let program = session.check(id, CheckOptions { input: Input::Expression, tree: false }).expr?;
    let obj = lower::lower_eval(&program, &Lines::new(expr)).ok()?;
    linc_runtime::verify::verify(obj).ok()?.link(store, &[Linking { unit: 0, own: None }]).ok()
}

/// Runs an element's expression (it only reads the store: an expression
/// assigns nothing) and takes its truth.
fn eval(linked: &Linked, store: &mut Store) -> Option<bool> {
    let mut act = Activation::new(linked, 0, 0);
    Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0)).run(linked, &mut act, store, None).ok()?;
    match act.result? {
        Value::Bool(b) => Some(b),
        Value::Int(i) => Some(i != 0),
        _ => None,
    }
}

/// A ladder file's elements compiled once against a running plant's store,
/// so a live picture (`linc serve`) evaluates them after each scan without
/// compiling them again.
pub struct LiveElements {
    items: Vec<((usize, usize), Linked)>,
}

impl LiveElements {
    pub fn new(text: &str, stem: &str, store: &Store) -> LiveElements {
        let items = linc_draw::ladder_text::element_spans(text, stem)
            .into_iter()
            .filter_map(|span| {
                let linked = element(text.get(span.start..span.end)?, &store.db, store)?;
                Some(((span.start, span.end), linked))
            })
            .collect();
        LiveElements { items }
    }

    /// The truth of each element in `store` now, by span.
    pub fn truths(&self, store: &mut Store) -> HashMap<(usize, usize), bool> {
        self.items.iter().filter_map(|(span, linked)| Some((*span, eval(linked, store)?))).collect()
    }
}

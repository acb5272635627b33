//! The values of a ladder drawing (`linc ladder show --values`): runs a ladder file's actions against a
//! database, then evaluates each element (contact operands, coil targets)
//! in the database as the run left it, for the drawing.

use crate::database::load as load_db;
use crate::database::set_and_show;
use crate::strategy::own_block;
use crate::Reporter;
use linc_compiler::diag::render::SourceFiles;
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_compiler::st::lower::{self, Lines};
use linc_compiler::Context;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Database, Linked, Program, Store};
use linc_stdlib::Value;
use std::collections::HashMap;
use std::path::Path;

/// The truth of each element after `cycles` runs of every action, by span.
pub fn after_run(
    file: &Path,
    db_path: &Path,
    set: &[String],
    cycles: u32,
    r: &mut Reporter,
) -> Result<HashMap<(usize, usize), bool>, u8> {
    let mut files = SourceFiles::new();
    let db = load_db(Some(db_path), &mut files, r)?.unwrap_or_default();
    let mut store = Store::new(db.clone());
    set_and_show(&mut store, set, &[], r)?;
    let obj = crate::build::compile(&[file.to_path_buf()], Some(&db), r, 1).map_err(|crate::build::Failed(s)| s)?;
    let name = file.display().to_string();
    let verified = linc_runtime::verify::verify(obj).map_err(|e| {
        r.whole_file(&name, e.code(), e.to_string());
        2u8
    })?;
    let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
    for unit in 0..verified.object().units.len() {
        let own = own_block(&store, None, &verified.object().units[unit].block_type)
            .map_err(|d| crate::report::refused(r, *d))?;
        let linked = verified.clone().link(&store, &[Program { unit, own }]).map_err(|e| {
            r.whole_file(&name, e.code(), e.to_string());
            2u8
        })?;
        let mut act = Activation::new(&linked, 0, 0);
        for _ in 0..cycles {
            if let Err(e) = vm.run(&linked, &mut act, &mut store, None) {
                r.runtime(&e);
                break;
            }
        }
    }
    let text = crate::files::read_input_text(file).unwrap_or_default();
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("ladder");
    let mut known = HashMap::new();
    for span in linc_compiler::ladder::element_spans(&text, stem) {
        if let Some(v) = text.get(span.start..span.end).and_then(|e| truth(e, &db, &store)) {
            known.insert((span.start, span.end), v);
        }
    }
    Ok(known)
}

/// An expression's value in `store`, as a truth value (`None` if it is not
/// one or does not evaluate).
fn truth(expr: &str, db: &Database, store: &Store) -> Option<bool> {
    eval(&element(expr, db, store)?, &mut store.clone())
}

/// An element's expression compiled and linked to `store`.
fn element(expr: &str, db: &Database, store: &Store) -> Option<Linked> {
    let mut session = Session::new(Context { db, resolve_blocks: true, steps: None });
    let id = session.add("<element>", expr.as_bytes().to_vec());
    let program = session.check(id, CheckOptions { input: Input::Expression, tree: false }).expr?;
    let obj = lower::lower_eval(&program, &Lines::new(expr)).ok()?;
    linc_runtime::verify::verify(obj).ok()?.link(store, &[Program { unit: 0, own: None }]).ok()
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
        let items = linc_compiler::ladder::element_spans(text, stem)
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

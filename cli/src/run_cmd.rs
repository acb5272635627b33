//! `linc run`: run an action against a database for some cycles.

use crate::report::usage;
use linc_compiler::diag::render::SourceFiles;
use linc_driver::database::load as load_db;
use linc_driver::database::{set_and_show, start_time, write_db};
use linc_driver::strategy::{own_block, program_object};
use linc_driver::Reporter;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm};
use linc_runtime::{Linked, Program};
use std::path::{Path, PathBuf};

/// What running one action and running a strategy have in common.
pub struct Common {
    pub set: Vec<String>,
    pub show: Vec<String>,
    /// `-` prints the trace; a path collects it into that file.
    pub trace: Option<PathBuf>,
    pub out: Option<PathBuf>,
    pub now: Option<String>,
    pub seed: Option<u64>,
    pub watchdog: u64,
    /// Which tier runs the code (interpreter, compiled, or the default mix).
    pub tier: linc_runtime::vm::Tier,
}

pub struct Options {
    pub file: PathBuf,
    pub db: PathBuf,
    pub action: Option<String>,
    pub block: Option<String>,
    pub cycles: u32,
    pub period: f64,
    pub common: Common,
}

pub use linc_engines::console::fields::show_value;

pub fn run(o: &Options, r: &mut Reporter) -> u8 {
    // `--out` and `--trace FILE` may not replace an input or anything but a
    // regular file; checked before the run, so a refused run changes nothing.
    let outputs = [("--out", &o.common.out), ("--trace", &o.common.trace)];
    let outputs: Vec<(&str, &Path)> = outputs.iter().filter_map(|(f, p)| Some((*f, p.as_deref()?))).collect();
    if let Err(e) = linc_driver::files::check_distinct(&outputs) {
        return crate::report::refused(r, e.diagnostic());
    }
    for (_, out) in outputs.iter().filter(|(_, p)| p.as_os_str() != "-") {
        if let Err(e) = linc_driver::files::check_output(out, &[&o.file, &o.db]) {
            return crate::report::refused(r, e.diagnostic());
        }
    }
    let mut dbfiles = SourceFiles::new();
    let db = match load_db(Some(&o.db), &mut dbfiles, r) {
        Ok(Some(db)) => db,
        Ok(None) => return 2,
        Err(status) => return status,
    };
    let db_text = dbfiles.get(0).map(|f| f.source().clone()).unwrap_or_default();
    let obj = match program_object(&o.file, &db, r) {
        Ok(obj) => obj,
        Err(status) => return status,
    };
    let units = &obj.object().units;
    let index = match &o.action {
        Some(name) => match obj.unit_named(name) {
            Some(i) => i,
            None => {
                let names: Vec<&str> = units.iter().map(|a| a.name.as_str()).collect();
                return usage(r, format_args!("--action: no action `{name}` (the file has {})", names.join(", ")));
            }
        },
        None if units.is_empty() => return usage(r, "the file has no actions"),
        None => 0,
    };
    let action = &units[index];
    let mut store = Store::new(db);
    let own = match own_block(&store, o.block.as_deref(), &action.block_type) {
        Ok(b) => b,
        Err(d) => return crate::report::refused(r, *d),
    };
    let shows = match set_and_show(&mut store, &o.common.set, &o.common.show, r) {
        Ok(v) => v,
        Err(status) => return status,
    };
    let now = match start_time(o.common.now.as_deref()) {
        Ok(s) => s,
        Err(msg) => return usage(r, msg),
    };
    store.now = now as f64;
    let linked = match obj.link(&store, &[Program { unit: index, own }]) {
        Ok(l) => l,
        Err(e) => {
            r.whole_file(&o.file.display().to_string(), e.code(), e.to_string());
            return 2;
        }
    };
    let seed = o.common.seed.unwrap_or_else(|| now as u64 ^ u64::from(std::process::id()));
    let to_stdout = o.common.trace.as_ref().is_some_and(|p| p.as_os_str() == "-");
    let (status, traced) = cycles(o, &linked, &mut store, (seed, to_stdout), r);
    say_compiled(o.common.tier, linked.compiled_blocks());
    for (path, a) in &shows {
        crate::out::line(&format!("{path} = {}", show_value(&store, *a)));
    }
    if let Some(path) = o.common.trace.as_ref().filter(|_| !to_stdout) {
        if let Err(e) = linc_driver::files::write_atomic(path, traced.as_bytes()) {
            return crate::report::refused(r, e.diagnostic());
        }
    }
    if let Some(out) = &o.common.out {
        if let Err(e) = write_db(out, &db_text, &store) {
            return crate::report::refused(r, e.diagnostic());
        }
    }
    status
}

/// `--tier compiled` says how many of the (compiled, all) code blocks ran
/// compiled, so a user can see what the compiling tier took.
pub fn say_compiled(tier: linc_runtime::vm::Tier, (compiled, all): (usize, usize)) {
    if tier == linc_runtime::vm::Tier::Compiled {
        eprintln!("linc: {compiled} of {all} code blocks ran compiled");
    }
}

/// Runs the action `--cycles` times, `--period` apart; returns the exit
/// status (1 after a runtime error, which ends the run) and the trace text
/// kept for a `--trace FILE`.
fn cycles(
    o: &Options,
    linked: &Linked,
    store: &mut Store,
    (seed, to_stdout): (u64, bool),
    r: &mut Reporter,
) -> (u8, String) {
    let mut act = Activation::new(linked, 0, 0);
    let mut vm = Vm::new(o.common.watchdog, Clock::new(seed, 0));
    vm.set_tier(o.common.tier);
    let mut traced = String::new();
    for cycle in 1..=o.cycles {
        let mut tracer = |s: &Store, cell: u32| {
            let line = format!("cycle {cycle}: {} = {}\n", s.describe(cell), s.show(cell));
            if to_stdout {
                crate::out::print(&line);
            } else {
                traced.push_str(&line);
            }
        };
        let trace: linc_runtime::vm::Tracer = if o.common.trace.is_some() { Some(&mut tracer) } else { None };
        if let Err(e) = vm.run(linked, &mut act, store, trace) {
            r.runtime(&e);
            return (1, traced);
        }
        store.now += o.period;
    }
    (0, traced)
}

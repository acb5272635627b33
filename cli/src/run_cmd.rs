//! `linc run`: run an action against a database for some cycles.

use crate::build::{compile, Failed};
use crate::check_cmd::load_db;
use crate::report::usage;
use linc_compiler::render::SourceFiles;
use linc_compiler::Diagnostic;
use linc_driver::Reporter;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm};
use linc_runtime::{text, Database, Linked, Program, Verified};
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

pub use linc_runtime::console::fields::{address, set, show_value, Addr};

/// Applies every `--set` and resolves every `--show` (reporting the first
/// problem, E0903; `Err` is the exit status).
pub fn set_and_show(
    store: &mut Store,
    sets: &[String],
    shows: &[String],
    r: &mut Reporter,
) -> Result<Vec<(String, Addr)>, u8> {
    for s in sets {
        set(store, s).map_err(|msg| usage(r, format_args!("--set {s}: {msg}")))?;
    }
    let mut out = Vec::with_capacity(shows.len());
    for p in shows {
        let a = address(store, p).map_err(|msg| usage(r, format_args!("--show {p}: {msg}")))?;
        out.push((p.clone(), a));
    }
    Ok(out)
}

/// Loads a program file: a `.sto` object as is (verified), anything else
/// compiled against `db`. Errors are printed; `Err` carries the exit status.
pub fn program_object(path: &Path, db: &Database, r: &mut Reporter) -> Result<Verified, u8> {
    let name = path.display().to_string();
    let mut fail = |code: &'static str, message: String| {
        r.whole_file(&name, code, message);
        2
    };
    let is_object = path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("sto"));
    if !is_object {
        let obj = compile(&[path.to_path_buf()], Some(db), r, 2).map_err(|Failed(s)| s)?;
        return linc_runtime::verify::verify(obj).map_err(|e| {
            r.whole_file(&name, e.code(), e.to_string());
            2
        });
    }
    let bytes = linc_driver::files::read_input(path).map_err(|e| fail("E0900", format!("can't read `{name}`: {e}")))?;
    linc_runtime::load(&bytes).map_err(|e| fail(e.code(), e.to_string()))
}

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

/// The clock's start in POSIX seconds: `--now`, or the system time.
pub fn start_time(now: Option<&str>) -> Result<i64, String> {
    match now {
        Some(t) => text::parse_timestamp(t)
            .ok_or_else(|| format!("--now `{t}` is not a real date and time YYYY-MM-DDTHH:MM:SS")),
        None => Ok(std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_secs() as i64)
            .unwrap_or(0)),
    }
}

/// Picks the block that runs an `ACTION name : TYPE` action. A block named
/// with `--block` must be of that type: the action's lone field names would
/// otherwise link to whatever same-named fields another type happens to have.
pub(crate) fn own_block(
    store: &Store,
    named: Option<&str>,
    block_type: &str,
) -> Result<Option<usize>, Box<Diagnostic>> {
    let t = store.db.template(block_type);
    if let Some(n) = named {
        let b = store.db.block(n).ok_or_else(|| {
            Box::new(Diagnostic::command("E0904", format!("--block: the database has no block `{n}`")))
        })?;
        let actual = store.db.blocks[b].template;
        if !block_type.is_empty() && Some(actual) != t {
            let name = &store.db.templates[actual].name;
            return Err(Box::new(Diagnostic::command(
                "E0904",
                format!("--block {n} has type {name}, but the action runs on a block of type {block_type}"),
            )));
        }
        return Ok(Some(b));
    }
    if block_type.is_empty() {
        return Ok(None);
    }
    let of_type: Vec<usize> = (0..store.db.blocks.len()).filter(|&b| Some(store.db.blocks[b].template) == t).collect();
    let why = match of_type.as_slice() {
        [b] => return Ok(Some(*b)),
        [] => format!("the action runs on a {block_type} block and the database has none"),
        _ => format!("the database has several {block_type} blocks; choose one with --block"),
    };
    Err(Box::new(Diagnostic::command("E0904", why)))
}

/// Writes the database with the store's values, in the input's JSON shape.
pub fn write_db(out: &std::path::Path, original: &str, store: &Store) -> Result<(), linc_driver::files::Refused> {
    let json_error = |e: serde_json::Error| linc_driver::files::Refused {
        code: "E0900",
        message: format!("can't write `{}`: {e}", out.display()),
    };
    let mut root: serde_json::Value = serde_json::from_str(original).map_err(json_error)?;
    let values = store.values_json();
    if let Some(blocks) = root.get_mut("blocks").and_then(|b| b.as_object_mut()) {
        for (name, block) in blocks.iter_mut() {
            if let (Some(obj), Some(v)) = (block.as_object_mut(), values.get(name)) {
                obj.insert("values".to_string(), v.clone());
            }
        }
    }
    // The ROC device's logs and archives, when the database has history
    // points or a table logged something (the loader skips this key).
    let roc = &store.roc;
    if !roc.history.points().is_empty() || !roc.alarms.is_empty() || !roc.events.is_empty() {
        if let Some(obj) = root.as_object_mut() {
            obj.insert("roc".to_string(), roc.to_json());
        }
    }
    let text = serde_json::to_string_pretty(&root).map_err(json_error)? + "\n";
    linc_driver::files::write_atomic(out, text.as_bytes())
}

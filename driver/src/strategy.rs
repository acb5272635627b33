//! Building what a command runs: each program a strategy's blocks name,
//! compiled or loaded once, and the block an action runs on. Used alike by
//! `linc run`, the console and scenario tests.

use crate::build::{compile, Failed};
use crate::Reporter;
use linc_compiler::diag::span::FileId;
use linc_compiler::{Diagnostic, Span};
use linc_engines::strategy::{StrategyError, Want};
use linc_format::Code;
use linc_runtime::{Database, Store, Verified};
use std::collections::HashMap;
use std::path::Path;

/// Compiles or loads each action file the strategy names, once each.
/// The verified objects, and each wanted action with the index of its object.
pub type Plan = (Vec<Verified>, Vec<(Want, usize)>);

/// Compiles or loads each file `wants` name (relative to `dir`), once each.
pub fn compile_wants(dir: &Path, db: &Database, wants: &[Want], r: &mut Reporter) -> Result<Plan, u8> {
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut objects = Vec::new();
    let mut pairs = Vec::with_capacity(wants.len());
    for w in wants {
        let i = match index.get(&w.file) {
            Some(&i) => i,
            None => {
                let path = dir.join(&w.file);
                objects.push(program_object(&path, db, r)?);
                index.insert(w.file.clone(), objects.len() - 1);
                objects.len() - 1
            }
        };
        pairs.push((w.clone(), i));
    }
    Ok((objects, pairs))
}

/// Loads a program file: a `.sto` object as is (verified), anything else
/// compiled against `db`. Errors are printed; `Err` carries the exit status.
pub fn program_object(path: &Path, db: &Database, r: &mut Reporter) -> Result<Verified, u8> {
    let name = path.display().to_string();
    let mut fail = |code: Code, message: String| {
        r.whole_file(&name, code, message);
        2
    };
    if !crate::source::is_object(path) {
        let obj = compile(&[path.to_path_buf()], Some(db), r, 2).map_err(|Failed(s)| s)?;
        return linc_runtime::verify::verify(obj).map_err(|e| {
            r.whole_file(&name, e.code(), e.to_string());
            2
        });
    }
    let bytes = crate::files::read_input(path).map_err(|e| fail(Code::E0900, format!("can't read `{name}`: {e}")))?;
    linc_runtime::load(&bytes).map_err(|e| fail(e.code(), e.to_string()))
}

/// A strategy error as a diagnostic at the block's key in the database text.
pub fn strategy_diagnostic(db_id: FileId, db_text: &str, e: &StrategyError) -> Diagnostic {
    let quoted = format!("\"{}\"", e.block);
    let span = db_text.find(&quoted).map(|at| Span::new(at, at + quoted.len())).unwrap_or_default();
    Diagnostic::error(e.code, e.message.clone(), span).label("this block").in_file(db_id)
}

/// Picks the block that runs an `ACTION name : TYPE` action. A block named
/// with `--block` must be of that type: the action's lone field names would
/// otherwise link to whatever same-named fields another type happens to have.
pub fn own_block(store: &Store, named: Option<&str>, block_type: &str) -> Result<Option<usize>, Box<Diagnostic>> {
    let t = store.db.template(block_type);
    if let Some(n) = named {
        let b = store.db.block(n).ok_or_else(|| {
            Box::new(Diagnostic::command(Code::E0904, format!("--block: the database has no block `{n}`")))
        })?;
        let actual = store.db.blocks[b].template;
        if !block_type.is_empty() && Some(actual) != t {
            let name = &store.db.templates[actual].name;
            return Err(Box::new(Diagnostic::command(
                Code::E0904,
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
    Err(Box::new(Diagnostic::command(Code::E0904, why)))
}

/// How to build a whole plant: `linc run PLANT.json`'s options that shape
/// the strategy before it runs.
#[derive(Clone, Debug)]
pub struct PlantOptions {
    pub set: Vec<String>,
    pub now: Option<String>,
    pub seed: Option<u64>,
    pub watchdog: u64,
    pub tier: linc_runtime::vm::Tier,
}

impl Default for PlantOptions {
    fn default() -> PlantOptions {
        PlantOptions {
            set: Vec::new(),
            now: None,
            seed: None,
            watchdog: linc_runtime::vm::DEFAULT_WATCHDOG,
            tier: linc_runtime::vm::Tier::default(),
        }
    }
}

/// The whole strategy of a database as `linc run PLANT.json` builds it
/// (`--set` applied, every program compiled), with the programs its blocks
/// name; the console and `linc serve` start from it. Errors are printed,
/// `Err` is the exit status.
pub fn plant(
    db_path: &Path,
    o: &PlantOptions,
    r: &mut Reporter,
) -> Result<(linc_engines::strategy::Strategy, Vec<Want>), u8> {
    use linc_compiler::diag::render::SourceFiles;
    let now = crate::database::start_time(o.now.as_deref()).map_err(|m| crate::report::usage(r, m))?;
    let mut files = SourceFiles::new();
    let Some(db) = crate::database::load(Some(db_path), &mut files, r)? else { return Err(2) };
    let db_text = files.get(0).map(|f| f.source().clone()).unwrap_or_default();
    let mut store = Store::new(db);
    crate::database::set_and_show(&mut store, &o.set, &[], r)?;
    let wants = linc_engines::strategy::wanted(&store);
    let dir = db_path.parent().map(Path::to_path_buf).unwrap_or_default();
    let s = assemble(&dir, (&files, &db_text), store, &wants, now, o, r)?;
    Ok((s, wants))
}

/// Compiles the programs `wants` name (files relative to `dir`) and builds
/// the strategy over `store`, starting at `now`; a strategy error is
/// located in the database (`db`: its files and text). Errors are printed,
/// `Err` is the exit status. What `linc run`, the console, `linc serve` and
/// `linc draw` build their strategies with.
pub fn assemble(
    dir: &Path,
    db: (&linc_compiler::diag::render::SourceFiles, &str),
    store: Store,
    wants: &[Want],
    now: i64,
    o: &PlantOptions,
    r: &mut Reporter,
) -> Result<linc_engines::strategy::Strategy, u8> {
    let report = |e: &StrategyError, r: &mut Reporter| {
        r.emit(db.0, &strategy_diagnostic(FileId(0), db.1, e));
        2u8
    };
    if let Some(e) = wants.iter().find_map(|w| w.complete(&store).err()) {
        return Err(report(&e, r));
    }
    let (objects, pairs) = compile_wants(dir, &store.db, wants, r)?;
    let clock = linc_runtime::vm::Clock::new(o.seed.unwrap_or(now as u64), 0);
    let mut vm = linc_runtime::vm::Vm::new(o.watchdog, clock);
    vm.set_tier(o.tier);
    linc_engines::strategy::Strategy::build(store, objects, &pairs, vm, now as f64).map_err(|e| report(&e, r))
}

//! The one plant builder: every command that runs something — `run`, the
//! console, `serve`, `draw` and `test` — builds it here and nowhere else,
//! so the options that shape a plant mean the same in each
//! (`docs/state.md`): the database's values, then the saved state (a warm
//! start), then `--set`; the clock from `--now` (or the state), RANDOM's
//! seed, the watchdog and the tier; and what runs — the strategy the
//! database describes, one sequence or FST table, or actions of one file
//! run outside any strategy.

use crate::database::{self, DbFile};
use crate::single::{self, Kind};
use linc_compiler::diag::{Diagnostic, Problems, Span};
use linc_engines::strategy::{self, Strategy, StrategyError, Want};
use linc_format::Code;
use linc_runtime::vm::{Activation, Clock, Vm};
/// Which tier runs the code (ADR 0011), and the watchdog's default budget.
pub use linc_runtime::vm::{Tier, DEFAULT_WATCHDOG};
use linc_runtime::{Database, Linked, Program as Linking, Store, Verified};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// What to build.
#[derive(Clone, Debug)]
pub struct PlantSpec {
    /// The database: a strategy's, or the one a program runs against.
    pub db: PathBuf,
    pub program: Program,
    /// `BLOCK.FIELD=VALUE`, applied last (after a warm start's state).
    pub set: Vec<String>,
    /// The clock's start in POSIX seconds; `None`: the system's time. A
    /// warm start continues the saved clock instead.
    pub now: Option<i64>,
    /// RANDOM's seed; `None`: from the start time.
    pub seed: Option<u64>,
    pub watchdog: u64,
    pub tier: Tier,
    /// A retentive state to start from (`--state FILE`, `--cold`).
    pub state: Option<StateFile>,
    /// Outputs the command will write, by option (`--out`, `--trace` …):
    /// refused (E0902, E0901) when one names another or an input of the
    /// plant, before anything is compiled or run.
    pub outputs: Vec<(String, PathBuf)>,
    /// Inputs the command reads besides the plant's own (a console script).
    pub inputs: Vec<PathBuf>,
}

impl PlantSpec {
    /// The strategy of `db`, with the default options.
    pub fn strategy(db: impl Into<PathBuf>) -> PlantSpec {
        PlantSpec {
            db: db.into(),
            program: Program::Strategy,
            set: Vec::new(),
            now: None,
            seed: None,
            watchdog: DEFAULT_WATCHDOG,
            tier: Tier::default(),
            state: None,
            outputs: Vec::new(),
            inputs: Vec::new(),
        }
    }
}

/// What runs.
#[derive(Clone, Debug)]
pub enum Program {
    /// Every program the database's blocks name.
    Strategy,
    /// One sequence (`.sfc`) or FST table (`.csv`), or an object of one,
    /// run by an SFC_CON or FST block: `block`, or the only one.
    One {
        file: PathBuf,
        block: Option<String>,
        /// Seconds per scan: the period of the block's task.
        period: Option<f64>,
    },
    /// Actions of an action or ladder file (or object), each run by the
    /// block of its type (`block`, or the only one), outside any strategy.
    Actions { file: PathBuf, action: Choice, block: Option<String> },
}

/// Which actions of a file run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Choice {
    /// The first (`linc run FILE --db`).
    First,
    /// The one named (`--action NAME`).
    Named(String),
    /// Every one, in order (a ladder file's rungs drawn after a run).
    Every,
}

/// `--state FILE`, warm or `--cold`.
#[derive(Clone, Debug)]
pub struct StateFile {
    pub path: PathBuf,
    /// Ignore the file (it is still saved by the commands that save).
    pub cold: bool,
}

/// How the plant started.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// As the database describes it: `--cold`, no state file yet, or none.
    Cold,
    /// From the saved state.
    Warm,
}

/// A plant built and ready to run.
pub struct Plant {
    pub running: Running,
    /// The database file it was built from (to locate problems, and for
    /// `--out`).
    pub db: DbFile,
    /// The programs the blocks name (sources relative to [`Plant::dir`]).
    pub wants: Vec<Want>,
    /// The database's folder.
    pub dir: PathBuf,
    /// The block of a [`Program::One`].
    pub block: Option<usize>,
    pub start: Start,
    /// What compiling the programs warned of.
    pub warnings: Problems,
}

/// A strategy, or actions run outside one.
pub enum Running {
    Strategy(Box<Strategy>),
    Actions(Box<Actions>),
}

/// Actions of one file linked to a store, each run cycle by cycle.
pub struct Actions {
    pub store: Store,
    pub vm: Vm,
    /// The actions linked, one program each, from the one object: a copy
    /// of the object per action took 8 bytes per byte of its file.
    pub linked: Linked,
    /// Each action's name and its activation (of program `i` for the
    /// `i`th).
    pub programs: Vec<(String, Activation)>,
}

impl Plant {
    /// The strategy, for the commands that run one.
    pub fn strategy(&mut self) -> Option<&mut Strategy> {
        match &mut self.running {
            Running::Strategy(s) => Some(s),
            Running::Actions(_) => None,
        }
    }

    /// The store, whatever runs.
    pub fn store(&self) -> &Store {
        match &self.running {
            Running::Strategy(s) => &s.store,
            Running::Actions(a) => &a.store,
        }
    }

    /// The strategy, given up (`None` for actions run outside one).
    pub fn into_strategy(self) -> Option<Strategy> {
        match self.running {
            Running::Strategy(s) => Some(*s),
            Running::Actions(_) => None,
        }
    }
}

/// Builds what `spec` describes; anything that stops it is a refused
/// request.
pub fn build(spec: &PlantSpec) -> Result<Plant, Problems> {
    if let Program::Actions { file, .. } = &spec.program {
        if spec.state.is_some() {
            return Err(database::usage("--state keeps a strategy's state: actions run alone have none"));
        }
        let outputs = outputs(spec);
        crate::files::check_distinct(&outputs)?;
        check_outputs(&outputs, &[file.clone(), spec.db.clone()])?;
    }
    let db = database::load(&spec.db)?;
    let now = match spec.now {
        Some(t) => t,
        None => database::start_time(None)?,
    };
    let dir = spec.db.parent().map(Path::to_path_buf).unwrap_or_default();
    match &spec.program {
        Program::Actions { file, action, block } => actions(spec, db, dir, now, (file, action, block.as_deref())),
        _ => plant(spec, db, dir, now),
    }
}

fn outputs(spec: &PlantSpec) -> Vec<(&str, &Path)> {
    spec.outputs.iter().map(|(flag, p)| (flag.as_str(), p.as_path())).collect()
}

/// Outputs (but standard output, `-`) may not replace an input.
fn check_outputs(outputs: &[(&str, &Path)], inputs: &[PathBuf]) -> Result<(), Problems> {
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    for (_, out) in outputs.iter().filter(|(_, p)| p.as_os_str() != "-") {
        crate::files::check_output(out, &inputs)?;
    }
    Ok(())
}

/// A strategy, or one sequence or table run as one.
fn plant(spec: &PlantSpec, mut db: DbFile, dir: PathBuf, now: i64) -> Result<Plant, Problems> {
    let one = match &spec.program {
        Program::One { file, block, period } => {
            let kind = Kind::of(file);
            let b = single::find_block(&db.db, block.as_deref(), kind)?;
            if let Some(p) = period {
                single::set_period(&mut db.db, b, *p);
            }
            Some((single::want_for(file, kind, b), b))
        }
        _ => None,
    };
    let mut store = Store::new(db.db.clone());
    // --set applies before the build too: a set FileName or ActName
    // chooses what is built.
    database::apply_sets(&mut store, &spec.set)?;
    let wants = match &one {
        Some((want, _)) => vec![want.clone()],
        None => strategy::wanted(&store),
    };
    let outputs = outputs(spec);
    crate::files::check_distinct(&outputs)?;
    let inputs: Vec<PathBuf> = std::iter::once(spec.db.clone())
        .chain(spec.inputs.iter().cloned())
        .chain(wants.iter().map(|w| dir.join(&w.file)))
        .collect();
    check_outputs(&outputs, &inputs)?;
    if let Some(e) = wants.iter().find_map(|w| strategy::complete(w, &store).err()) {
        return Err(located(&db, &e));
    }
    let (objects, pairs, warnings) = compile_wants(&dir, &store.db, &wants)?;
    let mut vm = Vm::new(spec.watchdog, Clock::new(spec.seed.unwrap_or(now as u64), 0));
    vm.set_tier(spec.tier);
    let built = Strategy::build(store, objects, &pairs, vm, now as f64);
    let mut s = built.map_err(|e| located(&db, &e))?;
    let start = match &spec.state {
        Some(state) => crate::state::warm_start(&state.path, state.cold, &mut s)?,
        None => Start::Cold,
    };
    if start == Start::Warm {
        // The saved state replaced every value: --set goes on top of it.
        database::apply_sets(&mut s.store, &spec.set)?;
    }
    let block = one.map(|(_, b)| b);
    Ok(Plant { running: Running::Strategy(Box::new(s)), db, wants, dir, block, start, warnings })
}

/// A strategy error as a refused request, at the block's key in the
/// database text.
pub fn located(db: &DbFile, e: &StrategyError) -> Problems {
    db.problems(strategy_diagnostic(&db.text, e)).refused()
}

/// A strategy error as a diagnostic at the block's key in the database
/// text (file 0).
pub fn strategy_diagnostic(db_text: &str, e: &StrategyError) -> Diagnostic {
    let quoted = format!("\"{}\"", e.block);
    let span = db_text.find(&quoted).map(|at| Span::new(at, at + quoted.len())).unwrap_or_default();
    Diagnostic::error(e.code, e.message.clone(), span).label("this block")
}

/// The verified objects of a strategy, each wanted program with the index
/// of its object, and what compiling them warned of.
type Compiled = (Vec<Verified>, Vec<(Want, usize)>, Problems);

/// Compiles or loads each file `wants` name (relative to `dir`), once each.
fn compile_wants(dir: &Path, db: &Database, wants: &[Want]) -> Result<Compiled, Problems> {
    let mut index: HashMap<String, usize> = HashMap::new();
    let mut objects = Vec::new();
    let mut warnings = Problems::new();
    let mut pairs = Vec::with_capacity(wants.len());
    for w in wants {
        let i = match index.get(&w.file) {
            Some(&i) => i,
            None => {
                let (object, warned) = crate::build::program_object(&dir.join(&w.file), db).map_err(|mut p| {
                    // What was warned of before stays before the error.
                    let mut all = std::mem::take(&mut warnings);
                    all.append(std::mem::take(&mut p));
                    all
                })?;
                warnings.append(warned);
                objects.push(object);
                index.insert(w.file.clone(), objects.len() - 1);
                objects.len() - 1
            }
        };
        pairs.push((w.clone(), i));
    }
    Ok((objects, pairs, warnings))
}

/// Actions of one file, linked to the database's store.
fn actions(
    spec: &PlantSpec,
    db: DbFile,
    dir: PathBuf,
    now: i64,
    (file, choice, block): (&Path, &Choice, Option<&str>),
) -> Result<Plant, Problems> {
    let (obj, warnings) = crate::build::program_object(file, &db.db)?;
    let units = &obj.object().units;
    let chosen: Vec<usize> = match choice {
        Choice::Named(name) => match obj.unit_named(name) {
            Some(i) => vec![i],
            None => {
                let names: Vec<&str> = units.iter().map(|a| a.name.as_str()).collect();
                let why = format!("--action: no action `{name}` (the file has {})", names.join(", "));
                return Err(warned(warnings, database::usage(why)));
            }
        },
        _ if units.is_empty() => return Err(warned(warnings, database::usage("the file has no actions"))),
        Choice::First => vec![0],
        Choice::Every => (0..units.len()).collect(),
    };
    let mut store = Store::new(db.db.clone());
    let mut owns = Vec::with_capacity(chosen.len());
    for &u in &chosen {
        match own_block(&store, block, &units[u].block_type) {
            Ok(own) => owns.push(own),
            Err(d) => return Err(warned(warnings, Problems::refusal(*d))),
        }
    }
    database::apply_sets(&mut store, &spec.set)?;
    store.now = now as f64;
    let name = file.display().to_string();
    let names: Vec<String> = chosen.iter().map(|&u| units[u].name.clone()).collect();
    let wanted: Vec<Linking> = chosen.iter().zip(owns).map(|(&unit, own)| Linking { unit, own }).collect();
    let linked = obj.link(&store, &wanted).map_err(|e| Problems::whole_file(&name, e.code(), e.to_string()))?;
    let programs = names.into_iter().enumerate().map(|(p, n)| (n, Activation::new(&linked, p, 0))).collect();
    let seed = spec.seed.unwrap_or_else(|| now as u64 ^ u64::from(std::process::id()));
    let mut vm = Vm::new(spec.watchdog, Clock::new(seed, 0));
    vm.set_tier(spec.tier);
    let running = Running::Actions(Box::new(Actions { store, vm, linked, programs }));
    Ok(Plant { running, db, wants: Vec::new(), dir, block: None, start: Start::Cold, warnings })
}

/// `warnings`, then what stopped the build.
fn warned(mut warnings: Problems, stop: Problems) -> Problems {
    warnings.append(stop);
    warnings
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

/// Saves the strategy's retentive state to `path`, atomically.
pub fn save_state(path: &Path, s: &Strategy) -> Result<(), Problems> {
    Ok(crate::files::write_atomic(path, &s.save_state())?)
}

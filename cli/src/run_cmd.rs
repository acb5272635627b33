//! `linc run`: a strategy, one sequence or FST table for a simulated time,
//! or one action for some cycles. The driver builds the plant and runs it;
//! this chooses the program from the arguments and prints what it asks.

use crate::report::Reporter;
use linc_driver::plant::Tier;
use linc_driver::plant::{Choice, PlantSpec, Program, StateFile};
use linc_driver::run::RunRequest;
use std::io::Write;
use std::path::PathBuf;

/// What every form of `linc run` takes.
pub struct Common {
    pub set: Vec<String>,
    pub show: Vec<String>,
    /// `-` prints the trace; a path collects it into that file.
    pub trace: Option<PathBuf>,
    pub out: Option<PathBuf>,
    pub now: Option<i64>,
    pub seed: Option<u64>,
    pub watchdog: u64,
    pub tier: Tier,
    /// `--state FILE [--cold]`.
    pub state: Option<StateFile>,
}

/// What runs, and for how long.
pub enum Form {
    /// A strategy, or one sequence or table, for a duration.
    For { program: Program, duration: String, controls: linc_driver::run::Controls },
    /// One action, `cycles` times, `period` seconds apart.
    Cycles { program: Program, cycles: u32, period: f64 },
}

pub fn run(db: PathBuf, form: Form, c: Common, r: &Reporter) -> u8 {
    let duration = match &form {
        Form::For { duration, .. } => match linc_driver::database::duration("--for", duration) {
            Ok(d) => Some(d),
            Err(p) => return r.report(&p),
        },
        Form::Cycles { .. } => None,
    };
    let program = match &form {
        Form::For { program, .. } | Form::Cycles { program, .. } => program.clone(),
    };
    let outputs = [("--out", &c.out), ("--trace", &c.trace), ("--state", &c.state.as_ref().map(|s| s.path.clone()))];
    let spec = PlantSpec {
        program,
        set: c.set,
        now: c.now,
        seed: c.seed,
        watchdog: c.watchdog,
        tier: c.tier,
        state: c.state.clone(),
        outputs: outputs.iter().filter_map(|(f, p)| Some((f.to_string(), (*p).clone()?))).collect(),
        ..PlantSpec::strategy(db)
    };
    let mut plant = match linc_driver::plant::build(&spec) {
        Ok(p) => p,
        Err(p) => return r.report(&p),
    };
    let warned = r.report(&std::mem::take(&mut plant.warnings));
    let to_stdout = c.trace.as_ref().is_some_and(|p| p.as_os_str() == "-");
    let trace: Option<(Box<dyn Write>, String)> = match &c.trace {
        None => None,
        Some(_) if to_stdout => Some((stdout_trace(&form), "-".into())),
        Some(path) => match linc_driver::run::trace_file(path) {
            Ok(w) => Some((w, path.display().to_string())),
            Err(p) => return r.report(&p),
        },
    };
    let save_state = match &form {
        Form::For { .. } => c.state.map(|s| s.path),
        Form::Cycles { .. } => None,
    };
    let mut req = RunRequest { shows: c.show, trace, out: c.out, save_state, tier: c.tier, ..Default::default() };
    let ran = match form {
        Form::For { controls, .. } => {
            req.controls = controls;
            linc_driver::run::strategy(&mut plant, duration.unwrap_or_default(), req)
        }
        Form::Cycles { cycles, period, .. } => linc_driver::run::actions(&mut plant, cycles, period, req),
    };
    match ran {
        Ok(ran) => {
            for (path, value) in &ran.shows {
                crate::out::line(&format!("{path} = {value}"));
            }
            warned.max(r.report(&ran.problems))
        }
        Err(p) => r.report(&p),
    }
}

/// `--trace -`: a strategy's JSON lines as they are (JSON escapes every
/// control character), an action's `cycle N: …` lines escaped as all
/// standard output is.
fn stdout_trace(form: &Form) -> Box<dyn Write> {
    match form {
        Form::For { .. } => Box::new(std::io::BufWriter::new(std::io::stdout().lock())),
        Form::Cycles { .. } => Box::new(crate::out::Stream::new()),
    }
}

/// The action to run of `linc run FILE --db DB`.
pub fn action(file: PathBuf, action: Option<String>, block: Option<String>) -> Program {
    Program::Actions { file, action: action.map_or(Choice::First, Choice::Named), block }
}

//! Running a plant built by [`crate::plant`]: a strategy (or one sequence or
//! table) for a simulated time, or actions for a number of cycles; what the
//! run shows, its trace, the database and state it leaves. Returns what
//! happened as data: the values asked for, and the problems (runtime faults
//! located in their sources, a file that could not be written).

use crate::plant::{Actions, Plant, Running};
use linc_compiler::diag::{Diagnostic, Problems};
use linc_engines::console::fields::show_value;
use linc_engines::strategy::trace::Trace;
use linc_format::Code;
use linc_runtime::vm::{Tier, Tracer};
use linc_runtime::{RuntimeError, Store};
use std::io::Write;
use std::path::{Path, PathBuf};

/// What a run is asked to give back besides running.
#[derive(Default)]
pub struct RunRequest<'a> {
    /// `--show BLOCK.FIELD` (or `Step.X`, `Step.T` of a sequence run alone).
    pub shows: Vec<String>,
    /// Where the trace goes (`--trace`), and its name for messages.
    pub trace: Option<(Box<dyn Write + 'a>, String)>,
    /// `--out`: the database written with its values after the run.
    pub out: Option<PathBuf>,
    /// `--state`: the retentive state saved after the run.
    pub save_state: Option<PathBuf>,
    /// The tier the plant was built with (`--tier compiled` notes how much
    /// ran compiled, I0002).
    pub tier: Tier,
    /// The monitor's controls a sequence run alone starts with
    /// (`--hold-step`, `--force`).
    pub controls: Controls,
}

pub use crate::single::Controls;

/// What a run gave.
pub struct Ran {
    /// Each `--show` with its value, in order.
    pub shows: Vec<(String, String)>,
    /// Runtime faults (errors found), notes, and a file that could not be
    /// written (a refused request).
    pub problems: Problems,
}

/// Runs a strategy for `duration_us` of simulated time, then shows, saves
/// and writes what `req` asks. `Err`: a `--show` the plant can't show.
pub fn strategy(plant: &mut Plant, duration_us: u64, req: RunRequest) -> Result<Ran, Problems> {
    let seq_block = plant.block;
    let Running::Strategy(s) = &mut plant.running else {
        return Err(crate::database::usage("--for runs a strategy, a sequence or an FST table"));
    };
    let step_shows: Vec<String> = req.shows.iter().filter(|p| is_step_show(&s.store, seq_block, p)).cloned().collect();
    let field_shows: Vec<String> = req.shows.iter().filter(|p| !step_shows.contains(p)).cloned().collect();
    let fields = crate::database::shows(&s.store, &field_shows)?;
    if let Some(seq) = seq_block.and_then(|b| s.sequence_mut(b)) {
        crate::single::monitor(seq, &req.controls, &step_shows)?;
    }
    let (writer, trace_name) = req.trace.map(|(w, n)| (Some(w), n)).unwrap_or((None, String::new()));
    let mut trace = writer.map(|w| Trace::new(w, &s.store));
    let failures = s.run_for(duration_us, trace.as_mut());
    let traced = trace.map(Trace::finish);
    let mut problems = faults(&failures);
    compiled_note(&mut problems, req.tier, s.compiled_blocks());
    let shows = req
        .shows
        .iter()
        .map(|path| {
            let step = seq_block.and_then(|b| s.sequence(b)).and_then(|q| crate::single::step_flag(q, path));
            let field = fields.iter().find(|(p, _)| p == path).map(|(_, a)| show_value(&s.store, *a));
            (path.clone(), step.or(field).unwrap_or_default())
        })
        .collect();
    if let Some(Err(e)) = traced {
        problems.append(Problems::usage(Code::E0900, format!("can't write the trace `{trace_name}`: {e}")));
        return Ok(Ran { shows, problems });
    }
    let saved = req.save_state.as_deref().map(|p| crate::plant::save_state(p, s)).transpose();
    let written = saved.and_then(|_| write_out(req.out.as_deref(), &plant.db.text, plant.store()));
    if let Err(p) = written {
        problems.append(p);
    }
    Ok(Ran { shows, problems })
}

/// `--show Step.X` (or `.T`) of the sequence being run: the first part is
/// not a block or alias of the database.
fn is_step_show(store: &Store, seq_block: Option<usize>, path: &str) -> bool {
    let Some((first, flag)) = path.split_once('.') else { return false };
    seq_block.is_some()
        && store.db.block(first).is_none()
        && store.db.alias(first).is_none()
        && matches!(flag.to_ascii_uppercase().as_str(), "X" | "T")
}

/// Runs the actions `cycles` times, `period` seconds apart, each traced
/// change written to `trace` as `cycle N: FIELD = VALUE`; a runtime error
/// ends the run. Then shows and writes what `req` asks.
pub fn actions(plant: &mut Plant, cycles: u32, period: f64, req: RunRequest) -> Result<Ran, Problems> {
    let Running::Actions(a) = &mut plant.running else {
        return Err(crate::database::usage("--cycles runs one action: a strategy runs --for DURATION"));
    };
    let fields = crate::database::shows(&a.store, &req.shows)?;
    let (mut writer, trace_name) = req.trace.map(|(w, n)| (Some(w), n)).unwrap_or((None, String::new()));
    let (failure, written) = cycle(a, cycles, period, writer.as_deref_mut());
    let mut problems = faults(&failure);
    compiled_note(&mut problems, req.tier, a.linked.compiled_blocks());
    let shows = fields.iter().map(|(p, addr)| (p.clone(), show_value(&a.store, *addr))).collect();
    let flushed = written.and_then(|()| writer.map_or(Ok(()), |mut w| w.flush()));
    if let Err(e) = flushed {
        problems.append(Problems::usage(Code::E0900, format!("can't write the trace `{trace_name}`: {e}")));
        return Ok(Ran { shows, problems });
    }
    if let Err(p) = write_out(req.out.as_deref(), &plant.db.text, plant.store()) {
        problems.append(p);
    }
    Ok(Ran { shows, problems })
}

/// The cycles: each action `cycles` times, in order; a runtime error ends
/// that action's cycles. The faults, and the trace's first write error.
fn cycle(
    a: &mut Actions,
    cycles: u32,
    period: f64,
    mut trace: Option<&mut (dyn Write + '_)>,
) -> (Vec<RuntimeError>, std::io::Result<()>) {
    let mut written = Ok(());
    let mut failures = Vec::new();
    let tracing = trace.is_some();
    for (_, act) in &mut a.programs {
        for n in 1..=cycles {
            let mut tracer = |s: &Store, cell: u32| {
                if let (Some(w), Ok(())) = (trace.as_deref_mut(), &written) {
                    written = writeln!(w, "cycle {n}: {} = {}", s.describe(cell), s.show(cell));
                }
            };
            let t: Tracer = if tracing { Some(&mut tracer) } else { None };
            if let Err(e) = a.vm.run(&a.linked, act, &mut a.store, t) {
                failures.push(e);
                break;
            }
            a.store.now += period;
        }
    }
    (failures, written)
}

/// `--tier compiled` says how many of the (compiled, all) code blocks ran
/// compiled, so a user can see what the compiling tier took (I0002).
fn compiled_note(problems: &mut Problems, tier: Tier, (compiled, all): (usize, usize)) {
    if tier == Tier::Compiled {
        problems.push(Diagnostic::note(Code::I0002, format!("linc: {compiled} of {all} code blocks ran compiled")));
    }
}

/// Writes the database with its values (`--out`).
fn write_out(out: Option<&Path>, db_text: &str, store: &Store) -> Result<(), Problems> {
    match out {
        Some(out) => crate::database::write_db(out, db_text, store),
        None => Ok(()),
    }
}

/// Runtime faults, each located in its source (errors found, not a
/// refused request).
pub fn faults(failures: &[RuntimeError]) -> Problems {
    let mut p = Problems::new();
    for e in failures {
        p.append(fault(e));
    }
    p
}

/// A runtime fault at its place in its source. When the source can't be
/// read (an object run without it), line and column still print right,
/// against empty lines.
pub fn fault(e: &RuntimeError) -> Problems {
    let text = crate::files::read_input_text(Path::new(&e.file))
        .unwrap_or_else(|_| "\n".repeat((e.line as usize).saturating_sub(1)) + &" ".repeat(e.col as usize));
    fault_in(&e.file, text, e)
}

/// A runtime fault of a program whose source is `text` (an expression of
/// `linc eval` has no file to read back).
pub fn fault_in(name: &str, text: String, e: &RuntimeError) -> Problems {
    let at = offset(&text, e.line, e.col);
    let mut p = Problems::new();
    let id = p.add_file(name, text);
    let message = if e.action.is_empty() { e.message.clone() } else { format!("in `{}`: {}", e.action, e.message) };
    let span = linc_compiler::diag::Span::new(at, at);
    p.push(Diagnostic::error(e.code, message, span).label("the program stopped here").in_file(id));
    p
}

/// Byte offset of a 1-based line and column in `text` (clamped).
fn offset(text: &str, line: u32, col: u32) -> usize {
    let start: usize = text.split_inclusive('\n').take((line as usize).saturating_sub(1)).map(str::len).sum();
    (start + (col as usize).saturating_sub(1)).min(text.len())
}

/// Where `--trace FILE` goes: a file written atomically, committed when
/// the trace is flushed at its end, so a run that fails to write leaves no
/// partial file.
pub fn trace_file(path: &Path) -> Result<Box<dyn Write + Send>, Problems> {
    Ok(Box::new(TraceFile(Some(crate::files::AtomicFile::create(path)?))))
}

struct TraceFile(Option<crate::files::AtomicFile>);

impl Write for TraceFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self.0.as_mut() {
            Some(f) => f.write(buf),
            None => Err(std::io::Error::other("the trace was already committed")),
        }
    }

    /// The trace flushes once, at its end ([`Trace::finish`]): that commits the file.
    fn flush(&mut self) -> std::io::Result<()> {
        match self.0.take() {
            Some(f) => f.commit().map_err(|e| std::io::Error::other(e.to_string())),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use linc_compiler::diag::Format;

    #[test]
    fn runtime_errors_point_at_their_line_and_column() {
        let e = RuntimeError {
            code: Code::R0001,
            message: "division by zero".into(),
            action: "fault".into(),
            file: "rt.st".into(),
            line: 2,
            col: 3,
        };
        let p = fault_in("rt.st", "a := 1;\nb := a / 0;\n".into(), &e);
        assert_eq!(p.render(Format::Short), "rt.st:2:3: error[R0001]: in `fault`: division by zero\n");
        assert!(!p.is_refused());
    }
}

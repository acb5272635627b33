//! `linc draw`: a source as a picture (docs/pictures.md) — read and
//! checked as `linc check` reads it, optionally run as `linc run` would
//! run it (built by [`crate::plant`]) for the state it leaves, then handed
//! to `linc-draw`; or a trace read a line at a time into a trend chart.

use crate::database::{load_opt, usage};
use crate::plant::{PlantSpec, Program, StateFile};
use linc_compiler::diag::{Diagnostic, Problems};
use linc_compiler::source_kind::SourceKind;
use linc_compiler::{fst, ladder, sfc, Context};
use linc_draw::fst::FstState;
use linc_draw::sfc::StepState;
use linc_engines::strategy::Strategy;
use linc_format::Code;
use std::io::BufRead;
use std::path::PathBuf;

/// What to draw and, for a picture of a run, how to run it.
#[derive(Clone, Debug, Default)]
pub struct Options {
    pub file: PathBuf,
    pub db: Option<PathBuf>,
    /// Run the sequence or table this long first (`--for`).
    pub duration: Option<String>,
    /// Run a ladder file's actions this many times first (`--cycles`).
    pub cycles: Option<u32>,
    pub block: Option<String>,
    pub period: Option<f64>,
    pub set: Vec<String>,
    /// Start the run warm from this state file (it is only read).
    pub state: Option<PathBuf>,
    pub now: Option<i64>,
    pub seed: Option<u64>,
    /// Trend fields of a trace, and the range in seconds of it.
    pub fields: Vec<String>,
    pub from: Option<String>,
    pub to: Option<String>,
}

/// A picture, and what drawing it found: the errors of a run that stopped
/// a program (the picture shows the state the fault left), warnings.
pub struct Picture {
    pub svg: String,
    pub problems: Problems,
}

/// The most bytes one line of a trace may have (a trace line is short).
const MAX_TRACE_LINE: usize = 1 << 20;

/// Draws the file. A source with errors, a refused option or an unreadable
/// file is `Err`; a run that stopped a program with a runtime error is
/// still drawn (as the fault left it), the error in the picture's problems.
pub fn picture(o: &Options) -> Result<Picture, Problems> {
    let name = o.file.to_string_lossy().to_ascii_lowercase();
    if name.ends_with(".jsonl") {
        return trend(o).map(|svg| Picture { svg, problems: Problems::new() });
    }
    if !o.fields.is_empty() || o.from.is_some() || o.to.is_some() {
        return Err(usage("--field, --from and --to draw a trend of a trace (.jsonl)"));
    }
    let run_only = o.block.is_some()
        || o.period.is_some()
        || !o.set.is_empty()
        || o.state.is_some()
        || o.now.is_some()
        || o.seed.is_some();
    let kind = SourceKind::of_name(&o.file.to_string_lossy());
    if run_only && o.duration.is_none() && matches!(kind, SourceKind::Sequence | SourceKind::FstTable) {
        return Err(usage("--block, --period, --set, --state, --now and --seed shape a run: give --db and --for too"));
    }
    match kind {
        SourceKind::Sequence => sequence(o),
        SourceKind::Ladder => ladder_file(o),
        SourceKind::FstTable => table(o),
        _ => Err(usage(
            "linc draw draws a sequence (.sfc), a ladder file (.ld), an FST table (.csv) or a trace (.jsonl)",
        )),
    }
}

/// The source's problems: `Err` when one is an error, else its warnings.
fn checked(source: &crate::source::Source, diagnostics: Vec<Diagnostic>) -> Result<Problems, Problems> {
    let failed = diagnostics.iter().any(Diagnostic::is_error);
    let problems = source.problems_of(&diagnostics);
    if failed {
        Err(problems)
    } else {
        Ok(problems)
    }
}

fn sequence(o: &Options) -> Result<Picture, Problems> {
    if o.cycles.is_some() {
        return Err(usage("--cycles runs a ladder file: a sequence runs --for DURATION"));
    }
    let source = crate::source::read(&o.file)?;
    let db = load_opt(o.db.as_deref())?;
    let report = sfc::check_sequence(&source.text, Context::of(db.as_ref().map(|d| &d.db)));
    let mut problems = checked(&source, report.diagnostics)?;
    let Some(tree) = report.tree else { return Err(problems) };
    if o.duration.is_none() {
        return Ok(Picture { svg: linc_draw::sfc::sequence(&source.text, &tree, None).0, problems });
    }
    let (mut s, block, ran) = run(o)?;
    problems.append(ran);
    let Some(seq) = s.sequence_mut(block) else { return Err(problems.refused()) };
    let seq = &*seq;
    let look = |name: &str| step_state(seq, name);
    Ok(Picture { svg: linc_draw::sfc::sequence(&source.text, &tree, Some(&look)).0, problems })
}

fn ladder_file(o: &Options) -> Result<Picture, Problems> {
    if o.duration.is_some()
        || o.block.is_some()
        || o.period.is_some()
        || o.state.is_some()
        || o.now.is_some()
        || o.seed.is_some()
    {
        return Err(usage("a ladder file is drawn after --cycles N runs of its actions (--db, --set)"));
    }
    let source = crate::source::read(&o.file)?;
    let stem = crate::source::stem(&o.file, "ladder");
    let (file, diagnostics) = ladder::parser::parse(&source.text, stem);
    let mut problems = checked(&source, diagnostics)?;
    // With a database the rungs are compiled against it (names checked)
    // and drawn with its values: as it holds them, or after --cycles runs.
    let Some(db) = o.db.as_deref() else {
        if o.cycles.is_some() || !o.set.is_empty() {
            return Err(usage("--cycles and --set run the ladder: give --db DB.json"));
        }
        return Ok(Picture { svg: linc_draw::ladder::file(&source.text, &file.actions, None, None).0, problems });
    };
    let (after, ran) = crate::ladder::after_run(&o.file, db, &o.set, o.cycles.unwrap_or(0))?;
    problems.append(ran);
    let look = |span: linc_compiler::diag::Span| after.truths.get(&(span.start, span.end)).copied();
    let svg = linc_draw::ladder::file(&source.text, &file.actions, Some(&look), after.lines_ran.as_deref()).0;
    Ok(Picture { svg, problems })
}

fn table(o: &Options) -> Result<Picture, Problems> {
    if o.cycles.is_some() {
        return Err(usage("--cycles runs a ladder file: an FST table runs --for DURATION"));
    }
    let source = crate::source::read(&o.file)?;
    let db = load_opt(o.db.as_deref())?;
    let (read, mut diagnostics) = fst::reader::read(&source.text);
    let stem = crate::source::stem(&o.file, "fst");
    let (more, _) = fst::compile(&source.text, stem, &o.file.display().to_string(), db.as_ref().map(|d| &d.db));
    if db.is_some() {
        diagnostics = more;
    } else {
        diagnostics.extend(fst::check::check(&read, None).1);
    }
    let mut problems = checked(&source, diagnostics)?;
    if o.duration.is_none() {
        return Ok(Picture { svg: linc_draw::fst::table(&read, None).0, problems });
    }
    let (s, block, ran) = run(o)?;
    problems.append(ran);
    let state = fst_state(&s, block);
    Ok(Picture { svg: linc_draw::fst::table(&read, Some(&state)).0, problems })
}

/// A step as a sequence's picture shows it: active, its `.T`, held by the
/// monitor. Shared with `linc serve`'s live pictures.
pub fn step_state(seq: &linc_engines::sequence::Sequence, name: &str) -> Option<StepState> {
    let (active, t_us) = seq.step(name)?;
    let held = seq.monitor.held.iter().any(|h| h.eq_ignore_ascii_case(name));
    Some(StepState { active, t_us, held })
}

/// What an FST block shows of its table's run, for a picture: the step
/// the table goes on with (the one `IP` names, as the program list and
/// `P?` show it: [`Strategy::fst_step`]), RR, CF, RUNFLG and the
/// registers, as the console displays them. Shared with `linc serve`'s
/// live pictures.
pub fn fst_state(s: &Strategy, block: usize) -> FstState {
    let store = &s.store;
    let field = |f: &str| store.cell_of(block, f).map(|c| store.show(c)).unwrap_or_default();
    let registers = (1..=10)
        .map(|k| format!("R{k}"))
        .filter(|n| store.cell_of(block, n).is_some())
        .map(|n| {
            let v = field(&n);
            (n, v)
        })
        .collect();
    FstState { current: s.fst_step(block), rr: field("RR"), cf: field("CMPFLG"), runflg: field("RUNFLG"), registers }
}

/// Runs the one sequence or table as `linc run FILE --db … --for …` does
/// (block, period, set, a warm start from --state, which is only read) and
/// returns the strategy as the run left it, the program's block and the
/// run's problems (warnings, runtime faults).
fn run(o: &Options) -> Result<(Strategy, usize, Problems), Problems> {
    let Some(db) = o.db.clone() else {
        return Err(usage("--for runs the file against a database: give --db PLANT.json"));
    };
    let length = crate::database::duration("--for", o.duration.as_deref().unwrap_or("0s"))?;
    let spec = PlantSpec {
        program: Program::One { file: o.file.clone(), block: o.block.clone(), period: o.period },
        set: o.set.clone(),
        now: o.now,
        seed: o.seed,
        state: o.state.clone().map(|path| StateFile { path, cold: false }),
        ..PlantSpec::strategy(db)
    };
    let mut plant = crate::plant::build(&spec)?;
    let mut problems = std::mem::take(&mut plant.warnings);
    let block = plant.block.unwrap_or_default();
    let Some(mut s) = plant.into_strategy() else { return Err(problems.refused()) };
    problems.append(crate::run::faults(&s.run_for(length, None)));
    Ok((s, block, problems))
}

/// Seconds of a `--from`/`--to` time into the trace (`0`, `90s`, `T#1h`).
fn seconds(text: Option<&str>, flag: &str) -> Result<Option<f64>, Problems> {
    let Some(t) = text else { return Ok(None) };
    match t.trim().parse::<f64>().or_else(|_| linc_runtime::db::duration_seconds(t)) {
        Ok(s) if s.is_finite() && s >= 0.0 => Ok(Some(s)),
        _ => Err(usage(format!("{flag} `{t}` is not a time into the trace like 0, 90s or 1h30m"))),
    }
}

fn trend(o: &Options) -> Result<String, Problems> {
    if o.fields.is_empty() {
        return Err(usage("a trend needs the fields to draw: --field BLOCK.FIELD (repeatable)"));
    }
    let source_only = o.db.is_some()
        || o.duration.is_some()
        || o.cycles.is_some()
        || o.block.is_some()
        || o.period.is_some()
        || !o.set.is_empty()
        || o.state.is_some()
        || o.now.is_some()
        || o.seed.is_some();
    if source_only {
        return Err(usage("a trace is drawn as it was recorded: only --field, --from and --to apply"));
    }
    let (from, to) = (seconds(o.from.as_deref(), "--from")?, seconds(o.to.as_deref(), "--to")?);
    if let (Some(f), Some(t)) = (from, to) {
        if t <= f {
            return Err(usage(format!("--to must be later than --from ({t} s is not after {f} s)")));
        }
    }
    let name = o.file.display().to_string();
    let file = std::fs::File::open(&o.file).map_err(|e| Problems::unreadable(&o.file, &e))?;
    let mut reader = std::io::BufReader::new(file);
    let mut t = linc_draw::trend::Trend::new(&o.fields, from, to);
    let mut line = Vec::new();
    let fail = |e: linc_draw::trend::TrendError| {
        let at = e.line.map(|l| format!("line {l} of `{name}` is not a trace record: ")).unwrap_or_default();
        Problems::finding(Diagnostic::command(e.code, format!("{at}{}", e.message)))
    };
    let mut number = 0usize;
    loop {
        line.clear();
        number += 1;
        let n = std::io::Read::take(&mut reader, MAX_TRACE_LINE as u64 + 1)
            .read_until(b'\n', &mut line)
            .map_err(|e| Problems::unreadable(&o.file, &e))?;
        if n == 0 {
            break;
        }
        if line.len() > MAX_TRACE_LINE {
            let message =
                format!("line {number} of `{name}` is not a trace record: longer than {MAX_TRACE_LINE} bytes");
            return Err(Problems::finding(Diagnostic::command(Code::E0910, message)));
        }
        let text = String::from_utf8_lossy(&line);
        t.feed(&text).map_err(fail)?;
    }
    t.finish().map_err(fail)
}

//! `linc draw`: a source as a picture (docs/pictures.md) — read and
//! checked as `linc check` reads it, optionally run as `linc run` would
//! run it for the state it leaves, then handed to `linc-draw`; or a trace
//! read a line at a time into a trend chart.

use crate::database::{duration, load as load_db, set_and_show, start_time};
use crate::report::{refused, usage};
use crate::Reporter;
use linc_compiler::diag::render::SourceFiles;
use linc_compiler::source_kind::SourceKind;
use linc_compiler::Context;
use linc_compiler::{fst, ladder, sfc, Diagnostic, FileId};
use linc_draw::fst::FstState;
use linc_draw::sfc::StepState;
use linc_engines::strategy::Strategy;
use linc_format::Code;
use linc_runtime::{Database, Store};
use std::io::BufRead;
use std::path::{Path, PathBuf};

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
    pub now: Option<String>,
    pub seed: Option<u64>,
    /// Trend fields of a trace, and the range in seconds of it.
    pub fields: Vec<String>,
    pub from: Option<String>,
    pub to: Option<String>,
}

/// The most bytes one line of a trace may have (a trace line is short).
const MAX_TRACE_LINE: usize = 1 << 20;

/// Draws the file; `Err` is the exit status, the reason reported. A run
/// that stopped a program with a runtime error is still drawn (as the
/// fault left it), and the error makes the exit status 1, as `linc run`'s.
pub fn picture(o: &Options, r: &mut Reporter) -> Result<(String, u8), u8> {
    let before = r.errors();
    let svg = draw(o, r)?;
    Ok((svg, u8::from(r.errors() > before)))
}

fn draw(o: &Options, r: &mut Reporter) -> Result<String, u8> {
    let name = o.file.to_string_lossy().to_ascii_lowercase();
    if name.ends_with(".jsonl") {
        return trend(o, r);
    }
    if !o.fields.is_empty() || o.from.is_some() || o.to.is_some() {
        return Err(usage(r, "--field, --from and --to draw a trend of a trace (.jsonl)"));
    }
    let run_only = o.block.is_some()
        || o.period.is_some()
        || !o.set.is_empty()
        || o.state.is_some()
        || o.now.is_some()
        || o.seed.is_some();
    let kind = SourceKind::of_name(&o.file.to_string_lossy());
    if run_only && o.duration.is_none() && matches!(kind, SourceKind::Sequence | SourceKind::FstTable) {
        return Err(usage(
            r,
            "--block, --period, --set, --state, --now and --seed shape a run: give --db and --for too",
        ));
    }
    match kind {
        SourceKind::Sequence => sequence(o, r),
        SourceKind::Ladder => ladder_file(o, r),
        SourceKind::FstTable => table(o, r),
        _ => Err(usage(
            r,
            "linc draw draws a sequence (.sfc), a ladder file (.ld), an FST table (.csv) or a trace (.jsonl)",
        )),
    }
}

/// The source's text, or the status of an unreadable or non-UTF-8 file.
fn source(o: &Options, r: &mut Reporter) -> Result<(String, SourceFiles, FileId), u8> {
    match crate::source::read(&o.file, r)? {
        (Some(t), files, id) => Ok((t, files, id)),
        (None, ..) => Err(1),
    }
}

fn errors(files: &SourceFiles, id: FileId, diagnostics: Vec<Diagnostic>, r: &mut Reporter) -> Result<(), u8> {
    let failed = diagnostics.iter().any(Diagnostic::is_error);
    r.emit_all(files, &diagnostics.into_iter().map(|d| d.in_file(id)).collect::<Vec<_>>());
    if failed {
        Err(1)
    } else {
        Ok(())
    }
}

/// The database for checking: `--db`, or none (names taken on trust).
fn database(o: &Options, r: &mut Reporter) -> Result<Option<Database>, u8> {
    let mut files = SourceFiles::new();
    load_db(o.db.as_deref(), &mut files, r)
}

fn sequence(o: &Options, r: &mut Reporter) -> Result<String, u8> {
    if o.cycles.is_some() {
        return Err(usage(r, "--cycles runs a ladder file: a sequence runs --for DURATION"));
    }
    let (text, files, id) = source(o, r)?;
    let db = database(o, r)?;
    let report = sfc::check_sequence(&text, Context::of(db.as_ref()));
    errors(&files, id, report.diagnostics, r)?;
    let Some(tree) = report.tree else { return Err(1) };
    if o.duration.is_none() {
        return Ok(linc_draw::sfc::sequence(&text, &tree, None).0);
    }
    let (mut s, block) = run(o, crate::single::Kind::Sequence, r)?;
    let Some(seq) = s.sequence_mut(block) else { return Err(2) };
    let seq = &*seq;
    let look = |name: &str| step_state(seq, name);
    Ok(linc_draw::sfc::sequence(&text, &tree, Some(&look)).0)
}

fn ladder_file(o: &Options, r: &mut Reporter) -> Result<String, u8> {
    if o.duration.is_some()
        || o.block.is_some()
        || o.period.is_some()
        || o.state.is_some()
        || o.now.is_some()
        || o.seed.is_some()
    {
        return Err(usage(r, "a ladder file is drawn after --cycles N runs of its actions (--db, --set)"));
    }
    let (text, files, id) = source(o, r)?;
    let stem = o.file.file_stem().and_then(|s| s.to_str()).unwrap_or("ladder");
    let (file, diagnostics) = ladder::parser::parse(&text, stem);
    errors(&files, id, diagnostics, r)?;
    // With a database the rungs are compiled against it (names checked)
    // and drawn with its values: as it holds them, or after --cycles runs.
    let Some(db) = o.db.as_deref() else {
        if o.cycles.is_some() || !o.set.is_empty() {
            return Err(usage(r, "--cycles and --set run the ladder: give --db DB.json"));
        }
        return Ok(linc_draw::ladder::file(&text, &file.actions, None).0);
    };
    let known = crate::ladder::after_run(&o.file, db, &o.set, o.cycles.unwrap_or(0), r)?;
    let look = |span: linc_compiler::diag::span::Span| known.get(&(span.start, span.end)).copied();
    Ok(linc_draw::ladder::file(&text, &file.actions, Some(&look)).0)
}

fn table(o: &Options, r: &mut Reporter) -> Result<String, u8> {
    if o.cycles.is_some() {
        return Err(usage(r, "--cycles runs a ladder file: an FST table runs --for DURATION"));
    }
    let (text, files, id) = source(o, r)?;
    let db = database(o, r)?;
    let (read, mut diagnostics) = fst::reader::read(&text);
    let stem = o.file.file_stem().and_then(|s| s.to_str()).unwrap_or("fst");
    let (more, object) = fst::compile(&text, stem, &o.file.display().to_string(), db.as_ref());
    if db.is_some() {
        diagnostics = more;
    } else {
        diagnostics.extend(fst::check::check(&read, None).1);
    }
    errors(&files, id, diagnostics, r)?;
    if o.duration.is_none() {
        return Ok(linc_draw::fst::table(&read, None).0);
    }
    let offsets = object.as_ref().and_then(fst::offsets).unwrap_or_default();
    let (s, block) = run(o, crate::single::Kind::Fst, r)?;
    let state = fst_state(&s.store, block, &offsets);
    Ok(linc_draw::fst::table(&read, Some(&state)).0)
}

/// A step as a sequence's picture shows it: active, its `.T`, held by the
/// monitor. Shared with `linc serve`'s live pictures.
pub fn step_state(seq: &linc_engines::sequence::Sequence, name: &str) -> Option<StepState> {
    let (active, t_us) = seq.step(name)?;
    let held = seq.monitor.held.iter().any(|h| h.eq_ignore_ascii_case(name));
    Some(StepState { active, t_us, held })
}

/// What an FST block shows of its table's run, for a picture: the step
/// the table goes on with (from `IP`, by the table's instruction offsets),
/// RR, CF, RUNFLG and the registers, as the console displays them. Shared
/// with `linc serve`'s live pictures.
pub fn fst_state(store: &Store, block: usize, offsets: &[u32]) -> FstState {
    let field = |f: &str| store.cell_of(block, f).map(|c| store.show(c)).unwrap_or_default();
    let ip: Option<u32> = field("IP").trim().parse().ok();
    let registers = (1..=10)
        .map(|k| format!("R{k}"))
        .filter(|n| store.cell_of(block, n).is_some())
        .map(|n| {
            let v = field(&n);
            (n, v)
        })
        .collect();
    FstState {
        current: ip.and_then(|ip| offsets.iter().position(|&o| o == ip)),
        rr: field("RR"),
        cf: field("CMPFLG"),
        runflg: field("RUNFLG"),
        registers,
    }
}

/// Runs the one sequence or table as `linc run FILE --db … --for …` does
/// (block, period, set, a warm start from --state) and returns the
/// strategy as the run left it, with the program's block.
fn run(o: &Options, kind: crate::single::Kind, r: &mut Reporter) -> Result<(Strategy, usize), u8> {
    let Some(db_path) = o.db.as_deref() else {
        return Err(usage(r, "--for runs the file against a database: give --db PLANT.json"));
    };
    let length = duration(o.duration.as_deref().unwrap_or("0s")).map_err(|m| usage(r, m))?;
    let now = start_time(o.now.as_deref()).map_err(|m| usage(r, m))?;
    let mut files = SourceFiles::new();
    let Some(mut db) = load_db(Some(db_path), &mut files, r)? else { return Err(2) };
    let db_text = files.get(0).map(|f| f.source().clone()).unwrap_or_default();
    let block = crate::single::find_block(&db, o.block.as_deref(), kind).map_err(|d| refused(r, *d))?;
    if let Some(p) = o.period {
        crate::single::set_period(&mut db, block, p);
    }
    let mut store = Store::new(db);
    set_and_show(&mut store, &o.set, &[], r)?;
    let wants = vec![crate::single::want_for(&o.file, kind, block)];
    let dir = db_path.parent().map(Path::to_path_buf).unwrap_or_default();
    let plant = crate::strategy::PlantOptions { seed: o.seed, ..Default::default() };
    let mut s = crate::strategy::assemble(&dir, (&files, &db_text), store, &wants, now, &plant, r)?;
    if let Some(path) = &o.state {
        if crate::state::warm_start(path, false, &mut s, r)? == crate::state::Start::Warm {
            set_and_show(&mut s.store, &o.set, &[], r)?;
        }
    }
    for e in s.run_for(length, None) {
        r.runtime(&e);
    }
    Ok((s, block))
}

/// Seconds of a `--from`/`--to` time into the trace (`0`, `90s`, `T#1h`).
fn seconds(text: Option<&str>, flag: &str, r: &mut Reporter) -> Result<Option<f64>, u8> {
    let Some(t) = text else { return Ok(None) };
    match t.trim().parse::<f64>().or_else(|_| linc_runtime::db::duration_seconds(t)) {
        Ok(s) if s.is_finite() && s >= 0.0 => Ok(Some(s)),
        _ => Err(usage(r, format_args!("{flag} `{t}` is not a time into the trace like 0, 90s or 1h30m"))),
    }
}

fn trend(o: &Options, r: &mut Reporter) -> Result<String, u8> {
    if o.fields.is_empty() {
        return Err(usage(r, "a trend needs the fields to draw: --field BLOCK.FIELD (repeatable)"));
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
        return Err(usage(r, "a trace is drawn as it was recorded: only --field, --from and --to apply"));
    }
    let (from, to) = (seconds(o.from.as_deref(), "--from", r)?, seconds(o.to.as_deref(), "--to", r)?);
    if let (Some(f), Some(t)) = (from, to) {
        if t <= f {
            return Err(usage(r, format_args!("--to must be later than --from ({t} s is not after {f} s)")));
        }
    }
    let name = o.file.display().to_string();
    let file = std::fs::File::open(&o.file).map_err(|e| {
        r.unreadable(&o.file, &e);
        2u8
    })?;
    let mut reader = std::io::BufReader::new(file);
    let mut t = linc_draw::trend::Trend::new(&o.fields, from, to);
    let mut line = Vec::new();
    let fail = |e: linc_draw::trend::TrendError, r: &mut Reporter| {
        let at = e.line.map(|l| format!("line {l} of `{name}` is not a trace record: ")).unwrap_or_default();
        r.command(e.code, format!("{at}{}", e.message));
        1u8
    };
    let mut number = 0usize;
    loop {
        line.clear();
        number += 1;
        let n =
            std::io::Read::take(&mut reader, MAX_TRACE_LINE as u64 + 1).read_until(b'\n', &mut line).map_err(|e| {
                r.unreadable(&o.file, &e);
                2u8
            })?;
        if n == 0 {
            break;
        }
        if line.len() > MAX_TRACE_LINE {
            let message =
                format!("line {number} of `{name}` is not a trace record: longer than {MAX_TRACE_LINE} bytes");
            r.command(Code::E0910, message);
            return Err(1);
        }
        let text = String::from_utf8_lossy(&line);
        t.feed(&text).map_err(|e| fail(e, r))?;
    }
    t.finish().map_err(|e| fail(e, r))
}

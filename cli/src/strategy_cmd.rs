//! `linc run PLANT.json --for DURATION`: run a whole strategy. The CLI
//! reads, compiles and prints; the runtime's strategy engine runs.

use crate::report::usage;
use crate::run_cmd::Common;
use linc_compiler::diag::render::SourceFiles;
use linc_driver::database::load as load_db;
use linc_driver::database::{duration, set_and_show, start_time, write_db};
use linc_driver::single::SequenceRun;
use linc_driver::Reporter;
use linc_engines::console::fields::show_value;
use linc_engines::strategy::{self, trace::Trace, Strategy, Want};
use linc_format::Code;

use linc_runtime::Store;
use std::path::{Path, PathBuf};

pub struct Options {
    pub db: PathBuf,
    pub duration: String,
    pub common: Common,
    /// Run only this sequence or FST table (`linc run batch.sfc --db … --for …`).
    pub single: Option<SequenceRun>,
    pub retain: Retain,
    /// The console's script, an input no output may replace.
    pub script: Option<PathBuf>,
}

/// `--state FILE` and `--cold`.
#[derive(Clone, Debug, Default)]
pub struct Retain {
    pub state: Option<PathBuf>,
    pub cold: bool,
}

/// The whole strategy of a database, as `linc run PLANT.json` builds it
/// (with `--set` applied), for the console and `linc serve`.
pub fn load(o: &Options, r: &mut Reporter) -> Result<Strategy, u8> {
    let (s, wants) = linc_driver::strategy::plant(&o.db, &plant_options(&o.common), r)?;
    check_outputs(o, &wants, r)?;
    Ok(s)
}

/// What of the common options shapes a strategy before it runs.
pub fn plant_options(c: &Common) -> linc_driver::strategy::PlantOptions {
    linc_driver::strategy::PlantOptions {
        set: c.set.clone(),
        now: c.now.clone(),
        seed: c.seed,
        watchdog: c.watchdog,
        tier: c.tier,
    }
}

pub fn run(o: &Options, r: &mut Reporter) -> u8 {
    let duration = match duration(&o.duration) {
        Ok(d) => d,
        Err(msg) => return usage(r, msg),
    };
    let now = match start_time(o.common.now.as_deref()) {
        Ok(s) => s,
        Err(msg) => return usage(r, msg),
    };
    let mut files = SourceFiles::new();
    let mut db = match load_db(Some(&o.db), &mut files, r) {
        Ok(Some(db)) => db,
        Ok(None) => return 2,
        Err(status) => return status,
    };
    let db_text = files.get(0).map(|f| f.source().clone()).unwrap_or_default();
    let seq_block =
        match o.single.as_ref().map(|q| linc_driver::single::find_block(&db, q.block.as_deref(), q.kind)).transpose() {
            Ok(b) => b,
            Err(d) => return crate::report::refused(r, *d),
        };
    if let (Some(b), Some(p)) = (seq_block, o.single.as_ref().and_then(|q| q.period)) {
        linc_driver::single::set_period(&mut db, b, p);
    }
    let mut store = Store::new(db.clone());
    let step_shows: Vec<String> =
        o.common.show.iter().filter(|p| is_step_show(&store, seq_block, p)).cloned().collect();
    let field_shows: Vec<String> = o.common.show.iter().filter(|p| !step_shows.contains(p)).cloned().collect();
    let shows = match set_and_show(&mut store, &o.common.set, &field_shows, r) {
        Ok(v) => v,
        Err(status) => return status,
    };
    let wants = match (&o.single, seq_block) {
        (Some(q), Some(b)) => vec![linc_driver::single::want(q, b)],
        _ => strategy::wanted(&store),
    };
    if let Err(status) = check_outputs(o, &wants, r) {
        return status;
    }
    let dir = o.db.parent().map(Path::to_path_buf).unwrap_or_default();
    let built =
        linc_driver::strategy::assemble(&dir, (&files, &db_text), store, &wants, now, &plant_options(&o.common), r);
    let mut s = match built {
        Ok(s) => s,
        Err(status) => return status,
    };
    if let (Some(q), Some(seq)) = (&o.single, seq_block.and_then(|b| s.sequence_mut(b))) {
        if let Err(d) = linc_driver::single::monitor(seq, q, &step_shows) {
            return crate::report::refused(r, *d);
        }
    }
    if let Some(path) = &o.retain.state {
        match linc_driver::state::warm_start(path, o.retain.cold, &mut s, r) {
            // A warm start restored the values: --set applies on top of them.
            Ok(linc_driver::state::Start::Warm) => {
                if let Err(status) = set_and_show(&mut s.store, &o.common.set, &[], r) {
                    return status;
                }
            }
            Ok(linc_driver::state::Start::Cold) => {}
            Err(status) => return status,
        }
    }
    // The trace streams to its file (or standard output) as the run goes.
    let mut sink = match trace_sink(o.common.trace.as_deref(), r) {
        Ok(s) => s,
        Err(status) => return status,
    };
    let mut trace = sink.as_mut().map(|w| Trace::new(w.as_mut(), &s.store));
    let failures = s.run_for(duration, trace.as_mut());
    let traced = trace.map(Trace::finish);
    drop(sink);
    for e in &failures {
        r.runtime(e);
    }
    crate::run_cmd::say_compiled(o.common.tier, s.compiled_blocks());
    for path in &o.common.show {
        let step = seq_block.and_then(|b| s.sequence_mut(b)).and_then(|q| linc_driver::single::step_flag(q, path));
        let field = shows.iter().find(|(p, _)| p == path).map(|(_, a)| show_value(&s.store, *a));
        crate::out::line(&format!("{path} = {}", step.or(field).unwrap_or_default()));
    }
    if let Some(Err(e)) = traced {
        return trace_unwritten(o.common.trace.as_deref(), &e, r);
    }
    if let Some(Err(status)) = o.retain.state.as_ref().map(|p| linc_driver::state::save(p, &s, r)) {
        return status;
    }
    match write_outputs(o, &db_text, &s.store, r) {
        Ok(()) => u8::from(!failures.is_empty()),
        Err(status) => status,
    }
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

/// Outputs may not replace an input or anything but a regular file;
/// checked before the run, so a refused run changes nothing.
/// No two outputs may name one file (E0902), and the console's `--script`
/// is an input too.
fn check_outputs(o: &Options, wants: &[Want], r: &mut Reporter) -> Result<(), u8> {
    let dir = o.db.parent().map(Path::to_path_buf).unwrap_or_default();
    let inputs: Vec<PathBuf> =
        std::iter::once(o.db.clone()).chain(o.script.clone()).chain(wants.iter().map(|w| dir.join(&w.file))).collect();
    let input_refs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let outputs = [("--out", &o.common.out), ("--trace", &o.common.trace), ("--state", &o.retain.state)];
    let outputs: Vec<(&str, &Path)> = outputs.iter().filter_map(|(f, p)| Some((*f, p.as_deref()?))).collect();
    let refused = linc_driver::files::check_distinct(&outputs).err().or_else(|| {
        outputs
            .iter()
            .filter(|(_, p)| p.as_os_str() != "-")
            .find_map(|(_, out)| linc_driver::files::check_output(out, &input_refs).err())
    });
    match refused {
        Some(e) => Err(crate::report::refused(r, e.diagnostic())),
        None => Ok(()),
    }
}

/// Where `--trace` goes: standard output for `-`, else a file committed
/// when the trace is finished.
pub fn trace_sink(path: Option<&Path>, r: &mut Reporter) -> Result<Option<Box<dyn std::io::Write>>, u8> {
    match path {
        Some(p) if p.as_os_str() == "-" => Ok(Some(Box::new(std::io::BufWriter::new(std::io::stdout().lock())))),
        Some(p) => match linc_driver::files::AtomicFile::create(p) {
            Ok(f) => Ok(Some(Box::new(TraceFile(Some(f))))),
            Err(e) => Err(crate::report::refused(r, e.diagnostic())),
        },
        None => Ok(None),
    }
}

/// A trace file: committed (renamed into place) when the trace is
/// flushed at its end, so a run that fails to write leaves no partial file.
struct TraceFile(Option<linc_driver::files::AtomicFile>);

impl std::io::Write for TraceFile {
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

/// Writes the database with its values.
fn write_outputs(o: &Options, db_text: &str, store: &Store, r: &mut Reporter) -> Result<(), u8> {
    if let Some(out) = &o.common.out {
        if let Err(e) = write_db(out, db_text, store) {
            return Err(crate::report::refused(r, e.diagnostic()));
        }
    }
    Ok(())
}

/// A trace that could not be written to the end (E0900, exit status 2).
pub fn trace_unwritten(path: Option<&Path>, e: &std::io::Error, r: &mut Reporter) -> u8 {
    let name = path.map_or("-".into(), |p| p.display().to_string());
    r.command(Code::E0900, format!("can't write the trace `{name}`: {e}"));
    2
}

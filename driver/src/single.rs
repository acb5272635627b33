//! `linc run batch.sfc --db plant.json --for 10m`: one sequence run by an
//! SFC_CON block of the database (`--block`, or the only one), with the
//! monitor's controls (`--hold-step`, `--force`) and step flags for
//! `--show Step.X` / `Step.T`.

use linc_compiler::diag::Problems;
use linc_engines::sequence::Sequence;
use linc_engines::strategy::{Want, WantKind};
use linc_format::Code;
use linc_runtime::db::Task;
use linc_runtime::Database;

/// Which program a single-program run is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Sequence,
    Fst,
}

impl Kind {
    /// What `file` holds: an FST table (`.csv`, or an object whose first
    /// unit is one) or a sequence. An unreadable object is taken for a
    /// sequence here; loading it later reports why it can't be read.
    pub fn of(file: &std::path::Path) -> Kind {
        if crate::source::is_fst(file) {
            return Kind::Fst;
        }
        let fst_object = crate::files::read_input(file)
            .ok()
            .and_then(|bytes| linc_runtime::ObjectFile::from_bytes(&bytes).ok())
            .is_some_and(|o| o.units.first().is_some_and(|u| u.kind == linc_runtime::object::UnitKind::Fst));
        if fst_object {
            Kind::Fst
        } else {
            Kind::Sequence
        }
    }
}

/// The block that runs the program: an SFC_CON block for a sequence, an
/// FST block for a table (`--block`, or the only one); E0904 otherwise.
pub fn find_block(db: &Database, named: Option<&str>, kind: Kind) -> Result<usize, Problems> {
    let refuse = |why: String| Problems::usage(Code::E0904, why);
    let (template, what) = match kind {
        Kind::Sequence => ("SFC_CON", "the sequence"),
        Kind::Fst => ("FST", "the table"),
    };
    let runs = |b: usize| db.block_template(b).name.eq_ignore_ascii_case(template);
    if let Some(n) = named {
        return match db.block(n) {
            Some(b) if runs(b) => Ok(b),
            Some(_) => Err(refuse(format!("--block {n} is not an {template} block"))),
            None => Err(refuse(format!("--block: the database has no block `{n}`"))),
        };
    }
    let all: Vec<usize> = (0..db.blocks.len()).filter(|&b| runs(b)).collect();
    match all.as_slice() {
        [b] => Ok(*b),
        [] => Err(refuse(format!("the database has no {template} block to run {what}; add one"))),
        _ => Err(refuse(format!("the database has several {template} blocks; choose one with --block"))),
    }
}

/// `--period`: the block's task runs at this period for this run.
pub fn set_period(db: &mut Database, block: usize, seconds: f64) {
    let number = db.blocks[block].task;
    db.tasks.retain(|t| t.number != number);
    db.tasks.push(Task { number, period: seconds });
    db.tasks.sort_by_key(|t| t.number);
}

/// The program `file` of `kind` run by `block`, by its absolute path (the
/// strategy resolves `FileName` against the database's folder).
pub fn want_for(file: &std::path::Path, kind: Kind, block: usize) -> Want {
    let file = std::path::absolute(file).unwrap_or_else(|_| file.to_path_buf());
    let kind = match kind {
        Kind::Sequence => WantKind::Sequence,
        Kind::Fst => WantKind::Fst,
    };
    Want { block, file: file.display().to_string(), action: String::new(), kind }
}

/// The monitor's controls a run of one sequence starts with.
#[derive(Clone, Debug, Default)]
pub struct Controls {
    /// `--hold-step STEP`.
    pub hold_steps: Vec<String>,
    /// `--force NAME=hold|continue|normal`.
    pub force: Vec<String>,
}

/// Applies `--hold-step` and `--force NAME=hold|continue|normal`, and
/// checks that every `--show Step.X` names a step (E0903).
pub fn monitor(seq: &mut Sequence, o: &Controls, step_shows: &[String]) -> Result<(), Problems> {
    let usage = |why: String| Problems::usage(Code::E0903, why);
    for p in step_shows {
        let step = p.split_once('.').map_or(p.as_str(), |(s, _)| s);
        if !seq.chart.has_step(step) {
            return Err(usage(format!("--show {p}: no block, alias or step of the sequence is called `{step}`")));
        }
    }
    for s in &o.hold_steps {
        if !seq.chart.has_step(s) {
            return Err(usage(format!("--hold-step: the sequence has no step `{s}`")));
        }
        seq.monitor.held.insert(s.clone());
    }
    for f in &o.force {
        let (name, how) = f.rsplit_once('=').unwrap_or((f.as_str(), ""));
        if !seq.chart.has_transition(name.trim()) {
            return Err(usage(format!("--force: the sequence has no transition `{}`", name.trim())));
        }
        let value = match how.trim().to_ascii_lowercase().as_str() {
            "hold" => Some(false),
            "continue" => Some(true),
            "normal" => None,
            other => return Err(usage(format!("--force {f}: `{other}` is not hold, continue or normal"))),
        };
        match value {
            Some(v) => seq.monitor.forced.insert(name.trim().to_string(), v),
            None => seq.monitor.forced.remove(name.trim()),
        };
    }
    Ok(())
}

/// `Step.X` or `Step.T` of the sequence, as `--show` prints it.
pub fn step_flag(seq: &Sequence, path: &str) -> Option<String> {
    let (step, flag) = path.split_once('.')?;
    let (x, t_us) = seq.step(step)?;
    match flag.to_ascii_uppercase().as_str() {
        "X" => Some(if x { "TRUE" } else { "FALSE" }.to_string()),
        "T" => Some(linc_runtime::text::format_real((t_us as f64 / 1e6) as f32)),
        _ => None,
    }
}

//! `linc test [PATH…]`: runs scenario files (`*.ltest`, a directory is
//! searched) and reports like `cargo test`. The scenario language is the
//! compiler's (`linc_compiler::scenario`), running it the runtime's
//! (`linc_engines::scenario`); this reads files, builds strategies, runs
//! scenarios on all cores and prints (`docs/testing.md`).

use crate::report::usage;
use linc_compiler::scenario::{self, Target};
use linc_driver::coverage::{Coverage, Format, Gate};
use linc_driver::scenarios::{Outcome, Recording};
use linc_driver::Reporter;
use std::path::{Path, PathBuf};

pub struct Options {
    pub paths: Vec<PathBuf>,
    pub jobs: Option<usize>,
    pub junit: Option<PathBuf>,
    pub vcd: Option<PathBuf>,
    /// Run only this shard of the scenarios.
    pub shard: Option<linc_driver::scenarios::Shard>,
    /// List the scenarios that would run, and run none.
    pub list: bool,
    /// Count coverage and report it in this format (to `out`).
    pub coverage: Option<linc_driver::coverage::Format>,
    /// Add these lcov files instead of running anything (`-o` the sum).
    pub merge_coverage: Vec<PathBuf>,
    pub out: Option<PathBuf>,
    /// The shares of coverage under which the run fails.
    pub gate: Gate,
}

/// Every `.ltest` file under the paths, sorted, each once.
fn scenarios(paths: &[PathBuf]) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            walk(p, &mut out, 0).map_err(|e| format!("can't read `{}`: {e}", p.display()))?;
        } else if p.is_file() {
            out.push(p.clone());
        } else {
            return Err(format!("`{}` is not a scenario file or directory", p.display()));
        }
    }
    out.sort();
    out.dedup();
    Ok(out)
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>, depth: usize) -> std::io::Result<()> {
    if depth > 32 {
        return Ok(());
    }
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let kind = entry.file_type()?;
        let path = entry.path();
        if kind.is_dir() {
            walk(&path, out, depth + 1)?;
        } else if kind.is_file() && path.extension().is_some_and(|e| e == "ltest") {
            out.push(path);
        }
    }
    Ok(())
}

/// `--merge-coverage A.info B.info… -o OUT.info`: the sum as lcov, and
/// its summary table on standard output.
fn merge(o: &Options, r: &mut Reporter) -> u8 {
    let Some(out) = &o.out else { return usage(r, "--merge-coverage needs -o OUT.info, where the sum goes") };
    let inputs: Vec<&Path> = o.merge_coverage.iter().map(PathBuf::as_path).collect();
    if let Err(e) = linc_driver::files::check_output(out, &inputs) {
        return crate::report::refused(r, e.diagnostic());
    }
    let sum = match linc_driver::coverage::merge_files(&o.merge_coverage, r) {
        Ok(c) => c,
        Err(status) => return status,
    };
    if let Err(e) = linc_driver::files::write_atomic(out, sum.to_lcov().as_bytes()) {
        return crate::report::refused(r, e.diagnostic());
    }
    crate::out::line(sum.summary().trim_end());
    gate(&sum, &o.gate, r)
}

/// Reports each kind of coverage under what `--fail-under-*` asks (E0913);
/// the exit status, 1 if any is.
fn gate(coverage: &Coverage, gate: &Gate, r: &mut Reporter) -> u8 {
    let short = coverage.short_of(gate);
    for (kind, share, want) in &short {
        r.command(
            linc_format::Code::E0913,
            format!("{share:.2}% of {kind} covered, under the {want}% --fail-under-{kind} asks for"),
        );
    }
    u8::from(!short.is_empty())
}

pub fn run(o: &Options, r: &mut Reporter) -> u8 {
    if !o.merge_coverage.is_empty() {
        return merge(o, r);
    }
    if o.gate.is_set() && o.coverage.is_none() {
        return usage(r, "--fail-under-* needs --coverage (or --merge-coverage), whose counts it checks");
    }
    if o.out.is_some() && o.coverage.is_none() {
        return usage(r, "-o names where --coverage or --merge-coverage writes; give one of them");
    }
    if o.coverage.is_some_and(|f| f != Format::Summary) && o.out.is_none() {
        return usage(r, "--coverage lcov and --coverage cobertura need -o FILE, where the report goes");
    }
    let paths = if o.paths.is_empty() { vec![PathBuf::from(".")] } else { o.paths.clone() };
    let mut files = match scenarios(&paths) {
        Ok(f) => f,
        Err(msg) => return usage(r, msg),
    };
    if let Some(shard) = o.shard {
        files.retain(|f| shard.holds(f));
    }
    if o.list {
        for f in &files {
            crate::out::line(&f.display().to_string());
        }
        return 0;
    }
    if let Err(e) = check_outputs(o, &files) {
        return crate::report::refused(r, e.diagnostic());
    }
    let jobs = o.jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())).max(1);
    let started = std::time::Instant::now();
    let rec = Recording { vcd: o.vcd.is_some(), coverage: o.coverage.is_some() };
    let outcomes = linc_driver::scenarios::run_all(&files, jobs, rec);
    crate::out::line(&format!("running {} scenario{}", outcomes.len(), if outcomes.len() == 1 { "" } else { "s" }));
    for out in &outcomes {
        crate::out::line(&format!("test {} ... {}", out.name, if out.passed { "ok" } else { "FAILED" }));
    }
    let failed: Vec<&linc_driver::scenarios::Outcome> = outcomes.iter().filter(|o| !o.passed).collect();
    if !failed.is_empty() {
        crate::out::line("\nfailures:\n");
        for f in &failed {
            crate::out::line(&format!("---- {} ----\n{}", f.name, f.details));
        }
        crate::out::line("failures:");
        for f in &failed {
            crate::out::line(&format!("    {}", f.name));
        }
    }
    let passed = outcomes.len() - failed.len();
    let verdict = if failed.is_empty() { "ok" } else { "FAILED" };
    crate::out::line(&format!("\ntest result: {verdict}. {passed} passed, {} failed", failed.len()));
    eprintln!("linc test: {} scenarios in {:.2}s on {jobs} thread(s)", outcomes.len(), started.elapsed().as_secs_f64());
    if let Some(path) = &o.junit {
        if let Err(e) = linc_driver::files::write_atomic(path, crate::test_report::junit(&outcomes).as_bytes()) {
            return crate::report::refused(r, e.diagnostic());
        }
    }
    if let Some(path) = &o.vcd {
        if let Err(status) = crate::test_report::write_vcds(path, &outcomes, r) {
            return status;
        }
    }
    if let Some(format) = o.coverage {
        match write_coverage(format, o.out.as_deref(), &outcomes, r) {
            Ok(all) if gate(&all, &o.gate, r) != 0 => return 1,
            Ok(_) => {}
            Err(status) => return status,
        }
    }
    u8::from(!failed.is_empty())
}

/// The scenarios' coverage added up (in file order; sums do not depend on
/// it) and written as `format`: to `out`, or a summary to standard output.
/// The sum, for the gate.
fn write_coverage(format: Format, out: Option<&Path>, outcomes: &[Outcome], r: &mut Reporter) -> Result<Coverage, u8> {
    let mut all = Coverage::default();
    outcomes.iter().filter_map(|o| o.coverage.as_ref()).for_each(|c| all.merge(c));
    let text = match format {
        Format::Lcov => all.to_lcov(),
        Format::Cobertura => all.to_cobertura(),
        Format::Summary => all.summary(),
    };
    match out {
        Some(path) => linc_driver::files::write_atomic(path, text.as_bytes())
            .map_err(|e| crate::report::refused(r, e.diagnostic()))?,
        None => crate::out::line(text.trim_end()),
    }
    Ok(all)
}

/// `--junit` and `--vcd` may not name one file, nor a scenario or a file a
/// scenario names (its strategy or program and database); checked before
/// any scenario runs. Files read later (a strategy's action files) are
/// protected when the report is written (`files::AtomicFile`).
fn check_outputs(o: &Options, files: &[PathBuf]) -> Result<(), linc_driver::files::Refused> {
    let outputs = [("--junit", &o.junit), ("--vcd", &o.vcd), ("-o", &o.out)];
    let outputs: Vec<(&str, &Path)> = outputs.iter().filter_map(|(f, p)| Some((*f, p.as_deref()?))).collect();
    linc_driver::files::check_distinct(&outputs)?;
    let mut inputs: Vec<PathBuf> = files.to_vec();
    for file in files {
        let dir = file.parent().map(Path::to_path_buf).unwrap_or_default();
        let Ok(text) = linc_driver::files::read_input_text(file) else { continue };
        match scenario::parse(&text).0.target {
            Some(Target::Strategy(db)) => inputs.push(dir.join(db)),
            Some(Target::Program { file, db }) => inputs.extend([dir.join(file), dir.join(db)]),
            None => {}
        }
    }
    let inputs: Vec<&Path> = inputs.iter().map(PathBuf::as_path).collect();
    let mut targets: Vec<PathBuf> = o.junit.iter().chain(&o.out).cloned().collect();
    if let Some(vcd) = &o.vcd {
        targets.extend(crate::test_report::vcd_targets(vcd, files));
    }
    targets.iter().try_for_each(|t| linc_driver::files::check_output(t, &inputs))
}

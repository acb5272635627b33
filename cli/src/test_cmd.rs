//! `linc test [PATH…]`: runs scenario files (`*.ltest`, a directory is
//! searched) and reports like `cargo test`. Reading and running scenarios
//! is the driver's (`linc_driver::scenarios`), on all cores; this finds the
//! files, prints the report and writes JUnit, VCD and coverage files
//! (`docs/testing.md`).

use crate::report::{usage, Reporter};
use linc_compiler::diag::Problems;
use linc_driver::coverage::{Coverage, Format, Gate};
use linc_driver::scenarios::file::{self as scenario, Target};
use linc_driver::scenarios::{Outcome, Recording};
use linc_format::Code;
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
fn merge(o: &Options, r: &Reporter) -> u8 {
    let Some(out) = &o.out else { return usage(r, "--merge-coverage needs -o OUT.info, where the sum goes") };
    let inputs: Vec<&Path> = o.merge_coverage.iter().map(PathBuf::as_path).collect();
    let sum = linc_driver::files::check_output(out, &inputs)
        .map_err(Problems::from)
        .and_then(|()| linc_driver::coverage::merge_files(&o.merge_coverage))
        .and_then(|sum| {
            let text = sum.to_lcov()?;
            linc_driver::files::write_atomic(out, text.as_bytes()).map(|()| sum).map_err(Problems::from)
        });
    match sum {
        Ok(sum) => {
            crate::out::line(sum.summary().trim_end());
            r.report(&linc_driver::coverage::gate_problems(&sum, &o.gate))
        }
        Err(p) => r.report(&p),
    }
}

pub fn run(o: &Options, r: &Reporter) -> u8 {
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
        return r.report(&e.into());
    }
    let jobs = o.jobs.unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get())).max(1);
    let started = std::time::Instant::now();
    let rec = Recording { vcd: o.vcd.is_some(), coverage: o.coverage.is_some() };
    let outcomes = linc_driver::scenarios::run_all(&files, jobs, rec);
    print_report(&outcomes);
    let failed = outcomes.iter().any(|o| !o.passed);
    let took = started.elapsed().as_secs_f64();
    r.note(Code::I0003, format!("linc test: {} scenarios in {took:.2}s on {jobs} thread(s)", outcomes.len()));
    let written = write_files(o, &outcomes);
    match written {
        Ok(gate) if gate.has_errors() => r.report(&gate),
        Ok(_) => u8::from(failed),
        Err(p) => r.report(&p),
    }
}

/// The report, as `cargo test` prints one.
fn print_report(outcomes: &[Outcome]) {
    crate::out::line(&format!("running {} scenario{}", outcomes.len(), if outcomes.len() == 1 { "" } else { "s" }));
    for out in outcomes {
        crate::out::line(&format!("test {} ... {}", out.name, if out.passed { "ok" } else { "FAILED" }));
    }
    let failed: Vec<&Outcome> = outcomes.iter().filter(|o| !o.passed).collect();
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
}

/// `--junit`, `--vcd` and `--coverage`'s files; what `--fail-under-*`
/// finds short (E0913).
fn write_files(o: &Options, outcomes: &[Outcome]) -> Result<Problems, Problems> {
    if let Some(path) = &o.junit {
        linc_driver::files::write_atomic(path, linc_driver::reports::junit(outcomes).as_bytes())?;
    }
    if let Some(path) = &o.vcd {
        linc_driver::reports::write_vcds(path, outcomes)?;
    }
    match o.coverage {
        Some(format) => {
            let all = write_coverage(format, o.out.as_deref(), outcomes)?;
            Ok(linc_driver::coverage::gate_problems(&all, &o.gate))
        }
        None => Ok(Problems::new()),
    }
}

/// The scenarios' coverage added up (in file order; sums do not depend on
/// it) and written as `format`: to `out`, or a summary to standard output.
/// The sum, for the gate.
fn write_coverage(format: Format, out: Option<&Path>, outcomes: &[Outcome]) -> Result<Coverage, Problems> {
    let mut all = Coverage::default();
    outcomes.iter().filter_map(|o| o.coverage.as_ref()).for_each(|c| all.merge(c));
    let text = match format {
        Format::Lcov => all.to_lcov()?,
        Format::Cobertura => all.to_cobertura(),
        Format::Summary => all.summary(),
    };
    match out {
        Some(path) => linc_driver::files::write_atomic(path, text.as_bytes())?,
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
        targets.extend(linc_driver::reports::vcd_targets(vcd, files));
    }
    targets.iter().try_for_each(|t| linc_driver::files::check_output(t, &inputs))
}

//! Scenario tests (`.ltest`, docs/testing.md) as a library: each file is
//! read ([`mod@file`]), its plant built by [`crate::plant`] and its
//! expectations compiled, then run by the engines' scenario runner;
//! everything that goes wrong before the run is rendered into the
//! scenario's own outcome (short format), so reports are the same for any
//! number of threads. `linc test` prints the outcomes ([`crate::reports`]
//! writes JUnit and VCD).

pub mod file;

use crate::plant::{PlantSpec, Program, StateFile};
use file::{Action, How, Target};
use linc_compiler::diag::{Diagnostic, FileId, Format, Problems, SourceFiles, Span};
use linc_engines::scenario::{Check, Report, Step};
use linc_engines::strategy::Strategy;
use linc_format::Code;
use std::path::{Path, PathBuf};

/// Every simulation starts at this time (2026-01-05 00:00:00 UTC, a
/// Monday), so scenarios are repeatable; `at` times count from it.
pub const START: f64 = 1_767_571_200.0;

/// What one scenario gave: its name, whether it passed, the text to print
/// under `failures:`, its report (for JUnit and VCD).
pub struct Outcome {
    pub name: String,
    pub passed: bool,
    pub details: String,
    pub report: Report,
    /// What the scenario's strategy ran, when coverage was asked for.
    pub coverage: Option<crate::coverage::Coverage>,
}

/// What a scenario run records besides its result.
#[derive(Clone, Copy, Debug, Default)]
pub struct Recording {
    /// Sample the fields the scenario names (for VCD).
    pub vcd: bool,
    /// Count coverage (ADR 0020).
    pub coverage: bool,
}

/// A shard of a suite: the `k`-th (from 1) of `n`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    pub k: u32,
    pub n: u32,
}

impl Shard {
    /// `K/N` with 1 ≤ K ≤ N ≤ 1000.
    pub fn parse(text: &str) -> Result<Shard, String> {
        let bad = || format!("`{text}` is not a shard K/N (1 <= K <= N <= 1000, like 2/4)");
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let (k, n): (u32, u32) = (k.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if k == 0 || k > n || n > 1000 {
            return Err(bad());
        }
        Ok(Shard { k, n })
    }

    /// Whether a scenario file belongs to this shard: by a stable hash
    /// (64-bit FNV-1a) of its path as [`shard_key`] writes it, so every
    /// runner of a CI matrix, on any platform, splits a suite alike.
    pub fn holds(&self, path: &Path) -> bool {
        fnv1a(shard_key(path).as_bytes()) % u64::from(self.n) == u64::from(self.k - 1)
    }
}

/// A path as the shard hash reads it and coverage reports name source
/// files: relative to the current directory when it is under it, `/`
/// between components, without `.` components (`./examples/a.ltest` and
/// `examples/a.ltest` are one key).
pub fn shard_key(path: &Path) -> String {
    let cwd = std::env::current_dir().ok();
    let rel = cwd.as_deref().and_then(|c| path.strip_prefix(c).ok()).unwrap_or(path);
    let parts: Vec<String> = rel
        .components()
        .filter(|c| !matches!(c, std::path::Component::CurDir))
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    parts.join("/")
}

/// 64-bit FNV-1a: fixed by its definition, unlike the standard library's
/// hasher, which may change between releases.
fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// Runs the scenarios on `jobs` threads; the outcomes come back in file
/// order whatever order they finish in, so reports are identical.
pub fn run_all(files: &[PathBuf], jobs: usize, rec: Recording) -> Vec<Outcome> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let mut slots: Vec<Option<Outcome>> = (0..files.len()).map(|_| None).collect();
    let results = std::sync::Mutex::new(&mut slots);
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(files.len()) {
            scope.spawn(|| loop {
                let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(file) = files.get(i) else { break };
                let out = run_one(file, rec);
                if let Ok(mut r) = results.lock() {
                    r[i] = Some(out);
                }
            });
        }
    });
    slots.into_iter().flatten().collect()
}

/// Runs one scenario file; everything it would print is in the outcome.
/// The fields it names are sampled only for a VCD, coverage counted only
/// when asked for (a scenario that fails before its run counts nothing).
pub fn run_one(file: &Path, rec: Recording) -> Outcome {
    let name = file.display().to_string();
    // What goes wrong before the run is part of the scenario's report, in
    // the short format, so that reports come out in file order.
    let fail = |p: Problems| Outcome {
        name: name.clone(),
        passed: false,
        details: p.render(Format::Short),
        report: Report::default(),
        coverage: rec.coverage.then(Default::default),
    };
    let (mut strategy, steps, sc) = match prepare(file, &name) {
        Ok(ready) => ready,
        Err(p) => return fail(p),
    };
    let watch = if rec.vcd { watched(&sc) } else { Vec::new() };
    if rec.coverage {
        strategy.enable_coverage();
    }
    let mut console = linc_engines::console::Console::new(strategy);
    let report = linc_engines::scenario::run(&mut console, steps, &watch);
    let details = details(&name, &report);
    let coverage = rec.coverage.then(|| {
        let mut cov = crate::coverage::Coverage::default();
        for (object, counts) in console.strategy.coverage() {
            crate::coverage_map::add_object(&mut cov, object, &counts, &|f| shard_key(Path::new(f)));
        }
        cov
    });
    Outcome { name, passed: report.failures.is_empty(), details, report, coverage }
}

/// A scenario read, its plant built and its expectations compiled: the
/// strategy, the runner's steps and the scenario as read.
fn prepare(path: &Path, name: &str) -> Result<(Strategy, Vec<Step>, file::Scenario), Problems> {
    let bytes = crate::files::read_input(path).map_err(|e| Problems::unreadable(path, &e))?;
    let mut sources = SourceFiles::new();
    let (text, invalid) = linc_compiler::diag::decode(bytes);
    sources.add_decoded(name.to_string(), text.clone(), invalid.clone());
    if let Some(e) = linc_compiler::session::SessionError::not_utf8(&invalid) {
        return Err(Problems::of(sources, vec![e.to_diagnostic().in_file(FileId(0))]));
    }
    // Spans count from after a byte order mark: put them back in the file.
    let bom = if text.starts_with('\u{feff}') { 3 } else { 0 };
    let shifted = |ds: Vec<Diagnostic>| -> Vec<Diagnostic> {
        ds.into_iter()
            .map(|d| Diagnostic { span: Span::new(d.span.start + bom, d.span.end + bom), ..d }.in_file(FileId(0)))
            .collect()
    };
    let (sc, diagnostics) = file::parse(text.strip_prefix('\u{feff}').unwrap_or(&text));
    if !diagnostics.is_empty() {
        return Err(Problems::of(sources, shifted(diagnostics)));
    }
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let spec = spec(&dir, &sc)?;
    if let Some(d) = bad_set(&spec.db, &sc) {
        return Err(Problems::of(sources, shifted(vec![d])));
    }
    let plant = crate::plant::build(&spec)?;
    let Some(strategy) = plant.into_strategy() else {
        return Err(Problems::usage(Code::E0500, "the scenario runs a strategy, a sequence or an FST table"));
    };
    let (steps, errors) = steps(&sc, &strategy);
    if !errors.is_empty() {
        return Err(Problems::of(sources, shifted(errors)));
    }
    Ok((strategy, steps, sc))
}

/// The plant a scenario runs: its strategy or program, from the start of
/// every scenario (2026-01-05, seed 1), its `state` and its `set`s.
fn spec(dir: &Path, sc: &file::Scenario) -> Result<PlantSpec, Problems> {
    let (db, program) = match &sc.target {
        Some(Target::Strategy(db)) => (dir.join(db), Program::Strategy),
        Some(Target::Program { file, db }) => {
            (dir.join(db), Program::One { file: dir.join(file), block: None, period: None })
        }
        None => {
            return Err(Problems::usage(Code::E0500, "the scenario names nothing to run: write `strategy PLANT.json`"))
        }
    };
    Ok(PlantSpec {
        program,
        set: sc.sets.iter().map(|(s, _)| s.clone()).collect(),
        now: Some(START as i64),
        seed: Some(1),
        state: sc.state.as_ref().map(|(f, _)| StateFile { path: dir.join(f), cold: false }),
        ..PlantSpec::strategy(db)
    })
}

/// The first `set` line the database refuses (E0505 at the line): a field
/// it does not have, or a value the field does not take. A database that
/// does not load is left to the plant builder to report.
fn bad_set(db: &Path, sc: &file::Scenario) -> Option<Diagnostic> {
    let loaded = crate::database::load(db).ok()?;
    let mut store = linc_runtime::Store::new(loaded.db);
    sc.sets.iter().find_map(|(text, span)| {
        let why = linc_engines::console::fields::set(&mut store, text).err()?;
        Some(Diagnostic::error(Code::E0505, format!("set {text}: {why}"), *span).label("not a field and value"))
    })
}

/// The failures as `FILE:LINE: at TIME: message` with the values read.
fn details(name: &str, r: &Report) -> String {
    let mut out = String::new();
    for f in &r.failures {
        let line = if f.line == 0 { String::new() } else { format!(":{}", f.line) };
        out.push_str(&format!("{name}{line}: at {}: {}\n", linc_engines::scenario::time(f.at_us), f.message));
        for (field, value) in &f.values {
            out.push_str(&format!("    {field} = {value}\n"));
        }
    }
    out
}

/// The fields, aliases and step variables a scenario names in its commands
/// and expectations, for VCD.
fn watched(sc: &file::Scenario) -> Vec<String> {
    let mut out = Vec::new();
    for l in &sc.lines {
        let text = match &l.action {
            Action::At { command, .. } => command.as_str(),
            Action::Expect { expr, .. } => expr.as_str(),
            Action::Run { .. } => continue,
        };
        for token in text.split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '.' || c == ' ' || c == '-')) {
            for part in token.split_whitespace() {
                // BLOCK.FIELD and Step.X, or an alias (a bare name): the
                // runner keeps those the strategy has and skips the rest.
                let name = part.contains('.') || part.starts_with(|c: char| c.is_alphabetic() || c == '_');
                if name && !out.iter().any(|o: &String| o.eq_ignore_ascii_case(part)) {
                    out.push(part.to_string());
                }
            }
        }
    }
    out
}

/// The runtime steps: expectations checked and compiled against the
/// strategy's database and its sequences' steps; the diagnostics of those
/// that do not, located in the scenario.
fn steps(sc: &file::Scenario, s: &Strategy) -> (Vec<Step>, Vec<Diagnostic>) {
    let names = s.step_names();
    let mut out = Vec::new();
    let mut errors = Vec::new();
    for l in &sc.lines {
        match &l.action {
            Action::At { at_us, command } => {
                out.push(Step::At { line: l.line, at_us: *at_us, command: command.clone() })
            }
            Action::Run { for_us } => out.push(Step::Run { line: l.line, for_us: *for_us }),
            Action::Expect { how, expr, span } => {
                let compiled = linc_compiler::compile_expectation(expr, &s.store.db, &names)
                    .and_then(|obj| linc_runtime::verify::verify(obj).map_err(|e| vec![load_error(e)]));
                match compiled {
                    Ok(object) => {
                        let check = match *how {
                            How::Within(d) => Check::Within(d),
                            How::After(d) => Check::After(d),
                            How::Always => Check::Always,
                            How::Never => Check::Never,
                        };
                        out.push(Step::Expect { line: l.line, check, text: expr.clone(), object });
                    }
                    Err(diagnostics) => errors.extend(diagnostics.into_iter().map(|d| {
                        let shifted = Span::new(d.span.start + span.start, d.span.end + span.start);
                        Diagnostic { span: shifted, ..d }
                    })),
                }
            }
        }
    }
    (out, errors)
}

fn load_error(e: linc_runtime::LoadError) -> Diagnostic {
    Diagnostic::error(e.code(), e.to_string(), Span::new(0, 0))
}

#[cfg(test)]
mod shard_tests {
    use super::*;

    #[test]
    fn shards_parse_and_split_by_a_hash_that_does_not_change() {
        assert_eq!(Shard::parse("2/4"), Ok(Shard { k: 2, n: 4 }));
        for bad in ["0/4", "5/4", "1/0", "4", "a/b", "1/1001"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        // FNV-1a's published test vectors pin the hash.
        assert_eq!(fnv1a(b""), 0xcbf2_9ce4_8422_2325);
        assert_eq!(fnv1a(b"a"), 0xaf63_dc4c_8601_ec8c);
        assert_eq!(shard_key(Path::new("./examples/./fst/plant.ltest")), "examples/fst/plant.ltest");
        let here = std::env::current_dir().unwrap().join("x/y.ltest");
        assert_eq!(shard_key(&here), "x/y.ltest");
        // Every file is in exactly one shard.
        for i in 0..200 {
            let p = PathBuf::from(format!("suite/s{i}.ltest"));
            let owners = (1..=4).filter(|&k| Shard { k, n: 4 }.holds(&p)).count();
            assert_eq!(owners, 1, "{}", p.display());
        }
    }
}

//! The outputs of every example plant, pinned: each run's standard output
//! and error, `--out` database, `--trace` and `--state` file are compared
//! with `cli/tests/pinned/NAME.txt`, written before the driver was made a
//! library (issue 27), so a refactoring that changes a byte of what a user
//! sees fails here. A small output is kept whole (a diff shows what moved);
//! a large one as its length, line count and 64-bit FNV-1a hash.
//! `LINC_BLESS=1 cargo test -p linc --test pinned` writes them anew, for a
//! change of behaviour that is meant (say why in the commit).
mod common;

use common::{linc, linc_with_input};
use std::fmt::Write as _;
use std::path::Path;

const NOW: &str = "2026-01-05T06:00:00";

/// Outputs longer than this are pinned by their hash.
const WHOLE: usize = 64 * 1024;

/// One pinned run: its name, `linc`'s arguments (`{dir}` is a fresh
/// directory for its files), its standard input, and the files it writes.
struct Run {
    name: &'static str,
    args: &'static [&'static str],
    input: Option<&'static str>,
    files: &'static [&'static str],
    /// Whether the run takes `--now` (a strategy's clock).
    now: bool,
}

const RUNS: &[Run] = &[
    Run {
        name: "strategy",
        args: &["run", "examples/strategy/plant.json", "--for", "10m", "--show", "TANK1.HighCnt", "--seed", "7"],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "sequences",
        args: &["run", "examples/sequences/plant.json", "--for", "20m", "--seed", "7"],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "fst",
        args: &["run", "examples/fst/plant.json", "--for", "10m", "--seed", "7"],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "ladder",
        args: &["run", "examples/ladder/plant.json", "--for", "10m", "--seed", "7"],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "roc",
        args: &["run", "examples/roc/plant.json", "--for", "10m", "--seed", "7"],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "batch-sequence",
        args: &[
            "run",
            "examples/sequences/batch.sfc",
            "--db",
            "examples/sequences/plant.json",
            "--for",
            "5m",
            "--show",
            "Fill.X",
            "--show",
            "R1.Level",
        ],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "pump-table",
        args: &["run", "examples/fst/pump.csv", "--db", "examples/fst/plant.json", "--block", "FST 1", "--for", "5m"],
        input: None,
        files: &["trace.jsonl", "out.json", "state"],
        now: true,
    },
    Run {
        name: "guide-action",
        args: &[
            "run",
            "examples/guide/shift.st",
            "--db",
            "examples/guide/plant.db.json",
            "--cycles",
            "3",
            "--show",
            "Block_5.Val1",
            "--show",
            "Block_5.Val8",
        ],
        input: None,
        files: &["trace.jsonl", "out.json"],
        now: false,
    },
    Run {
        name: "console",
        args: &["console", "examples/strategy/plant.json", "--set", "TANK1.Level=75"],
        input: Some("D TANK1.Level\nADVANCE 2m\nD TANK1.HighCnt\nP?\nM TANK1.Level=10\nF TANK1.Valve=TRUE\nADVANCE 30s\nD TANK1.Level\nNOPE\n"),
        files: &["trace.jsonl", "state"],
        now: true,
    },
    Run { name: "scenarios", args: &["test", "examples/", "--jobs", "1"], input: None, files: &[], now: false },
];

fn fnv1a(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

/// One output as the pin file holds it.
fn pin(what: &str, bytes: &[u8]) -> String {
    let lines = bytes.iter().filter(|&&b| b == b'\n').count();
    match std::str::from_utf8(bytes) {
        Ok(text) if bytes.len() <= WHOLE => format!("== {what}: {} bytes, {lines} lines\n{text}\n", bytes.len()),
        _ => format!("== {what}: {} bytes, {lines} lines, fnv1a64 {:016x}\n", bytes.len(), fnv1a(bytes)),
    }
}

/// Everything `run` shows a user, as its pin file holds it.
fn outputs(run: &Run, dir: &Path) -> String {
    let d = dir.to_str().unwrap().to_string();
    let mut args: Vec<String> = run.args.iter().map(|a| a.to_string()).collect();
    if run.now {
        args.extend(["--now".into(), NOW.into()]);
    }
    for f in run.files {
        let flag = match *f {
            "trace.jsonl" => "--trace",
            "out.json" => "--out",
            _ => "--state",
        };
        args.extend([flag.to_string(), format!("{d}/{f}")]);
    }
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let o = match run.input {
        Some(input) => linc_with_input(&args, input),
        None => linc(&args),
    };
    let mut text = format!("linc {}\nexit {:?}\n", run.args.join(" "), o.status.code());
    text += &pin("stdout", &o.stdout);
    text += &pin("stderr", timing_removed(&o.stderr).as_bytes());
    for f in run.files {
        let bytes = std::fs::read(dir.join(f)).unwrap_or_else(|e| panic!("{}: {f}: {e}", run.name));
        text += &pin(f, &bytes);
    }
    text
}

/// `linc test`'s summary line says how long the run took: that alone is
/// left out (`in 3.07s` becomes `in …s`).
fn timing_removed(stderr: &[u8]) -> String {
    let text = String::from_utf8_lossy(stderr);
    let mut out = String::new();
    for line in text.split_inclusive('\n') {
        match (line.find(" in "), line.find("s on ")) {
            (Some(a), Some(b)) if line.starts_with("linc test:") && a < b => {
                out.push_str(&line[..a + 4]);
                out.push('…');
                out.push_str(&line[b..]);
            }
            _ => out.push_str(line),
        }
    }
    out
}

#[test]
fn every_example_plant_s_outputs_are_as_pinned() {
    let pinned = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/pinned");
    let mut stale = String::new();
    for run in RUNS {
        let dir = common::temp_dir(&format!("pinned-{}", run.name));
        let now = outputs(run, &dir);
        let path = pinned.join(format!("{}.txt", run.name));
        if std::env::var_os("LINC_BLESS").is_some() {
            std::fs::create_dir_all(&pinned).unwrap();
            std::fs::write(&path, &now).unwrap();
            continue;
        }
        let old = std::fs::read_to_string(&path).unwrap_or_default();
        if old != now {
            let actual = dir.join("actual.txt");
            std::fs::write(&actual, &now).unwrap();
            let _ = writeln!(stale, "{}: differs from {} (now: {})", run.name, path.display(), actual.display());
        }
    }
    assert!(stale.is_empty(), "{stale}");
}

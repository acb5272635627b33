//! Every output of every command is checked before anything runs: no output
//! may replace an input (a scenario, a console script, a database, an
//! action file), and no two outputs of one command may name one file
//! (E0902). The inputs are left byte for byte as they were, and no output
//! is created.
#![cfg(unix)]

mod common;

use common::{linc, stderr, stdout};
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Output;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// A fresh copy of the example strategy (database, actions, scenario).
fn plant(tag: &str) -> PathBuf {
    let dir = linc_test_support::fresh_dir(&format!("outputs-{tag}"));
    for f in ["plant.json", "actions.stx", "modbus.stx", "plant.ltest"] {
        fs::copy(Path::new(ROOT).join("examples/strategy").join(f), dir.join(f)).expect("copy example");
    }
    dir
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

/// Exit 2, E0902 named, nothing run (no scenario report, no replies).
fn assert_refused(o: &Output) {
    assert_eq!(o.status.code(), Some(2), "{}{}", stderr(o), stdout(o));
    assert!(stderr(o).contains("error[E0902]"), "{}", stderr(o));
    assert!(!stdout(o).contains("test result"), "scenarios ran: {}", stdout(o));
}

/// The files of `dir` with their contents, to prove nothing changed.
fn snapshot(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<(String, Vec<u8>)> = fs::read_dir(dir)
        .expect("list")
        .map(|e| e.expect("entry").path())
        .map(|p| (p.file_name().and_then(|n| n.to_str()).unwrap_or_default().to_string(), fs::read(&p).expect("read")))
        .collect();
    out.sort();
    out
}

#[test]
fn scenario_reports_may_not_replace_a_scenario_or_its_strategy() {
    let dir = plant("test");
    let before = snapshot(&dir);
    let scenario = dir.join("plant.ltest");
    let respelled = format!("{}/./plant.ltest", s(&dir));
    for (flag, out) in [
        ("--junit", s(&scenario)),
        ("--vcd", s(&scenario)),
        ("--junit", respelled.as_str()),
        ("--vcd", s(&dir.join("plant.json"))),
    ] {
        assert_refused(&linc(&["test", s(&scenario), flag, out]));
        assert_eq!(snapshot(&dir), before, "{flag} {out} changed the inputs");
    }
    // A file read during the run (an action file the strategy names) is
    // an input too: the report is refused, the action file kept.
    let o = linc(&["test", s(&scenario), "--junit", s(&dir.join("actions.stx"))]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("E0902"), "{}", stderr(&o));
    assert_eq!(snapshot(&dir), before);
}

#[test]
fn junit_and_vcd_may_not_name_one_file() {
    let dir = plant("test-both");
    let before = snapshot(&dir);
    let report = dir.join("report.xml");
    let respelled = format!("{}/../{}/report.xml", s(&dir), dir.file_name().and_then(|n| n.to_str()).expect("name"));
    let o = linc(&["test", s(&dir.join("plant.ltest")), "--junit", s(&report), "--vcd", &respelled]);
    assert_refused(&o);
    assert!(stderr(&o).contains("--junit writes the same file"), "{}", stderr(&o));
    assert!(!report.exists());
    assert_eq!(snapshot(&dir), before);
    // Different files: both written.
    let vcd = dir.join("trace.vcd");
    let o = linc(&["test", s(&dir.join("plant.ltest")), "--junit", s(&report), "--vcd", s(&vcd)]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(report.is_file() && vcd.is_file());
}

#[test]
fn console_trace_may_not_replace_its_script() {
    let dir = plant("console");
    let script = dir.join("commands.txt");
    fs::write(&script, "D TANK1.Level\nADVANCE 10s\n").expect("script");
    let before = snapshot(&dir);
    for flag in ["--trace", "--state"] {
        let o = linc(&["console", s(&dir.join("plant.json")), "--script", s(&script), flag, s(&script)]);
        assert_refused(&o);
        assert!(stdout(&o).is_empty(), "the console ran: {}", stdout(&o));
        assert_eq!(snapshot(&dir), before, "{flag} changed the inputs");
    }
    let o = linc(&[
        "console",
        s(&dir.join("plant.json")),
        "--script",
        s(&script),
        "--trace",
        s(&dir.join("x")),
        "--state",
        s(&dir.join("x")),
    ]);
    assert_refused(&o);
    assert_eq!(snapshot(&dir), before);
}

#[test]
fn two_outputs_of_a_strategy_run_may_not_name_one_file() {
    let dir = plant("run");
    let before = snapshot(&dir);
    let db = dir.join("plant.json");
    let x = dir.join("x.json");
    let dotted = format!("{}/./x.json", s(&dir));
    for (a, b) in [("--out", "--trace"), ("--state", "--out"), ("--trace", "--state")] {
        let o = linc(&["run", s(&db), "--for", "1m", a, s(&x), b, &dotted]);
        assert_refused(&o);
        let said = stderr(&o);
        assert!(said.contains("writes the same file") && said.contains(a) && said.contains(b), "{said}");
        assert!(!x.exists(), "{a} {b}: an output was written");
        assert_eq!(snapshot(&dir), before);
    }
    // An output over the strategy's action file is refused too.
    assert_refused(&linc(&["run", s(&db), "--for", "1m", "--trace", s(&dir.join("actions.stx"))]));
    assert_eq!(snapshot(&dir), before);
    // And by the server, before it serves: the trace would be lost under
    // the state it saves when it stops.
    let o = linc(&["serve", s(&db), "--http", "127.0.0.1:0", "--for", "1s", "--state", s(&x), "--trace", &dotted]);
    assert_refused(&o);
    assert!(stderr(&o).contains("writes the same file"), "{}", stderr(&o));
    assert!(!x.exists());
    assert_eq!(snapshot(&dir), before);
}

#[test]
fn two_outputs_of_an_action_run_may_not_name_one_file() {
    let dir = plant("action");
    let src = dir.join("a.st");
    fs::write(&src, "Counters.N0 := Counters.N0 + 1;\n").expect("source");
    fs::copy(Path::new(ROOT).join(common::DB), dir.join("db.json")).expect("db");
    let before = snapshot(&dir);
    let x = dir.join("x.json");
    let o = linc(&["run", s(&src), "--db", s(&dir.join("db.json")), "--out", s(&x), "--trace", s(&x)]);
    assert_refused(&o);
    assert!(!x.exists());
    assert_eq!(snapshot(&dir), before);
}

#[test]
fn the_state_file_is_read_and_written_by_one_run() {
    // --state is both an input and an output by design: a warm start reads
    // it and the end of the run saves it.
    let dir = plant("state");
    let db = dir.join("plant.json");
    let state = dir.join("plant.state");
    for _ in 0..2 {
        let o = linc(&["run", s(&db), "--for", "1m", "--state", s(&state)]);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    }
    assert!(state.is_file());
}

//! `linc run PLANT.json --for DURATION`: the example strategy, pinned.
mod common;
use common::{linc, temp_dir};

fn temp(name: &str) -> String {
    common::temp_path("strategy", name)
}

/// Runs the example for ten simulated minutes; returns (out, trace, stdout).
fn run_example(tag: &str) -> (String, String, String) {
    let (out, trace) = (temp(&format!("{tag}-out.json")), temp(&format!("{tag}-trace.jsonl")));
    let o = linc(&[
        "run",
        "examples/strategy/plant.json",
        "--for",
        "10m",
        "--now",
        "2026-01-05T06:00:00",
        "--trace",
        &trace,
        "--out",
        &out,
        "--show",
        "TANK1.HighCnt",
        "--show",
        "POLL.Tx_Value",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
    let read = |p: &str| std::fs::read_to_string(p).expect("written");
    (read(&out), read(&trace), String::from_utf8_lossy(&o.stdout).into_owned())
}

#[test]
fn the_example_strategy_runs_ten_minutes_and_is_pinned() {
    let (out, trace, stdout) = run_example("a");
    assert_eq!(stdout, "TANK1.HighCnt = 17\nPOLL.Tx_Value = '$01$03$9CA$00$02$BAO'\n");
    insta::assert_snapshot!("strategy_final_database", out);
    insta::assert_snapshot!("strategy_trace", trace);
    // Deterministic: a second run gives the same bytes.
    let (out2, trace2, _) = run_example("b");
    assert_eq!((out, trace), (out2, trace2));
}

#[test]
fn a_runtime_error_in_a_strategy_is_rendered_and_exits_one() {
    let dir = temp_dir("strategy-err");
    std::fs::write(dir.join("a.st"), "ACTION Bad\n  R.N0 := R.N0 + 1;\n  R.N1 := 1 / (2 - R.N0);\nEND_ACTION\n")
        .expect("write");
    let db = dir.join("plant.json");
    std::fs::write(
        &db,
        r#"{ "blocks": { "R": { "type": "RECIPE" }, "SYS": { "type": "SYSTEM" },
              "BAD": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Bad", "Trigger": true } } } }"#,
    )
    .expect("write");
    let db = db.to_string_lossy().into_owned();
    let o =
        linc(&["run", &db, "--for", "1s", "--message-format", "short", "--show", "SYS.ErrNum", "--show", "BAD.Status"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.ends_with("a.st:3:3: error[R0001]: in `Bad`: division by zero\n"), "{err}");
    assert_eq!(String::from_utf8_lossy(&o.stdout), "SYS.ErrNum = 1\nBAD.Status = 'ERROR'\n");
}

#[test]
fn bad_durations_and_mixed_modes_are_usage_errors() {
    for d in ["0s", "ten minutes", "400d", "T#"] {
        let o = linc(&["run", "examples/strategy/plant.json", "--for", d]);
        assert_eq!(o.status.code(), Some(2), "{d}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--for"), "{d}");
    }
    let o = linc(&["run", "examples/strategy/plant.json", "--for=-1s"]);
    assert_eq!(o.status.code(), Some(2));
    let o = linc(&["run", "examples/strategy/plant.json", "--for", "1s", "--db", "examples/guide/plant.db.json"]);
    assert_eq!(o.status.code(), Some(2));
    let o = linc(&["run", "examples/strategy/plant.json"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn blocks_without_an_action_run_nothing_and_half_named_ones_are_refused() {
    // Action-type blocks with no action: nothing to run.
    let dir = temp_dir("strategy-half");
    let idle = dir.join("idle.json");
    let blocks = r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "A0": 3.0 } },
        "A": { "type": "ACTION" }, "C": { "type": "RAW_COM" } } }"#;
    std::fs::write(&idle, blocks).expect("write");
    let o = linc(&["run", idle.to_str().unwrap(), "--for", "1s", "--show", "R.A0"]);
    assert_eq!((o.status.code(), String::from_utf8_lossy(&o.stdout).as_ref()), (Some(0), "R.A0 = 3.0\n"));
    let db = dir.join("plant.json");
    std::fs::write(&db, r#"{ "blocks": { "A": { "type": "ACTION", "values": { "ActName": "Fill" } } } }"#)
        .expect("write");
    let o = linc(&["run", db.to_str().unwrap(), "--for", "1s", "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(2));
    let out = String::from_utf8_lossy(&o.stderr);
    assert!(out.contains(":1:15: error[E0830]: the block names no action: its FileName is empty"), "{out}");
}

//! FST tables through the CLI: `check`, `compile`, `fst list`, `run` of one
//! table and of the example strategy (examples/fst), each example run for a
//! simulated day with its logs and final values pinned.
mod common;
use common::{linc, stderr, stdout, temp_dir};
use serde_json::Value;

const PLANT: &str = "examples/fst/plant.json";
const START: &str = "2026-01-05T06:00:00";

fn temp(name: &str) -> String {
    common::temp_path("fst", name)
}

#[test]
fn the_examples_check_clean() {
    for t in ["pump", "branching", "alarm", "history"] {
        let o = linc(&["check", &format!("examples/fst/{t}.csv"), "--db", PLANT]);
        assert_eq!(o.status.code(), Some(0), "{t}: {}{}", stdout(&o), stderr(&o));
        assert_eq!(stdout(&o), "", "{t}");
    }
}

#[test]
fn fst_list_shows_the_table_with_instruction_offsets() {
    let o = linc(&["fst", "list", "examples/fst/branching.csv", "--db", PLANT]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let expected = "\
IP  STEP  LABEL   CMD  ARGUMENT1  ARGUMENT2  COMMENT
0   0             GO   PMPOFF                ROCLINK 800 Table B-4: branch over step 1
2   1     PUMPON  DO   DOU 4-1    1          never reached
14  2     PMPOFF  DO   DOU 4-2    0          pump 2 off
";
    assert_eq!(stdout(&o), expected);
    // Without a database the table is listed without offsets.
    let o = linc(&["fst", "list", "examples/fst/branching.csv"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).starts_with("STEP  LABEL   CMD"), "{}", stdout(&o));
}

#[test]
fn errors_are_located_at_their_cell() {
    let dir = temp_dir("fst-errors");
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n0,,VAL,\"AIN 9-9,EU\",\n1,,GO,NOWHR,\n").unwrap();
    let bad = bad.to_string_lossy().into_owned();
    let o = linc(&["check", &bad, "--db", PLANT, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    let out = stderr(&o);
    assert!(out.contains("bad.csv:2:8: error[E0421]"), "{out}");
    assert!(out.contains("bad.csv:3:7: error[E0407]"), "{out}");
    // Compiling a table needs its point database, and is done on its own.
    let o = linc(&["compile", "examples/fst/alarm.csv", "-o", &temp("a.sto")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0025]") && stderr(&o).contains("--db"), "{}", stderr(&o));
    let both = ["compile", "examples/fst/alarm.csv", "examples/guide/control.stx", "--db", PLANT, "-o", &temp("b.sto")];
    let o = linc(&both);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0024]: `examples/fst/alarm.csv` is an FST table"), "{}", stderr(&o));
}

/// Runs the example strategy for a day; returns stdout and the output database.
fn plant_day(tag: &str, extra: &[&str]) -> (String, Value) {
    let out = temp(&format!("{tag}.json"));
    let mut args = vec!["run", PLANT, "--for", "1d", "--now", START, "--out", &out];
    args.extend_from_slice(extra);
    let o = linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let db: Value = serde_json::from_str(&std::fs::read_to_string(&out).expect("--out")).expect("json");
    (stdout(&o), db)
}

#[test]
fn the_example_plant_runs_a_day_beside_its_st_simulation() {
    let shows = ["FST 1.R5", "FST 1.R7", "FST 1.MISC1", "FST 4.R3", "DOU 4-1.STATUS", "DOU 4-2.STATUS", "TANK.Int1"];
    let mut extra = Vec::new();
    for s in &shows {
        extra.extend(["--show", s]);
    }
    let (out, db) = plant_day("plant", &extra);
    assert_eq!(
        out,
        "FST 1.R5 = 2189.0\nFST 1.R7 = 1.0\nFST 1.MISC1 = 0\nFST 4.R3 = 142.0\nDOU 4-1.STATUS = 1\n\
         DOU 4-2.STATUS = 0\nTANK.Int1 = 216000\n"
    );
    let roc = &db["roc"];
    // One high-level alarm, in the maintenance hour (the pump in manual).
    let alarms = roc["alarms"]["entries"].as_array().expect("alarms");
    assert_eq!(alarms.len(), 1);
    assert_eq!(alarms[0]["text"], "HIGH LEVEL");
    assert_eq!(alarms[0]["time"], "2026-01-05T10:43:26");
    // The pump's starts and stops (the ST simulation read every DO the table wrote) and the day total.
    let events = roc["events"]["entries"].as_array().expect("events");
    assert_eq!(roc["events"]["total"], 46);
    assert_eq!(
        (events[0]["time"].as_str(), events[0]["text"].as_str()),
        (Some("2026-01-05T06:25:00"), Some("PUMP ON"))
    );
    assert!(events.iter().any(|e| e["text"] == "DAY TOTAL" && e["value"] == 6500.0), "{events:?}");
    let points = roc["history"]["points"].as_array().expect("points");
    let total = &points[0]["periodic"][0];
    assert_eq!((total["time"].as_str(), total["value"].as_f64()), (Some("2026-01-06T00:00:00"), Some(6500.0)));
    // The B.5 table logged every 5.1 s into 840 entries; the level is logged each hour and day.
    let hist = |n: u64| points.iter().find(|p| p["number"] == n).expect("point");
    assert_eq!(hist(9)["periodic"].as_array().map(Vec::len), Some(840));
    assert_eq!(hist(3)["periodic"].as_array().map(Vec::len), Some(23));
    assert_eq!(hist(3)["daily"].as_array().map(Vec::len), Some(1));
    // Deterministic: the same day twice gives the same database.
    let (_, again) = plant_day("plant-again", &[]);
    assert_eq!(db, again);
}

#[test]
fn each_manual_table_runs_a_day_on_its_own() {
    let run = |table: &str, block: &str, show: &str| {
        let o = linc(&["run", table, "--db", PLANT, "--block", block, "--for", "1d", "--now", START, "--show", show]);
        assert_eq!(o.status.code(), Some(0), "{table}: {}", stderr(&o));
        stdout(&o)
    };
    assert_eq!(run("examples/fst/branching.csv", "FST 2", "DOU 4-2.STATUS"), "DOU 4-2.STATUS = 0\n");
    assert_eq!(run("examples/fst/branching.csv", "FST 2", "DOU 4-1.STATUS"), "DOU 4-1.STATUS = 0\n");
    assert_eq!(run("examples/fst/alarm.csv", "FST 3", "DOU 4-1.STATUS"), "DOU 4-1.STATUS = 1\n");
    assert_eq!(run("examples/fst/history.csv", "FST 4", "FST 4.R3"), "FST 4.R3 = 142.0\n");
}

#[test]
fn the_trace_shows_each_step_and_a_removed_point_stops_the_table() {
    let trace = temp("alarm.jsonl");
    let o = linc(&[
        "run",
        "examples/fst/alarm.csv",
        "--db",
        PLANT,
        "--block",
        "FST 3",
        "--for",
        "150ms",
        "--trace",
        &trace,
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let lines = std::fs::read_to_string(&trace).expect("trace");
    let steps: Vec<&str> = lines.lines().filter(|l| l.contains("\"step\"")).collect();
    assert_eq!(steps.len(), 6, "two cycles of three steps: {lines}");
    assert_eq!(steps[2], r#"{"time":0.0,"task":1,"program":"FST 3","step":3,"cmd":"DO DOU 4-1 1","RR":95.0,"CF":0}"#);
    // Compiled against the plant, run against a database without AIN 3-1.
    let sto = temp("alarm.sto");
    assert_eq!(linc(&["compile", "examples/fst/alarm.csv", "--db", PLANT, "-o", &sto]).status.code(), Some(0));
    let small = temp("small.json");
    std::fs::write(&small, r#"{"blocks": {"FST 3": {"type": "FST"}, "DOU 4-1": {"type": "DOU"}}}"#).unwrap();
    let o = linc(&["run", &sto, "--db", &small, "--for", "1s", "--show", "FST 3.RUNFLG", "--show", "FST 3.IP"]);
    assert_eq!(o.status.code(), Some(1), "a runtime error: {}", stderr(&o));
    assert!(stderr(&o).contains("error[R0010]"), "{}", stderr(&o));
    assert!(stderr(&o).contains("AIN 3-1.EU"), "{}", stderr(&o));
    assert_eq!(stdout(&o), "FST 3.RUNFLG = 5\nFST 3.IP = 0\n");
}

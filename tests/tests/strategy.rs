//! Strategies (docs/strategies.md): tasks, qualifiers of action-type
//! blocks, the error status and the error program, determinism.
use linc_conformance::exec::compile;
use linc_conformance::exec::strategy;
use linc_engines::strategy::{micros, trace::Trace, wanted, Strategy};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

fn get(s: &Strategy, path: &str) -> String {
    let (b, f) = path.split_once('.').expect("BLOCK.FIELD");
    let block = s.store.db.block(b).expect("block");
    s.store.show(s.store.cell_of(block, f).expect("field"))
}

fn set(s: &mut Strategy, path: &str, v: bool) {
    let (b, f) = path.split_once('.').expect("BLOCK.FIELD");
    let cell = s.store.cell_of(s.store.db.block(b).expect("block"), f).expect("field");
    s.store.cells[cell as usize] = linc_runtime::store::Cell::Bool(v);
}

const QUALIFIED: &str = r#"{ "tasks": { "1": { "period": "T#1s" } }, "blocks": {
    "N": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "N" } },
    "P": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "P" } },
    "L": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "L", "QualTime": 2.0 } },
    "D": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "D", "QualTime": 2.0 } },
    "E": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "E", "QualTime": 2.0 } },
    "F": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "F" } },
    "S": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Qualifier": "S" } } } }"#;

/// One action, run by seven blocks: each counts its own runs in `Int1`.
const COUNT: &str = "ACTION Count : ACTION\n  Int1 := Int1 + 1;\nEND_ACTION\n";

#[test]
fn each_qualifier_as_the_table_says() {
    let mut s = strategy(QUALIFIED, COUNT);
    let blocks = ["N", "P", "L", "D", "E", "F", "S"];
    let mut active: Vec<String> = vec![String::new(); blocks.len()];
    for second in 0..10 {
        let trigger = (1..=6).contains(&second);
        for b in blocks {
            set(&mut s, &format!("{b}.Trigger"), trigger);
        }
        s.run_for(micros(1.0), None);
        for (i, b) in blocks.iter().enumerate() {
            active[i].push(if get(&s, &format!("{b}.Active")) == "TRUE" { '1' } else { '.' });
        }
    }
    // The table of docs/strategies.md.
    assert_eq!(
        active,
        [".111111...", ".1........", ".11.......", "...1111...", "...1......", ".......1..", ".111111111"]
    );
    let counts: Vec<String> = blocks.iter().map(|b| get(&s, &format!("{b}.Int1"))).collect();
    assert_eq!(counts, ["6", "1", "2", "4", "1", "1", "9"]);
}

#[test]
fn r_stops_a_stored_action() {
    let mut s = strategy(QUALIFIED, COUNT);
    set(&mut s, "S.Trigger", true);
    s.run_for(micros(3.0), None);
    assert_eq!(get(&s, "S.Int1"), "3");
    let cell = s.store.cell_of(s.store.db.block("S").unwrap(), "Qualifier").unwrap();
    s.store.cells[cell as usize] = linc_runtime::store::Cell::Enum { idx: 7 }; // R
    set(&mut s, "S.Trigger", false);
    s.run_for(micros(2.0), None);
    assert_eq!(get(&s, "S.Int1"), "5", "still stored while R's trigger is low");
    set(&mut s, "S.Trigger", true);
    s.run_for(micros(3.0), None);
    assert_eq!((get(&s, "S.Int1").as_str(), get(&s, "S.Active").as_str()), ("5", "FALSE"));
}

#[test]
fn d_counts_time_at_a_tenth_of_a_second() {
    let db = QUALIFIED.replace("T#1s", "T#100ms").replace("\"QualTime\": 2.0", "\"QualTime\": 0.5");
    let mut s = strategy(&db, COUNT);
    set(&mut s, "D.Trigger", true);
    s.run_for(micros(1.0), None);
    // Scans at 0.0 … 0.9; D runs from 0.5 on.
    assert_eq!(get(&s, "D.Int1"), "5");
    assert_eq!(get(&s, "E.Int1"), "0", "E's trigger never rose");
}

const TASKS: &str = r#"{ "tasks": { "1": { "period": "T#100ms" }, "2": { "period": "T#1s" }, "4": { "period": "T#250ms" } },
  "blocks": {
    "R": { "type": "RECIPE" },
    "SLOW": { "type": "ACTION", "task": 2, "values": { "FileName": "a.st", "ActName": "Slow", "Trigger": true } },
    "FAST": { "type": "ACTION", "task": 1, "values": { "FileName": "a.st", "ActName": "Fast", "Trigger": true } },
    "LOW": { "type": "ACTION", "task": 4, "values": { "FileName": "a.st", "ActName": "Low", "Trigger": true } } } }"#;

const TASK_ACTIONS: &str = "ACTION Fast\n  R.N0 := R.N0 + 1;\nEND_ACTION\nACTION Slow\n  R.N1 := R.N0;\n  R.N3 := R.N3 + 1;\nEND_ACTION\nACTION Low\n  R.N2 := R.N2 + 1;\nEND_ACTION\n";

#[test]
fn tasks_run_every_period_in_task_order() {
    let mut s = strategy(TASKS, TASK_ACTIONS);
    s.run_for(micros(1.0), None);
    // Task 1 ran at 0.0 … 0.9, task 2 at 0.0 after task 1 (it saw N0 = 1),
    // task 4 at 0.0, 0.25, 0.5, 0.75.
    assert_eq!([get(&s, "R.N0"), get(&s, "R.N1"), get(&s, "R.N2"), get(&s, "R.N3")], ["10", "1", "4", "1"]);
    s.run_for(micros(1.0), None);
    assert_eq!([get(&s, "R.N0"), get(&s, "R.N1"), get(&s, "R.N2"), get(&s, "R.N3")], ["20", "11", "8", "2"]);
    assert_eq!(s.elapsed_us(), 2_000_000);
    assert_eq!(s.store.now, 1_000_002.0, "the clock ends at start + duration");
}

const FAULTS: &str = r#"{ "tasks": { "1": { "period": "T#1s" } }, "blocks": {
    "R": { "type": "RECIPE" },
    "SYS": { "type": "SYSTEM", "values": { "ErrProg": "%ERRPROG%" } },
    "BAD": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Bad", "Trigger": true } },
    "GOOD": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Good", "Trigger": true } },
    "LATE": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Late", "Trigger": true } },
    "ONERR": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "OnErr", "Trigger": true } } } }"#;

const FAULT_ACTIONS: &str = "ACTION Bad\n  R.N0 := R.N0 + 1;\n  R.N1 := 10 / (3 - R.N0);\nEND_ACTION\n\
ACTION Good\n  R.N2 := R.N2 + 1;\nEND_ACTION\n\
ACTION Late\n  R.N3 := R.N3 + 1;\n  IF R.N3 = 5 THEN R.A0 := SQRT(-1.0); END_IF;\nEND_ACTION\n\
ACTION OnErr\n  R.N4 := R.N4 + 1;\n  R.N5 := SYS.ErrNum;\n  SYS.Clear := R.N4 >= 2;\nEND_ACTION\n";

#[test]
fn the_first_error_is_kept_and_only_its_program_stops() {
    // No error program, and ONERR's trigger off: nothing clears the error.
    let db = FAULTS.replace("%ERRPROG%", "").replace(r#""OnErr", "Trigger": true"#, r#""OnErr", "Trigger": false"#);
    let mut s = strategy(&db, FAULT_ACTIONS);
    let failures = s.run_for(micros(10.0), None);
    // BAD fails in its third run (t = 2 s, line 3), LATE in its fifth (t = 4 s, line 10).
    assert_eq!(failures.iter().map(|e| (e.code.as_str(), e.line)).collect::<Vec<_>>(), [("R0001", 3), ("R0005", 10)]);
    let st = s.error().expect("error status");
    assert_eq!((st.error.code.as_str(), st.block.as_str(), st.at_us), ("R0001", "BAD", 2_000_000));
    assert_eq!(get(&s, "R.N0"), "3", "BAD stopped after its third run");
    assert_eq!(get(&s, "R.N3"), "5", "LATE stopped too, but its error was not entered");
    assert_eq!(get(&s, "R.N2"), "10", "GOOD went on");
    assert_eq!(
        ["ErrNum", "ErrCode", "ErrBlock", "ErrLine", "Double"].map(|f| get(&s, &format!("SYS.{f}"))),
        ["1", "'R0001'", "'BAD'", "3", "FALSE"]
    );
    assert_eq!(
        [get(&s, "BAD.Status"), get(&s, "BAD.Active"), get(&s, "BAD.Alarms")],
        ["'ERROR'", "FALSE", "[Software]"]
    );
    assert_eq!(get(&s, "GOOD.Status"), "'OK'");
    // Clearing: the engine resets Clear; stopped programs stay stopped.
    set(&mut s, "SYS.Clear", true);
    s.run_for(micros(1.0), None);
    assert!(s.error().is_none());
    assert_eq!([get(&s, "SYS.ErrNum"), get(&s, "SYS.Clear"), get(&s, "R.N0")], ["0", "FALSE", "3"]);
}

#[test]
fn the_error_program_runs_when_an_error_is_entered_and_may_clear_it() {
    // First an error program that does not clear: LATE's error is not entered.
    let mut s = strategy(&FAULTS.replace("%ERRPROG%", "ONERR"), FAULT_ACTIONS);
    s.run_for(micros(10.0), None);
    assert_eq!([get(&s, "R.N4"), get(&s, "R.N5")], ["1", "1"], "not run by its task; once, for BAD's R0001");
    assert_eq!(s.error().map(|e| e.block.as_str()), Some("BAD"));
    // Then one that clears: each error is entered and handled.
    let clears = FAULT_ACTIONS.replace("SYS.Clear := R.N4 >= 2;", "SYS.Clear := TRUE;");
    let mut s = strategy(&FAULTS.replace("%ERRPROG%", "ONERR"), &clears);
    s.run_for(micros(10.0), None);
    assert_eq!([get(&s, "R.N4"), get(&s, "R.N5")], ["2", "5"], "ran for BAD (R0001) and LATE (R0005)");
    assert!(s.error().is_none(), "it cleared the error");
    assert_eq!(get(&s, "R.N2"), "10", "GOOD went on");
    assert!(!s.halted());
}

#[test]
fn an_error_in_the_error_program_is_a_double_error_and_stops_everything() {
    let actions = FAULT_ACTIONS.replace("R.N4 := R.N4 + 1;", "R.N4 := R.N4 + 1 / 0;");
    let mut s = strategy(&FAULTS.replace("%ERRPROG%", "ONERR"), &actions);
    let failures = s.run_for(micros(10.0), None);
    assert_eq!(failures.iter().map(|e| e.action.as_str()).collect::<Vec<_>>(), ["Bad", "OnErr"]);
    assert!(s.halted());
    let st = s.error().expect("status");
    assert!(st.double && st.error.code == "R0001" && st.block == "BAD", "{st:?}");
    assert_eq!(get(&s, "SYS.Double"), "TRUE");
    assert_eq!(get(&s, "R.N2"), "2", "GOOD ran at 0 and 1 s; at 2 s BAD (before it) failed and everything stopped");
}

#[test]
fn the_same_run_gives_the_same_bytes() {
    let run = || {
        let mut s = strategy(TASKS, TASK_ACTIONS);
        let mut out = Vec::new();
        let mut t = Trace::new(&mut out, &s.store);
        s.run_for(micros(3.0), Some(&mut t));
        t.finish().expect("trace");
        (out, serde_json::to_string(&s.store.values_json()).unwrap())
    };
    let (a, b) = (run(), run());
    assert_eq!(a, b);
    let trace = String::from_utf8(a.0).unwrap();
    assert_eq!(trace.lines().count(), 30 + 3 + 3 + 12 + 3, "one line per change");
    assert!(
        trace.starts_with(r#"{"time":0.0,"task":1,"program":"FAST","field":"FAST.Active","old":"FALSE","new":"TRUE"}"#)
    );
}

#[test]
fn a_missing_action_is_located_at_its_block() {
    let db = Database::from_json(
        &QUALIFIED.replace("\"ActName\": \"Count\", \"Qualifier\": \"F\"", "\"ActName\": \"Nope\""),
    )
    .unwrap();
    let object = linc_runtime::load(&compile(COUNT, &db)).expect("loads");
    let store = Store::new(db);
    let wants: Vec<_> = wanted(&store).into_iter().map(|w| (w, 0)).collect();
    let e = Strategy::build(store, vec![object], &wants, Vm::new(10, Clock::new(1, 0)), 0.0).err().expect("fails");
    assert_eq!((e.code.as_str(), e.block.as_str()), ("E0831", "F"));
    assert_eq!(e.message, "`a.st` has no action `Nope` (it has Count)");
}

//! The console over a strategy (docs/console.md): forced fields hold
//! against every write path of the VM and the engine, dropped writes are
//! traced, and the console's contract (`;` lines, failures, programs).
use linc_conformance::exec::strategy;
use linc_engines::console::Console;
use linc_engines::strategy::{micros, trace::Trace, ProgramState};

const DB: &str = r#"{
  "templates": { "T": { "fields": {
      "R0": "REAL", "R1": "REAL", "I": "INT", "B": "BOOL", "W": "BITS16", "S": "STRING",
      "E": { "ENUM": ["OFF", "ON"] }, "N": "INT" } } },
  "tasks": { "1": { "period": "T#1s" } },
  "blocks": {
    "X": { "type": "T" },
    "W": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Write", "Trigger": true } },
    "BAD": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Bad", "Trigger": true } } } }"#;

/// Writes every kind of field, directly and through an offset, and counts its runs.
const WRITE: &str =
    "ACTION Write\n  X.R0 := 1.5;\n  X.R0{1} := 2.5;\n  X.I := 7;\n  X.B := TRUE;\n  X.W.Bit3 := TRUE;\n  \
                     X.S := 'written';\n  X.E := 'ON';\n  X.N := X.N + 1;\nEND_ACTION\n\
                     ACTION Bad\n  X.N := X.N / (X.I - X.I);\nEND_ACTION\n";

fn lines(c: &mut Console, line: &str) -> Vec<String> {
    c.execute(line).into_iter().map(|r| r.unwrap_or_else(|e| format!("{} {}", e.code, e.message))).collect()
}

#[test]
fn forced_fields_hold_against_every_write_path_and_are_traced() {
    let mut s = strategy(DB, WRITE);
    let mut c = Console::new(s);
    let forced = "F X.R0=9; F X.R1=9; F X.I=9; F X.B=0; F X.W=0; F X.S='kept'; F X.E=OFF; PSUSPEND BAD";
    assert!(c.execute(forced).iter().all(Result::is_ok));
    s = c.strategy;
    let mut out = Vec::new();
    let mut trace = Trace::new(&mut out, &s.store);
    s.run_for(micros(2.0), Some(&mut trace));
    trace.finish().expect("trace");
    let mut c = Console::new(s);
    let shown = lines(&mut c, "D X.R0, X.R1, X.I, X.B, X.W, X.S, X.E, X.N");
    assert_eq!(shown, ["X.R0 = 9.0\nX.R1 = 9.0\nX.I = 9\nX.B = FALSE\nX.W = 0\nX.S = 'kept'\nX.E = 'OFF'\nX.N = 2"]);
    // Seven fields, two runs: fourteen writes dropped, each traced.
    assert_eq!(c.strategy.store.ignored_writes, 14);
    let trace = String::from_utf8(out).expect("utf8");
    let dropped: Vec<&str> = trace.lines().filter(|l| l.contains("\"forced\":true")).collect();
    assert_eq!(dropped.len(), 14, "{trace}");
    assert_eq!(dropped[0], r#"{"time":0.0,"task":1,"program":"W","field":"X.R0","forced":true}"#);
    // Released, the program's writes land again.
    let released = "F X.R0=N; F X.R1=N; F X.I=N; F X.B=N; F X.W=N; F X.S=N; F X.E=N; SCAN";
    assert!(c.execute(released).iter().all(Result::is_ok));
    assert_eq!(
        lines(&mut c, "D X.R0, X.R1, X.I, X.B, X.W, X.S, X.E"),
        ["X.R0 = 1.5\nX.R1 = 2.5\nX.I = 7\nX.B = TRUE\nX.W = 8\nX.S = 'written'\nX.E = 'ON'"]
    );
}

#[test]
fn a_line_runs_every_command_and_failures_are_taken_once() {
    let mut c = Console::new(strategy(DB, WRITE));
    let replies = c.execute("M X.N=5; FROB; D X.N;; NOW");
    assert_eq!(replies.len(), 4);
    assert_eq!(replies[1].as_ref().map_err(|e| e.code.as_str()), Err("C0001"));
    assert_eq!(replies[2], Ok("X.N = 5".to_string()));
    assert_eq!(replies[3], Ok("1970-01-12T13:46:40.000".to_string()));
    // BAD divides by zero at its first scan: the reply is the clock, the
    // runtime error is data in take_failures, once.
    let advanced = lines(&mut c, "ADVANCE 1s");
    assert_eq!(advanced, ["1970-01-12T13:46:41.000"]);
    let failures = c.take_failures();
    assert_eq!(failures.iter().map(|e| e.code.as_str()).collect::<Vec<_>>(), ["R0001"]);
    assert_eq!(failures[0].message, "division by zero");
    assert_eq!(failures[0].action, "Bad");
    assert!(c.take_failures().is_empty());
    assert!(lines(&mut c, "ERR?")[0].starts_with("error 1 [R0001] in BAD line 12"), "{:?}", lines(&mut c, "ERR?"));
    let bad = c.strategy.store.db.block("BAD").expect("block");
    assert_eq!(c.strategy.program_state(bad), Some(ProgramState::Inactive));
    assert_eq!(lines(&mut c, "P?"), ["W action task 1 running -\nBAD action task 1 inactive line 12"]);
    // START begins a failed program afresh: it fails again.
    lines(&mut c, "ERRCLR; START BAD; SCAN");
    assert_eq!(c.take_failures().len(), 1);
}

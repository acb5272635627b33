//! An FST table and a LIN action side by side in one strategy, against one
//! database: the action reads what the table wrote (in the same scan, as
//! the FST block comes first in the task), and the table reads what the
//! action wrote (one scan later). docs/fst.md, docs/strategies.md.

use linc_conformance::exec::compile;
use linc_conformance::fst::{num, table, START};
use linc_engines::strategy::{Strategy, Want, WantKind};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

const DB: &str = r#"{
  "device": "FB107",
  "blocks": {
    "FST 1": { "type": "FST" },
    "SFP 1": { "type": "SFP" },
    "COPY": { "type": "ACTION", "values": { "Trigger": true, "Qualifier": "N" } }
  },
  "aliases": { "Count": "SFP 1.DATA1", "Echo": "SFP 1.DATA2", "FstRR": "FST 1.RR" }
}"#;

const ACTION: &str = "ACTION Copy
    (* Reads the table's counter and answers with twice it. *)
    COPY.Real1 := Count;
    COPY.Real2 := FstRR;
    Echo := Count * 2.0;
END_ACTION
";

fn strategy() -> Strategy {
    let db = Database::from_json(DB).expect("database");
    // The FST counts in SFP 1,DATA1 (the FB107's numeric TLP 17,0,2) and
    // copies the action's answer into R2.
    let fst = table(&[
        ",VAL,\"17,0,2\",",
        ",+,1,",
        ",SAV,\"SFP 1,DATA1\",",
        ",VAL,\"SFP 1,DATA2\",",
        ",SAV,\"FST 1,R2\",",
        ",VAL,\"SFP 1,DATA1\",",
        ",END,,",
    ]);
    let (d, fst) = linc_compiler::fst::compile(&fst, "count", "count.csv", Some(&db));
    let fst = linc_runtime::verify::verify(fst.unwrap_or_else(|| panic!("{d:?}"))).expect("verify");
    let st = linc_runtime::load(&compile(ACTION, &db)).expect("load");
    let store = Store::new(db);
    let b = |n: &str| store.db.block(n).expect("block");
    let wants = [
        (Want { block: b("FST 1"), file: "count.csv".into(), action: String::new(), kind: WantKind::Fst }, 0),
        (Want { block: b("COPY"), file: "copy.stx".into(), action: "Copy".into(), kind: WantKind::Action }, 1),
    ];
    let vm = Vm::new(linc_runtime::vm::DEFAULT_WATCHDOG, Clock::new(1, 0));
    Strategy::build(store, vec![fst, st], &wants, vm, START).expect("build")
}

#[test]
fn the_action_reads_what_the_table_wrote_and_back() {
    let mut s = strategy();
    assert!(s.run_for(950_000, None).is_empty());
    // Ten scans (0 … 900 ms): the table counted to 10.
    assert_eq!(num(&s, "SFP 1.DATA1"), 10.0);
    assert_eq!(num(&s, "COPY.Real1"), 10.0, "the action saw this scan's count");
    assert_eq!(num(&s, "COPY.Real2"), 10.0, "and the table's RR, a field of its block");
    assert_eq!(num(&s, "SFP 1.DATA2"), 20.0);
    assert_eq!(num(&s, "FST 1.R2"), 18.0, "the table saw the action's answer of the scan before");
}

#[test]
fn st_stops_and_restarts_the_table_through_its_run_flag() {
    let mut s = strategy();
    assert!(s.run_for(450_000, None).is_empty());
    assert_eq!(num(&s, "SFP 1.DATA1"), 5.0);
    let b = s.store.db.block("FST 1").unwrap();
    let runflg = s.store.cell_of(b, "RUNFLG").unwrap() as usize;
    s.store.cells[runflg] = linc_runtime::store::Cell::Int(0);
    assert!(s.run_for(500_000, None).is_empty());
    assert_eq!(num(&s, "SFP 1.DATA1"), 5.0, "stopped");
    s.store.cells[runflg] = linc_runtime::store::Cell::Int(1);
    assert!(s.run_for(300_000, None).is_empty());
    assert_eq!(num(&s, "SFP 1.DATA1"), 8.0, "running again, from step 0");
}

/// The table's current step is the one it goes on with, for the program
/// list (`P?`, `linc serve`) as for its picture: after END, step 0 — not
/// the END step that ran last (docs/fst.md).
#[test]
fn the_current_step_after_end_is_step_0_everywhere() {
    let mut s = strategy();
    assert!(s.run_for(150_000, None).is_empty());
    let b = s.store.db.block("FST 1").unwrap();
    assert_eq!(s.fst_step(b), Some(0));
    let fst = s.programs().into_iter().find(|p| p.block == "FST 1").expect("FST 1");
    assert_eq!(fst.position, "step 0 RUNFLG 1");
    assert_eq!(s.fst_step(s.store.db.block("COPY").unwrap()), None, "an action runs no table");
}

/// A watched action keeps which of its lines its last execution ran; a
/// table cannot be watched.
#[test]
fn a_watched_action_keeps_the_lines_its_last_execution_ran() {
    let mut s = strategy();
    let copy = s.store.db.block("COPY").unwrap();
    assert!(!s.watch_runs(s.store.db.block("FST 1").unwrap()));
    assert_eq!(s.lines_ran(copy), None, "not watched");
    assert!(s.watch_runs(copy));
    assert_eq!(s.lines_ran(copy).map(|r| r.executions), Some(0));
    assert!(s.run_for(250_000, None).is_empty());
    let ran = s.lines_ran(copy).expect("watched");
    assert_eq!((ran.lines.as_slice(), ran.executions), (&[3, 4, 5][..], 3), "three scans, each ran lines 3–5");
}

//! A compiled sequence unit run by the engine through the VM: conditions
//! and actions are code blocks, and step flags are retained slots that code
//! reads. The charts are written here as object tables (the `.sfc` front
//! end will produce the same).
use linc_conformance::guide_db;
use linc_engines::sequence::chart::Chart;
use linc_engines::sequence::host::{Traced, VmHost};
use linc_engines::sequence::{Command, Sequence};
use linc_runtime::isa::Op::{self, *};
use linc_runtime::object::{
    ActionRec, AssocRec, ChartRec, Class, CodeBlock, ObjectFile, StepRec, Sub, Symbol, TransitionRec, Unit, UnitKind,
};
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm};
use linc_runtime::wire::Code;
use linc_runtime::{verify, Program};

fn block(ops: Vec<Op>) -> CodeBlock {
    CodeBlock { ops: Code(ops), ..CodeBlock::default() }
}

fn sym(field: &str) -> Symbol {
    Symbol { block: "Counters".into(), field: field.into(), sub: Sub::Field, class: Class::Int }
}

/// A (initial, counts N0 every scan) → B when N0 >= 3; B copies A.X and A.T.
fn sequence() -> ObjectFile {
    let blocks = vec![
        block(vec![LoadI { sym: 0 }, PushI { v: 3 }, GeI {}, Return { kind: 2 }]),
        block(vec![LoadI { sym: 0 }, PushI { v: 1 }, AddI {}, StoreI { sym: 0 }, Ret {}]),
        block(vec![LoadRet { n: 0 }, StoreI { sym: 1 }, LoadRet { n: 1 }, RToI {}, StoreI { sym: 2 }, Ret {}]),
    ];
    let chart = ChartRec {
        steps: vec![
            StepRec {
                name: "A".into(),
                initial: 1,
                slot: 0,
                assocs: vec![AssocRec { action: 0, qualifier: b'N', time_us: 0 }],
                line: 1,
            },
            StepRec {
                name: "B".into(),
                initial: 0,
                slot: 1,
                assocs: vec![AssocRec { action: 1, qualifier: b'P', time_us: 0 }],
                line: 2,
            },
        ],
        transitions: vec![TransitionRec {
            name: "A to B".into(),
            from: vec![0],
            to: vec![1],
            priority: u32::MAX,
            block: 0,
            line: 3,
        }],
        actions: vec![
            ActionRec { name: "count".into(), kind: 0, index: 1 },
            ActionRec { name: "show".into(), kind: 0, index: 2 },
        ],
    };
    let unit = Unit {
        kind: UnitKind::Sequence,
        name: "Batch".into(),
        file: "batch.sfc".into(),
        block_type: String::new(),
        retained: 4,
        blocks,
        charts: vec![chart],
        steps: Vec::new(),
    };
    ObjectFile {
        source: "batch.sfc".into(),
        symbols: vec![sym("N0"), sym("N1"), sym("N2")],
        strings: vec![],
        units: vec![unit],
    }
}

#[test]
fn a_sequence_unit_runs_its_code_blocks_and_code_reads_step_flags() {
    let obj = sequence();
    let bytes = obj.to_bytes();
    let v = linc_runtime::load(&bytes).expect("verifies");
    let mut store = Store::new(guide_db().clone());
    let linked = v.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut seq = Sequence::new(Chart::from_unit(&linked.object().units[0], 0));
    seq.command(Command::Run);
    let mut act = Activation::new(&linked, 0, 0);
    let mut vm = Vm::new(10_000, Clock::new(1, 0));
    let mut out = Vec::new();
    let mut trace = linc_engines::strategy::trace::Trace::new(&mut out, &store);
    for second in 0..5u64 {
        let traced = Traced { trace: &mut trace, now_us: second * 1_000_000, task: 1, program: "SEQ" };
        let mut host = VmHost { vm: &mut vm, linked: &linked, act: &mut act, store: &mut store, trace: Some(traced) };
        seq.scan(second * 1_000_000, &mut host).expect("scan");
    }
    trace.finish().expect("trace");
    let events = String::from_utf8(out).expect("utf-8");
    let get = |f: &str| store.show(store.cell_of(store.db.block("Counters").unwrap(), f).unwrap());
    // N0 counted in scans 0, 1, 2; A left in scan 3 after 3 s; B's P action saw A.X = 0 and A.T = 3.
    assert_eq!([get("N0"), get("N1"), get("N2")], ["3", "0", "3"]);
    assert_eq!(seq.active_steps(), ["B"]);
    assert!(events.contains(r#"{"time":3.0,"task":1,"program":"SEQ","fired":"A to B"}"#), "{events}");
    assert!(
        events.contains(r#"{"time":2.0,"task":1,"program":"SEQ","field":"Counters.N0","old":"2","new":"3"}"#),
        "{events}"
    );
}

fn refused(edit: impl FnOnce(&mut Unit)) -> Option<&'static str> {
    let mut obj = sequence();
    edit(&mut obj.units[0]);
    verify::verify(obj).err().map(|e| e.code().as_str())
}

#[test]
fn the_verifier_checks_every_chart_table() {
    assert_eq!(refused(|_| {}), None);
    assert_eq!(refused(|u| u.charts[0].transitions[0].to = vec![7]), Some("E0714"), "unknown step");
    assert_eq!(refused(|u| u.charts[0].transitions[0].block = 1), Some("E0714"), "an action's block as a condition");
    assert_eq!(refused(|u| u.blocks[0].ops.0 = vec![Ret {}]), Some("E0714"), "a condition that returns nothing");
    assert_eq!(refused(|u| u.charts[0].steps[1].slot = 2), Some("E0714"), "no retained slots for the step");
    assert_eq!(refused(|u| u.charts[0].steps[0].assocs[0].qualifier = b'Q'), Some("E0714"), "unknown qualifier");
    assert_eq!(refused(|u| u.charts[0].actions[0] = ActionRec { name: "x".into(), kind: 1, index: 0 }), Some("E0714"));
    assert_eq!(refused(|u| u.kind = UnitKind::Action), Some("E0714"), "an action unit with charts");
    assert_eq!(refused(|u| u.blocks[1].ops.0.insert(0, Yield {})), Some("E0714"), "a block that suspends");
    // Chart actions nest as a tree, at most 32 deep.
    let deep = |n: usize| {
        refused(move |u| {
            for i in 0..n {
                let next = ActionRec { name: format!("c{i}"), kind: 1, index: (i + 1) as u16 };
                u.charts[i].actions.push(next);
                u.charts.push(ChartRec::default());
            }
        })
    };
    assert_eq!(deep(32), None);
    assert_eq!(deep(33), Some("E0714"));
}

/// A strategy with one SFC_CON block running `sequence()` every second.
fn strategy(run: bool) -> linc_engines::strategy::Strategy {
    strategy_of(sequence(), run)
}

/// A strategy with one SFC_CON block running `obj` every second.
fn strategy_of(obj: ObjectFile, run: bool) -> linc_engines::strategy::Strategy {
    use linc_engines::strategy::{wanted, Strategy};
    let db = linc_runtime::Database::from_json(&format!(
        r#"{{ "tasks": {{ "1": {{ "period": "T#1s" }} }}, "blocks": {{
            "Counters": {{ "type": "RECIPE" }},
            "SEQ": {{ "type": "SFC_CON", "values": {{ "FileName": "batch.sto", "Run": {run} }} }} }} }}"#
    ))
    .expect("db");
    let store = Store::new(db);
    let wants: Vec<_> = wanted(&store).into_iter().map(|w| (w, 0)).collect();
    assert_eq!(wants.len(), 1);
    assert_eq!(wants[0].0.kind, linc_engines::strategy::WantKind::Sequence);
    let v = verify::verify(obj).expect("verifies");
    Strategy::build(store, vec![v], &wants, Vm::new(10_000, Clock::new(1, 0)), 0.0).expect("builds")
}

fn field(s: &linc_engines::strategy::Strategy, path: &str) -> String {
    let (b, f) = path.split_once('.').unwrap();
    s.store.show(s.store.cell_of(s.store.db.block(b).unwrap(), f).unwrap())
}

#[test]
fn an_sfc_con_block_runs_its_sequence_in_a_strategy() {
    let mut s = strategy(true);
    let mut out = Vec::new();
    let mut trace = linc_engines::strategy::trace::Trace::new(&mut out, &s.store);
    let failures = s.run_for(5_000_000, Some(&mut trace));
    trace.finish().expect("trace");
    assert!(failures.is_empty(), "{failures:?}");
    assert_eq!([field(&s, "Counters.N0"), field(&s, "Counters.N2")], ["3", "3"]);
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "SEQ.Steps"), field(&s, "SEQ.Run")], ["'RUNNING'", "1", "TRUE"]);
    let trace = String::from_utf8(out).unwrap();
    for needle in [
        r#"{"time":0.0,"task":1,"program":"SEQ","step":"A","active":true}"#,
        r#"{"time":0.0,"task":1,"program":"SEQ","ran":"count"}"#,
        r#"{"time":3.0,"task":1,"program":"SEQ","fired":"A to B"}"#,
        r#"{"time":3.0,"task":1,"program":"SEQ","step":"B","active":true}"#,
    ] {
        assert!(trace.contains(needle), "{needle} not in\n{trace}");
    }
}

#[test]
fn sfc_con_fields_command_the_sequence() {
    let mut s = strategy(false);
    s.run_for(2_000_000, None);
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "Counters.N0"), field(&s, "SEQ.Init")], ["'RESET'", "0", "TRUE"]);
    let set = |s: &mut linc_engines::strategy::Strategy, path: &str, v: bool| {
        let (b, f) = path.split_once('.').unwrap();
        let c = s.store.cell_of(s.store.db.block(b).unwrap(), f).unwrap();
        s.store.cells[c as usize] = linc_runtime::store::Cell::Bool(v);
    };
    set(&mut s, "SEQ.Run", true);
    s.run_for(2_000_000, None);
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "Counters.N0")], ["'RUNNING'", "2"]);
    set(&mut s, "SEQ.Stop", true);
    s.run_for(3_000_000, None);
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "Counters.N0"), field(&s, "SEQ.Stop")], ["'STOPPED'", "2", "FALSE"]);
    set(&mut s, "SEQ.Run", true);
    set(&mut s, "SEQ.Hold", true);
    s.run_for(3_000_000, None);
    assert_eq!(
        [field(&s, "SEQ.Status"), field(&s, "Counters.N0")],
        ["'HELD'", "5"],
        "held: actions go on, no transition"
    );
    set(&mut s, "SEQ.Hold", false);
    s.run_for(1_000_000, None);
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "SEQ.Steps")], ["'RUNNING'", "1"]);
    set(&mut s, "SEQ.Reset", true);
    s.run_for(1_000_000, None);
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "SEQ.Steps"), field(&s, "SEQ.Init")], ["'RESET'", "0", "TRUE"]);
}

/// `sequence()` whose step B, at each scan, counts in N1 and writes
/// `value` to its own SFC_CON block's `field` (`SEQ.Run := FALSE`).
fn commanding_itself(field: &str, value: i32) -> ObjectFile {
    let mut obj = sequence();
    obj.symbols.push(Symbol { block: "SEQ".into(), field: field.into(), sub: Sub::Field, class: Class::Bool });
    obj.units[0].blocks.push(block(vec![
        LoadI { sym: 1 },
        PushI { v: 1 },
        AddI {},
        StoreI { sym: 1 },
        PushI { v: value },
        StoreI { sym: 3 },
        Ret {},
    ]));
    let chart = &mut obj.units[0].charts[0];
    chart.actions.push(ActionRec { name: "command".into(), kind: 0, index: 3 });
    chart.steps[1].assocs = vec![AssocRec { action: 2, qualifier: b'N', time_us: 0 }];
    obj
}

#[test]
fn a_sequence_that_stops_itself_stops_at_the_next_scan() {
    // A counts in scans 0, 1, 2 (N0 = 3); A to B fires in scan 3, where B's
    // action counts N1 = 1 and writes SEQ.Run := FALSE (or SEQ.Stop :=
    // TRUE). The write stands, and the next scan reads it and stops.
    for (command, value) in [("Run", 0), ("Stop", 1)] {
        let mut s = strategy_of(commanding_itself(command, value), true);
        assert!(s.run_for(4_000_000, None).is_empty());
        assert_eq!(field(&s, "Counters.N1"), "1", "{command}");
        assert_eq!(field(&s, &format!("SEQ.{command}")), if value == 0 { "FALSE" } else { "TRUE" }, "{command}");
        assert_eq!(field(&s, "SEQ.Status"), "'RUNNING'", "{command}: read at the next scan");
        assert!(s.run_for(3_000_000, None).is_empty());
        assert_eq!(field(&s, "Counters.N1"), "1", "{command}: no action ran after the scan that wrote it");
        let shown = ["SEQ.Status", "SEQ.Run", "SEQ.Stop", "SEQ.Steps"].map(|f| field(&s, f));
        assert_eq!(shown, ["'STOPPED'", "FALSE", "FALSE", "1"], "{command}");
    }
}

#[test]
fn a_sequence_that_releases_its_own_hold_runs_on() {
    // Held from the start, A's action counts; B is never reached while
    // held. Here B writes SEQ.Hold := FALSE while HELD: a write the engine
    // used to overwrite with TRUE.
    let mut s = strategy_of(commanding_itself("Hold", 0), true);
    assert!(s.run_for(4_000_000, None).is_empty());
    set_flag(&mut s, "SEQ.Hold", true);
    assert!(s.run_for(1_000_000, None).is_empty());
    assert_eq!([field(&s, "SEQ.Status"), field(&s, "Counters.N1")], ["'HELD'", "2"]);
    assert_eq!(field(&s, "SEQ.Hold"), "FALSE", "B's write stands");
    assert!(s.run_for(1_000_000, None).is_empty());
    assert_eq!(field(&s, "SEQ.Status"), "'RUNNING'", "read at the next scan");
}

fn set_flag(s: &mut linc_engines::strategy::Strategy, path: &str, v: bool) {
    let (b, f) = path.split_once('.').unwrap();
    let c = s.store.cell_of(s.store.db.block(b).unwrap(), f).unwrap();
    s.store.cells[c as usize] = linc_runtime::store::Cell::Bool(v);
}

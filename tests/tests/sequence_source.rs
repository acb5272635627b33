//! A `.sfc` sequence from source to a running SFC_CON block: checked,
//! lowered into one sequence unit, verified, and run by a strategy.
use linc_compiler::sfc::compile_sequence;
use linc_compiler::Context;
use linc_engines::strategy::{trace::Trace, wanted, Strategy};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

const DB: &str = r#"{ "tasks": { "1": { "period": "T#1s" } },
  "templates": { "TANK": { "fields": { "Level": "REAL", "Valve": "BOOL", "Heater": "BOOL", "Stirs": "INT", "Log": "INT", "HeatT": "REAL" } } },
  "blocks": {
    "TANK1": { "type": "TANK" },
    "Plant": { "type": "RECIPE" },
    "SEQ1": { "type": "SFC_CON", "values": { "FileName": "batch.sfc", "Run": true } } } }"#;

const BATCH: &str = "(* fill, then heat and stir together, then done *)
INITIAL_STEP Idle: END_STEP
STEP Fill: FillOn(N); FillOff(F); END_STEP
STEP Heat: HeatOn(S); Note(E, T#3s); END_STEP
STEP Stir: Stirring(N); END_STEP
STEP Done: HeatOn(R); END_STEP
TRANSITION FROM Idle TO Fill := Plant.N0 = 1; END_TRANSITION
TRANSITION Full FROM Fill TO (Heat, Stir) := TANK1.Level >= 90.0; END_TRANSITION
TRANSITION FROM (Heat, Stir) TO Done := Heat.T >= 5.0; END_TRANSITION
ACTION FillOn
    TANK1.Valve := TRUE;
    TANK1.Level := TANK1.Level + 30.0;
END_ACTION
ACTION FillOff
    TANK1.Valve := FALSE;
END_ACTION
ACTION HeatOn
    TANK1.Heater := TRUE;
    TANK1.HeatT := Heat.T;
END_ACTION
ACTION Note
    TANK1.Log := TANK1.Log + 1;
END_ACTION
ACTION Stirring
    TANK1.Stirs := TANK1.Stirs + 1;
END_ACTION
";

#[test]
fn a_sequence_compiles_and_runs_in_an_sfc_con_block() {
    let db = Database::from_json(DB).expect("db");
    let ctx = Context::of(Some(&db));
    let (diagnostics, obj) = compile_sequence(BATCH, "batch", "batch.sfc", ctx);
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    let obj = obj.expect("an object");
    let verified = linc_runtime::load(&obj.to_bytes()).expect("verifies");
    let mut store = Store::new(db);
    let plant_n0 = store.cell_of(store.db.block("Plant").unwrap(), "N0").unwrap();
    store.cells[plant_n0 as usize] = linc_runtime::store::Cell::Int(1);
    let wants: Vec<_> = wanted(&store).into_iter().map(|w| (w, 0)).collect();
    let mut s =
        Strategy::build(store, vec![verified], &wants, Vm::new(100_000, Clock::new(1, 0)), 0.0).expect("builds");
    let mut out = Vec::new();
    let mut trace = Trace::new(&mut out, &s.store);
    let failures = s.run_for(20_000_000, Some(&mut trace));
    trace.finish().expect("trace");
    assert!(failures.is_empty(), "{failures:?}");
    let get = |f: &str| s.store.show(s.store.cell_of(s.store.db.block("TANK1").unwrap(), f).unwrap());
    // Idle (0 s) → Fill (1 s: +30, 2 s: +60, 3 s: +90) → Heat and Stir (4 s) → Done at 9 s (Heat.T = 5 s).
    assert_eq!(
        ["Level", "Valve", "Heater", "Stirs", "Log"].map(get),
        ["90.0", "FALSE", "TRUE", "5", "1"],
        "\n{}",
        String::from_utf8_lossy(&out)
    );
    // HeatOn is stored at Heat's activation and runs every scan, reading
    // Heat.T, until Done's R stops it (at 9 s, without running): last at 8 s.
    assert_eq!(get("HeatT"), "4.0");
    let trace = String::from_utf8(out).unwrap();
    assert!(trace.contains(r#""fired":"Full""#) && trace.contains(r#""fired":"(Heat, Stir) to Done""#), "{trace}");
    assert!(trace.contains(r#"{"time":9.0,"task":1,"program":"SEQ1","step":"Done","active":true}"#), "{trace}");
}

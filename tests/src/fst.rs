//! Running FST tables in tests: a table and a ROC database in, a strategy
//! out, built the way `linc run TABLE.csv --db DB.json` builds it.

use linc_engines::strategy::{trace::Trace, Strategy, Want, WantKind};
use linc_runtime::store::Cell;
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

/// 2026-01-05T06:00:00Z, a Monday: the start of every test run.
pub const START: f64 = 1_767_592_800.0;

/// The points every FST test may use, besides the blocks a test adds.
pub const POINTS: &str = r#"
    "FST 1": { "type": "FST" },
    "SFP 1": { "type": "SFP" },
    "AIN 3-1": { "type": "AIN", "values": { "EU": 42.0, "HIAL": 90.0 } },
    "AOU 5-1": { "type": "AOU" },
    "DOU 4-1": { "type": "DOU" },
    "HIST 9": { "type": "HIST", "values": { "ARCHTYP": "FSTDATA", "PERIODIC": 4 } },
    "HIST 10": { "type": "HIST", "values": { "ARCHTYP": "FSTSEC", "PERIODIC": 4 } },
    "HIST 3": { "type": "HIST", "values": { "ARCHTYP": "CURRENT", "ARCHPT": "AIN 3-1,EU" } }
"#;

/// A ROC800 database of [`POINTS`] with `values` (JSON members
/// `"FIELD": value`) given to `FST 1`.
pub fn database(fst_values: &str) -> Database {
    let points = POINTS.replace(
        r#""FST 1": { "type": "FST" }"#,
        &format!(r#""FST 1": {{ "type": "FST", "values": {{ {fst_values} }} }}"#),
    );
    let text = format!(r#"{{ "device": "ROC800", "blocks": {{ {points} }} }}"#);
    Database::from_json(&text).unwrap_or_else(|e| panic!("test database: {e}"))
}

/// The table compiled against `db` and run by its block `FST 1`.
pub fn strategy(table: &str, db: Database) -> Strategy {
    strategy_at(table, db, START)
}

/// [`strategy`] with the clock starting at `start` (POSIX seconds).
pub fn strategy_at(table: &str, db: Database, start: f64) -> Strategy {
    let (diagnostics, object) = linc_compiler::fst::compile(table, "t", "t.csv", Some(&db));
    let object = object.unwrap_or_else(|| panic!("table does not compile: {diagnostics:?}"));
    strategy_of(object, db, start)
}

/// A table's compiled `object` run by the block `FST 1` of `db`, the clock
/// starting at `start`.
pub fn strategy_of(object: linc_runtime::ObjectFile, db: Database, start: f64) -> Strategy {
    let verified = linc_runtime::verify::verify(object).unwrap_or_else(|e| panic!("verify: {e}"));
    let store = Store::new(db);
    let block = store.db.block("FST 1").expect("FST 1");
    let want = Want { block, file: "t.csv".into(), action: String::new(), kind: WantKind::Fst };
    let vm = Vm::new(linc_runtime::vm::DEFAULT_WATCHDOG, Clock::new(1, 0));
    Strategy::build(store, vec![verified], &[(want, 0)], vm, start).unwrap_or_else(|e| panic!("build: {e:?}"))
}

/// Runs `table` (with `fst_values` for `FST 1`) for `ms` milliseconds.
pub fn run(table: &str, fst_values: &str, ms: u64) -> Strategy {
    let mut s = strategy(table, database(fst_values));
    let errors = s.run_for(ms * 1000, None);
    assert!(errors.is_empty(), "runtime errors: {errors:?}");
    s
}

/// A field's value as a number (`"FST 1.RR"`).
pub fn num(s: &Strategy, path: &str) -> f64 {
    let (block, field) = path.rsplit_once('.').expect("BLOCK.FIELD");
    let b = s.store.db.block(block).unwrap_or_else(|| panic!("no block {block}"));
    let c = s.store.cell_of(b, field).unwrap_or_else(|| panic!("no field {path}"));
    match &s.store.cells[c as usize] {
        Cell::Real(r) => f64::from(*r),
        Cell::Int(i) => f64::from(*i),
        Cell::Bits { v, .. } => f64::from(*v),
        Cell::Bool(b) => f64::from(u8::from(*b)),
        other => panic!("{path} is not a number: {other:?}"),
    }
}

/// A field's value as the store shows it (`"FST 1.MSG1"`).
pub fn text(s: &Strategy, path: &str) -> String {
    let (block, field) = path.rsplit_once('.').expect("BLOCK.FIELD");
    let b = s.store.db.block(block).unwrap_or_else(|| panic!("no block {block}"));
    s.store.show(s.store.cell_of(b, field).unwrap_or_else(|| panic!("no field {path}")))
}

/// Runs with a trace and returns its lines.
pub fn traced(table: &str, fst_values: &str, ms: u64) -> (Strategy, Vec<String>) {
    let mut s = strategy(table, database(fst_values));
    let mut bytes = Vec::new();
    let mut trace = Trace::new(&mut bytes, &s.store);
    let errors = s.run_for(ms * 1000, Some(&mut trace));
    trace.finish().expect("trace");
    assert!(errors.is_empty(), "runtime errors: {errors:?}");
    let lines = String::from_utf8(bytes).expect("utf-8").lines().map(str::to_string).collect();
    (s, lines)
}

/// A table from rows `LABEL,CMD,ARG1,ARG2` (steps numbered here).
pub fn table(rows: &[&str]) -> String {
    let mut t = String::from("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n");
    for (i, r) in rows.iter().enumerate() {
        t.push_str(&format!("{i},{r}\n"));
    }
    t
}

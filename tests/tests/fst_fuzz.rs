//! Random and mutated FST tables through the whole pipeline: reader,
//! checker, lowering, verifier, strategy and VM. None may panic; every table
//! that compiles must pass the verifier (the compiler only makes valid
//! objects) and run; a run may stop a table with a coded runtime error.
//!
//! `cargo test` runs 20,000 cases; `FST_FUZZ_CASES=1000000 cargo test
//! --release -p linc-conformance --test fst_fuzz` is the long run whose
//! figure the README gives.

use linc_conformance::fst::{table, START};
use linc_conformance::rng::Rng;
use linc_engines::strategy::{Strategy, Want, WantKind};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

const DB: &str = r#"{ "device": "ROC800", "blocks": {
    "FST 1": { "type": "FST" }, "FST 2": { "type": "FST" }, "FST 3": { "type": "FST" }, "FST 4": { "type": "FST" },
    "SFP 2": { "type": "SFP" }, "AIN 2-1": { "type": "AIN" }, "DOU 4-2": { "type": "DOU" }, "DOU 6-1": { "type": "DOU" },
    "HIST 1": { "type": "HIST", "values": { "ARCHTYP": "FSTDATA", "PERIODIC": 8 } },
    "HIST 2": { "type": "HIST", "values": { "ARCHTYP": "FSTSEC", "PERIODIC": 8 } },
    "SFP 1": { "type": "SFP" }, "AIN 3-1": { "type": "AIN", "values": { "EU": 42.0, "HIAL": 90.0 } },
    "AOU 5-1": { "type": "AOU" }, "DIN 4-1": { "type": "DIN" }, "DOU 4-1": { "type": "DOU" },
    "HIST 9": { "type": "HIST", "values": { "ARCHTYP": "FSTDATA", "PERIODIC": 8 } },
    "HIST 10": { "type": "HIST", "values": { "ARCHTYP": "FSTSEC", "PERIODIC": 8 } },
    "HIST 3": { "type": "HIST", "values": { "ARCHTYP": "CURRENT", "ARCHPT": "AIN 3-1,EU", "PERIODIC": 8 } }
} }"#;

/// Cells a mutation may put anywhere.
const CELLS: &[&str] = &[
    "",
    "0",
    "1",
    "-1",
    "2",
    "4",
    "5",
    "0.1",
    "-0",
    "1e38",
    "1e39",
    "999999",
    "1000000",
    "255",
    "300",
    "1225",
    "1332",
    "1700000000",
    "VAL",
    "SAV",
    "GO",
    "END",
    "ST",
    "CT",
    "WT",
    "BRK",
    "WDB",
    "WTM",
    "RDB",
    "DHV",
    "PHT",
    "MHV",
    "DIS",
    "PIN",
    "GTE",
    "MSG",
    "ALM",
    "EVT",
    "AO",
    "DO",
    "TDO",
    "DWK",
    "MND",
    "P3",
    "SQR",
    "LOG",
    "LN",
    "EXP",
    "**",
    "/",
    "==",
    "!=",
    "<",
    ">=",
    "AND",
    "XOR",
    "NOT",
    "LOOP",
    "TOP",
    "A",
    "PMPOFF",
    "\"AIN 3-1,EU\"",
    "\"AIN 3-1,HIAL\"",
    "\"SFP 1,DATA1\"",
    "\"FST 1,R1\"",
    "\"FST 2,R3\"",
    "\"FST 1,TMR1\"",
    "\"FST 1,CMPFLG\"",
    "\"FST 1,IP\"",
    "\"FST 1,BRK\"",
    "\"FST 1,RUNFLG\"",
    "\"98,0,2\"",
    "\"96,1,1\"",
    "\"17,0,2\"",
    "DOU 4-1",
    "AOU 5-1",
    "DIN 4-1",
    "\"DOU 4-1,MODE\"",
    "HIGH LEVEL ALARM TEXT",
    "\"a\"\"b\"",
    "é€",
    ";",
    "\"",
    "\r",
];

/// Seed tables: the examples and a few covering every command family.
fn corpus() -> Vec<String> {
    let mut c: Vec<String> = [
        include_str!("../../examples/fst/pump.csv"),
        include_str!("../../examples/fst/branching.csv"),
        include_str!("../../examples/fst/alarm.csv"),
        include_str!("../../examples/fst/history.csv"),
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    c.push(table(&[
        "TOP,VAL,\"SFP 1,DATA1\",",
        ",+,0.5,",
        ",SAV,\"SFP 1,DATA1\",",
        ",WDB,9,\"FST 1,R3\"",
        ",WTM,10,\"FST 1,R4\"",
        ",DIS,3,105",
        ",PHV,3,\"FST 1,R2\"",
        ",GTE,1700000000,4",
        ",BRK,\"FST 1,R9\",",
        ",CT,1,TOP",
        ",ST,1,3",
        ",WT,0.2,",
        ",GO,TOP,",
    ]));
    c.push(table(&[
        ",VAL,\"AIN 3-1,EU\",",
        ",/,\"FST 1,R1\",",
        ",LOG,,",
        ",P3,,",
        ",AND,\"FST 1,R2\",",
        ",NOT,,",
        ",AO,AOU 5-1,\"FST 1,RR\"",
        ",TDO,DOU 4-1,0.3",
        ",ALM,HI,\"FST 1,CMPFLG\"",
        ",MSG,hello,1",
        ",DWK,,",
        ",MND,,",
    ]));
    c
}

/// Splits a table into rows of cells (plain commas; quoting is what the
/// mutations are allowed to break).
fn cells(text: &str) -> Vec<Vec<String>> {
    text.lines().map(|l| l.split(',').map(str::to_string).collect()).collect()
}

fn join(rows: &[Vec<String>]) -> String {
    rows.iter().map(|r| r.join(",")).collect::<Vec<_>>().join("\n")
}

/// A cell for column `col` (2 is CMD): mostly one that fits the column.
fn cell_for(rng: &mut Rng, col: usize) -> String {
    let fits = |c: &&str| {
        let is_cmd = linc_compiler::fst::Cmd::parse(c).is_some();
        if col == 2 {
            is_cmd
        } else {
            !is_cmd
        }
    };
    let pool: Vec<&str> = if rng.one_in(5) { CELLS.to_vec() } else { CELLS.iter().copied().filter(fits).collect() };
    pool[rng.below(pool.len())].to_string()
}

/// One mutated or random table. Rows are renumbered after most
/// mutations, so the checker sees more than gaps in the STEP column.
fn case(rng: &mut Rng, corpus: &[String]) -> String {
    if rng.one_in(20) {
        // Pure noise from the cell alphabet.
        let n = rng.below(60);
        let sep = if rng.one_in(2) { "," } else { "\n" };
        return (0..n).map(|_| CELLS[rng.below(CELLS.len())]).collect::<Vec<_>>().join(sep);
    }
    let mut rows = cells(&corpus[rng.below(corpus.len())]);
    let header = if rng.one_in(30) { Vec::new() } else { vec![rows.remove(0)] };
    let mutations = if rng.one_in(4) { 2 + rng.below(3) } else { 1 };
    for _ in 0..mutations {
        let r = rng.below(rows.len().max(1));
        match rng.below(8) {
            0..=3 => {
                if let Some(row) = rows.get_mut(r) {
                    let c = 1 + rng.below(row.len().saturating_sub(1).max(1));
                    if let Some(cell) = row.get_mut(c) {
                        *cell = cell_for(rng, c);
                    }
                }
            }
            4 if !rows.is_empty() => {
                rows.remove(r);
            }
            5 if !rows.is_empty() => {
                let row = rows[r].clone();
                rows.insert(rng.below(rows.len()), row);
            }
            6 => {
                let mut text = join(&rows).into_bytes();
                if !text.is_empty() {
                    let at = rng.below(text.len());
                    let alphabet = b"\",;\n 0A-9.";
                    text[at] = alphabet[rng.below(alphabet.len())];
                }
                rows = cells(&String::from_utf8_lossy(&text));
            }
            _ => {
                if let Some(row) = rows.get_mut(r) {
                    row.truncate(rng.below(row.len() + 1));
                }
            }
        }
    }
    if !rng.one_in(10) {
        for (i, row) in rows.iter_mut().enumerate() {
            if let Some(step) = row.first_mut() {
                *step = i.to_string();
            }
        }
    }
    join(&[header, rows].concat())
}

#[derive(Default, Debug)]
struct Tally {
    refused: u64,
    compiled: u64,
    faulted: u64,
}

fn exercise(text: &str, db: &Database, store: &Store, tally: &mut Tally) {
    let (diagnostics, object) = linc_compiler::fst::compile(text, "t", "t.csv", Some(db));
    for d in &diagnostics {
        assert!(d.span.end <= text.len() && d.span.start <= d.span.end, "span out of the text: {d:?}\n{text}");
    }
    let Some(object) = object else {
        tally.refused += 1;
        return;
    };
    tally.compiled += 1;
    // The object must also survive its own encoding.
    let bytes = object.to_bytes();
    let verified =
        linc_runtime::load(&bytes).unwrap_or_else(|e| panic!("compiled table fails the verifier: {e}\n{text}"));
    let block = store.db.block("FST 1").expect("FST 1");
    let want = Want { block, file: "t.csv".into(), action: String::new(), kind: WantKind::Fst };
    let vm = Vm::new(100_000, Clock::new(7, 0));
    let mut s = Strategy::build(store.clone(), vec![verified], &[(want, 0)], vm, START)
        .unwrap_or_else(|e| panic!("compiled table does not link: {e:?}\n{text}"));
    let errors = s.run_for(1_000_000, None);
    if let Some(e) = errors.first() {
        assert!(e.code.as_str().starts_with('R'), "a run fails with a runtime code: {e:?}\n{text}");
        tally.faulted += 1;
    }
}

#[test]
fn mutated_tables_never_panic_anywhere_in_the_pipeline() {
    let cases: u64 = std::env::var("FST_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(20_000);
    let db = Database::from_json(DB).expect("database");
    let store = Store::new(db.clone());
    let corpus = corpus();
    let mut tally = Tally::default();
    let started = std::time::Instant::now();
    for n in 0..cases {
        let mut rng = Rng::new(n);
        let text = case(&mut rng, &corpus);
        exercise(&text, &db, &store, &mut tally);
    }
    eprintln!("{cases} tables in {:.1} s: {tally:?}", started.elapsed().as_secs_f64());
    assert_eq!(tally.refused + tally.compiled, cases);
    // The mutations must reach every stage, not stop at the reader.
    assert!(tally.compiled > cases / 5, "{tally:?}");
    assert!(tally.refused > cases / 5, "{tally:?}");
}

#[test]
fn every_seed_table_compiles_and_runs() {
    let db = Database::from_json(DB).expect("database");
    let store = Store::new(db.clone());
    let mut tally = Tally::default();
    for t in corpus() {
        exercise(&t, &db, &store, &mut tally);
    }
    assert_eq!((tally.refused, tally.faulted), (0, 0), "{tally:?}");
}

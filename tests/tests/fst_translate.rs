//! `linc fst to-st` and `to-sfc` against the table they translate (issue
//! 20): generated tables run as FST tables and, translated, as an ST action
//! on an ACTION block or a sequence on an SFC_CON block of the same
//! database, must leave the same database and the same trace of field
//! changes (time, field, old and new value), IP aside for a sequence (the
//! table's instruction pointer: `docs/fst-translation.md`); a table the
//! translation refuses must be refused with a located E0430–E0433.
//!
//! `cargo test` runs 200 tables for 60 simulated seconds each, both ways;
//! `FST_TRANSLATE_CASES=10000 FST_TRANSLATE_SECONDS=3600 cargo test
//! --release -p linc-conformance --test fst_translate -- --nocapture` is the
//! long run whose figures the README gives.

use linc_compiler::fst;
use linc_conformance::fst::START;
use linc_conformance::rng::Rng;
use linc_engines::strategy::{trace::Trace, Strategy};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};
use std::borrow::Cow;
use std::fmt::Write as _;

/// The points of a test database; `FST 1` gets the case's values.
const POINTS: &str = r#"
    "SFP 1": { "type": "SFP", "values": { "DATA1": 12.5 } },
    "AIN 3-1": { "type": "AIN", "values": { "EU": 42.0, "HIAL": 90.0 } },
    "AOU 5-1": { "type": "AOU" },
    "DOU 4-1": { "type": "DOU" }"#;

/// Argument values: constants (zeros of both signs, halves, the edges of
/// the REAL range) and parameters of every class a table reads.
const VALUES: &[&str] = &[
    "0",
    "-0",
    "1",
    "-1",
    "0.5",
    "-0.5",
    "2.5",
    "3",
    "255",
    "300",
    "1e38",
    "-1e38",
    "\"FST 1,R1\"",
    "\"FST 1,R2\"",
    "\"FST 1,RR\"",
    "\"FST 1,CMPFLG\"",
    "\"FST 1,TMR1\"",
    "\"FST 1,MISC1\"",
    "\"AIN 3-1,EU\"",
    "\"SFP 1,DATA1\"",
    "\"DOU 4-1,STATUS\"",
];

/// Parameters SAV writes (REAL, 8-bit, timer, status).
const TARGETS: &[&str] = &[
    "\"FST 1,R1\"",
    "\"FST 1,R2\"",
    "\"SFP 1,DATA1\"",
    "\"FST 1,CMPFLG\"",
    "\"FST 1,TMR2\"",
    "\"FST 1,MISC1\"",
    "\"DOU 4-1,STATUS\"",
];

const PLAIN: &[&str] = &["ABS", "EXP", "INT", "LOG", "LN", "SQR", "P3", "NOT"];
const VALUED: &[&str] = &["+", "-", "*", "/", "VAL"];
const LOGICAL: &[&str] = &["AND", "OR", "XOR"];
/// What AND, OR and XOR take: whole constants 0–255 or any parameter.
const BYTES: &[&str] = &["0", "1", "3", "255", "\"FST 1,R1\"", "\"FST 1,CMPFLG\"", "\"AIN 3-1,EU\""];
const COMPARE: &[&str] = &["==", "!=", "<", "<=", ">", ">="];

/// One random table of 2–16 steps (one in ten of 20–39), every step labelled `Sn`; branches go
/// forward mostly, and now and then a command the translation refuses.
fn generated(rng: &mut Rng) -> String {
    // Now and then longer than a cycle's 20 steps.
    let n = if rng.one_in(10) { 20 + rng.below(20) } else { 2 + rng.below(15) };
    let pick = |rng: &mut Rng, from: &[&'static str]| from[rng.below(from.len())];
    let mut rows = Vec::new();
    let mut ended = false;
    for i in 0..n {
        let value = pick(rng, VALUES);
        let ahead = |rng: &mut Rng| {
            let to = if rng.one_in(12) { rng.below(i + 1) } else { i + 1 + rng.below(n - i) };
            format!("S{}", to.min(n - 1))
        };
        let (cmd, a1, a2) = match rng.below(21) {
            0..=2 => (pick(rng, VALUED), value.to_string(), String::new()),
            3 => (pick(rng, LOGICAL), pick(rng, BYTES).to_string(), String::new()),
            4..=5 => (pick(rng, PLAIN), String::new(), String::new()),
            6..=8 => (pick(rng, COMPARE), value.to_string(), ahead(rng)),
            9 => ("CT", (1 + rng.below(4)).to_string(), ahead(rng)),
            10 => ("ST", (1 + rng.below(4)).to_string(), value.to_string()),
            11..=12 => ("SAV", pick(rng, TARGETS).to_string(), String::new()),
            13 => ("GO", ahead(rng), String::new()),
            14 => ("MSG", "LEVEL $1 'OK'".to_string(), value.to_string()),
            15 => (pick(rng, &["DO", "TDO"]), "DOU 4-1".to_string(), value.to_string()),
            16 => ("AO", "AOU 5-1".to_string(), value.to_string()),
            17 => match rng.below(5) {
                0 => ("WT", pick(rng, &["0.1", "0.25", "1", "2.5"]).to_string(), String::new()),
                1 => ("ALM", "HI".to_string(), value.to_string()),
                2 => ("**", value.to_string(), String::new()),
                3 => ("BRK", "1".to_string(), String::new()),
                _ => ("DWK", String::new(), String::new()),
            },
            18 if !ended => {
                ended = true;
                ("END", String::new(), String::new())
            }
            _ => ("VAL", value.to_string(), String::new()),
        };
        rows.push(format!("{i},S{i},{cmd},{a1},{a2}"));
    }
    format!("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n{}\n", rows.join("\n"))
}

/// How a case's table is translated.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    St,
    Sfc,
}

/// The database of a case: `FST 1` running (RUNFLG 1) with random
/// registers, and for a translation the block that runs it (`TRANS`) and,
/// for a sequence, the soft point whose DATA9 records its way out.
fn database(rng: &mut Rng, translation: Option<Mode>) -> String {
    let reg = |rng: &mut Rng| ["0", "1.5", "-2", "0.25", "3", "-0.0", "100"][rng.below(7)];
    let fst = format!(
        r#""FST 1": {{ "type": "FST", "values": {{ "RUNFLG": 1, "IP": 0, "R1": {}, "R2": {}, "R3": {}, "R4": {}, "CMPFLG": {} }} }}"#,
        reg(rng),
        reg(rng),
        reg(rng),
        reg(rng),
        rng.below(256)
    );
    let extra = match translation {
        Some(Mode::St) => {
            r#", "TRANS": { "type": "ACTION", "values": { "FileName": "t.st", "ActName": "T", "Trigger": true, "Qualifier": "N" } }"#
        }
        Some(Mode::Sfc) => {
            r#", "TRANS": { "type": "SFC_CON", "values": { "FileName": "t.sfc", "Run": true } }, "SFP 9": { "type": "SFP" }"#
        }
        None => "",
    };
    format!(r#"{{ "device": "ROC800", "blocks": {{ {fst}, {POINTS}{extra} }} }}"#)
}

/// The parts of a trace line the comparison reads: other keys (the task,
/// the program, a sequence's steps) are skipped unread.
#[derive(serde::Deserialize)]
struct Change<'a> {
    time: f64,
    #[serde(borrow)]
    field: Option<Cow<'a, str>>,
    #[serde(borrow)]
    old: Option<Cow<'a, str>>,
    #[serde(borrow)]
    new: Option<Cow<'a, str>>,
}

/// The changes a trace records, without the program that made them, one
/// per line: a long run gives hundreds of thousands, so they are read
/// into one string rather than a value each.
fn changes(trace: &[u8]) -> String {
    let text = std::str::from_utf8(trace).expect("traces are UTF-8");
    let mut out = String::with_capacity(text.len() / 2);
    // Most lines are a table's steps; the writer puts a change's keys as
    // `"field":`, so a line without that is passed over unparsed.
    for line in text.lines().filter(|l| l.contains("\"field\":")) {
        let c: Change = serde_json::from_str(line).expect("trace lines are JSON");
        // The translation's own blocks are not the table's; IP is the
        // table's instruction pointer, which a sequence has no use for.
        let own = |f: &str| f.starts_with("TRANS.") || f.starts_with("SFP 9.") || f == "FST 1.IP";
        if let (Some(field), Some(old), Some(new)) = (c.field, c.old, c.new) {
            if !own(&field) {
                let _ = writeln!(out, "{} {field:?} {old:?} -> {new:?}", c.time);
            }
        }
    }
    out
}

/// Runs `s` for `seconds` with a trace; the store's cells (IP of `FST 1`
/// left out) and the changes.
fn run(mut s: Strategy, seconds: u64) -> (Vec<String>, String) {
    let mut bytes = Vec::new();
    let mut trace = Trace::new(&mut bytes, &s.store);
    let errors = s.run_for(seconds * 1_000_000, Some(&mut trace));
    trace.finish().expect("trace");
    assert!(errors.is_empty(), "runtime errors: {errors:?}");
    let ip = s.store.db.block("FST 1").and_then(|b| s.store.cell_of(b, "IP")).map(|c| c as usize);
    let cells =
        (s.store.cells.iter().enumerate()).map(|(i, c)| if Some(i) == ip { String::new() } else { format!("{c:?}") });
    let cells = cells.collect();
    (cells, changes(&bytes))
}

enum Outcome {
    /// The table does not compile: its first error's code.
    NotATable(&'static str),
    /// The translation's codes.
    Refused(Vec<&'static str>),
    Same,
}

/// The translation's text and object: the ST action or the sequence,
/// compiled against `db`; or the translation's codes.
fn translated(table: &str, db: &Database, mode: Mode) -> Result<(String, Vec<u8>), Outcome> {
    let (read, _) = fst::reader::read(table);
    let (checked, _) = fst::check::check(&read, Some(db));
    let checked = checked.expect("a table that compiles checks");
    let text = match mode {
        Mode::St => {
            let target = fst::translate::Target { block: "FST 1", steps_per_cycle: 20, action: "T" };
            fst::translate::to_st(&read, &checked, &target)
        }
        Mode::Sfc => {
            let exit = fst::check::field_param(db, "SFP 9.DATA9").expect("a free numeric field");
            let target = fst::translate::SfcTarget { block: "FST 1", steps_per_cycle: 20, exit: Some(&exit) };
            fst::translate::to_sfc(&read, &checked, &target)
        }
    };
    let text = match text {
        Ok(t) => t,
        Err(refusals) => {
            for d in &refusals {
                let code = d.code.as_str();
                assert!(["E0430", "E0431", "E0432", "E0433"].contains(&code), "refused with {code}:\n{table}");
                assert!(
                    d.span.end > d.span.start && d.span.end <= table.len(),
                    "a refusal at its cell: {d:?}\n{table}"
                );
            }
            return Err(Outcome::Refused(refusals.iter().map(|d| d.code.as_str()).collect()));
        }
    };
    match compile_translation(&text, db, mode) {
        Ok(b) => Ok((text, b)),
        Err(codes) => panic!("the translation does not compile ({codes:?}):\n{table}\n{text}"),
    }
}

/// The object of a translation's text, or its codes if it does not compile.
fn compile_translation(text: &str, db: &Database, mode: Mode) -> Result<Vec<u8>, Vec<&'static str>> {
    match mode {
        Mode::St => linc_conformance::compiled(text, "t.st", db),
        Mode::Sfc => {
            let ctx = linc_compiler::Context::of(Some(db));
            let (diagnostics, object) = linc_compiler::sfc::compile_sequence(text, "t", "t.sfc", ctx);
            object.map(|o| o.to_bytes()).ok_or_else(|| diagnostics.iter().map(|d| d.code.as_str()).collect())
        }
    }
}

/// The databases of case `db_seed`: the table's, and the translation's
/// (the same, with the block that runs the translation).
fn databases(db_seed: u64, mode: Mode) -> (Database, Database) {
    let db_a = database(&mut Rng::new(db_seed), None);
    let db_b = database(&mut Rng::new(db_seed), Some(mode));
    (Database::from_json(&db_a).expect("database"), Database::from_json(&db_b).expect("database"))
}

/// One case: the table against its translation.
fn differential(table: &str, db_seed: u64, seconds: u64, mode: Mode) -> Outcome {
    let (db, db_translated) = databases(db_seed, mode);
    let (diagnostics, object) = fst::compile(table, "t", "t.csv", Some(&db));
    let Some(object) = object else {
        let first = diagnostics.iter().find(|d| d.is_error()).expect("a table that does not compile has an error");
        return Outcome::NotATable(first.code.as_str());
    };
    let (text, bytes) = match translated(table, &db_translated, mode) {
        Ok(t) => t,
        Err(outcome) => return outcome,
    };
    if let Err(difference) = same(object, db, &bytes, db_translated, seconds) {
        panic!("{difference}\n{table}\n{text}");
    }
    Outcome::Same
}

/// Runs the table's object on `FST 1` of `db` and the translation's on its
/// block of `db_translated`, each for `seconds`; where their traces or
/// databases first differ, if they do.
fn same(
    table: linc_runtime::ObjectFile,
    db: Database,
    translation: &[u8],
    db_translated: Database,
    seconds: u64,
) -> Result<(), String> {
    let a = linc_conformance::fst::strategy_of(table, db, START);
    let verified = linc_runtime::load(translation).expect("loads");
    let store = Store::new(db_translated);
    let wants: Vec<_> = linc_engines::strategy::wanted(&store).into_iter().map(|w| (w, 0)).collect();
    let vm = Vm::new(linc_runtime::vm::DEFAULT_WATCHDOG, Clock::new(1, 0));
    let b = Strategy::build(store, vec![verified], &wants, vm, START).expect("builds");
    let ((cells_a, trace_a), (cells_b, trace_b)) = (run(a, seconds), run(b, seconds));
    if trace_a != trace_b {
        let (mut a, mut b) = (trace_a.lines(), trace_b.lines());
        let at = (0..).find(|_| a.next() != b.next()).unwrap_or_default();
        let (a, b) = (trace_a.lines().nth(at), trace_b.lines().nth(at));
        return Err(format!("the traces differ at change {at}: table {a:?}, translation {b:?}"));
    }
    if cells_a[..] != cells_b[..cells_a.len()] {
        return Err(format!("the databases differ: {cells_a:?} against {:?}", &cells_b[..cells_a.len()]));
    }
    Ok(())
}

#[test]
fn generated_tables_and_their_translations_do_the_same() {
    generated_tables_against(Mode::St);
}

#[test]
fn generated_tables_and_their_sequences_do_the_same() {
    generated_tables_against(Mode::Sfc);
}

fn generated_tables_against(mode: Mode) {
    let env = |k: &str, d: u64| std::env::var(k).ok().and_then(|v| v.parse().ok()).unwrap_or(d);
    let (cases, seconds) = (env("FST_TRANSLATE_CASES", 200), env("FST_TRANSLATE_SECONDS", 60));
    let (mut same, mut refused, mut invalid) = (0u64, 0u64, 0u64);
    let mut codes = std::collections::BTreeMap::<&str, u64>::new();
    let started = std::time::Instant::now();
    for case in 0..cases {
        let table = generated(&mut Rng::new(case));
        match differential(&table, case, seconds, mode) {
            Outcome::Same => same += 1,
            Outcome::Refused(c) => {
                refused += 1;
                c.into_iter().for_each(|c| *codes.entry(c).or_default() += 1);
            }
            Outcome::NotATable(c) => {
                invalid += 1;
                *codes.entry(c).or_default() += 1;
            }
        }
    }
    eprintln!("codes: {codes:?}");
    eprintln!(
        "{cases} tables: {same} translated and the same for {seconds} s, {refused} refused, {invalid} did not compile; {:.1} s",
        started.elapsed().as_secs_f64()
    );
    assert!(same * 3 >= cases, "only {same} of {cases} tables were translated");
    assert!(refused * 20 >= cases, "the refusals are exercised too: {refused}");
}

/// The translation's codes for `rows` (`LABEL,CMD,ARG1,ARG2`), each with the
/// line and text of the cell it points at.
fn refusals(rows: &[&str]) -> Vec<(&'static str, usize, String)> {
    let table = linc_conformance::fst::table(rows);
    let db = Database::from_json(&database(&mut Rng::new(0), None)).expect("database");
    let (read, _) = fst::reader::read(&table);
    let (checked, diagnostics) = fst::check::check(&read, Some(&db));
    assert!(!diagnostics.iter().any(|d| d.is_error()), "{diagnostics:?}");
    let target = fst::translate::Target { block: "FST 1", steps_per_cycle: 20, action: "T" };
    match fst::translate::to_st(&read, &checked.expect("checked"), &target) {
        Ok(st) => panic!("translated:\n{st}"),
        Err(ds) => ds
            .iter()
            .map(|d| {
                let line = table[..d.span.start].matches('\n').count() + 1;
                (d.code.as_str(), line, table[d.span.start..d.span.end].to_string())
            })
            .collect(),
    }
}

#[test]
fn refusals_are_located_at_the_step_that_stops_the_translation() {
    // Each command without an ST equivalent, at its own cell.
    let r = refusals(&[",VAL,1,", ",WT,5,", ",ALM,HI,1", ",END,,"]);
    assert_eq!(r, [("E0430", 3, "WT".to_string()), ("E0430", 4, "ALM".to_string())]);
    // A loop: at the step whose jump goes back.
    let r = refusals(&["TOP,VAL,\"AIN 3-1,EU\",", ",>,50,TOP", ",END,,"]);
    assert_eq!(r, [("E0431", 3, ">".to_string())]);
    // 25 steps in a row: the cycle stops before the 21st (step 20).
    let mut long = vec![",+,1,"; 24];
    long.push(",END,,");
    assert_eq!(refusals(&long), [("E0432", 22, "+".to_string())]);
    // MSG text that no ST string constant stores as written.
    assert_eq!(refusals(&[",MSG,it's \"x\",1"])[0].0, "E0430");
    // Branches that cross: each step reachable two ways, over and over.
    let crossing: Vec<String> = (0..17).map(|i| format!("S{i},<,1,S{}", i + 2)).collect();
    let mut rows: Vec<&str> = crossing.iter().map(String::as_str).collect();
    rows.extend(["S17,VAL,1,", "S18,END,,"]);
    assert_eq!(refusals(&rows)[0].0, "E0433");
}

#[test]
fn a_translation_reads_like_the_table() {
    let table = linc_conformance::fst::table(&[
        ",VAL,\"AIN 3-1,EU\",",
        ",>=,\"AIN 3-1,HIAL\",HIGH",
        ",DO,DOU 4-1,0",
        ",END,,",
        "HIGH,DO,DOU 4-1,1",
    ]);
    let db = Database::from_json(&database(&mut Rng::new(0), None)).expect("database");
    let (read, _) = fst::reader::read(&table);
    let (checked, _) = fst::check::check(&read, Some(&db));
    let target = fst::translate::Target { block: "FST 1", steps_per_cycle: 20, action: "ALARM" };
    let st = fst::translate::to_st(&read, &checked.expect("checked"), &target).expect("translates");
    insta::assert_snapshot!("fst_to_st_alarm", st);
}

/// `to-sfc` of `rows` with `exit` as the exit field.
fn as_sequence(rows: &[&str], exit: Option<&str>) -> Result<String, Vec<&'static str>> {
    let table = linc_conformance::fst::table(rows);
    let db = Database::from_json(&database(&mut Rng::new(0), None)).expect("database");
    let (read, _) = fst::reader::read(&table);
    let (checked, _) = fst::check::check(&read, Some(&db));
    let exit = exit.map(|f| fst::check::field_param(&db, f.trim_matches(|c| c == '[' || c == ']')).expect("a field"));
    let target = fst::translate::SfcTarget { block: "FST 1", steps_per_cycle: 20, exit: exit.as_ref() };
    fst::translate::to_sfc(&read, &checked.expect("checked"), &target)
        .map_err(|ds| ds.iter().map(|d| d.code.as_str()).collect())
}

#[test]
fn a_sequence_has_a_step_where_each_cycle_can_start() {
    let rows = [",VAL,\"AIN 3-1,EU\",", ",>,50,HIGH", ",END,,", "HIGH,WT,2.5,", ",DO,DOU 4-1,1", ",WT,1,"];
    // END on one path and a WT on another: the way out must be noted.
    assert_eq!(as_sequence(&rows, None), Err(vec!["E0434"]));
    let sfc = as_sequence(&rows, Some("[SFP 1.DATA9]")).expect("translates");
    insta::assert_snapshot!("fst_to_sfc_wait", sfc);
    // A WT whose time is a parameter has no transition to test it.
    assert_eq!(as_sequence(&[",WT,\"FST 1,R1\",", ",END,,"], None), Err(vec!["E0430"]));
}

#[test]
fn a_table_that_stops_itself_has_no_sequence() {
    // SAV 0 to its own RUNFLG stops the table; a sequence would run on.
    let rows = [",VAL,\"SFP 1,DATA1\",", ",>,50,STOP", ",END,,", "STOP,VAL,0,", ",SAV,\"FST 1,RUNFLG\",", ",WT,1,"];
    assert_eq!(as_sequence(&rows, Some("[SFP 1.DATA9]")), Err(vec!["E0430"]));
    // Its other fields are ordinary ones.
    assert!(as_sequence(&[",VAL,0,", ",SAV,\"FST 1,R5\",", ",END,,"], None).is_ok());
}

#[test]
fn the_exit_field_is_writable_numeric_and_not_the_table_s() {
    let rows = [",VAL,\"SFP 1,DATA9\",", ",>,50,HIGH", ",END,,", "HIGH,WT,2.5,", ",WT,1,"];
    assert_eq!(as_sequence(&rows, Some("[SFP 1.DATA9]")), Err(vec!["E0434"]), "the table reads it");
    assert!(as_sequence(&rows, Some("[SFP 1.DATA8]")).is_ok());
    let db = Database::from_json(&database(&mut Rng::new(0), None)).expect("database");
    let refused = |f: &str| fst::check::field_param(&db, f).expect_err(f);
    assert!(refused("FST 1.IP").contains("read-only"));
    assert!(refused("FST 1.MSG1").contains("text, not a number"));
    assert!(refused("SFP 1.NOPE").contains("no field"));
    assert!(refused("SFP 1.DATA1.Bit0").contains("bit") || refused("SFP 1.DATA1.Bit0").contains("no bit"));
}

/// The differential can fail: translations changed by one token each — a
/// comparison's edge, a constant, an output, the sign of a zero — run
/// against their table are each told apart, as ST and as a sequence.
#[test]
fn the_differential_tells_a_wrong_translation_apart() {
    let table = linc_conformance::fst::table(&[
        ",VAL,\"SFP 1,DATA1\",",
        ",+,0.5,",
        ",SAV,\"SFP 1,DATA1\",",
        ",>,2,HIGH",
        ",DO,DOU 4-1,0",
        ",END,,",
        "HIGH,VAL,0,",
        ",SAV,\"SFP 1,DATA1\",",
        ",DO,DOU 4-1,1",
    ]);
    let mutants = [
        ("[FST 1.RR] > 2.0", "[FST 1.RR] >= 2.0"),
        ("[FST 1.RR] := [FST 1.RR] + 0.5;", "[FST 1.RR] := [FST 1.RR] + 0.25;"),
        ("[DOU 4-1.STATUS] := 1;", "[DOU 4-1.STATUS] := 0;"),
        ("[FST 1.RR] := 0.0;", "[FST 1.RR] := -0.0;"),
    ];
    for mode in [Mode::St, Mode::Sfc] {
        let case = |text: &str| {
            let (db, db_translated) = databases(0, mode);
            let bytes = compile_translation(text, &db_translated, mode).expect("compiles");
            let (_, object) = fst::compile(&table, "t", "t.csv", Some(&db));
            same(object.expect("the table compiles"), db, &bytes, db_translated, 10)
        };
        let Ok((text, _)) = translated(&table, &databases(0, mode).1, mode) else { panic!("translates") };
        assert_eq!(case(&text), Ok(()), "the translation itself");
        for (from, to) in mutants {
            let mutant = text.replacen(from, to, 1);
            assert_ne!(mutant, text, "{from} is in the translation");
            let difference = case(&mutant).expect_err(to);
            assert!(difference.starts_with("the traces differ at change "), "{difference}");
        }
    }
}

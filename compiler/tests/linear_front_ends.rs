//! The front ends other than `linc check` of ST take time linear in the size
//! of their input: FST tables, map files, sequences compiled, and the
//! parser's error recovery. Each is measured at a size and at four times it,
//! in processor time (`linc_test_support::work`: how busy the machine is
//! does not count); the bound (a ratio under 8) is generous for a debug
//! build, and a quadratic step gives a ratio near 16.

mod workload;

use linc_compiler::diag::MAX_ERRORS;
use linc_compiler::Context;
use linc_runtime::Database;
use linc_test_support::alloc::serial;
use linc_test_support::work::{cpu, growth};

/// How much more work `f(4n)` takes than `f(n)` (processor time, the least
/// of three each). Every test of this binary holds [`serial`], so that none
/// runs beside another's measurement.
fn ratio<T>(n: usize, make: impl Fn(usize) -> T, mut f: impl FnMut(&T)) -> f64 {
    let (small, large) = (make(n), make(4 * n));
    growth(|big| cpu(|| f(if big { &large } else { &small })).1)
}

/// A table of `rows` steps over the FST example's points, with labels and
/// branches, that checks clean.
fn fst_table(rows: usize) -> String {
    let mut out = String::from("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n");
    for i in 0..rows {
        out.push_str(&match i % 4 {
            0 => format!("{i},L{i},VAL,\"AIN 2-1,EU\",,level\n"),
            1 => format!("{i},,+,\"SFP 2,DATA1\",,\n"),
            2 => format!("{i},,SAV,\"FST 1,R5\",,\n"),
            _ => format!("{i},,>=,1,L{},\n", i - 3),
        });
    }
    out
}

fn fst_check(text: &str, db: &Database) {
    let (table, d) = linc_compiler::fst::reader::read(text);
    assert!(d.is_empty(), "{:?}", d.first());
    let (checked, d) = linc_compiler::fst::check::check(&table, Some(db));
    assert!(d.is_empty() && checked.is_some(), "{:?}", d.first());
}

#[test]
fn fst_tables_check_in_linear_time() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/fst/plant.json")).expect("fst example db");
    let r = ratio(2_400, fst_table, |t| fst_check(t, &db));
    assert!(r < 7.0, "4x the rows took {r:.1}x the time");
}

/// A database of `n` soft points and a table reading each: looking points
/// up must not search the database for every cell.
fn points_and_table(n: usize) -> (Database, String) {
    let blocks: Vec<String> = (1..=n).map(|i| format!("\"SFP {i}\": {{\"type\": \"SFP\"}}")).collect();
    let db =
        format!("{{\"device\": \"ROC800\", \"blocks\": {{\"FST 1\": {{\"type\": \"FST\"}}, {}}}}}", blocks.join(", "));
    let db = Database::from_json(&db).expect("generated db");
    let mut table = String::from("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n");
    for i in 0..n {
        table.push_str(&format!("{i},,VAL,\"SFP {},DATA1\",\n", i + 1));
    }
    (db, table)
}

#[test]
fn fst_points_are_found_in_constant_time() {
    let _one = serial();
    let r = ratio(1_000, points_and_table, |(db, t)| fst_check(t, db));
    assert!(r < 8.0, "4x the points and rows took {r:.1}x the time");
}

/// A table with as many errors as are shown (cheap ones), then `rows`
/// branches to labels no step has: the "did you mean" search through every
/// label is for errors shown, not for the ones over the cap, only counted.
fn unknown_labels(rows: usize) -> String {
    let mut out = String::from("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2\n");
    for i in 0..MAX_ERRORS {
        out.push_str(&format!("{i},,ABS,1,\n"));
    }
    for i in MAX_ERRORS..MAX_ERRORS + rows {
        out.push_str(&format!("{i},L{i},GO,M{i},\n"));
    }
    out
}

#[test]
fn fst_errors_over_the_cap_cost_no_search() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/fst/plant.json")).expect("fst example db");
    let r = ratio(1_000, unknown_labels, |t| {
        let (table, _) = linc_compiler::fst::reader::read(t);
        let (_, d) = linc_compiler::fst::check::check(&table, Some(&db));
        assert_eq!(d.last().map(|d| d.code.as_str()), Some("E0023"));
    });
    assert!(r < 8.0, "4x the rows took {r:.1}x the time");
}

fn ctx(db: &Database) -> Context<'_> {
    Context::of(Some(db))
}

#[test]
fn sequences_compile_in_linear_time() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/sequences/plant.json")).expect("sequence example db");
    let r = ratio(
        800,
        |n| workload::ring(n, "1.0"),
        |src| {
            let (d, object) = linc_compiler::sfc::compile_sequence(src, "ring", "ring.sfc", ctx(&db));
            assert!(object.is_some(), "{:?}", d.first());
        },
    );
    assert!(r < 7.0, "4x the steps took {r:.1}x the time");
}

/// A map of `n` generic names and a generic sequence of `n` steps (each
/// step's name is looked up in the map, E0255) that reads the last name.
fn map_and_sequence(n: usize) -> (String, String) {
    let entries: Vec<String> = (0..n).map(|i| format!("  \"G{i}\": \"R1.Level\"")).collect();
    let map = format!("{{\n{}\n}}\n", entries.join(",\n"));
    let mut seq = workload::ring(n, "1.0");
    seq.push_str(&format!("ACTION Last\n    R1.Temp := G{};\nEND_ACTION\n", n - 1));
    (map, seq.replace("Count(N);", "Count(N); Last(N);"))
}

#[test]
fn generic_sequences_check_with_a_map_in_linear_time() {
    let _one = serial();
    use linc_compiler::sfc::generic;
    let db = Database::from_json(include_str!("../../examples/sequences/plant.json")).expect("sequence example db");
    let r = ratio(1_000, map_and_sequence, |(map, seq)| {
        let (map, errors) = generic::parse_map(map);
        assert!(errors.is_empty(), "{errors:?}");
        let (bound, errors) = generic::bind(&map, &db, true);
        assert!(errors.is_empty(), "{errors:?}");
        let named = generic::Named { map, file: "map.json".into() };
        let report = linc_compiler::sfc::check_generic(seq, ctx(&bound), &named, false);
        assert!(report.diagnostics.is_empty(), "{:?}", report.diagnostics.first());
    });
    assert!(r < 7.0, "4x the entries and steps took {r:.1}x the time");
}

/// One error deep inside 99 nested IFs, followed by `n` tokens up to the
/// `;`: lalrpop's own recovery searched the whole parser stack for every
/// token it dropped (0.2 MB took 2.2 s in a release build; 90 KB/s).
fn junk_after_an_error(n: usize) -> String {
    format!("ACTION A\n{}X := ) {}\nEND_ACTION\n", "IF X THEN ".repeat(99), "+ ".repeat(n))
}

fn syntax_errors(src: &str) -> Vec<&'static str> {
    let (_, errors) = linc_compiler::st::parser::parse_file(src, "a");
    errors.syntax.iter().map(|e| e.to_diagnostic().code.as_str()).collect()
}

#[test]
fn tokens_after_a_syntax_error_are_skipped_in_linear_time() {
    let _one = serial();
    let r = ratio(20_000, junk_after_an_error, |src| assert!(!syntax_errors(src).is_empty()));
    assert!(r < 7.0, "4x the tokens took {r:.1}x the time");
    let junk = junk_after_an_error(100_000);
    let t = cpu(|| drop(syntax_errors(&junk))).1;
    assert!(t < std::time::Duration::from_secs(2), "0.2 MB of tokens after one error took {t:?} of work");
}

#[test]
fn reading_stops_after_the_errors_that_are_shown() {
    let _one = serial();
    // A file of `;`: every one an error. Reading stops after the errors
    // that are shown (E0023 where it stopped), so a file four times as
    // long costs no more.
    let semis = |n: usize| format!("ACTION A\n{}\nEND_ACTION\n", ";".repeat(n));
    let errors = syntax_errors(&semis(100_000));
    assert_eq!(errors.last(), Some(&"E0023"), "{:?}", &errors[errors.len().saturating_sub(3)..]);
    assert!(errors.len() <= MAX_ERRORS + 2, "{} errors", errors.len());
    let r = ratio(50_000, semis, |src| drop(syntax_errors(src)));
    assert!(r < 2.0, "4x the errors took {r:.1}x the time");
    // Under the limit, every error is read and reported.
    let errors = syntax_errors(&semis(10));
    assert_eq!(errors.len(), 10, "{errors:?}");
    assert!(!errors.contains(&"E0023"));
}

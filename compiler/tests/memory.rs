//! `linc check` needs memory in proportion to the largest action, not to the
//! file: actions are checked as they are parsed and then dropped. A counting
//! allocator measures the peak of live heap bytes while a session checks a
//! generated file of realistic actions.

mod workload;

use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::Database;
use linc_test_support::alloc::{peak_of, serial, Counting};

#[global_allocator]
static ALLOCATOR: Counting = Counting;

#[test]
fn junk_and_many_errors_need_little_memory() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    for src in ["@".repeat(1 << 20), "xx := 1; ".repeat(120_000)] {
        let size = src.len();
        let peak = peak_of(|| {
            let mut s = Session::new(Context::of(Some(&db)));
            let id = s.add("junk.st", src.into_bytes());
            let c = s.check(id, CheckOptions::default());
            assert!(c.diagnostics.len() <= 1_001 + 1, "{}", c.diagnostics.len());
        });
        assert!(peak < size * 2, "peak heap {peak} bytes for a {size}-byte file");
    }
}

#[test]
fn checking_needs_less_than_twice_the_size_of_the_file() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let mut size = 0;
    let peak = peak_of(|| {
        let src = workload::actions(2 << 20).into_bytes();
        size = src.len();
        let mut s = Session::new(Context::of(Some(&db)));
        let id = s.add("workload.st", src);
        let checked = s.check(id, CheckOptions::default());
        assert!(checked.diagnostics.is_empty(), "{:?}", checked.diagnostics.first());
    });
    // The text itself is 1x (the session keeps it, for the diagnostics);
    // the README's target for the whole process is 10x.
    assert!(peak < size * 2, "peak heap {peak} bytes for a {size}-byte file");
}

#[test]
fn compiling_lowers_as_it_checks_and_keeps_no_checked_program() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let mut size = 0;
    let mut object_bytes = 0;
    let peak = peak_of(|| {
        let src = workload::actions(2 << 20).into_bytes();
        size = src.len();
        let mut s = Session::compiling(Context::of(Some(&db)));
        let id = s.add("workload.st", src);
        let checked = s.check(id, CheckOptions::default());
        assert!(checked.diagnostics.is_empty(), "{:?}", checked.diagnostics.first());
        let object = s.compile().expect("compiles");
        object_bytes = object.to_bytes().len();
    });
    // The text (1x), the object being built and its encoding; the checked
    // program of the whole file (about 25x the text) is never held.
    eprintln!("compile: peak heap {peak} bytes for a {size}-byte file, object {object_bytes} bytes");
    assert!(peak < size * 6, "peak heap {peak} bytes for a {size}-byte file");
}

/// Deep nesting: the parser holds each open bracket, waiting prefix
/// operator and open statement on its stack, about 100 bytes each, so 1 MB
/// of `(` held about 110 MB (7.5 GB for 100 MB) before the depth guard.
#[test]
fn deep_nesting_needs_little_memory() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let n = 1 << 20;
    let cases = [
        format!("Recipe.A0 := {}1;\n", "(".repeat(n)),
        format!("Recipe.A0 := {}1{};\n", "(".repeat(n / 2), ")".repeat(n / 2)),
        format!("Recipe.A0 := {}1;\n", "- ".repeat(n / 2)),
        format!("Recipe.A0 := {}1;\n", "-".repeat(n)),
        format!("Recipe.A0 := {}0;\n", "ABS(".repeat(n / 4)),
        // A flat chain is bound as it is read: the parser holds one pending
        // operator per precedence level, never the chain.
        format!("Recipe.A0 := {}1;\n", "1 + 2 * ".repeat(n / 8)),
        format!("Recipe.A0 := {}0;\n", "Block_5.Val1{".repeat(n / 13)),
        "IF 1 THEN\n".repeat(n / 10),
        "WHILE 1 DO\n".repeat(n / 11) + &"END_WHILE;\n".repeat(n / 11),
    ];
    for src in cases {
        let size = src.len();
        let head = src[..16].to_string();
        let mut codes = Vec::new();
        let peak = peak_of(|| {
            let mut s = Session::new(Context::of(Some(&db)));
            let id = s.add("deep.st", src.into_bytes());
            let c = s.check(id, CheckOptions::default());
            codes = c.diagnostics.iter().map(|d| d.code.as_str()).collect();
        });
        assert!(codes[0] == "E0021" || codes[0] == "E0022", "{head}: {codes:?}");
        assert!(peak < size * 2, "{head}…: peak heap {peak} bytes for a {size}-byte file");
    }
}

/// The peak of checking the ladder file `src` (with the ladder example's
/// database), and its codes.
fn ladder_peak(src: String) -> (usize, Vec<&'static str>) {
    let db = Database::from_json(include_str!("../../examples/ladder/plant.json")).expect("ladder db");
    let mut codes = Vec::new();
    let peak = peak_of(|| {
        let mut s = Session::new(Context::of(Some(&db)));
        let id = s.add("big.ld", src.into_bytes());
        codes = s.check(id, CheckOptions::default()).diagnostics.iter().map(|d| d.code.as_str()).collect();
    });
    (peak, codes)
}

/// A ladder action is read, checked and dropped before the next one, and
/// holds at most MAX_ELEMENTS elements (about a kilobyte each while it is
/// checked): a 48 MB series took more than 4 GB.
#[test]
fn ladder_needs_memory_for_one_action_at_a_time() {
    let _one = serial();
    let series = format!("{}-> (Dig_1b.Out);\n", "[Dig_1a.In] ".repeat(200_000));
    let size = series.len();
    let (peak, codes) = ladder_peak(series);
    assert_eq!(codes, ["E0313"]);
    assert!(peak < size * 2, "series: peak heap {peak} bytes for a {size}-byte file");
    let action = |i: usize| format!("ACTION A{i}\n{}-> (Dig_1b.Out);\nEND_ACTION\n", "[Dig_1a.In] ".repeat(2_000));
    let (two, codes) = ladder_peak((0..2).map(action).collect());
    assert!(codes.is_empty(), "{codes:?}");
    let (twenty, _) = ladder_peak((0..20).map(action).collect());
    assert!(twenty < two * 3 / 2, "20 actions peak at {twenty} bytes, 2 at {two}");
}

#[test]
fn formatting_needs_less_than_ten_times_the_size_of_the_file() {
    let _one = serial();
    let src = workload::actions(2 << 20);
    let size = src.len();
    let mut formatted = 0;
    let peak = peak_of(|| {
        let kind = linc_compiler::source_kind::SourceKind::Actions;
        formatted = linc_compiler::fmt::format(kind, &src).expect("the workload parses").len();
    });
    assert!(formatted > size / 2, "{formatted}");
    // The input (not counted: made before), the tokens (about 32 bytes a
    // token) and the output.
    assert!(peak < size * 10, "peak heap {peak} bytes for a {size}-byte file");
}

//! Limits of the object format (E0132) and literals out of range: `check`
//! reports them exactly as `compile` does, once per action.
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_conformance::{assert_check_agrees_with_compile, check_and_compile, invalid, valid};
use linc_runtime::Database;

fn max_call(n: usize) -> String {
    let args: Vec<String> = (1..=n).map(|i| i.to_string()).collect();
    format!("Recipe.A0 := MAX({});\n", args.join(", "))
}

fn for_loops(n: usize) -> String {
    "FOR Counters.N0 := 1 TO 2 DO Recipe.N1 := 1; END_FOR;\n".repeat(n)
}

#[test]
fn sixteen_arguments_are_the_most_a_call_takes() {
    assert_eq!(check_and_compile(&max_call(16)), (vec![], vec![]));
    assert_eq!(check_and_compile(&max_call(17)), (vec!["E0132"], vec!["E0132"]));
    // Once per action, not once per call.
    let two = max_call(17) + &max_call(20);
    assert_eq!(check_and_compile(&two).0, ["E0132"]);
    let actions = format!("ACTION a\n{}END_ACTION\nACTION b\n{}END_ACTION\n", max_call(17), max_call(17));
    assert_eq!(check_and_compile(&actions), (vec!["E0132", "E0132"], vec!["E0132", "E0132"]));
}

#[test]
fn an_action_has_at_most_254_for_loops() {
    assert_eq!(check_and_compile(&for_loops(254)), (vec![], vec![]));
    assert_eq!(check_and_compile(&for_loops(255)), (vec!["E0132"], vec!["E0132"]));
    assert_eq!(check_and_compile(&for_loops(300)).0, ["E0132"]);
    let split = format!("ACTION a\n{}END_ACTION\nACTION b\n{}END_ACTION\n", for_loops(200), for_loops(200));
    assert_eq!(check_and_compile(&split), (vec![], vec![]));
}

/// A database of 257 blocks of 256 REAL fields: 65,792 different fields.
fn wide_db() -> Database {
    let fields: Vec<String> = (0..256).map(|f| format!("\"F{f}\": \"REAL\"")).collect();
    let blocks: Vec<String> = (0..257).map(|b| format!("\"B{b}\": {{ \"type\": \"WIDE\" }}")).collect();
    let json = format!(
        "{{ \"templates\": {{ \"WIDE\": {{ \"fields\": {{ {} }} }} }}, \"blocks\": {{ {} }} }}",
        fields.join(", "),
        blocks.join(", ")
    );
    Database::from_json(&json).expect("wide database")
}

/// Assignments to the first `n` different fields of the wide database, in
/// actions of `per_action` assignments.
fn references(n: usize, per_action: usize) -> String {
    let mut out = String::new();
    for (i, k) in (0..n).enumerate() {
        if i % per_action == 0 {
            out.push_str(&format!("ACTION A{}\n", i / per_action));
        }
        out.push_str(&format!("B{}.F{} := 1;\n", k / 256, k % 256));
        if i % per_action == per_action - 1 || i == n - 1 {
            out.push_str("END_ACTION\n");
        }
    }
    out
}

/// Error codes (with their lines) of checking `files` in one session,
/// then of lowering them when `compile` is set.
fn session_codes(db: &Database, files: &[&str], compile: bool) -> Vec<(&'static str, usize)> {
    let ctx = Context::of(Some(db));
    let mut s = if compile { Session::compiling(ctx) } else { Session::new(ctx) };
    let mut out = Vec::new();
    for (i, src) in files.iter().enumerate() {
        let id = s.add(format!("f{i}.st"), src.as_bytes().to_vec());
        for d in s.check(id, CheckOptions::default()).diagnostics {
            out.push((d.code.as_str(), linc_compiler::diag::render::line_col(s.files(), d.file, d.span.start).0));
        }
    }
    if compile {
        for d in s.compile().err().unwrap_or_default() {
            out.push((d.code.as_str(), linc_compiler::diag::render::line_col(s.files(), d.file, d.span.start).0));
        }
    }
    out
}

#[test]
fn an_object_has_at_most_65536_database_references() {
    let db = wide_db();
    let full = references(65_536, 4096);
    assert_eq!(session_codes(&db, &[&full], false), []);
    assert_eq!(session_codes(&db, &[&full], true), []);
    // Two more fields in the last action of 4096: one error, at the first.
    let over = references(65_538, 4096);
    let at = 16 * (4096 + 2) + 2;
    assert_eq!(session_codes(&db, &[&over], false), [("E0132", at)]);
    assert_eq!(session_codes(&db, &[&over], true), [("E0132", at)]);
    // Counted across the files of one session: the second file goes over.
    let (a, b) = (references(40_000, 40_000), references(65_537, 65_537).replace("ACTION A0", "ACTION Z0"));
    assert_eq!(session_codes(&db, &[&a, &b], true), [("E0132", 65_537 + 1)]);
}

invalid!(s12_9_real_beyond_f32, "§12.9", Action, "PIC_004.PV := 3.5E38;\nPIC_004.PV := -1.0E39;\n", ["E0019", "E0019"]);
invalid!(s12_9_exponent_without_point_is_real, "§12.9", Action, "PIC_004.PV := 1E39;\n", ["E0019"]);
valid!(s12_9_largest_real, "§12.9", Action, "PIC_004.PV := 3.4028234E38;\nPIC_004.PV := 1E3;\n");
invalid!(s12_9_time_beyond_int_seconds, "§12.9", Action, "Recipe.A3 := T#99999999999999999999d;\n", ["E0020"]);
valid!(s12_9_longest_time, "§12.9", Action, "Recipe.A3 := T#24855d;\nRecipe.A4 := T#2147483647s;\n");
invalid!(
    s12_4_3_for_step_zero,
    "§12.4.3",
    Action,
    "FOR Counters.N0 := 0 TO 10 BY 0 DO\n  Recipe.N1 := 1;\nEND_FOR;\n",
    ["E0121"]
);
invalid!(
    s12_4_3_for_step_rounding_to_zero,
    "§12.4.3",
    Action,
    "FOR Counters.N0 := 0 TO 10 BY 0.4 DO\n  Recipe.N1 := 1;\nEND_FOR;\nFOR Counters.N0 := 0 TO 10 BY -0.5 DO\n  Recipe.N1 := 1;\nEND_FOR;\n",
    ["E0121"]
);
valid!(
    s12_4_3_for_real_step_on_real_index,
    "§12.4.3",
    Action,
    "FOR PIC_004.PV := 0 TO 1 BY 0.4 DO\n  Recipe.A0 := PIC_004.PV;\nEND_FOR;\n"
);

#[test]
fn limits_and_literals_agree_between_check_and_compile() {
    for src in
        [max_call(17), for_loops(255), "PIC_004.PV := 1E39;\n".into(), "Recipe.A3 := T#99999999999999999999d;\n".into()]
    {
        assert_check_agrees_with_compile(&src);
    }
}

#[test]
fn the_example_files_agree_between_check_and_compile() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/guide");
    let mut seen = 0;
    for entry in std::fs::read_dir(dir).expect("examples") {
        let path = entry.expect("entry").path();
        if matches!(path.extension().and_then(|e| e.to_str()), Some("st" | "stx")) {
            assert_check_agrees_with_compile(&std::fs::read_to_string(&path).expect("read"));
            seen += 1;
        }
    }
    assert_eq!(seen, 3);
}

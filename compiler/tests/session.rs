//! One compile session over several files: diagnostics name their own file,
//! action names are unique across files, and checking and compiling agree.

use linc_compiler::diag::render::{render, Format};
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_compiler::{Diagnostic, FileId};
use linc_runtime::Database;

fn guide() -> Database {
    Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db")
}

/// Checks `files` in one session (compiling when `compile`), returning the
/// session and every diagnostic.
fn run<'a>(ctx: Context<'a>, files: &[(&str, &str)], compile: bool) -> (Session<'a>, Vec<Diagnostic>) {
    let mut s = if compile { Session::compiling(ctx) } else { Session::new(ctx) };
    let mut all = Vec::new();
    for (name, src) in files {
        let id = s.add(*name, src.as_bytes().to_vec());
        all.extend(s.check(id, CheckOptions::default()).diagnostics);
    }
    if compile {
        all.extend(s.compile().err().unwrap_or_default());
    }
    (s, all)
}

fn short(s: &Session, d: &[Diagnostic]) -> Vec<String> {
    d.iter().map(|d| render(s.files(), d, Format::Short).trim_end().to_string()).collect()
}

#[test]
fn lowering_errors_are_shown_against_their_own_file() {
    // Without a database, compiling needs the types: E0130 in the second file.
    let db = Database::builtin();
    let ctx = Context::of(Some(&db)).unresolved();
    let files = [("a.st", "ACTION a : PID\n  PV := 1.0;\nEND_ACTION\n"), ("b.st", "\n\nX.Y := 1;\n")];
    let (s, d) = run(ctx, &files, true);
    assert_eq!(short(&s, &d), ["b.st:3:1: error[E0130]: the type of `X.Y` is unknown"]);
    assert_eq!(d[0].file, FileId(1));
}

#[test]
fn an_action_defined_in_two_files_points_at_both() {
    let db = guide();
    let ctx = Context::of(Some(&db));
    let files = [
        ("a.st", "ACTION Fill\n  Recipe.N0 := 1;\nEND_ACTION\n"),
        ("b.st", "\nACTION FILL\n  Recipe.N0 := 2;\nEND_ACTION\n"),
    ];
    for compile in [false, true] {
        let (s, d) = run(ctx, &files, compile);
        assert_eq!(short(&s, &d), ["b.st:2:8: error[E0117]: action `FILL` is defined twice"]);
        assert_eq!((d[0].secondary[0].file, d[0].secondary[0].span.start), (Some(FileId(0)), 7));
        let human = render(s.files(), &d[0], Format::Human);
        assert!(human.contains("┌─ b.st:2:8") && human.contains("┌─ a.st:1:8"), "{human}");
    }
}

#[test]
fn two_files_with_the_same_stem_name_the_same_action() {
    let db = guide();
    let ctx = Context::of(Some(&db));
    let files = [("one/fill.st", "Recipe.N0 := 1;\n"), ("two/fill.st", "Recipe.N0 := 2;\n")];
    for compile in [false, true] {
        let (s, d) = run(ctx, &files, compile);
        assert_eq!(short(&s, &d), ["two/fill.st:1:1: error[E0117]: action `fill` is defined twice"]);
    }
}

#[test]
fn names_are_compared_with_one_lookup_each() {
    // 20,000 actions in two files: every name is new but the last.
    let db = guide();
    let ctx = Context::of(Some(&db));
    let many = |from: usize| -> String {
        (from..from + 10_000).map(|i| format!("ACTION A{i} Recipe.N0 := 1; END_ACTION\n")).collect()
    };
    let (a, b) = (many(0), many(10_000) + "ACTION a17 Recipe.N0 := 1; END_ACTION\n");
    let (s, d) = run(ctx, &[("a.st", &a), ("b.st", &b)], false);
    assert_eq!(short(&s, &d), ["b.st:10001:8: error[E0117]: action `a17` is defined twice"]);
}

#[test]
fn a_file_that_is_not_utf8_is_located_at_its_first_bad_byte() {
    let db = guide();
    let mut s = Session::new(Context::of(Some(&db)));
    let id = s.add("lat.st", b"PIC_004.PV := 1; (* 85 \xB0C *)\nPIC_004.PV := 2; \xE9\n".to_vec());
    let d = s.check(id, CheckOptions::default()).diagnostics;
    assert_eq!(short(&s, &d), ["lat.st:1:24: error[E0017]: byte 0xB0 is not UTF-8"]);
    assert_eq!(d[0].help[1], "1 more byte in this file is not UTF-8");
    let human = render(s.files(), &d[0], Format::Human);
    assert!(human.contains("(* 85 \\xB0C *)"), "{human}");
}

#[test]
fn a_byte_order_mark_is_not_part_of_the_text() {
    let db = guide();
    let mut s = Session::new(Context::of(Some(&db)));
    let id = s.add("bom.st", "\u{FEFF}PIC_004.PV := 'x';\n".as_bytes().to_vec());
    let d = s.check(id, CheckOptions::default()).diagnostics;
    assert_eq!(short(&s, &d), ["bom.st:1:15: error[E0103]: can't store a STRING value in a REAL field"]);
    assert_eq!(d[0].span.start, 17, "offsets are those of the file");
    let human = render(s.files(), &d[0], Format::Human);
    assert!(human.contains("1 │ PIC_004.PV := 'x';\n"), "{human}");
}

#[test]
fn an_object_file_is_not_read_as_source() {
    let db = guide();
    let mut s = Session::new(Context::of(Some(&db)));
    let mut bytes = linc_runtime::object::MAGIC.to_vec();
    bytes.extend_from_slice(&[1, 0, 0, 0, 0xFF, 0xFE]);
    let id = s.add("x.sto", bytes);
    let d = s.check(id, CheckOptions::default()).diagnostics;
    assert_eq!(short(&s, &d), ["x.sto:1:1: error[E0018]: `x.sto` is a linc object file, not ST source"]);
    assert!(d[0].help[0].contains("linc disasm x.sto"), "{:?}", d[0].help);
}

#[test]
fn control_characters_never_reach_the_output_raw() {
    let db = guide();
    let mut s = Session::new(Context::of(Some(&db)));
    let id = s.add("esc.st", "PIC_004.PV := '\u{1b}[31m'; (* \u{1b}[2J *) \u{1b}\u{7}\n".as_bytes().to_vec());
    let d = s.check(id, CheckOptions { tree: true, ..Default::default() });
    let codes: Vec<&str> = d.diagnostics.iter().map(|d| d.code.as_str()).collect();
    // The stray ESC and BEL are one run of characters: one error.
    assert_eq!(codes, ["E0103", "E0001"]);
    for diag in &d.diagnostics {
        for f in [Format::Human, Format::Short, Format::Json] {
            let out = render(s.files(), diag, f);
            assert!(!out.contains('\u{1b}') && !out.contains('\u{7}'), "{f:?}: {out}");
        }
    }
    let human = render(s.files(), &d.diagnostics[1], Format::Human);
    assert!(human.contains("error[E0001]: unexpected characters, from `\\u{1b}` on"), "{human}");
    assert!(human.contains("'\\u{1b}[31m'; (* \\u{1b}[2J *) \\u{1b}\\u{7}"), "{human}");
    let tree = d.tree.map(|t| t.pretty()).unwrap_or_default();
    assert!(tree.contains("'\\u{1b}[31m'") && !tree.contains('\u{1b}'), "{tree}");
}

#[test]
fn a_misspelt_block_is_an_unknown_name_not_a_step() {
    let db = guide();
    let ctx = Context::of(Some(&db));
    let (s, d) = run(ctx, &[("m.st", "PIC_04.T := 1;\nPIC_04.PV := 1;\nSTEP1.X := 1;\n")], false);
    assert_eq!(
        short(&s, &d),
        [
            "m.st:1:1: error[E0100]: can't find `PIC_04`",
            "m.st:2:1: error[E0100]: can't find `PIC_04`",
            "m.st:3:1: error[E0113]: step variable `STEP1.X` outside a sequence",
        ]
    );
    assert_eq!(d[0].help, ["did you mean `PIC_004`?"]);
}

/// One session classifies every source (issue 16): action and ladder files
/// are checked together, a sequence and an FST table each alone, and
/// compiling takes one of those only on its own.
#[test]
fn one_session_checks_and_compiles_every_kind_of_source() {
    use linc_compiler::source_kind::SourceKind;
    let db = Database::from_json(include_str!("../../examples/sequences/plant.json")).expect("db");
    let ctx = Context::of(Some(&db));
    let seq = "INITIAL_STEP S0: Count(N); END_STEP\nACTION Count\n    R1.Batches := R1.Batches + 1;\nEND_ACTION\n";
    let mut s = Session::compiling(ctx);
    let id = s.add("batch.sfc", seq.as_bytes().to_vec());
    assert_eq!(s.kind(id), SourceKind::Sequence);
    assert!(s.check(id, CheckOptions::default()).diagnostics.is_empty());
    let object = s.compile().expect("a sequence alone compiles");
    assert_eq!(object.units.len(), 1);
    // A sequence with an error is reported like any source, in its file.
    let mut s = Session::compiling(ctx);
    let id = s.add("bad.sfc", b"INITIAL_STEP S0: Nope(N); END_STEP\n".to_vec());
    let d = s.check(id, CheckOptions::default()).diagnostics;
    assert!(d.iter().any(|d| d.is_error() && d.file == id), "{d:?}");
    assert!(s.compile().is_err());
    // With another file: E0024 at compile time (checking each is fine).
    let mut s = Session::compiling(ctx);
    let a = s.add("batch.sfc", seq.as_bytes().to_vec());
    let b = s.add("count.stx", b"R1.Batches := 0;\n".to_vec());
    assert_eq!((s.kind(a), s.kind(b)), (SourceKind::Sequence, SourceKind::Actions));
    assert!(s.check(a, CheckOptions::default()).diagnostics.is_empty());
    assert!(s.check(b, CheckOptions::default()).diagnostics.is_empty());
    let e = s.compile().expect_err("not alone");
    assert_eq!(e.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0024"]);
    // An FST table without a database: checked for its form, not compiled.
    let table = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n0,,VAL,1,,\n1,,END,,,\n";
    let bare = Context { resolve_blocks: false, ..ctx };
    let mut s = Session::compiling(bare);
    let id = s.add("t.csv", table.as_bytes().to_vec());
    assert_eq!(s.kind(id), SourceKind::FstTable);
    assert!(s.check(id, CheckOptions::default()).diagnostics.is_empty());
    let e = s.compile().expect_err("no points");
    assert_eq!(e.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0025"]);
    // An object is never a source, whatever its name.
    assert_eq!(SourceKind::of("x.stx", linc_format::object::MAGIC), SourceKind::Object);
    // By name alone a `.sto` is an object (commands load it); given to a
    // session without the magic number, it is text like any other.
    assert_eq!(SourceKind::of_name("x.sto"), SourceKind::Object);
    assert_eq!(SourceKind::of("x.sto", b"R1.Batches := 0;\n"), SourceKind::Actions);
}

/// `Context::of`: with a database names are resolved; without, any block
/// may exist at run time, but the built-in block types are still known.
#[test]
fn a_context_without_a_database_accepts_unknown_blocks() {
    let codes = |ctx: Context| {
        let mut s = Session::new(ctx);
        let id = s.add(
            "a.st",
            b"ACTION a\n    XYZ_1.PV := 1.0;\nEND_ACTION\nACTION b : PID\n    PV := 1.0;\n    Nope := 1;\nEND_ACTION\n"
                .to_vec(),
        );
        let diags = s.check(id, CheckOptions::default()).diagnostics;
        diags.iter().map(|d| format!("{} {}", d.code.as_str(), d.message)).collect::<Vec<_>>()
    };
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let with = codes(Context::of(Some(&db)));
    assert!(with.len() == 2 && with[0].contains("XYZ_1") && with[1].contains("Nope"), "{with:?}");
    // The unknown block passes; a lone name not a field of the own block does not.
    let without = codes(Context::of(None));
    assert!(without.len() == 1 && without[0].starts_with("E0100") && without[0].contains("Nope"), "{without:?}");
    assert!(!Context::of(None).resolve_blocks && Context::of(Some(&db)).resolve_blocks);
}

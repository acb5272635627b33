//! Deep and long code: every stage (parser, checker, lowering, the tree
//! printer and dropping the trees) stays within the default 2 MiB stack of a
//! test thread, at the nesting limits and far beyond them.

use linc_compiler::check::Context;
use linc_compiler::lower::{self, Lines};
use linc_compiler::parse_support::{MAX_EXPR_DEPTH, MAX_NESTING};
use linc_runtime::Database;

fn db() -> Database {
    Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db")
}

/// Checks, lowers, prints and drops `src` on a fresh 2 MiB thread; returns
/// the codes.
fn codes(src: String) -> Vec<&'static str> {
    std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(move || {
            let db = db();
            let ctx = Context { db: &db, resolve_blocks: true, steps: None };
            let r = linc_compiler::check_source(&src, "deep", ctx);
            if let Some(t) = &r.tree {
                let _ = linc_compiler::pretty::file(t);
            }
            if let Some(p) = &r.program {
                lower::lower_program(p, "deep.st", &Lines::new(&src)).expect("lowers");
            }
            r.diagnostics.iter().map(|d| d.code).collect()
        })
        .expect("thread")
        .join()
        .expect("no stack overflow")
}

/// An IF nested `n` deep around `inner` statements.
fn nested_ifs(n: usize, inner: &str) -> String {
    format!("{}{inner}{}", "IF Dig_A.Out.Bit0 THEN\n".repeat(n), "END_IF;\n".repeat(n))
}

/// A sum of `n` terms: as deep as it is long.
fn sum(n: usize) -> String {
    vec!["1"; n].join("+")
}

/// Offsets inside offsets, `n` deep.
fn offsets(n: usize) -> String {
    format!("{}0{}", "Block_5.Val1{".repeat(n - 1), "}".repeat(n - 1))
}

#[test]
fn the_deepest_accepted_program_fits_the_stack() {
    let e = MAX_EXPR_DEPTH as usize;
    let inner = format!(
        "Recipe.A0 := {};\nRecipe.A1 := {};\nRecipe.A2 := {}1{};\nRecipe.N0 := {}1;\n",
        sum(e),
        offsets(e),
        "ABS(".repeat(e - 1),
        ")".repeat(e - 1),
        "NOT ".repeat(e - 1)
    );
    assert_eq!(codes(nested_ifs(MAX_NESTING as usize, &inner)), Vec::<&str>::new());
}

#[test]
fn one_level_more_is_a_located_error() {
    let n = MAX_NESTING as usize;
    assert_eq!(codes(nested_ifs(n + 1, "Recipe.A0 := 1;\n")), ["E0021"]);
    assert_eq!(codes(format!("Recipe.A0 := {};\n", sum(MAX_EXPR_DEPTH as usize + 1))), ["E0022"]);
    assert_eq!(codes(format!("Recipe.A0 := {};\n", offsets(MAX_EXPR_DEPTH as usize + 1))), ["E0022"]);
}

#[test]
fn far_too_deep_code_gives_one_error_each() {
    assert_eq!(codes(nested_ifs(5_000, "Recipe.A0 := 1;\n")), ["E0021"]);
    assert_eq!(codes(format!("Recipe.A0 := {};\n", sum(12_000))), ["E0022"]);
    assert_eq!(codes(format!("Recipe.A0 := {};\n", offsets(6_000))), ["E0022"]);
    assert_eq!(codes(format!("Recipe.A0 := {}1;\n", "NOT ".repeat(12_000))), ["E0022"]);
    assert_eq!(codes(format!("Recipe.A0 := {}1{};\n", "ABS(".repeat(12_000), ")".repeat(12_000))), ["E0022"]);
    let mixed = "WHILE 1 DO\nFOR Counters.N0 := 1 TO 2 DO\nREPEAT\n".repeat(2_000)
        + &"UNTIL 1 END_REPEAT;\nEND_FOR;\nEND_WHILE;\n".repeat(2_000);
    assert_eq!(codes(mixed), ["E0021"]);
}

#[test]
fn brackets_alone_add_no_depth() {
    let src = format!("Recipe.A0 := {}1{};\n", "(".repeat(20_000), ")".repeat(20_000));
    assert_eq!(codes(src), Vec::<&str>::new());
}

//! Deep and long code: every stage (parser, checker, lowering, the tree
//! printer and dropping the trees) stays within the default 2 MiB stack of a
//! test thread, at the nesting limits and far beyond them.

use linc_compiler::st::lower::{self, Lines};
use linc_compiler::st::parse_support::{MAX_EXPR_DEPTH, MAX_NESTING};
use linc_compiler::Context;
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
            let ctx = Context::of(Some(&db));
            let r = linc_compiler::check_source(&src, "deep", ctx);
            if let Some(t) = &r.tree {
                let _ = linc_compiler::st::pretty::file(t);
            }
            if let Some(p) = &r.program {
                lower::lower_program(p, "deep.st", &Lines::new(&src)).expect("lowers");
            }
            r.diagnostics.iter().map(|d| d.code.as_str()).collect()
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
    // 200 brackets around a sum as deep as the limit allows.
    let e = MAX_EXPR_DEPTH as usize;
    let src = format!("Recipe.A0 := {}{}{};\n", "(".repeat(e), sum(e), ")".repeat(e));
    assert_eq!(codes(src), Vec::<&str>::new());
}

/// Code, line and column of each diagnostic of `src`.
fn located(src: &str) -> Vec<(&'static str, usize)> {
    let db = db();
    let ctx = Context::of(Some(&db));
    let r = linc_compiler::check_source(src, "deep", ctx);
    r.diagnostics.iter().map(|d| (d.code.as_str(), d.span.start)).collect()
}

#[test]
fn brackets_and_prefix_runs_are_limited_as_they_are_read() {
    // The parser holds every open bracket and waiting prefix operator, so
    // they are counted before they close (100 MB of `(` held 7.5 GB).
    let e = MAX_EXPR_DEPTH as usize;
    let at = "Recipe.A0 := ".len();
    let src = format!("Recipe.A0 := {}1{};\n", "(".repeat(20_000), ")".repeat(20_000));
    assert_eq!(located(&src), [("E0022", at + e)]);
    let src = format!("Recipe.A0 := {}1;\n", "-".repeat(20_000));
    assert_eq!(located(&src), [("E0022", at + e)]);
    let src = format!("Recipe.A0 := {}1;\n", "-".repeat(e));
    assert_eq!(located(&src), []);
    // Unclosed: the bracket is reported, and so is the missing `)`.
    let src = format!("Recipe.A0 := {}1;\nRecipe.A1 := 2;\n", "(".repeat(20_000));
    let codes: Vec<_> = located(&src).into_iter().map(|c| c.0).collect();
    assert_eq!(codes, ["E0022", "E0010"]);
}

#[test]
fn an_unclosed_statement_over_the_limit_is_reported_at_its_keyword() {
    let n = MAX_NESTING as usize;
    let src = "IF Dig_A.Out.Bit0 THEN\n".repeat(20_000);
    let keyword = "IF Dig_A.Out.Bit0 THEN\n".len() * n;
    let found = located(&src);
    assert_eq!(found[0], ("E0021", keyword));
    assert_eq!(found.iter().map(|c| c.0).collect::<Vec<_>>(), ["E0021", "E0011"]);
}

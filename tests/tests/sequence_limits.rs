//! The object format's limits on a sequence (E0132): each step has two
//! 16-bit retained slots, and each transition condition and ST action is a
//! code block with a 16-bit number. `check` reports them as `compile` does,
//! at the first step or transition over; below them the object loads. (A
//! sequence of 100,000 steps used to compile into an object whose slot
//! numbers had wrapped round.)

use linc_compiler::check::Context;
use linc_compiler::sfc::{self, lower::MAX_BLOCKS, lower::MAX_STEPS};
use linc_runtime::Database;

fn db() -> Database {
    Database::from_json(include_str!("../../examples/sequences/plant.json")).expect("sequence example db")
}

/// `n` steps in a ring, `per_step` transitions leaving each.
fn ring(n: usize, per_step: usize) -> String {
    let mut out = String::new();
    for i in 0..n {
        let kw = if i == 0 { "INITIAL_STEP" } else { "STEP" };
        out.push_str(&format!("{kw} S{i}: Count(N); END_STEP\n"));
    }
    for i in 0..n {
        for k in 0..per_step {
            out.push_str(&format!("TRANSITION FROM S{i} TO S{} := S{i}.T >= {k}.0; END_TRANSITION\n", (i + 1) % n));
        }
    }
    out.push_str("ACTION Count\n    R1.Batches := R1.Batches + 1;\nEND_ACTION\n");
    out
}

/// The errors of checking `src`, with the text each is at. Compiling
/// reports the same: it lowers only what checked clean.
fn errors(src: &str) -> Vec<(&'static str, String)> {
    let db = db();
    let ctx = Context { db: &db, resolve_blocks: true, steps: None };
    let at = |d: &linc_compiler::Diagnostic| (d.code, src[d.span.start..d.span.end].to_string());
    sfc::check_sequence(src, ctx).diagnostics.iter().filter(|d| d.is_error()).map(at).collect()
}

#[test]
fn a_sequence_has_at_most_32767_steps() {
    let db = db();
    let ctx = Context { db: &db, resolve_blocks: true, steps: None };
    let src = ring(MAX_STEPS, 1);
    let (d, object) = sfc::compile_sequence(&src, "ring", "ring.sfc", ctx);
    let object = object.unwrap_or_else(|| panic!("the most steps compile: {:?}", d.first()));
    let unit = &object.units[0];
    assert_eq!(usize::from(unit.retained), 2 * MAX_STEPS);
    let last = unit.charts[0].steps.last().expect("steps");
    assert_eq!((last.name.as_str(), usize::from(last.slot)), ("S32766", MAX_STEPS - 1), "no slot wraps round");
    linc_runtime::verify::verify(object).expect("the object loads");
    assert_eq!(errors(&ring(MAX_STEPS + 1, 1)), [("E0132", "S32767".to_string())]);
}

#[test]
fn a_sequence_has_at_most_65535_code_blocks() {
    // 21,846 steps with three transitions each: 65,538 transitions.
    let src = ring(MAX_BLOCKS / 3 + 1, 3);
    let check = errors(&src);
    assert_eq!(check.len(), 1, "{check:?}");
    assert_eq!(check[0].0, "E0132");
    // Transition 65,535 (from 0) is the first leaving step 21,845.
    assert!(check[0].1.starts_with("TRANSITION FROM S21845 TO S0 := S21845.T >= 0.0"), "{}", check[0].1);
}

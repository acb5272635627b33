//! The object format's and the loader's limits on a sequence (issue 16):
//! `check` refuses, located, what the loader would refuse, and below the
//! limits the object loads. Each step has two 16-bit retained slots (E0214);
//! transition conditions and ST actions are code blocks with 16-bit
//! numbers, and a chart action's chart is copied for each chart that uses
//! it (E0215); chart actions nest at most 32 deep (E0213). (A sequence of
//! 100,000 steps used to compile into an object whose slot numbers had
//! wrapped round.)

use linc_compiler::sfc::{self, MAX_BLOCKS, MAX_STEPS};
use linc_compiler::Context;
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

/// A chain of `n` chart actions, each running the next from one step.
fn nested(n: usize) -> String {
    let mut s = String::from("INITIAL_STEP S0: A0(N); END_STEP\n");
    for i in 0..n {
        s.push_str(&format!("ACTION A{i} : CHART\n INITIAL_STEP T{i}: A{}(N); END_STEP\nEND_ACTION\n", i + 1));
    }
    s.push_str(&format!("ACTION A{n}\n R1.Batches := 1;\nEND_ACTION\n"));
    s
}

/// Two chart actions at each of `n` levels, each using both of the next
/// level's (a chart is copied once for each chart that uses it): the
/// object holds 2^(k+1) copies of level k's charts.
fn doubled(n: usize) -> String {
    let mut s = String::from("INITIAL_STEP S0: A0(N); B0(N); END_STEP\n");
    for i in 0..n {
        for x in ["A", "B"] {
            s.push_str(&format!(
                "ACTION {x}{i} : CHART\n INITIAL_STEP {x}T{i}: A{j}(N); END_STEP\n STEP {x}U{i}: B{j}(N); END_STEP\n \
                 TRANSITION FROM {x}T{i} TO {x}U{i} := TRUE; END_TRANSITION\nEND_ACTION\n",
                j = i + 1
            ));
        }
    }
    s.push_str(&format!("ACTION A{n}\n R1.Batches := 1;\nEND_ACTION\nACTION B{n}\n R1.Batches := 2;\nEND_ACTION\n"));
    s
}

/// The errors of checking `src`, with the text each is at. Compiling
/// reports the same: it lowers only what checked clean.
fn errors(src: &str) -> Vec<(&'static str, String)> {
    let db = db();
    let ctx = Context::of(Some(&db));
    let at = |d: &linc_compiler::Diagnostic| (d.code.as_str(), src[d.span.start..d.span.end].to_string());
    sfc::check_sequence(src, ctx).diagnostics.iter().filter(|d| d.is_error()).map(at).collect()
}

/// Compiles `src` (which must check clean) and loads its object.
fn loads(src: &str) -> Result<(), String> {
    let db = db();
    let ctx = Context::of(Some(&db));
    let (d, object) = sfc::compile_sequence(src, "s", "s.sfc", ctx);
    let object = object.unwrap_or_else(|| panic!("compiles: {:?}", d.first()));
    linc_runtime::load(&object.to_bytes()).map(drop).map_err(|e| format!("{} {e}", e.code()))
}

#[test]
fn a_sequence_has_at_most_32767_steps() {
    let db = db();
    let ctx = Context::of(Some(&db));
    let src = ring(MAX_STEPS, 1);
    let (d, object) = sfc::compile_sequence(&src, "ring", "ring.sfc", ctx);
    let object = object.unwrap_or_else(|| panic!("the most steps compile: {:?}", d.first()));
    let unit = &object.units[0];
    assert_eq!(usize::from(unit.retained), 2 * MAX_STEPS);
    let last = unit.charts[0].steps.last().expect("steps");
    assert_eq!((last.name.as_str(), usize::from(last.slot)), ("S32766", MAX_STEPS - 1), "no slot wraps round");
    linc_runtime::verify::verify(object).expect("the object loads");
    assert_eq!(errors(&ring(MAX_STEPS + 1, 1)), [("E0214", "S32767".to_string())]);
}

#[test]
fn a_sequence_has_at_most_65535_code_blocks() {
    // 21,846 steps with three transitions each: 65,538 transitions, and
    // the ST action Count. The action and 65,534 transitions fill the
    // unit; transition 65,535 (the third leaving S21844) is over.
    let src = ring(MAX_BLOCKS / 3 + 1, 3);
    let db = db();
    let ctx = Context::of(Some(&db));
    let d = sfc::check_sequence(&src, ctx).diagnostics;
    let d: Vec<_> = d.iter().filter(|d| d.is_error()).collect();
    assert_eq!(d.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0215"]);
    let at = &src[d[0].span.start..];
    assert!(at.starts_with("TRANSITION FROM S21844 TO S21845 := S21844.T >= 2.0"), "{}", &at[..60]);
}

#[test]
fn chart_actions_nest_as_deep_as_the_loader_allows_and_no_deeper() {
    assert_eq!(errors(&nested(32)), []);
    assert_eq!(loads(&nested(32)), Ok(()));
    // The 33rd level: refused at the association that puts it there.
    assert_eq!(errors(&nested(33)), [("E0213", "A32(N)".to_string())]);
}

#[test]
fn chart_action_copies_are_counted_without_being_made() {
    // Ten levels: 2,046 charts and as many transition blocks.
    assert_eq!(errors(&doubled(10)), []);
    assert_eq!(loads(&doubled(10)), Ok(()));
    let start = std::time::Instant::now();
    let e = errors(&doubled(30));
    assert_eq!(e.iter().map(|e| e.0).collect::<Vec<_>>(), ["E0215"], "{e:?}");
    // 2^30 copies would take minutes and gigabytes to write out.
    assert!(start.elapsed() < std::time::Duration::from_secs(2), "{:?}", start.elapsed());
}

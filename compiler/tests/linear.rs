//! `linc check` time grows linearly with the size of the input (the
//! benchmark `benches/check.rs` measures the figures; this guards the shape
//! in a debug build, in processor time so that a busy machine does not
//! decide it: a quadratic step, such as comparing every action name with
//! every other, would give a ratio near 16).

mod workload;

use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::Database;
use linc_test_support::alloc::serial;
use linc_test_support::work::{cpu, growth};
use std::time::Duration;

/// The processor time of checking `src` (the parser of a long file runs on
/// a second thread: the whole process is counted, and the tests of this
/// binary take turns).
fn check(db: &Database, src: &str) -> Duration {
    cpu(|| {
        let mut s = Session::new(Context::of(Some(db)));
        let id = s.add("workload.st", src.as_bytes().to_vec());
        let c = s.check(id, CheckOptions::default());
        assert!(c.diagnostics.is_empty(), "the workload checks clean: {:?}", c.diagnostics.first());
    })
    .1
}

/// Many one-line actions: what makes a per-action step that looks at every
/// earlier action show.
fn small_actions(bytes: usize) -> String {
    let mut out = String::with_capacity(bytes + 64);
    let mut i = 0;
    while out.len() < bytes {
        out.push_str(&format!("ACTION A{i} Recipe.N{} := {i}; END_ACTION\n", i % 8));
        i += 1;
    }
    out
}

/// How much more checking `large` cost than `small`.
fn ratio(db: &Database, small: &str, large: &str) -> f64 {
    growth(|big| check(db, if big { large } else { small }))
}

#[test]
fn check_time_is_linear_in_size() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let r = ratio(&db, &workload::actions(200_000), &workload::actions(800_000));
    assert!(r < 7.0, "4x the realistic input took {r:.1}x the time");
    let r = ratio(&db, &small_actions(150_000), &small_actions(600_000));
    assert!(r < 7.0, "4x the actions took {r:.1}x the time");
}

/// The processor time of checking `src`, which has errors.
fn check_bad(db: &Database, src: &str) -> Duration {
    cpu(|| {
        let mut s = Session::new(Context::of(Some(db)));
        let id = s.add("bad.st", src.as_bytes().to_vec());
        let c = s.check(id, CheckOptions::default());
        assert_eq!(c.diagnostics[0].code, "E0021");
    })
    .1
}

/// Error recovery at the end of unclosed statements looked at every open
/// statement for each one it dropped: 20,000 unclosed IFs took 0.3 s and
/// 1,000,000 over ten minutes.
#[test]
fn unclosed_statements_take_linear_time() {
    let _one = serial();
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let (small, large) = ("IF 1 THEN\n".repeat(5_000), "IF 1 THEN\n".repeat(20_000));
    let r = growth(|big| check_bad(&db, if big { &large } else { &small }));
    assert!(r < 7.0, "4x the unclosed IFs took {r:.1}x the work");
}

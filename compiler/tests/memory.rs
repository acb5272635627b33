//! `linc check` needs memory in proportion to the largest action, not to the
//! file: actions are checked as they are parsed and then dropped. A counting
//! allocator measures the peak of live heap bytes while a session checks a
//! generated file of realistic actions.

mod workload;

use linc_compiler::check::Context;
use linc_compiler::session::{CheckOptions, Session};
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
            let mut s = Session::new(Context { db: &db, resolve_blocks: true, steps: None });
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
        let mut s = Session::new(Context { db: &db, resolve_blocks: true, steps: None });
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
        let mut s = Session::compiling(Context { db: &db, resolve_blocks: true, steps: None });
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

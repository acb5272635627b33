//! Checking a sequence needs memory within ten times its text (issue 30): a
//! sequence of 100,000 steps (10 MB) peaked at 25 times its size, most of
//! it the whole file's tokens (40 bytes each), a Vec of four associations
//! per step, transitions of 240 bytes and a copy of each step name in every
//! table of the checks. A counting allocator measures the peak of live heap
//! bytes while `check_sequence` reads and checks generated rings.

mod workload;

use linc_compiler::sfc;
use linc_compiler::Context;
use linc_runtime::Database;
use linc_test_support::alloc::{peak_of, serial, Counting};

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most heap checking may need beyond the text, in multiples of it.
const FACTOR: usize = 10;

/// The peak of checking a ring of `n` steps, its size, and its codes.
fn check_ring(n: usize) -> (usize, usize, Vec<&'static str>) {
    let db = Database::from_json(include_str!("../../examples/sequences/plant.json")).expect("sequence example db");
    let src = workload::ring(n, "0.0");
    let mut codes = Vec::new();
    let peak = peak_of(|| {
        let report = sfc::check_sequence(&src, Context::of(Some(&db)));
        codes = report.diagnostics.iter().map(|d| d.code.as_str()).collect();
    });
    codes.dedup();
    eprintln!("{n} steps, {} bytes: peak {peak} ({:.1}x) {codes:?}", src.len(), peak as f64 / src.len() as f64);
    (peak, src.len(), codes)
}

/// The case: 100,000 steps (over the 32,767 a sequence may have,
/// so reported, but read and checked whole).
#[test]
fn a_sequence_of_100000_steps_checks_within_ten_times_its_size() {
    let _one = serial();
    let (peak, size, codes) = check_ring(100_000);
    assert_eq!(codes, ["E0214", "E0215"]);
    assert!(peak <= size * FACTOR, "peak heap {peak} bytes checking a {size}-byte sequence");
}

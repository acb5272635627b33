//! The compiling tier's size limit (ADR 0011, docs/semantics.md §24): a
//! block longer than `jit::MAX_BLOCK_OPS` instructions stays on the
//! interpreter, so `--tier auto` never spends more than one bounded
//! translation on a block, however large the action; a block within the
//! limit translates in time and memory linear in its size. A 2.5 MB action
//! (one loop around 40,000 assignments) took 28 s and 730 MB to translate
//! before the limit.

use linc_conformance::exec::compile;
use linc_conformance::gen::slow_to_translate;
use linc_conformance::guide_db;
use linc_runtime::jit::{self, MAX_BLOCK_OPS};
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Tier, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Linked, Program};
use linc_test_support::alloc::{allocations_in, peak_of, serial, Counting};

#[global_allocator]
static GLOBAL: Counting = Counting;

/// What `f` returns, the peak of live heap bytes beyond those live before
/// it, and the allocations it made: counted work, which no load on the
/// machine changes (callers hold [`serial`]).
fn measure<T>(f: impl FnOnce() -> T) -> (T, usize, usize) {
    let mut t = None;
    let ((), allocations) = allocations_in(|| {
        let peak = peak_of(|| t = Some(f()));
        PEAK.with(|p| p.set(peak));
    });
    (t.expect("ran"), PEAK.with(|p| p.get()), allocations)
}

thread_local! {
    static PEAK: std::cell::Cell<usize> = const { std::cell::Cell::new(0) };
}

struct Case {
    linked: Linked,
    ops: usize,
}

fn case(n: usize) -> Case {
    let verified = linc_runtime::load(&compile(&slow_to_translate(n), guide_db())).expect("loads");
    let store = Store::new(guide_db().clone());
    let linked = verified.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let ops = linked.ops(0, 0).map_or(0, <[_]>::len);
    Case { linked, ops }
}

/// The database after one run on `tier`, as text (so -0.0 differs from 0.0).
fn run(c: &Case, tier: Tier) -> String {
    let mut store = Store::new(guide_db().clone());
    let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
    vm.set_tier(tier);
    let mut act = Activation::new(&c.linked, 0, 0);
    vm.run(&c.linked, &mut act, &mut store, None).expect("runs");
    format!("{:?}", store.cells)
}

#[test]
fn a_block_over_the_limit_runs_on_the_interpreter_at_once() {
    let _one = serial();
    let c = case(700);
    assert!(c.ops > MAX_BLOCK_OPS, "{} instructions: not over the limit", c.ops);
    let store = Store::new(guide_db().clone());
    let (code, peak, allocations) = measure(|| jit::compile(&c.linked, &store, 0, 0));
    assert!(code.is_none(), "a block of {} instructions was translated", c.ops);
    // Refused before anything is built (translating it took seconds and
    // hundreds of megabytes before).
    assert!(peak < 1 << 16, "refusing took {peak} bytes");
    assert!(allocations < 16, "refusing made {allocations} allocations");
    let interpreted = run(&c, Tier::Interpreter);
    let auto = run(&c, Tier::Auto);
    assert_eq!(c.linked.compiled_blocks(), (0, 1), "the loop ran compiled");
    assert!(auto == interpreted, "--tier auto differs from the interpreter");
}

#[test]
fn a_block_within_the_limit_translates_in_linear_time_and_memory() {
    let _one = serial();
    let big = case(205);
    assert!(big.ops <= MAX_BLOCK_OPS && big.ops * 10 > MAX_BLOCK_OPS * 9, "{} instructions", big.ops);
    let small = case(51);
    let store = Store::new(guide_db().clone());
    let cost = |c: &Case| {
        let (code, peak, allocations) = measure(|| jit::compile(&c.linked, &store, 0, 0));
        assert!(code.is_some(), "a block of {} instructions was not translated", c.ops);
        (peak, allocations)
    };
    let ((small_peak, small_work), (big_peak, big_work)) = (cost(&small), cost(&big));
    let n = big.ops as f64 / small.ops as f64;
    let work = big_work as f64 / small_work as f64;
    let peak = big_peak as f64 / small_peak as f64;
    eprintln!(
        "{} → {} instructions: {small_work} → {big_work} allocations, peak {small_peak} → {big_peak} bytes",
        small.ops, big.ops
    );
    assert!(work < 2.0 * n, "{n:.1}× the instructions took {work:.1}× the allocations");
    assert!(peak < 2.0 * n, "{n:.1}× the instructions took {peak:.1}× the memory");
    assert!(run(&big, Tier::Compiled) == run(&big, Tier::Interpreter), "the tiers differ");
    assert_eq!(big.linked.compiled_blocks(), (1, 1));
}

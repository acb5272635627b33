//! Performance assumption as a test: running an action that touches no
//! strings allocates nothing on the heap (after the first run sized the stacks).
use linc_conformance::exec::compile;
use linc_conformance::guide_db;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::Program;
use linc_test_support::alloc::{allocations_in, Counting};

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn numeric_actions_do_not_allocate() {
    let src = "FOR TC001 := 0 TO 6 DO\n  Block_5.Val1{TC001} := Block_5.Val1{TC001 + 1} * 1.5 + Recipe.A0;\nEND_FOR;\nIF Dig_A.Out.Bit3 AND Recipe.N0 MOD 2 = 0 THEN Dig_B.Out.Bit0 := NOT Dig_B.Out.Bit0; END_IF;\nRecipe.N0 := Recipe.N0 + ROUND(SQRT(Recipe.A1 + 4.0)) + MAX(1, Recipe.N1, 3);\nANIN_005.Alarms.HiLevel.Suppress := 10;\n";
    let bytes = compile(src, guide_db());
    let verified = linc_runtime::load(&bytes).expect("loads");
    let mut store = Store::new(guide_db().clone());
    let linked = verified.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut act = Activation::new(&linked, 0, 0);
    let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
    vm.run(&linked, &mut act, &mut store, None).expect("runs");
    // The first run queued the loop's translation; once it is in, one more
    // run sizes the compiled tier's buffers.
    linked.settle_translations();
    vm.run(&linked, &mut act, &mut store, None).expect("runs");
    let ((), allocations) = allocations_in(|| {
        for _ in 0..100 {
            vm.run(&linked, &mut act, &mut store, None).expect("runs");
        }
    });
    assert_eq!(allocations, 0, "allocations in 100 runs");
}

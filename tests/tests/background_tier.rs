//! No run waits for a translation (ADR 0023): under `--tier auto` a block
//! due for compilation is translated on a background thread while the
//! interpreter goes on running it, and the runs after the code is ready use
//! it. The translation thread is held for the whole of this binary's one
//! test, so the runs that finish are counted, not timed: they cannot have
//! waited for a translation that could not start.

use linc_conformance::exec::compile;
use linc_conformance::gen::slow_to_translate;
use linc_conformance::guide_db;
use linc_runtime::jit::{self, MAX_BLOCK_OPS};
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Tier, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Linked, Program};

fn linked() -> Linked {
    let verified = linc_runtime::load(&compile(&slow_to_translate(205), guide_db())).expect("loads");
    let store = Store::new(guide_db().clone());
    verified.link(&store, &[Program { unit: 0, own: None }]).expect("links")
}

/// A plant's scans of the block, on one tier.
struct Scans {
    vm: Vm,
    act: Activation,
    store: Store,
}

impl Scans {
    fn new(linked: &Linked, tier: Tier) -> Scans {
        let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
        vm.set_tier(tier);
        Scans { vm, act: Activation::new(linked, 0, 0), store: Store::new(guide_db().clone()) }
    }

    /// The store after `runs` more runs, as text (so -0.0 differs from 0.0).
    fn run(&mut self, linked: &Linked, runs: usize) -> String {
        for _ in 0..runs {
            self.vm.run(linked, &mut self.act, &mut self.store, None).expect("runs");
        }
        format!("{:?}", self.store.cells)
    }
}

#[test]
fn scans_run_on_while_a_large_block_translates_then_use_its_code() {
    let linked = linked();
    let ops = linked.ops(0, 0).map_or(0, <[_]>::len);
    assert!(ops <= MAX_BLOCK_OPS && ops * 10 > MAX_BLOCK_OPS * 9, "{ops} instructions: not near the limit");
    let reference = self::linked();
    let mut interpreted = Scans::new(&reference, Tier::Interpreter);
    let mut auto = Scans::new(&linked, Tier::Auto);
    {
        let _hold = jit::hold();
        // The loop is due at its first run: queued, and every scan until
        // the code is in runs on the interpreter instead of waiting.
        assert_eq!(auto.run(&linked, 5), interpreted.run(&reference, 5));
        assert_eq!(linked.runs_behind_translation(0, 0), 5, "a scan waited for the translation");
        assert!(!linked.is_compiled(0, 0), "translated while held");
    }
    linked.settle_translations();
    assert!(linked.is_compiled(0, 0), "the block was not translated");
    // Once in, the code runs: no scan goes back to the interpreter for
    // want of it, and the results are the interpreter's.
    assert_eq!(auto.run(&linked, 5), interpreted.run(&reference, 5));
    assert_eq!(linked.runs_behind_translation(0, 0), 5, "a scan after the translation did not use it");
}

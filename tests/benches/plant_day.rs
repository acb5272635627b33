//! `cargo bench -p linc-conformance --bench plant_day`: a simulated plant
//! day of the example strategy (`examples/strategy/plant.json`: 864,000
//! scans of task 1, 86,400 of task 2), built once per run, on the
//! compiling tier and on the interpreter alone. Issue 12 asks for under one
//! second; prints the best of five runs each.

use linc_conformance::exec::compile;
use linc_engines::strategy::{wanted, Strategy};
use linc_runtime::vm::{Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Database, Store};
use std::time::Instant;

const DAY_US: u64 = 86_400_000_000;

fn day(jit: bool) -> f64 {
    let db = Database::from_json(include_str!("../../examples/strategy/plant.json")).expect("the example database");
    let store = Store::new(db.clone());
    let wants = wanted(&store);
    let files = [
        ("actions.stx", include_str!("../../examples/strategy/actions.stx")),
        ("modbus.stx", include_str!("../../examples/strategy/modbus.stx")),
    ];
    let objects: Vec<_> =
        files.iter().map(|(_, src)| linc_runtime::load(&compile(src, &db)).expect("the example loads")).collect();
    let pairs: Vec<_> = wants
        .iter()
        .map(|w| (w.clone(), files.iter().position(|(f, _)| *f == w.file).expect("a known file")))
        .collect();
    let mut vm = Vm::new(DEFAULT_WATCHDOG, Clock::new(1, 0));
    vm.jit = jit;
    let mut s = Strategy::build(store, objects, &pairs, vm, 1_767_592_800.0).expect("the strategy builds");
    let started = Instant::now();
    let errors = s.run_for(DAY_US, None);
    let secs = started.elapsed().as_secs_f64();
    assert!(errors.is_empty(), "{errors:?}");
    secs
}

fn main() {
    for (name, jit) in [("compiling tier", true), ("interpreter", false)] {
        let best = (0..5).map(|_| day(jit)).fold(f64::INFINITY, f64::min);
        println!("plant day ({name}): {best:.3} s for 864,000 + 86,400 scans (target < 1 s)");
    }
}

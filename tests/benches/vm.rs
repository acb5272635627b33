//! ST kernels on the VM beside the same kernel in plain Rust, in one run.
//!
//! Each kernel is an action from the guide's world run by `linc`'s VM
//! (compiled once, linked once; the measurement is `Vm::run`), and the same
//! computation written natively over the same data. After criterion's
//! measurements the bench prints the VM/native ratio of each kernel, on the
//! interpreter and on the compiling tier (ADR 0011), and what counting
//! coverage costs on each (ADR 0020).

use criterion::{criterion_group, Criterion};
use linc_conformance::exec::compile;
use linc_conformance::guide_db;
use linc_runtime::store::{Cell, Store};
use linc_runtime::vm::{Activation, Clock, Vm, DEFAULT_WATCHDOG};
use linc_runtime::{Linked, Program};
use std::hint::black_box;
use std::time::{Duration, Instant};

struct Kernel {
    name: &'static str,
    source: &'static str,
    native: fn() -> f64,
}

const N: i32 = 10_000;

fn native_int_branch() -> f64 {
    let mut acc: i32 = 0;
    for i in 1..=black_box(N) {
        if i % 3 == 0 {
            acc = acc.wrapping_add(i);
        } else {
            acc = acc.wrapping_sub(1);
        }
    }
    f64::from(acc)
}

fn native_poly() -> f64 {
    let (a2, a3, a4, a5, a6) = black_box((1.5f32, -2.0f32, 0.5f32, 3.0f32, -1.0f32));
    let mut x = black_box(0.0f32);
    let mut y = 0.0f32;
    for _ in 0..black_box(N) {
        y = (((a2 * x + a3) * x + a4) * x + a5) * x + a6;
        x += 0.001;
    }
    f64::from(y)
}

fn native_shift() -> f64 {
    let mut v = black_box([1.0f32, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0]);
    for k in 0..black_box(N / 8) {
        for i in 0..7 {
            v[i] = v[i + 1];
        }
        v[7] = k as f32;
    }
    f64::from(v[0])
}

fn native_strings() -> f64 {
    let mut s: Vec<u8> = Vec::new();
    for i in 1..=black_box(100) {
        s.extend_from_slice(format!("{i:05}").as_bytes());
    }
    s.len() as f64
}

const KERNELS: &[Kernel] = &[
    Kernel {
        name: "integer loop with a data-dependent branch",
        source: "Counters.N1 := 0;\nFOR Counters.N0 := 1 TO 10000 DO\n  IF Counters.N0 MOD 3 = 0 THEN Counters.N1 := Counters.N1 + Counters.N0;\n  ELSE Counters.N1 := Counters.N1 - 1; END_IF;\nEND_FOR;\n",
        native: native_int_branch,
    },
    Kernel {
        name: "real polynomial (Horner, degree 4)",
        source: "Recipe.A0 := 0;\nRecipe.A2 := 1.5; Recipe.A3 := -2.0; Recipe.A4 := 0.5; Recipe.A5 := 3.0; Recipe.A6 := -1.0;\nFOR Counters.N0 := 1 TO 10000 DO\n  Recipe.A1 := (((Recipe.A2 * Recipe.A0 + Recipe.A3) * Recipe.A0 + Recipe.A4) * Recipe.A0 + Recipe.A5) * Recipe.A0 + Recipe.A6;\n  Recipe.A0 := Recipe.A0 + 0.001;\nEND_FOR;\n",
        native: native_poly,
    },
    Kernel {
        name: "offset-array shift register (§12.12)",
        source: "FOR Counters.N1 := 0 TO 1249 DO\n  FOR TC001 := 0 TO 6 DO\n    Block_5.Val1{TC001} := Block_5.Val1{TC001 + 1};\n  END_FOR;\n  Block_5.Val1{7} := Counters.N1;\nEND_FOR;\n",
        native: native_shift,
    },
    Kernel {
        name: "string building with CONCAT/FORMAT",
        source: "RAW_COM.Buffer1 := '';\nFOR Counters.N0 := 1 TO 100 DO\n  RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, FORMAT('05I', Counters.N0));\nEND_FOR;\n",
        native: native_strings,
    },
];

struct Ready {
    linked: Linked,
    act: Activation,
    store: Store,
    vm: Vm,
}

fn ready(k: &Kernel, jit: bool) -> Ready {
    ready_as(k, jit, false)
}

/// A kernel ready to run, counting coverage when `covered`.
fn ready_as(k: &Kernel, jit: bool, covered: bool) -> Ready {
    let verified = linc_runtime::load(&compile(k.source, guide_db())).expect("kernel loads");
    let store = Store::new(guide_db().clone());
    let mut linked = verified.link(&store, &[Program { unit: 0, own: None }]).expect("kernel links");
    if covered {
        linked.enable_coverage();
    }
    let act = Activation::new(&linked, 0, 0);
    let mut vm = Vm::new(DEFAULT_WATCHDOG * 10, Clock::new(1, 0));
    vm.jit = jit;
    vm.jit_after = 0;
    Ready { linked, act, store, vm }
}

fn run_vm(r: &mut Ready) -> f64 {
    r.vm.run(&r.linked, &mut r.act, &mut r.store, None).expect("kernel runs");
    match r.store.cells.first() {
        Some(Cell::Real(x)) => f64::from(*x),
        _ => 0.0,
    }
}

fn bench(c: &mut Criterion) {
    for k in KERNELS {
        let mut g = c.benchmark_group(k.name);
        let mut r = ready(k, false);
        g.bench_function("linc VM", |b| b.iter(|| r.vm.run(&r.linked, &mut r.act, &mut r.store, None).map(|_| ())));
        let mut r = ready(k, true);
        g.bench_function("linc compiled", |b| {
            b.iter(|| r.vm.run(&r.linked, &mut r.act, &mut r.store, None).map(|_| ()))
        });
        let mut r = ready_as(k, false, true);
        g.bench_function("linc VM, coverage on", |b| {
            b.iter(|| r.vm.run(&r.linked, &mut r.act, &mut r.store, None).map(|_| ()))
        });
        let mut r = ready_as(k, true, true);
        g.bench_function("linc compiled, coverage on", |b| {
            b.iter(|| r.vm.run(&r.linked, &mut r.act, &mut r.store, None).map(|_| ()))
        });
        g.bench_function("native Rust", |b| b.iter(k.native));
        g.finish();
    }
}

/// Median time of `f` over several timed batches.
fn median(mut f: impl FnMut() -> f64) -> Duration {
    let mut times = Vec::new();
    for _ in 0..15 {
        let start = Instant::now();
        for _ in 0..20 {
            black_box(f());
        }
        times.push(start.elapsed() / 20);
    }
    times.sort();
    times[times.len() / 2]
}

fn ratios() {
    println!("\nVM / native, median of 15 × 20 runs:");
    for k in KERNELS {
        let mut r = ready(k, false);
        let vm = median(|| run_vm(&mut r));
        let mut r = ready(k, true);
        let start = Instant::now();
        let translated = linc_runtime::jit::compile(&r.linked, &r.store, 0, 0).is_some();
        let compile = start.elapsed();
        let compiled = median(|| run_vm(&mut r));
        let native = median(k.native);
        let ratio = |t: Duration| t.as_secs_f64() / native.as_secs_f64().max(1e-12);
        println!("  {:<45} VM {:>10.1?}  native {:>10.1?}  ratio {:>6.1}x", k.name, vm, native, ratio(vm));
        let how = if translated { format!("compiled in {compile:.1?}") } else { "not compiled: interpreter".into() };
        println!("  {:<45} compiled {:>10.1?}  ratio {:>6.1}x  ({how})", "", compiled, ratio(compiled));
        let mut r = ready_as(k, false, true);
        let vm_cov = median(|| run_vm(&mut r));
        let mut r = ready_as(k, true, true);
        let compiled_cov = median(|| run_vm(&mut r));
        let slower = |on: Duration, off: Duration| on.as_secs_f64() / off.as_secs_f64().max(1e-12);
        println!(
            "  {:<45} coverage on: VM {:>10.1?} ({:.2}x of off)  compiled {:>10.1?} ({:.2}x of off)",
            "",
            vm_cov,
            slower(vm_cov, vm),
            compiled_cov,
            slower(compiled_cov, compiled)
        );
    }
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
    ratios();
}

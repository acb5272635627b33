//! ST kernels on the VM beside the same kernel in plain Rust, in one run.
//!
//! Each kernel is one of issue 30's four (`tests/perf/kernels`, with fewer
//! turns) run by `linc`'s VM
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
    /// The action of `tests/perf/kernels` (as `linc run` times it, the
    /// issue-30 kernels), with its loop count cut to `turns`.
    file: &'static str,
    turns: (&'static str, &'static str),
    native: fn() -> f64,
}

impl Kernel {
    /// The action's statements: the lines between its header and trailer.
    fn source(&self) -> String {
        let body: Vec<&str> = self
            .file
            .lines()
            .skip_while(|l| !l.starts_with("ACTION"))
            .skip(1)
            .take_while(|l| !l.starts_with("END_ACTION"))
            .collect();
        body.join("\n").replace(self.turns.0, self.turns.1) + "\n"
    }
}

/// Turns of each kernel's loop here (the whole-process runs do 10
/// million, or 100,000 rounds of strings).
const N: i32 = 10_000;

/// The native equivalents do what LIN's semantics make the ST do (as
/// `tests/perf/native/*.rs` do): 32-bit wrapping INT arithmetic, every
/// REAL stored checked to be finite, checked indexing.
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

fn finite(x: f32) -> f32 {
    if !x.is_finite() {
        std::process::abort();
    }
    x
}

fn native_poly() -> f64 {
    let (mut x, mut y) = (black_box(0.0f32), 0.0f32);
    for _ in 0..black_box(N) {
        y = finite((((1.5 * x - 2.0) * x + 0.5) * x + 3.0) * x - 1.0);
        x = finite(x + 0.001);
    }
    f64::from(y)
}

fn native_shift() -> f64 {
    let mut v = black_box([0.0f32; 8]);
    let top = black_box(7usize);
    for _ in 0..black_box(N) {
        let mut i = top;
        while i >= 1 {
            v[i] = finite(v[i - 1]);
            i -= 1;
        }
        v[0] = finite(v[7] * 0.5 + 1.0);
    }
    f64::from(v[0])
}

fn native_strings() -> f64 {
    fn concat(a: &[u8], b: &[u8]) -> Vec<u8> {
        let mut out = Vec::with_capacity((a.len() + b.len()).min(65_535));
        out.extend_from_slice(a);
        out.extend_from_slice(&b[..b.len().min(65_535 - a.len().min(65_535))]);
        out
    }
    let mut u: Vec<u8> = black_box(b"[M01G0DI*01C5E5$R".to_vec());
    let mut n: i32 = 0;
    for _ in 0..black_box(N / 10) {
        let t = concat(u.get(..4).unwrap_or(b""), b"ab");
        u = concat(&t, t.len().checked_sub(2).map_or(&b""[..], |s| &t[s..]));
        n = n.wrapping_add(u.len() as i32);
    }
    f64::from(n)
}

const KERNELS: &[Kernel] = &[
    Kernel {
        name: "integer loop with a data-dependent branch",
        file: include_str!("../perf/kernels/int.stx"),
        turns: ("10000000", "10000"),
        native: native_int_branch,
    },
    Kernel {
        name: "real polynomial (Horner, degree 4)",
        file: include_str!("../perf/kernels/poly.stx"),
        turns: ("10000000", "10000"),
        native: native_poly,
    },
    Kernel {
        name: "offset-array shift register (§12.12)",
        file: include_str!("../perf/kernels/shift.stx"),
        turns: ("10000000", "10000"),
        native: native_shift,
    },
    Kernel {
        name: "string building with LEFT/RIGHT/CONCAT/LEN",
        file: include_str!("../perf/kernels/strings.stx"),
        turns: ("100000", "1000"),
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
    let verified = linc_runtime::load(&compile(&k.source(), guide_db())).expect("kernel loads");
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

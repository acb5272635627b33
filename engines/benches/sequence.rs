//! Scans per second of a 50-step sequence, engine only: a ring of 50 steps,
//! each with an N action and a P action, whose transitions fire every other
//! scan; the host's code does nothing, so the figure is the engine's own.
//! Beside it, the same bookkeeping written directly in Rust (a baseline).
use criterion::{criterion_group, Criterion};
use linc_engines::sequence::chart::{Action, Assoc, Body, Chart, Step, Transition};
use linc_engines::sequence::engine::Host;
use linc_engines::sequence::{Command, Sequence};
use linc_engines::strategy::qualifier::Qualifier;
use linc_runtime::errors::RuntimeError;
use std::hint::black_box;
use std::time::Instant;

const STEPS: usize = 50;

struct Flip {
    scans: u64,
    ran: u64,
}

impl Host for Flip {
    fn condition(&mut self, _code: usize) -> Result<bool, RuntimeError> {
        Ok(self.scans % 2 == 1)
    }
    fn action(&mut self, _code: usize) -> Result<(), RuntimeError> {
        self.ran += 1;
        Ok(())
    }
}

fn ring() -> Sequence {
    let assoc = |action, qualifier| Assoc { action, qualifier, time_us: 0 };
    let steps = (0..STEPS)
        .map(|i| Step {
            name: format!("S{i}"),
            initial: i == 0,
            slot: i,
            assocs: vec![assoc(0, Qualifier::N), assoc(1, Qualifier::P)],
        })
        .collect();
    let transitions = (0..STEPS)
        .map(|i| Transition {
            name: format!("T{i}"),
            from: vec![i],
            to: vec![(i + 1) % STEPS],
            priority: None,
            code: i,
        })
        .collect();
    let actions =
        vec![Action { name: "work".into(), body: Body::Code(0) }, Action { name: "enter".into(), body: Body::Code(1) }];
    let mut seq = Sequence::new(Chart { steps, transitions, actions });
    seq.command(Command::Run);
    seq
}

fn scans(seq: &mut Sequence, host: &mut Flip, n: u64) {
    for _ in 0..n {
        host.scans += 1;
        let _ = seq.scan(host.scans * 100_000, host);
    }
}

/// The same ring in plain Rust: one active step, a toggle, two counters.
fn native(n: u64) -> u64 {
    let (mut active, mut ran, mut elapsed) = (0usize, 0u64, 0u64);
    for scan in 1..=n {
        elapsed += 100_000;
        if scan % 2 == 1 {
            active = (active + 1) % STEPS;
            elapsed = 0;
            ran += 1;
        }
        ran += 1;
    }
    black_box(active as u64 + elapsed) + ran
}

fn bench(c: &mut Criterion) {
    let mut g = c.benchmark_group("50-step sequence, 1,000 scans");
    let mut seq = ring();
    let mut host = Flip { scans: 0, ran: 0 };
    g.bench_function("engine", |b| b.iter(|| scans(&mut seq, &mut host, 1_000)));
    g.bench_function("native Rust", |b| b.iter(|| native(black_box(1_000))));
    g.finish();
    let n = 2_000_000;
    let start = Instant::now();
    scans(&mut seq, &mut host, n);
    let secs = start.elapsed().as_secs_f64();
    println!("50-step sequence: {:.0} scans per second ({n} scans in {secs:.2} s)", n as f64 / secs);
}

criterion_group!(benches, bench);

fn main() {
    benches();
    Criterion::default().configure_from_args().final_summary();
}

//! Front-end throughput on generated action files of about 5 MB.
//!
//! Measures lexing alone, lex + parse, and the whole of `linc check`'s work
//! (lex, parse, resolve against the guide database, type check), beside a
//! native-Rust baseline that only walks the bytes (counting lines), so the
//! figures say how far the front end is from memory speed.
//!
//! A second group checks files of realistic actions (`tests/workload.rs`:
//! about 1 KB each, with IF/ELSIF/ELSE, FOR, WHILE, calls and comments) at
//! 1.25 MB and 5 MB (about 5,000 actions) through a compile session, as
//! `linc check` does; the two sizes show whether time grows linearly.
//!
//! The generated inputs are also written to `target/check-bench.st`,
//! `target/check-actions-1.25M.st` and `target/check-actions-5M.st` so that
//! the CLI can be timed on the same text.

#[path = "../tests/workload.rs"]
mod workload;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::Database;
use std::hint::black_box;

const TARGET_BYTES: usize = 5 * 1024 * 1024;

/// Realistic statements over the guide database, varied by a counter, in
/// actions of 100 blocks (an action has at most 254 FOR loops).
fn generate() -> String {
    let mut out = String::with_capacity(TARGET_BYTES + 4096);
    let mut i = 0u32;
    while out.len() < TARGET_BYTES {
        let n = i % 7;
        if i.is_multiple_of(100) {
            if i > 0 {
                out.push_str("END_ACTION\n");
            }
            out.push_str(&format!("ACTION B{}\n", i / 100));
        }
        out.push_str(&format!(
            "(* block {i} *)\nIF PIC_004.PV < {i}.5 AND Dig_A.Out.Bit{n} THEN\n    TIC_100.SL := REC1.A{n} * 1.5 + (Block_5.PV - {i}) / Const.A7;\n    Dig_B.Out.Bit{n} := NOT Dig_A.Out.Bit{n} OR (PIC_005.PV > 30);\nELSIF Recipe.N{n} MOD 3 = 0 THEN\n    Raw1.I2 := CRC(Raw1.Tx_Value, 1, 16#8005, 16#FFFF);\nELSE\n    PIC_004.Mode := \"AUTO\";\nEND_IF;\nFOR Counters.N0 := 0 TO 6 DO\n    Block_5.Val1{{Counters.N0}} := Block_5.Val1{{Counters.N0 + 1}} + T#1m30s;\nEND_FOR;\n"
        ));
        i += 1;
    }
    out.push_str("END_ACTION\n");
    out
}

fn bench(c: &mut Criterion) {
    let src = generate();
    let _ = std::fs::create_dir_all("../target");
    let _ = std::fs::write("../target/check-bench.st", &src);
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide database");
    let ctx = Context::of(Some(&db));
    let clean = linc_compiler::check_source(&src, "bench", ctx);
    assert!(clean.diagnostics.is_empty(), "generated input must check clean: {:?}", clean.diagnostics.first());

    let mut g = c.benchmark_group("check");
    g.throughput(Throughput::Bytes(src.len() as u64));
    g.sample_size(10);
    g.bench_function("baseline: count lines (native)", |b| {
        b.iter(|| black_box(&src).bytes().filter(|&b| b == b'\n').count())
    });
    g.bench_function("lex", |b| b.iter(|| linc_compiler::st::lexer::lex(black_box(&src)).0.len()));
    g.bench_function("lex + parse", |b| {
        b.iter(|| linc_compiler::st::parser::parse_file(black_box(&src), "bench").0.map(|f| f.actions.len()))
    });
    g.bench_function("check (lex + parse + resolve + types)", |b| {
        b.iter(|| linc_compiler::check_source(black_box(&src), "bench", ctx).diagnostics.len())
    });
    g.finish();
}

/// Checks `src` as `linc check` does: one session, actions checked as read.
fn session_check(ctx: Context, src: &str) -> usize {
    let mut s = Session::new(ctx);
    let id = s.add("bench.st", src.as_bytes().to_vec());
    s.check(id, CheckOptions::default()).diagnostics.len()
}

fn bench_actions(c: &mut Criterion) {
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide database");
    let ctx = Context::of(Some(&db));
    let mut g = c.benchmark_group("check actions");
    g.sample_size(10);
    for (name, bytes) in [("1.25M", 5 * 1024 * 1024 / 4), ("5M", 5 * 1024 * 1024)] {
        let src = workload::actions(bytes);
        let _ = std::fs::write(format!("../target/check-actions-{name}.st"), &src);
        assert_eq!(session_check(ctx, &src), 0, "generated actions must check clean");
        g.throughput(Throughput::Bytes(src.len() as u64));
        g.bench_function(format!("session check, {name}"), |b| b.iter(|| session_check(ctx, black_box(&src))));
    }
    g.finish();
}

criterion_group!(benches, bench, bench_actions);
criterion_main!(benches);

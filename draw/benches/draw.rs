//! Drawing a 1,000-step chart (layout and SVG) beside a native baseline
//! in the same run: a plain loop writing the same number of step boxes,
//! labels and transition bars as SVG text, with no layout. The difference
//! is what the layout costs.

use criterion::{criterion_group, criterion_main, Criterion};
use std::fmt::Write;

#[path = "../tests/long_chart.rs"]
mod long_chart;

fn baseline(n: usize) -> String {
    let mut s = String::with_capacity(n * 400);
    for i in 0..n {
        let y = i as f64 * 96.0;
        let _ = writeln!(s, "<g id=\"step-S{i}\" class=\"step\">");
        let _ = writeln!(s, "<rect x=\"40\" y=\"{y}\" width=\"80\" height=\"32\" class=\"box\"/>");
        let _ = writeln!(s, "<text x=\"80\" y=\"{}\" text-anchor=\"middle\">S{i}</text>", y + 20.0);
        let _ = writeln!(s, "<rect x=\"136\" y=\"{y}\" width=\"24\" height=\"22\" class=\"box\"/>");
        let _ = writeln!(s, "<text x=\"170\" y=\"{}\">A{i}</text>\n</g>", y + 14.0);
        let _ = writeln!(s, "<g id=\"trans-{i}\" class=\"transition\">");
        let _ = writeln!(s, "<line x1=\"70\" y1=\"{0}\" x2=\"90\" y2=\"{0}\" class=\"bar\"/>", y + 64.0);
        let _ = writeln!(s, "<text x=\"100\" y=\"{}\">S{i}.T &gt; 1.0</text>\n</g>", y + 68.0);
        let _ = writeln!(s, "<line x1=\"80\" y1=\"{}\" x2=\"80\" y2=\"{}\" class=\"wire\"/>", y + 32.0, y + 96.0);
    }
    s
}

fn bench(c: &mut Criterion) {
    let src = long_chart::long_chart(1000);
    let (seq, d) = linc_compiler::sfc::parser::parse(&src);
    assert!(d.is_empty());
    let mut g = c.benchmark_group("draw 1,000-step chart");
    g.sample_size(20);
    g.bench_function("linc draw (layout + SVG)", |b| b.iter(|| linc_draw::sfc::sequence(&src, &seq, None).0.len()));
    g.bench_function("native: the same elements written with no layout", |b| b.iter(|| baseline(1000).len()));
    g.finish();
    // Four times the chart: the layout's growth (it should be about 4×).
    let src = long_chart::long_chart(4000);
    let (seq, _) = linc_compiler::sfc::parser::parse(&src);
    let mut g = c.benchmark_group("draw 4,000-step chart");
    g.sample_size(10);
    g.bench_function("linc draw (layout + SVG)", |b| b.iter(|| linc_draw::sfc::sequence(&src, &seq, None).0.len()));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);

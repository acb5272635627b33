//! Layout properties over random pictures: 500 random charts (with
//! selective and simultaneous branches, loops, long jumps and chart
//! actions), 500 random ladder files and 500 random FST tables, each read
//! by the real front end and drawn. In every picture no two boxes, action
//! blocks or labels overlap and every link joins its two ends with drawn
//! wire (a long sequence link joins its source to a connector naming its
//! target). And a 1,000-step chart draws quickly (under 2 s in this debug
//! test; the release benchmark, `benches/draw.rs`, is in the README) and
//! 4,000 steps take about four times as long.

mod long_chart;
mod support;

use long_chart::long_chart;

use linc_compiler::{fst, ladder, sfc};
use linc_test_support::alloc::{allocations_in, Counting};
use linc_test_support::work::{growth, thread_cpu};

#[global_allocator]
static A: Counting = Counting;
use linc_test_support::rng::Rng;
use std::fmt::Write;

const CASES: u64 = 500;

fn name(rng: &mut Rng, prefix: &str, i: usize) -> String {
    let pad = "x".repeat(rng.below(12));
    format!("{prefix}{i}{pad}")
}

/// A random chart as `.sfc` text: steps S0…, transitions between random
/// sets of them, some priorities, actions with qualifiers and times, and
/// now and then a chart action of its own.
fn chart(rng: &mut Rng, prefix: &str, out: &mut String, actions: &mut Vec<String>, depth: usize) {
    let n = 1 + rng.below(if depth == 0 { 14 } else { 4 });
    let steps: Vec<String> = (0..n).map(|i| name(rng, &format!("{prefix}S"), i)).collect();
    for (i, s) in steps.iter().enumerate() {
        let kw = if i == 0 { "INITIAL_STEP" } else { "STEP" };
        let _ = write!(out, "{kw} {s}: ");
        for k in 0..rng.below(3) {
            let a = format!("{s}A{k}");
            let q = ["N", "P", "S", "R", "L", "D", "E", "F"][rng.below(8)];
            if matches!(q, "L" | "D") {
                let _ = write!(out, "{a}({q}, T#{}s); ", 1 + rng.below(60));
            } else {
                let _ = write!(out, "{a}({q}); ");
            }
            if depth == 0 && rng.one_in(12) {
                let mut sub = String::new();
                chart(rng, &format!("{a}_"), &mut sub, actions, depth + 1);
                actions.push(format!("ACTION {a} : CHART\n{sub}END_ACTION\n"));
            } else {
                actions.push(format!("ACTION {a}\n    X.Y := 1;\nEND_ACTION\n"));
            }
        }
        out.push_str("END_STEP\n");
    }
    let pick = |rng: &mut Rng| {
        let k = 1 + if rng.one_in(4) { rng.below(3) } else { 0 };
        let mut v: Vec<&String> = (0..k).map(|_| &steps[rng.below(steps.len())]).collect();
        v.sort();
        v.dedup();
        v
    };
    let list = |v: &[&String]| {
        if v.len() == 1 {
            v[0].clone()
        } else {
            format!("({})", v.iter().map(|s| s.as_str()).collect::<Vec<_>>().join(", "))
        }
    };
    for t in 0..rng.below(n * 2 + 1) {
        let (from, to) = (pick(rng), pick(rng));
        let named = if rng.one_in(2) { format!(" {prefix}T{t}") } else { String::new() };
        let prio = if rng.one_in(3) { format!(" (PRIORITY := {})", rng.below(9)) } else { String::new() };
        let cond = "A.B > 1.0 AND C.D < 2.0 OR E.F = 3".repeat(1 + rng.below(2));
        let _ =
            writeln!(out, "TRANSITION{named}{prio} FROM {} TO {} := {cond}; END_TRANSITION", list(&from), list(&to));
    }
}

#[test]
fn random_charts_lay_out_cleanly() {
    let mut rng = Rng::new(17);
    for case in 0..CASES {
        let mut src = String::new();
        let mut actions = Vec::new();
        chart(&mut rng, "", &mut src, &mut actions, 0);
        actions.sort();
        actions.dedup_by(|a, b| a.lines().next() == b.lines().next());
        for a in &actions {
            src.push_str(a);
        }
        let (seq, _) = sfc::parser::parse(&src);
        let (svg, geo) = linc_draw::sfc::sequence(&src, &seq, None);
        assert!(geo.overlap().is_none(), "case {case}: {:?}\n{src}", geo.overlap());
        assert!(geo.broken_link().is_none(), "case {case}: {:?}\n{src}", geo.broken_link());
        // Every link of the source is drawn: directly, or to a connector naming its end.
        let links = seq.chart.transitions.iter().map(|t| t.from.len() + t.to.len()).sum::<usize>();
        assert!(geo.links.len() >= links, "case {case}");
        for (jump, text, target) in &geo.connectors {
            assert!(geo.links.iter().any(|l| &l.to == jump), "case {case}: {jump} is joined");
            assert!(geo.nodes.iter().any(|(n, _)| n == target), "case {case}: {text} names a node");
        }
        if case % 50 == 0 {
            let els = support::elements(&svg);
            // Each chart action here is named by one step and drawn once, beside it.
            let nested: usize = seq
                .actions
                .iter()
                .map(|a| match &a.body {
                    sfc::ast::ActionBody::Chart(c) => c.steps.len(),
                    sfc::ast::ActionBody::St(_) => 0,
                })
                .sum();
            let steps = support::groups(&els, "step-", "step");
            assert_eq!(steps.len(), seq.chart.steps.len() + nested, "case {case}");
        }
    }
}

fn cond(rng: &mut Rng, depth: usize) -> String {
    match if depth > 2 { 0 } else { rng.below(5) } {
        0 | 1 => {
            let x = format!("B{}.{}", rng.below(9), "F".repeat(1 + rng.below(8)));
            if rng.one_in(2) {
                format!("[{x}]")
            } else {
                format!("[/{x}]")
            }
        }
        2 => (0..2 + rng.below(2)).map(|_| cond(rng, depth + 1)).collect::<Vec<_>>().join(" "),
        3 => format!("({})", (0..2 + rng.below(2)).map(|_| cond(rng, depth + 1)).collect::<Vec<_>>().join(" | ")),
        _ => {
            let op = ["AND", "OR", "XOR"][rng.below(3)];
            format!("{op}({})", (0..2 + rng.below(2)).map(|_| cond(rng, depth + 1)).collect::<Vec<_>>().join(", "))
        }
    }
}

#[test]
fn random_rungs_lay_out_cleanly() {
    let mut rng = Rng::new(23);
    for case in 0..CASES {
        let mut src = String::new();
        let rungs = 1 + rng.below(8);
        for i in 0..rungs {
            if rng.one_in(4) {
                let _ = write!(src, "L{i}: ");
            }
            let c = if rng.one_in(8) { String::new() } else { cond(&mut rng, 0) };
            let out = match rng.below(6) {
                0 => "(Q.Out)".to_string(),
                1 => "(/Q.Out)".to_string(),
                2 => "(S Q.Out)".to_string(),
                3 => "(R Q.Out)".to_string(),
                4 => format!("JUMP L{}", rungs),
                _ => "Q.PV := Q.PV + 1.5".to_string(),
            };
            let _ = writeln!(src, "{c} -> {out};");
        }
        let _ = writeln!(src, "L{rungs}: -> Z.PV := 0;");
        let (file, d) = ladder::parser::parse(&src, "random");
        assert!(d.is_empty(), "case {case}: {d:?}\n{src}");
        let (_, geo) = linc_draw::ladder::file(&src, &file.actions, None, None);
        assert!(geo.overlap().is_none(), "case {case}: {:?}\n{src}", geo.overlap());
        assert!(geo.broken_link().is_none(), "case {case}: {:?}\n{src}", geo.broken_link());
        assert_eq!(geo.links.len(), rungs + 1, "case {case}");
    }
}

#[test]
fn random_tables_lay_out_cleanly() {
    let mut rng = Rng::new(29);
    for case in 0..CASES {
        let n = 1 + rng.below(40);
        let labels: Vec<String> = (0..n).map(|i| format!("L{i}")).collect();
        let mut src = String::from("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n");
        for i in 0..n {
            let label = if rng.one_in(3) { labels[i].as_str() } else { "" };
            let target = &labels[rng.below(n)];
            let (cmd, a1, a2) = match rng.below(6) {
                0 => ("VAL", "1".to_string(), String::new()),
                1 => (">=", "2".to_string(), target.clone()),
                2 => ("GO", target.clone(), String::new()),
                3 => ("CT", "1".to_string(), target.clone()),
                4 if i + 1 == n => ("END", String::new(), String::new()),
                _ => ("+", "1.5".to_string(), String::new()),
            };
            let _ = writeln!(src, "{i},{label},{cmd},{a1},{a2},{}", "c".repeat(rng.below(20)));
        }
        let (table, _) = fst::reader::read(&src);
        let (_, geo) = linc_draw::fst::table(&table, None);
        assert!(geo.overlap().is_none(), "case {case}: {:?}\n{src}", geo.overlap());
        assert!(geo.broken_link().is_none(), "case {case}: {:?}\n{src}", geo.broken_link());
    }
}

/// Drawing is linear in the chart, in counted work: the allocations a
/// drawing makes (every box, label and wire is built once) grow as the
/// steps do, whatever the machine is doing. Its processor time
/// (`linc_test_support::work`) is bounded too, and printed.
#[test]
fn a_thousand_step_chart_draws_quickly_and_linearly() {
    let charts: Vec<(String, usize)> = [1000, 4000].iter().map(|&n| (long_chart(n), n)).collect();
    let work = |(src, n): &(String, usize)| {
        let (seq, d) = sfc::parser::parse(src);
        assert!(d.is_empty());
        let (((svg, geo), took), allocations) =
            allocations_in(|| thread_cpu(|| linc_draw::sfc::sequence(src, &seq, None)));
        assert!(geo.broken_link().is_none());
        assert_eq!(svg.matches("class=\"step\"").count(), *n);
        // The loop back is longer than a lane: a connector named S0.
        assert!(geo.connectors.iter().any(|c| c.1 == "S0"));
        (took, allocations)
    };
    let (small, large) = (work(&charts[0]), work(&charts[1]));
    let counted = large.1 as f64 / small.1 as f64;
    assert!(counted < 5.0, "4x the steps made {counted:.2}x the allocations ({} then {})", small.1, large.1);
    // Debug builds are several times slower than the release figure in the README.
    assert!(small.0.as_millis() < 2000, "1,000 steps took {:?} of work", small.0);
    let r = growth(|big| work(&charts[usize::from(big)]).0);
    eprintln!("1,000 → 4,000 steps: {counted:.2}x the allocations, {r:.1}x the processor time");
}

//! Every example sequence, ladder file and FST table drawn: an insta
//! snapshot of the SVG, read back as XML, with one `step-*` group a step,
//! one `trans-*` a transition, one `rung-*` a rung and one `fst-step-*` a
//! table row; and a layout with nothing overlapping and every link joined.

mod support;

use linc_compiler::{fst, ladder, sfc};
use std::path::Path;

fn read(p: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples").join(p)).unwrap()
}

fn sequence(file: &str) {
    let src = read(file);
    let (seq, d) = sfc::parser::parse(&src);
    assert!(d.is_empty(), "{d:?}");
    let (svg, geo) = linc_draw::sfc::sequence(&src, &seq, None);
    let els = support::elements(&svg);
    let mut steps = seq.chart.steps.len();
    let mut transitions = seq.chart.transitions.len();
    for a in &seq.actions {
        if let sfc::ast::ActionBody::Chart(c) = &a.body {
            steps += c.steps.len();
            transitions += c.transitions.len();
        }
    }
    assert_eq!(support::groups(&els, "step-", "step").len(), steps, "{file}");
    assert_eq!(support::groups(&els, "trans-", "transition").len(), transitions, "{file}");
    assert!(geo.overlap().is_none(), "{file}: {:?}", geo.overlap());
    assert!(geo.broken_link().is_none(), "{file}: {:?}", geo.broken_link());
    insta::assert_snapshot!(file.replace(['/', '.'], "_"), svg);
}

/// Every `.sfc` under `examples/`, with its path.
fn charts(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let path = e.unwrap().path();
        if path.is_dir() {
            charts(&path, out);
        } else if path.extension().is_some_and(|x| x == "sfc") {
            out.push(path);
        }
    }
}

/// A selective branch's wire that runs through (or ends on) a simultaneous
/// branch's double bar reads as if it led into the parallel branch: in the
/// batch chart, the `Abort` link ran down through the double bar of `Full`.
#[test]
fn no_other_wire_meets_a_double_bar_in_any_example_chart() {
    let mut files = Vec::new();
    charts(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples"), &mut files);
    assert!(files.len() >= 2, "{files:?}");
    let mut bars = 0;
    for f in files {
        let src = std::fs::read_to_string(&f).unwrap();
        let (seq, _) = sfc::parser::parse(&src);
        let (_, geo) = linc_draw::sfc::sequence(&src, &seq, None);
        bars += geo.doubles.len();
        assert_eq!(geo.through_double(), None, "{}", f.display());
    }
    assert!(bars >= 2, "the examples have simultaneous branches");
}

#[test]
fn batch_sequence() {
    sequence("sequences/batch.sfc");
}

#[test]
fn generic_sequence() {
    sequence("sequences/generic.sfc");
}

#[test]
fn ladder_example() {
    let src = read("ladder/interlock.ld");
    let (file, d) = ladder::parser::parse(&src, "interlock");
    assert!(d.is_empty(), "{d:?}");
    let (svg, geo) = linc_draw::ladder::file(&src, &file.actions, None, None);
    let els = support::elements(&svg);
    let rungs: usize = file.actions.iter().map(|a| a.rungs.len()).sum();
    let ids = support::groups(&els, "rung-", "rung");
    assert_eq!(ids.len(), rungs);
    assert_eq!(ids.first(), Some(&"rung-1"));
    assert!(geo.overlap().is_none(), "{:?}", geo.overlap());
    assert!(geo.broken_link().is_none(), "{:?}", geo.broken_link());
    assert_eq!(geo.links.len(), rungs);
    insta::assert_snapshot!("ladder_interlock_ld", svg);
}

#[test]
fn fst_examples() {
    for name in ["pump", "branching", "alarm", "history"] {
        let src = read(&format!("fst/{name}.csv"));
        let (table, d) = fst::reader::read(&src);
        assert!(d.is_empty(), "{d:?}");
        let (svg, geo) = linc_draw::fst::table(&table, None);
        let els = support::elements(&svg);
        let has_end = table.rows.iter().any(|r| r.cmd.text.eq_ignore_ascii_case("END"));
        let boxes = support::groups(&els, "fst-step-", "fst-step");
        assert_eq!(boxes.len(), table.rows.len() + usize::from(!has_end), "{name}");
        assert!(geo.overlap().is_none(), "{name}: {:?}", geo.overlap());
        assert!(geo.broken_link().is_none(), "{name}: {:?}", geo.broken_link());
        // Every branch to a label is a link of its own.
        let branches = table
            .rows
            .iter()
            .filter(|r| {
                [&r.arg1, &r.arg2].iter().any(|a| {
                    a.as_ref().is_some_and(|c| {
                        table
                            .rows
                            .iter()
                            .any(|t| t.label.as_ref().is_some_and(|l| l.text.eq_ignore_ascii_case(&c.text)))
                    })
                })
            })
            .count();
        let jumps = geo.links.iter().filter(|l| l.path.len() == 4 && l.path[1].x > l.path[0].x).count();
        assert_eq!(jumps, branches, "{name}");
        insta::assert_snapshot!(format!("fst_{name}_csv"), svg);
    }
}

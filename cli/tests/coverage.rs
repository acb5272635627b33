//! `linc test --coverage`: each example's coverage pinned (read back by
//! the independent `lcov` parser), the Cobertura file validated against its
//! DTD by xmllint, the lcov file rendered by genhtml, and a branch moving
//! from missed to hit when a scenario takes it.
mod common;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Runs `linc test ARGS --coverage FORMAT -o OUT` in the repository root.
fn covered(args: &[&str], format: &str, out: &Path) -> std::process::Output {
    let out = out.to_string_lossy().into_owned();
    let mut all: Vec<&str> = vec!["test"];
    all.extend(args);
    all.extend(["--coverage", format, "-o", &out]);
    common::linc(&all)
}

/// What a report says of each file, as the `lcov` crate reads it: lines,
/// branch outcomes and functions hit of all, and by what the file holds —
/// steps entered and transitions fired (sequences), rung outcomes (ladder),
/// FST steps executed and branch outcomes (FST tables).
fn pinned(text: &str) -> String {
    let report = lcov::Report::from_reader(lcov::Reader::new(text.as_bytes())).expect("the lcov crate reads it");
    let mut out = String::new();
    for (key, file) in &report.sections {
        let path = key.source_file.display().to_string();
        let hit = |n: usize, of: usize| format!("{n}/{of}");
        let lines = hit(file.lines.values().filter(|l| l.count > 0).count(), file.lines.len());
        let taken = file.branches.values().filter(|b| b.taken.is_some_and(|t| t > 0)).count();
        let branches = hit(taken, file.branches.len());
        let named = |prefix: &str| {
            let f: Vec<_> = file.functions.iter().filter(|(k, _)| k.name.starts_with(prefix)).collect();
            hit(f.iter().filter(|(_, v)| v.count > 0).count(), f.len())
        };
        let what = match Path::new(&path).extension().and_then(|e| e.to_str()) {
            Some("sfc") => format!("steps entered {}, transitions fired {}", named("step "), named("transition ")),
            Some("ld") => format!("rung outcomes {branches}"),
            Some("csv") => format!("FST steps executed {lines}, FST branch outcomes {branches}"),
            _ => format!("actions run {}", named("")),
        };
        out.push_str(&format!("{path}: lines {lines}, branch outcomes {branches}; {what}\n"));
    }
    out
}

#[test]
fn every_example_s_coverage_is_pinned() {
    let dir = linc_test_support::fresh_dir("coverage-examples");
    let mut all = String::new();
    for example in ["fst", "ladder", "sequences", "strategy"] {
        let scenarios: Vec<PathBuf> =
            std::fs::read_dir(format!("{}/../examples/{example}", env!("CARGO_MANIFEST_DIR")))
                .expect("example dir")
                .flatten()
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|e| e == "ltest"))
                .collect();
        assert!(!scenarios.is_empty(), "{example} has scenarios");
        let info = dir.join(format!("{example}.info"));
        let o = covered(&[&format!("examples/{example}")], "lcov", &info);
        assert_eq!(o.status.code(), Some(0), "{}{}", common::stdout(&o), common::stderr(&o));
        let text = std::fs::read_to_string(&info).expect("the report is written");
        all.push_str(&format!("== examples/{example}\n{}", pinned(&text)));
    }
    insta::assert_snapshot!("example_coverage", all);
}

#[test]
fn the_summary_prints_a_table_per_file_with_totals() {
    let o = common::linc(&["test", "examples/ladder", "--coverage", "summary"]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let text = common::stdout(&o);
    let table = &text[text.find("Filename").expect("a table")..];
    insta::assert_snapshot!("ladder_summary", table);
    // lcov and cobertura need a file; -o alone means nothing.
    let o = common::linc(&["test", "examples/ladder", "--coverage", "lcov"]);
    assert_eq!(o.status.code(), Some(2), "{}", common::stderr(&o));
    let o = common::linc(&["test", "examples/ladder", "-o", "x.info"]);
    assert_eq!(o.status.code(), Some(2), "{}", common::stderr(&o));
    let o = common::linc(&["test", "examples/ladder", "--coverage", "html"]);
    assert_eq!(o.status.code(), Some(2), "{}", common::stderr(&o));
}

/// `--fail-under-*` fails the run (E0913, exit 1) when a share is under
/// its threshold, as `cargo llvm-cov` does; the ladder example covers 100%
/// of functions, 62.50% of lines and 58.33% of branch outcomes.
#[test]
fn a_share_under_its_threshold_fails_the_run() {
    let run = |extra: &[&str]| {
        let mut args = vec!["test", "examples/ladder", "--coverage", "summary"];
        args.extend(extra);
        common::linc(&args)
    };
    let o = run(&["--fail-under-functions", "100", "--fail-under-lines", "62.5", "--fail-under-branches", "58%"]);
    assert_eq!(o.status.code(), Some(0), "at or over each threshold: {}", common::stderr(&o));
    let o = run(&["--fail-under-lines", "63", "--fail-under-branches", "60"]);
    assert_eq!(o.status.code(), Some(1), "{}", common::stderr(&o));
    let err = common::stderr(&o);
    let errors: Vec<&str> = err.lines().filter(|l| l.contains("error[E0913]")).collect();
    assert_eq!(
        errors,
        [
            "error[E0913]: 62.50% of lines covered, under the 63% --fail-under-lines asks for",
            "error[E0913]: 58.33% of branches covered, under the 60% --fail-under-branches asks for"
        ],
        "{err}"
    );
    assert!(common::stdout(&o).contains("TOTAL"), "the report is still printed");
    // A share is a number from 0 to 100, and a gate needs counts.
    assert_eq!(run(&["--fail-under-lines", "101"]).status.code(), Some(2));
    assert_eq!(run(&["--fail-under-lines", "x"]).status.code(), Some(2));
    let o = common::linc(&["test", "examples/ladder", "--fail-under-lines", "50"]);
    assert_eq!(o.status.code(), Some(2), "{}", common::stderr(&o));
    // Merged shards are gated the same way; the sum is written first.
    let dir = linc_test_support::fresh_dir("coverage-gate");
    let info = dir.join("ladder.info");
    assert_eq!(covered(&["examples/ladder"], "lcov", &info).status.code(), Some(0));
    let sum = dir.join("sum.info").to_string_lossy().into_owned();
    let info = info.to_string_lossy().into_owned();
    let o = common::linc(&["test", "--merge-coverage", &info, "-o", &sum, "--fail-under-branches", "90"]);
    assert_eq!(o.status.code(), Some(1), "{}", common::stderr(&o));
    assert!(common::stderr(&o).contains("58.33% of branches covered"), "{}", common::stderr(&o));
    assert!(std::path::Path::new(&sum).exists(), "the sum is written");
}

/// The examples' report in `format`, written as `name` in a fresh
/// directory `tag`: the directory and the report.
fn examples_report(tag: &str, format: &str, name: &str) -> (PathBuf, PathBuf) {
    let dir = linc_test_support::fresh_dir(tag);
    let report = dir.join(name);
    let o = covered(&["examples"], format, &report);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    (dir, report)
}

#[test]
fn the_cobertura_report_validates_against_its_dtd() {
    if !common::tool("xmllint") {
        return;
    }
    let (dir, xml) = examples_report("coverage-cobertura", "cobertura", "coverage.xml");
    let dtd = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/cobertura-04.dtd");
    let check = |file: &Path| {
        std::process::Command::new("xmllint").args(["--noout", "--nonet", "--dtdvalid", dtd]).arg(file).output()
    };
    let v = check(&xml).expect("xmllint runs");
    assert!(v.status.success(), "{}", String::from_utf8_lossy(&v.stderr));
    let text = std::fs::read_to_string(&xml).unwrap();
    assert!(text.contains("<method name=\"step Fill\""), "steps are methods of their file");
    // The validation is real: a class without its file name is refused.
    let broken = dir.join("broken.xml");
    std::fs::write(&broken, text.replacen(" filename=", " file=", 1)).unwrap();
    assert!(!check(&broken).expect("xmllint runs").status.success());
}

#[test]
fn genhtml_renders_the_lcov_report() {
    if !common::tool("genhtml") {
        return;
    }
    let (dir, info) = examples_report("coverage-genhtml", "lcov", "coverage.info");
    let html = dir.join("html");
    let g = std::process::Command::new("genhtml")
        .args(["--quiet", "--branch-coverage", "--function-coverage", "-o"])
        .arg(&html)
        .arg(&info)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("genhtml runs");
    assert!(g.status.success(), "{}", String::from_utf8_lossy(&g.stderr));
    let index = std::fs::read_to_string(html.join("index.html")).expect("an index page");
    // genhtml drops the prefix every file shares (`examples/`).
    assert!(index.contains("href=\"ladder/index.html\""), "the index lists the example directories");
    let page = std::fs::read_to_string(html.join("ladder/interlock.ld.gcov.html")).expect("a source page");
    assert!(page.contains("Dig_1a.In"), "the page shows the rungs' source");
}

/// The outcomes of the decisions on `line` of `file` in an lcov report.
fn branches_at(text: &str, file: &str, line: u32) -> BTreeMap<(u32, u32), Option<u64>> {
    let report = lcov::Report::from_reader(lcov::Reader::new(text.as_bytes())).expect("lcov");
    let (_, f) = report.sections.iter().find(|(k, _)| k.source_file.ends_with(file)).expect("the file is reported");
    f.branches.iter().filter(|(k, _)| k.line == line).map(|(k, v)| ((k.block, k.branch), v.taken)).collect()
}

#[test]
fn a_scenario_that_energises_a_rung_moves_its_branch_from_missed_to_hit() {
    let dir = linc_test_support::fresh_dir("coverage-branch");
    let plant = std::fs::canonicalize(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/ladder/plant.json")).unwrap();
    let quiet = dir.join("quiet.ltest");
    std::fs::write(&quiet, format!("strategy {}\nrun 300ms\n", plant.display())).unwrap();
    let info = dir.join("quiet.info");
    let o = covered(&[&quiet.to_string_lossy()], "lcov", &info);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    // Rung 1 (line 2 of interlock.ld) is never energised: outcome 0 missed.
    let before = branches_at(&std::fs::read_to_string(&info).unwrap(), "interlock.ld", 2);
    assert_eq!(before, BTreeMap::from([((0, 0), Some(0)), ((0, 1), Some(3))]));
    let pressed = dir.join("pressed.ltest");
    std::fs::write(&pressed, format!("strategy {}\nat 100ms M Dig_1a.In=1\nrun 300ms\n", plant.display())).unwrap();
    let o = covered(&[&quiet.to_string_lossy(), &pressed.to_string_lossy()], "lcov", &info);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let after = branches_at(&std::fs::read_to_string(&info).unwrap(), "interlock.ld", 2);
    // The pressed scenario scans at 100 ms (before the press), then 200,
    // 300 and 400 ms with the rung energised.
    assert_eq!(after, BTreeMap::from([((0, 0), Some(3)), ((0, 1), Some(4))]), "now hit");
}

//! Every example run on the interpreter and on the compiling tier (ADR
//! 0011): the same trace (every change of every field, in order, with its
//! time and program), the same database after the run, the same output and
//! errors. `--tier compiled` compiles every block at its first run and says
//! how many blocks ran compiled, so the comparison is known not to be two
//! interpreter runs.
mod common;
use common::{linc, stderr, stdout, temp_dir};

/// Runs `args` on both tiers with a trace and the database written out;
/// returns how many code blocks ran compiled and how many there are.
fn same_on_both_tiers(tag: &str, args: &[&str]) -> (usize, usize) {
    let dir = temp_dir(&format!("tiers-{tag}"));
    let mut seen = Vec::new();
    for tier in ["interpreter", "compiled"] {
        let (trace, out) = (dir.join(format!("{tier}.trace")), dir.join(format!("{tier}.json")));
        let mut all: Vec<&str> = args.to_vec();
        let (t, o) = (trace.to_string_lossy().into_owned(), out.to_string_lossy().into_owned());
        all.extend(["--now", "2026-01-05T06:00:00", "--tier", tier, "--trace", &t, "--out", &o]);
        let r = linc(&all);
        let trace = std::fs::read_to_string(&trace).unwrap_or_else(|e| panic!("{tag} {tier}: no trace: {e}"));
        let out = std::fs::read_to_string(&out).unwrap_or_else(|e| panic!("{tag} {tier}: no database: {e}"));
        seen.push((r.status.code(), stdout(&r), stderr(&r), trace, out));
    }
    let _ = std::fs::remove_dir_all(&dir);
    let (a, b) = (&seen[0], &seen[1]);
    assert!(!a.3.is_empty(), "{tag}: an empty trace compares nothing");
    assert_eq!(a.0, b.0, "{tag}: exit status");
    assert_eq!(a.1, b.1, "{tag}: output");
    assert!(a.3 == b.3, "{tag}: the traces differ (first difference at line {:?})", first_difference(&a.3, &b.3));
    assert_eq!(a.4, b.4, "{tag}: the database after the run");
    let (counted, errors): (Vec<&str>, Vec<&str>) = b.2.lines().partition(|l| l.starts_with("linc: "));
    assert_eq!(a.2.lines().collect::<Vec<_>>(), errors, "{tag}: errors");
    let words: Vec<usize> = counted.first().map_or(vec![], |l| l.split(' ').filter_map(|w| w.parse().ok()).collect());
    match words[..] {
        [compiled, all] => (compiled, all),
        _ => panic!("{tag}: no count of compiled blocks in {:?}", b.2),
    }
}

fn first_difference(a: &str, b: &str) -> Option<usize> {
    a.lines().zip(b.lines()).position(|(x, y)| x != y).or(Some(a.lines().count().min(b.lines().count())))
}

#[test]
fn the_st_strategy_is_the_same_compiled() {
    let (compiled, all) = same_on_both_tiers("strategy", &["run", "examples/strategy/plant.json", "--for", "10m"]);
    assert_eq!((compiled, all), (5, 5));
}

#[test]
fn the_sequences_are_the_same_compiled() {
    let (compiled, _) = same_on_both_tiers("sequences", &["run", "examples/sequences/plant.json", "--for", "10m"]);
    assert!(compiled >= 15, "{compiled} blocks compiled");
    let one = ["run", "examples/sequences/batch.sfc", "--db", "examples/sequences/plant.json", "--for", "10m"];
    let (compiled, _) = same_on_both_tiers("batch", &one);
    assert!(compiled >= 5, "{compiled} blocks compiled");
}

#[test]
fn the_ladder_is_the_same_compiled() {
    let (compiled, _) = same_on_both_tiers("ladder", &["run", "examples/ladder/plant.json", "--for", "10m"]);
    assert!(compiled >= 1);
}

#[test]
fn the_fst_plant_is_the_same_with_its_st_action_compiled() {
    // FST tables suspend at their steps and stay on the interpreter; the
    // tank simulation beside them compiles.
    let (compiled, _) = same_on_both_tiers("fst", &["run", "examples/fst/plant.json", "--for", "10m"]);
    assert!(compiled >= 1);
}

#[test]
fn the_semantics_page_example_prints_what_it_says() {
    // docs/semantics.md §24.
    let args = ["run", "examples/strategy/plant.json", "--for", "10m", "--now", "2026-01-05T06:00:00"];
    for tier in ["compiled", "interpreter", "auto"] {
        let r = linc(&[&args[..], &["--tier", tier, "--show", "TANK1.HighCnt"]].concat());
        assert_eq!(stdout(&r), "TANK1.HighCnt = 17\n", "{tier}");
        let said = if tier == "compiled" { "linc: 5 of 5 code blocks ran compiled\n" } else { "" };
        assert_eq!(stderr(&r), said, "{tier}");
    }
}

#[test]
fn a_single_action_is_the_same_compiled() {
    let args = ["run", "examples/guide/shift.st", "--db", "examples/guide/plant.db.json", "--cycles", "5"];
    assert_eq!(same_on_both_tiers("shift", &args), (1, 1));
}

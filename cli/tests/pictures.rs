//! The README's pictures are `linc draw`'s output, checked in under
//! `docs/pictures/`. This test draws each again and fails when a checked-in
//! picture is stale; `LINC_BLESS=1 cargo test -p linc --test pictures`
//! writes them anew.
mod common;

use common::{linc, stderr, stdout};

/// The clock of every run, so that a picture does not depend on the day.
const NOW: &str = "2026-01-05T06:00:00";

/// Each picture and the `linc draw` arguments that make it.
const PICTURES: &[(&str, &[&str])] = &[
    ("batch.svg", &["draw", "examples/sequences/batch.sfc", "--db", "examples/sequences/plant.json", "--for", "45s"]),
    ("interlock.svg", &["draw", "examples/ladder/interlock.ld", "--db", "examples/ladder/plant.json", "--cycles", "2"]),
    (
        "pump.svg",
        &["draw", "examples/fst/pump.csv", "--db", "examples/fst/plant.json", "--block", "FST 1", "--for", "10s"],
    ),
];

/// The trend: twenty minutes of the batch plant, traced, then drawn.
const TREND_FIELDS: &[&str] = &["--field", "R1.Level", "--field", "R1.Temp", "--field", "R1.FillVlv"];

fn check(name: &str, drawn: &str) {
    let path = format!("{}/../docs/pictures/{name}", env!("CARGO_MANIFEST_DIR"));
    if std::env::var_os("LINC_BLESS").is_some() {
        std::fs::write(&path, drawn).expect("write picture");
        return;
    }
    let old = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(old == drawn, "docs/pictures/{name} is stale: run `LINC_BLESS=1 cargo test -p linc --test pictures`");
}

#[test]
fn the_readme_pictures_are_current() {
    for (name, args) in PICTURES {
        let o = linc(args);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
        check(name, &stdout(&o));
    }
    let dir = common::temp_dir("pictures");
    let trace = dir.join("batch.jsonl");
    let t = trace.to_str().unwrap();
    let o = linc(&["run", "examples/sequences/plant.json", "--for", "20m", "--now", NOW, "--trace", t]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let mut args = vec!["draw", t];
    args.extend_from_slice(TREND_FIELDS);
    let o = linc(&args);
    assert_eq!(o.status.code(), Some(0), "trend: {}", stderr(&o));
    check("trend.svg", &stdout(&o));
}

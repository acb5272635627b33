//! `linc fst to-st` on every example table: a table that translates runs
//! for a simulated hour in the example plant, once as the table and once
//! as its translation on an ACTION block, and the two `--out` databases and
//! the traces of field changes are the same; a table that does not is
//! refused with located E043x errors and exit status 1.
mod common;

use std::path::Path;

/// The example plant with `RUNFLG` 1 given to `block`, and, for the
/// translated copy, its table replaced by the ACTION block `TRANS`.
fn plant(table: &str, block: &str, translated: bool) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/fst/plant.json")).unwrap();
    let file = format!("\"FileName\": \"{table}\"");
    let mut out = String::new();
    for line in text.lines() {
        if line.contains(&format!("\"{block}\"")) && line.contains(&file) {
            let line = line.replace(&file, &format!("{file}, \"RUNFLG\": 1, \"IP\": 0"));
            if translated {
                out.push_str(&line.replace(&format!(", {file}"), ""));
                out.push_str("\n    \"TRANS\": { \"type\": \"ACTION\", \"values\": { \"FileName\": \"t.st\", \"ActName\": \"T\", \"Trigger\": true, \"Qualifier\": \"N\" } },\n");
                continue;
            }
            out.push_str(&line);
        } else {
            out.push_str(line);
        }
        out.push('\n');
    }
    out
}

/// A copy of the example directory with `plant` as its database.
fn copy_example(dir: &Path, plant: &str) {
    std::fs::create_dir_all(dir).unwrap();
    let src = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/fst"));
    for e in std::fs::read_dir(src).unwrap().flatten() {
        std::fs::copy(e.path(), dir.join(e.file_name())).unwrap();
    }
    std::fs::write(dir.join("plant.json"), plant).unwrap();
}

/// Runs the plant in `dir` for an hour: its output database (without
/// what only the translation has) and the changes its trace records.
fn run_hour(dir: &Path, table: &str, block: &str) -> (serde_json::Value, Vec<String>) {
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let now = "2026-01-05T06:00:00";
    let o = common::linc(&[
        "run",
        &p("plant.json"),
        "--for",
        "1h",
        "--now",
        now,
        "--trace",
        &p("t.jsonl"),
        "--out",
        &p("out.json"),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let mut db: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("out.json")).unwrap()).unwrap();
    let blocks = db["blocks"].as_object_mut().expect("blocks");
    blocks.remove("TRANS");
    // The table's block names the table in one and nothing in the other.
    if let Some(values) = blocks.get_mut(block).and_then(|b| b["values"].as_object_mut()) {
        let file = values.remove("FileName");
        assert!(file.as_ref().and_then(|f| f.as_str()).is_none_or(|f| f == table || f.is_empty()), "{file:?}");
    }
    let mut changes = Vec::new();
    for line in std::fs::read_to_string(dir.join("t.jsonl")).unwrap().lines() {
        let v: serde_json::Value = serde_json::from_str(line).unwrap();
        if let Some(field) = v.get("field").and_then(|f| f.as_str()).filter(|f| !f.starts_with("TRANS.")) {
            changes.push(format!("{} {field} {} -> {}", v["time"], v["old"], v["new"]));
        }
    }
    (db, changes)
}

#[test]
fn every_example_table_translates_faithfully_or_is_refused_with_its_reasons() {
    let dir = linc_test_support::fresh_dir("fst-to-st");
    let mut translated = Vec::new();
    for (table, block) in
        [("pump.csv", "FST 1"), ("branching.csv", "FST 2"), ("alarm.csv", "FST 3"), ("history.csv", "FST 4")]
    {
        let st = dir.join(format!("{table}.st")).to_string_lossy().into_owned();
        let path = format!("examples/fst/{table}");
        let o = common::linc(&["fst", "to-st", &path, "--db", "examples/fst/plant.json", "--block", block, "-o", &st]);
        if o.status.code() == Some(1) {
            let err = common::stderr(&o);
            assert!(err.contains("error[E0430]") && err.contains(&path), "{table}: {err}");
            continue;
        }
        assert_eq!(o.status.code(), Some(0), "{table}: {}", common::stderr(&o));
        let (a, b) = (dir.join(format!("{table}-table")), dir.join(format!("{table}-st")));
        copy_example(&a, &plant(table, block, false));
        copy_example(&b, &plant(table, block, true));
        let text = std::fs::read_to_string(&st).unwrap();
        std::fs::write(b.join("t.st"), text.replace(&format!("ACTION {}", action(table)), "ACTION T")).unwrap();
        // The two runs at once: each is a process of its own.
        let ((db_a, trace_a), (db_b, trace_b)) = std::thread::scope(|s| {
            let other = s.spawn(|| run_hour(&b, table, block));
            (run_hour(&a, table, block), other.join().expect("the translation's run"))
        });
        assert!(trace_a.len() > 10, "{table}: the table changes the plant ({} changes)", trace_a.len());
        if let Some(at) = (0..trace_a.len().max(trace_b.len())).find(|&i| trace_a.get(i) != trace_b.get(i)) {
            panic!("{table}: the traces differ at change {at}: {:?} against {:?}", trace_a.get(at), trace_b.get(at));
        }
        assert_eq!(db_a, db_b, "{table}: the databases differ");
        translated.push(table);
    }
    assert_eq!(translated, ["branching.csv", "alarm.csv"]);
}

/// The action name `linc fst to-st` gives a table.
fn action(table: &str) -> String {
    linc_driver::fst_translate::action_name(Path::new(table))
}

#[test]
fn to_st_never_writes_over_its_input() {
    let o = common::linc(&[
        "fst",
        "to-st",
        "examples/fst/alarm.csv",
        "--db",
        "examples/fst/plant.json",
        "--block",
        "FST 3",
        "-o",
        "examples/fst/alarm.csv",
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", common::stderr(&o));
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/fst/alarm.csv")).unwrap();
    assert!(text.starts_with("STEP,LABEL,CMD"), "the table is intact");
}

#[test]
fn a_block_whose_state_an_action_cannot_reproduce_is_refused() {
    let dir = linc_test_support::fresh_dir("fst-to-st-state");
    for (field, why) in [("\"IP\": 5", "IP 5"), ("\"IP\": 0, \"BRK\": 3", "BRK 3")] {
        let db = plant("alarm.csv", "FST 3", false).replace("\"IP\": 0", field);
        copy_example(&dir, &db);
        let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
        let o = common::linc(&["fst", "to-st", &p("alarm.csv"), "--db", &p("plant.json"), "--block", "FST 3"]);
        assert_eq!(o.status.code(), Some(1), "{}", common::stdout(&o));
        let err = common::stderr(&o);
        assert!(err.contains("error[E0430]") && err.contains(why), "{err}");
    }
}

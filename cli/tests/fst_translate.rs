//! `linc fst to-st` and `to-sfc` on every example table: a table that
//! translates runs for a simulated hour in the example plant, as the table
//! and as each translation (an ST action on an ACTION block, a sequence on
//! an SFC_CON block), and the `--out` databases and the traces of field
//! changes are the same; a table that does not is refused with located
//! E043x errors and exit status 1.
mod common;

use std::path::Path;

/// The example plant with `RUNFLG` 1 given to `block`, and, for a
/// translated copy, its table replaced by the block `TRANS` running the
/// translation: the ST action `T` of `t.st`, or the sequence `t.sfc`.
fn plant(table: &str, block: &str, translated: Option<&str>) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/fst/plant.json")).unwrap();
    let file = format!("\"FileName\": \"{table}\"");
    let mut out = String::new();
    for line in text.lines() {
        if line.contains(&format!("\"{block}\"")) && line.contains(&file) {
            let line = line.replace(&file, &format!("{file}, \"RUNFLG\": 1, \"IP\": 0"));
            if let Some(how) = translated {
                out.push_str(&line.replace(&format!(", {file}"), ""));
                out.push_str(match how {
                    "to-st" => "\n    \"TRANS\": { \"type\": \"ACTION\", \"values\": { \"FileName\": \"t.st\", \"ActName\": \"T\", \"Trigger\": true, \"Qualifier\": \"N\" } },\n",
                    _ => "\n    \"TRANS\": { \"type\": \"SFC_CON\", \"values\": { \"FileName\": \"t.sfc\", \"Run\": true } },\n",
                });
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

/// Translates `table` with `linc fst HOW` into `dir`: the translation's
/// plant directory, or `None` when refused (with E0430, as every example
/// table the translations refuse is).
fn translate(dir: &Path, how: &str, table: &str, block: &str) -> Option<std::path::PathBuf> {
    let out = dir.join(format!("{table}.{how}")).to_string_lossy().into_owned();
    let path = format!("examples/fst/{table}");
    let o = common::linc(&["fst", how, &path, "--db", "examples/fst/plant.json", "--block", block, "-o", &out]);
    if o.status.code() == Some(1) {
        let err = common::stderr(&o);
        assert!(err.contains("error[E0430]") && err.contains(&path), "{table}: {err}");
        return None;
    }
    assert_eq!(o.status.code(), Some(0), "{table}: {}", common::stderr(&o));
    let plant_dir = dir.join(format!("{table}-{how}"));
    copy_example(&plant_dir, &plant(table, block, Some(how)));
    let text = std::fs::read_to_string(&out).unwrap();
    match how {
        "to-st" => {
            std::fs::write(plant_dir.join("t.st"), text.replace(&format!("ACTION {}", action(table)), "ACTION T"))
        }
        _ => std::fs::write(plant_dir.join("t.sfc"), text),
    }
    .unwrap();
    Some(plant_dir)
}

#[test]
fn every_example_table_translates_faithfully_or_is_refused_with_its_reasons() {
    let dir = linc_test_support::fresh_dir("fst-translate");
    let mut translated = Vec::new();
    for (table, block) in
        [("pump.csv", "FST 1"), ("branching.csv", "FST 2"), ("alarm.csv", "FST 3"), ("history.csv", "FST 4")]
    {
        let ways: Vec<(&str, std::path::PathBuf)> = ["to-st", "to-sfc"]
            .into_iter()
            .filter_map(|how| Some((how, translate(&dir, how, table, block)?)))
            .collect();
        if ways.is_empty() {
            continue;
        }
        let original = dir.join(format!("{table}-table"));
        copy_example(&original, &plant(table, block, None));
        // The table and each translation run at once, each a process.
        let ((db_a, trace_a), others) = std::thread::scope(|s| {
            let others: Vec<_> = ways.iter().map(|(how, d)| (*how, s.spawn(|| run_hour(d, table, block)))).collect();
            let a = run_hour(&original, table, block);
            (a, others.into_iter().map(|(how, h)| (how, h.join().expect("a translation's run"))).collect::<Vec<_>>())
        });
        assert!(trace_a.len() > 10, "{table}: the table changes the plant ({} changes)", trace_a.len());
        for (how, (db_b, trace_b)) in others {
            if let Some(at) = (0..trace_a.len().max(trace_b.len())).find(|&i| trace_a.get(i) != trace_b.get(i)) {
                panic!(
                    "{table} {how}: the traces differ at change {at}: {:?} against {:?}",
                    trace_a.get(at),
                    trace_b.get(at)
                );
            }
            assert_eq!(db_a, db_b, "{table} {how}: the databases differ");
            translated.push(format!("{table} {how}"));
        }
    }
    assert_eq!(translated, ["branching.csv to-st", "branching.csv to-sfc", "alarm.csv to-st", "alarm.csv to-sfc"]);
}

/// The action name `linc fst to-st` gives a table.
fn action(table: &str) -> String {
    linc_driver::fst::action_name(Path::new(table))
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
        let db = plant("alarm.csv", "FST 3", None).replace("\"IP\": 0", field);
        copy_example(&dir, &db);
        let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
        let o = common::linc(&["fst", "to-st", &p("alarm.csv"), "--db", &p("plant.json"), "--block", "FST 3"]);
        assert_eq!(o.status.code(), Some(1), "{}", common::stdout(&o));
        let err = common::stderr(&o);
        assert!(err.contains("error[E0430]") && err.contains(why), "{err}");
        // Located at the value in the database file.
        let (_, value) = field.rsplit_once(": ").expect("key: value");
        let line = db.lines().position(|l| l.contains(field)).expect("the field's line") + 1;
        let column =
            db.lines().nth(line - 1).and_then(|l| l.find(field)).expect("column") + field.len() - value.len() + 1;
        assert!(err.contains(&format!("plant.json:{line}:{column}")), "at {line}:{column}:\n{err}");
    }
}

#[test]
fn an_exit_field_that_cannot_hold_the_way_out_is_refused() {
    let path = "examples/fst/branching.csv";
    for (field, why) in [("FST 1.IP", "read-only"), ("FST 1.MSG1", "not a number"), ("NOPE 1.X", "no block")] {
        let o = common::linc(&[
            "fst",
            "to-sfc",
            path,
            "--db",
            "examples/fst/plant.json",
            "--block",
            "FST 2",
            "--exit",
            field,
        ]);
        assert_eq!(o.status.code(), Some(2), "{field}: {}", common::stdout(&o));
        let err = common::stderr(&o);
        assert!(err.contains("error[E0434]") && err.contains("--exit") && err.contains(why), "{field}: {err}");
    }
}

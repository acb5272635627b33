//! One plant, one rule (docs/state.md): `run`, `console`, `serve --for`,
//! `draw --for` and `test` start the same plant from the same database,
//! state file and `--set`, and give the same store — the database's
//! values, then the saved state, then the set.
mod common;

use common::{linc, linc_with_input, stderr, stdout, temp_dir};
use std::path::{Path, PathBuf};

/// An FST table that adds R2 to R1 once a cycle (ten cycles a second).
const TABLE: &str = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n\
0,,VAL,\"FST 1,R1\",,\n\
1,,+,\"FST 1,R2\",,add the step\n\
2,,SAV,\"FST 1,R1\",,\n\
3,,END,,,\n";

const PLANT: &str = r#"{
  "device": "ROC800",
  "aliases": { "Count": "FST 1.R1", "Step": "FST 1.R2" },
  "blocks": { "FST 1": { "type": "FST", "values": { "FileName": "count.csv", "R2": 1.0 } } }
}"#;

const SET: &str = "FST 1.R2=5";

/// The plant's folder, with a state saved after 30 s of the plant as the
/// database describes it (Count 300, Step 1).
fn plant() -> PathBuf {
    let dir = temp_dir("plant-rule");
    std::fs::write(dir.join("count.csv"), TABLE).unwrap();
    std::fs::write(dir.join("plant.json"), PLANT).unwrap();
    let (db, state) = (path(&dir, "plant.json"), path(&dir, "saved.state"));
    let o = linc(&["run", &db, "--for", "30s", "--now", "2026-01-05T06:00:00", "--state", &state, "--show", "Count"]);
    assert_eq!(stdout(&o), "Count = 300.0\n", "{}", stderr(&o));
    dir
}

fn path(dir: &Path, name: &str) -> String {
    dir.join(name).to_str().unwrap().to_string()
}

/// A copy of the saved state for a command that saves over it.
fn state_copy(dir: &Path, name: &str) -> String {
    std::fs::copy(dir.join("saved.state"), dir.join(name)).unwrap();
    path(dir, name)
}

/// `NAME = VALUE` lines of standard output, as (NAME, VALUE).
fn values(out: &str) -> Vec<(String, String)> {
    out.lines().filter_map(|l| l.split_once(" = ")).map(|(n, v)| (n.into(), v.into())).collect()
}

/// What each command gives after 10 s of the plant, warm from the state
/// with Step set to 5: Count and Step, and the state it saved, if it saves.
struct Seen {
    values: Vec<(String, String)>,
    state: Option<Vec<u8>>,
}

fn run(dir: &Path) -> Seen {
    let state = state_copy(dir, "run.state");
    let args = ["run", &path(dir, "plant.json"), "--for", "10s", "--state", &state, "--set", SET];
    let o = linc(&[&args[..], &["--show", "Count", "--show", "Step"]].concat());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    Seen { values: values(&stdout(&o)), state: Some(std::fs::read(state).unwrap()) }
}

fn console(dir: &Path) -> Seen {
    let state = state_copy(dir, "console.state");
    let args = ["console", &path(dir, "plant.json"), "--state", &state, "--set", SET];
    let o = linc_with_input(&args, "ADVANCE 10s\nD Count\nD Step\n");
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    Seen { values: values(&stdout(&o)), state: Some(std::fs::read(state).unwrap()) }
}

fn serve(dir: &Path) -> Seen {
    let state = state_copy(dir, "serve.state");
    let db = path(dir, "plant.json");
    let args = ["serve", &db, "--for", "10s", "--speed", "max", "--http", "127.0.0.1:0", "--state", &state];
    let o = linc(&[&args[..], &["--set", SET]].concat());
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // The served plant shows its values on the monitor; its saved state
    // holds them, and it must be the other commands' to the byte.
    Seen { values: Vec::new(), state: Some(std::fs::read(state).unwrap()) }
}

fn draw(dir: &Path) -> Seen {
    let (table, db, state) = (path(dir, "count.csv"), path(dir, "plant.json"), path(dir, "saved.state"));
    let o = linc(&["draw", &table, "--db", &db, "--for", "10s", "--state", &state, "--set", SET]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // The table's picture shows its registers: `R1 = 800.0   R2 = 5.0 …`.
    let svg = stdout(&o);
    let registers = svg.split("R1 = ").nth(1).expect("the registers are drawn");
    let shown = |name: &str, register: &str| {
        let at = format!("{register} = ");
        let text = if register == "R1" { registers } else { registers.split(&at).nth(1).unwrap() };
        (name.to_string(), text.split_whitespace().next().unwrap().trim_end_matches("</text>").to_string())
    };
    Seen { values: vec![shown("Count", "R1"), shown("Step", "R2")], state: None }
}

/// The scenario expects the values `run` gave: it passes only if its
/// plant started as `run`'s did.
fn test(dir: &Path, expected: &[(String, String)]) -> Seen {
    let expects: String = expected.iter().map(|(n, v)| format!("expect after 0s {n} = {v}\n")).collect();
    let text = format!("strategy plant.json\nstate saved.state\nset {SET}\nrun 10s\n{expects}");
    std::fs::write(dir.join("rule.ltest"), text).unwrap();
    let o = linc(&["test", &path(dir, "rule.ltest")]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    Seen { values: expected.to_vec(), state: None }
}

/// A command of the table, run on the plant's folder.
type Command = fn(&Path) -> Seen;

#[test]
fn every_command_starts_the_plant_from_the_database_then_the_state_then_set() {
    let dir = plant();
    let by_run = run(&dir);
    // The rule itself: Count goes on from the state's 300, by the set Step
    // (ten cycles a second).
    let want = [("Count".to_string(), "800.0".to_string()), ("Step".to_string(), "5.0".to_string())];
    assert_eq!(by_run.values, want);
    let table: [(&str, Command); 3] = [("console", console), ("serve", serve), ("draw", draw)];
    for (name, command) in table {
        let seen = command(&dir);
        if !seen.values.is_empty() {
            assert_eq!(seen.values, by_run.values, "{name}");
        }
        if let Some(state) = seen.state {
            assert!(state == *by_run.state.as_ref().unwrap(), "{name} saved another state than run");
        }
    }
    test(&dir, &by_run.values);
    // A scenario that expects what the rule would not give fails.
    let other = "strategy plant.json\nstate saved.state\nrun 10s\nexpect after 0s Count = 800.0\n";
    std::fs::write(dir.join("other.ltest"), other).unwrap();
    let o = linc(&["test", &path(&dir, "other.ltest")]);
    assert_eq!(o.status.code(), Some(1), "without the set, Count is 400: {}", stdout(&o));
}

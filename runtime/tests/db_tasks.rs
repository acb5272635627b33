//! Strategy configuration: user tasks and the task each block runs in.

use linc_runtime::db::Task;
use linc_runtime::Database;

fn span(text: &str, needle: &str) -> Option<(usize, usize)> {
    text.find(needle).map(|at| (at, at + needle.len()))
}

fn fails(text: &str, code: &str, needle: &str) -> String {
    let e = Database::from_json(text).expect_err(text);
    assert_eq!((e.code.as_str(), e.span), (code, span(text, needle)), "{}", e.message);
    e.message
}

fn task(number: u8, period: f64) -> Task {
    Task { number, period }
}

#[test]
fn the_contract_example() {
    let text = r#"{ "tasks":  { "1": { "period": "T#100ms" }, "4": { "period": "T#1s" } },
      "blocks": { "FILL": { "type": "ACTION", "task": 1,
                 "values": { "FileName": "actions.stx", "ActName": "Fill", "Trigger": true } },
                  "SLOW": { "type": "RECIPE", "task": 4 } } }"#;
    let db = Database::from_json(text).expect("loads");
    assert_eq!(db.tasks, [task(1, 0.1), task(4, 1.0)]);
    assert_eq!(db.blocks.iter().map(|b| b.task).collect::<Vec<_>>(), [1, 4]);
    assert_eq!(db.task(4), Some(&task(4, 1.0)));
    assert_eq!(db.task(2), None);
}

#[test]
fn defaults() {
    let db = Database::from_json(r#"{ "blocks": { "R": { "type": "RECIPE" } } }"#).expect("loads");
    assert_eq!(db.tasks, [task(1, 0.1)]);
    assert_eq!(db.blocks[0].task, 1);
    assert_eq!(Database::builtin().tasks, [task(1, 0.1)]);
    // Task 1 exists at 100 ms even when `tasks` does not list it, and the
    // list comes out sorted whatever the order in the file.
    let text = r#"{ "tasks": { "3": { "period": 2 }, "2": { "period": "T#4m13.0s" } },
                    "blocks": { "R": { "type": "RECIPE" }, "S": { "type": "RECIPE", "task": 3 } } }"#;
    let db = Database::from_json(text).expect("loads");
    assert_eq!(db.tasks, [task(1, 0.1), task(2, 253.0), task(3, 2.0)]);
    assert_eq!(db.blocks.iter().map(|b| b.task).collect::<Vec<_>>(), [1, 3]);
}

#[test]
fn period_forms() {
    let cases = [
        ("\"T#1s500ms\"", 1.5),
        ("\"T#1.5s\"", 1.5),
        ("\"t#250MS\"", 0.25),
        ("\"T#1d\"", 86_400.0),
        ("\"T#1ms\"", 0.001),
        ("0.02", 0.02),
        ("86400", 86_400.0),
    ];
    for (period, seconds) in cases {
        let text = format!(r#"{{ "tasks": {{ "2": {{ "period": {period} }} }} }}"#);
        let db = Database::from_json(&text).unwrap_or_else(|e| panic!("{period}: {e}"));
        assert_eq!(db.task(2), Some(&task(2, seconds)), "{period}");
    }
}

#[test]
fn bad_periods_are_located_at_the_value() {
    for period in [
        "\"100ms\"",
        "\"T#100\"",
        "\"T#1s1m\"",
        "\"T#0s\"",
        "\"T#0.5ms\"",
        "\"T#1d1s\"",
        "0",
        "-1",
        "1e999",
        "true",
        "\"\"",
    ] {
        let text = format!(r#"{{ "tasks": {{ "1": {{ "period": {period} }} }} }}"#);
        let m = fails(&text, "E0809", period);
        assert!(m.starts_with("period of task 1: "), "{m}");
    }
    fails(r#"{ "tasks": { "1": { } } }"#, "E0801", "\"1\"");
    fails(r#"{ "tasks": { "1": { "period": 1, "priority": 2 } } }"#, "E0801", "\"priority\"");
    fails(r#"{ "tasks": { "1": "T#1s" } }"#, "E0801", "\"T#1s\"");
}

#[test]
fn task_numbers_are_one_to_four() {
    for key in ["\"0\"", "\"5\"", "\"01\"", "\"one\"", "\" 1\""] {
        fails(&format!(r#"{{ "tasks": {{ {key}: {{ "period": 1 }} }} }}"#), "E0808", key);
    }
    for task in ["0", "5", "1.5", "\"1\"", "null"] {
        let text = format!(r#"{{ "blocks": {{ "R": {{ "type": "RECIPE", "task": {task} }} }} }}"#);
        fails(&text, "E0808", task);
    }
}

#[test]
fn blocks_only_run_in_defined_tasks() {
    let text = r#"{ "tasks": { "2": { "period": 1 } }, "blocks": { "R": { "type": "RECIPE", "task": 3 } } }"#;
    let m = fails(text, "E0810", "3");
    assert!(m.contains("task 3"), "{m}");
    // Without `tasks` only task 1 exists.
    fails(r#"{ "blocks": { "R": { "type": "RECIPE", "task": 2 } } }"#, "E0810", "2");
    // `tasks` may come after `blocks` in the file.
    let text = r#"{ "blocks": { "R": { "type": "RECIPE", "task": 2 } }, "tasks": { "2": { "period": 1 } } }"#;
    assert_eq!(Database::from_json(text).map(|db| db.blocks[0].task), Ok(2));
}

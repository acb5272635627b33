//! The files the server reads from disk, whoever names them (the
//! initialization option `database`, `linc.toml`, a block's `FileName`,
//! `workspace/didChangeWatchedFiles`), are read by the commands' rules
//! (`linc_format::input`): a FIFO or a link to `/dev/zero` is no file, and
//! the server keeps answering (it used to hang on the FIFO for ever, and
//! grow to 11.5 GB on `/dev/zero`). And a database's diagnostics are
//! those of the loader `linc check --db` uses, a duplicate key included.

mod common;

use common::{example, workspace, Client};
use linc_format::Database;
use serde_json::{json, Value};
use std::path::Path;

fn mkfifo(path: &Path) {
    let ok = std::process::Command::new("mkfifo").arg(path).status().expect("mkfifo").success();
    assert!(ok, "mkfifo {}", path.display());
}

fn link_to_zero(path: &Path) {
    std::os::unix::fs::symlink("/dev/zero", path).expect("link");
}

/// What a hover on `TANK1.Level` in the example's `actions.stx` says.
fn hover_level(c: &mut Client) -> String {
    let text = example("strategy/actions.stx");
    c.open("actions.stx", &text);
    let line = text.lines().position(|l| l.contains("TANK1.Level := TANK1.Level + TANK1.Inflow")).expect("line");
    let h = c.at("hover", "actions.stx", line as u32, 16);
    h["contents"]["value"].as_str().unwrap_or("no hover").lines().next().unwrap_or("").to_string()
}

#[test]
fn a_fifo_or_a_device_given_as_the_database_is_no_database() {
    for (option, toml) in [(true, false), (false, true)] {
        let root = workspace("lsp-inputs-chosen", &[("actions.stx", &example("strategy/actions.stx"))]);
        mkfifo(&root.join("fifo.json"));
        link_to_zero(&root.join("zero.json"));
        if toml {
            std::fs::write(root.join("linc.toml"), "database = \"zero.json\"\n").expect("toml");
        }
        let options = if option { json!({ "database": "fifo.json" }) } else { json!({}) };
        let mut c = Client::start(&root, options);
        // Checked without a database: the hover says it has none.
        let hover = hover_level(&mut c);
        assert!(hover.contains("does not load") || hover.contains("no strategy database"), "{hover}");
    }
}

#[test]
fn block_files_and_watched_files_that_are_fifos_or_devices_are_no_files() {
    let plant = example("strategy/plant.json").replace("modbus.stx", "fifo.stx");
    let root =
        workspace("lsp-inputs-named", &[("plant.json", &plant), ("actions.stx", &example("strategy/actions.stx"))]);
    mkfifo(&root.join("fifo.stx"));
    link_to_zero(&root.join("zero.json"));
    mkfifo(&root.join("pipe.json"));
    let mut c = Client::start(&root, json!({}));
    // workspace/symbol reads every file a block names.
    let symbols = c.request("workspace/symbol", json!({ "query": "Request" }));
    assert_eq!(symbols, json!([]), "the FIFO named by POLL is no file");
    let changes: Vec<Value> =
        ["zero.json", "pipe.json", "plant.json"].iter().map(|f| json!({ "uri": c.uri(f), "type": 2 })).collect();
    c.notify("workspace/didChangeWatchedFiles", json!({ "changes": changes }));
    assert_eq!(hover_level(&mut c), "**TANK1.Level** : `REAL`", "the database still loads");
}

#[test]
fn a_database_with_a_key_twice_gets_the_diagnostic_linc_check_gives() {
    let plant = example("strategy/plant.json")
        .replace(r#""TANK1": { "type": "TANK","#, r#""TANK1": { "type": "TANK", "type": "TANK","#);
    let root = workspace("lsp-inputs-dup", &[("plant.json", &plant)]);
    let mut c = Client::start(&root, json!({ "debounceMs": 0 }));
    c.open("plant.json", &plant);
    let d = c.diagnostics("plant.json");
    let e = Database::from_file_text(&plant).expect_err("linc check refuses it");
    assert_eq!(e.code.as_str(), "E0807");
    let (start, end) = e.span.expect("located");
    let line = plant[..start].matches('\n').count();
    let col = start - plant[..start].rfind('\n').map_or(0, |i| i + 1);
    assert_eq!(
        d["diagnostics"],
        json!([{
            "range": { "start": { "line": line, "character": col }, "end": { "line": line, "character": col + end - start } },
            "severity": 1,
            "code": "E0807",
            "source": "linc",
            "message": e.message,
        }])
    );
}

/// A byte order mark is white space to `linc check --db`, and so to the
/// server: the database loads and names its files.
#[test]
fn a_database_with_a_byte_order_mark_loads() {
    let plant = format!("\u{feff}{}", example("strategy/plant.json"));
    let root = workspace("lsp-inputs-bom", &[("plant.json", &plant)]);
    let mut c = Client::start(&root, json!({ "debounceMs": 0 }));
    assert_eq!(hover_level(&mut c), "**TANK1.Level** : `REAL`");
    c.open("plant.json", &plant);
    assert_eq!(c.diagnostics("plant.json")["diagnostics"], json!([]));
}

//! Every feature of `linc lsp`, in process, with its exact answer pinned
//! (JSON snapshots; the workspace folder is written `$ROOT`).

mod common;

use common::{example, pos, workspace, Client};
use insta::assert_snapshot;
use serde_json::{json, Value};

/// A client on a workspace holding copies of example files of `dir`.
fn examples(tag: &str, dir: &str, names: &[&str]) -> Client {
    let texts: Vec<(&str, String)> = names.iter().map(|n| (*n, example(&format!("{dir}/{n}")))).collect();
    let files: Vec<(&str, &str)> = texts.iter().map(|(n, t)| (*n, t.as_str())).collect();
    Client::start(&workspace(tag, &files), json!({ "debounceMs": 0 }))
}

fn strategy(tag: &str) -> Client {
    examples(tag, "strategy", &["plant.json", "actions.stx", "modbus.stx"])
}

fn sequences(tag: &str) -> Client {
    examples(tag, "sequences", &["plant.json", "batch.sfc", "process.stx"])
}

fn guide(tag: &str) -> Client {
    let root = workspace(
        tag,
        &[("plant.db.json", &example("guide/plant.db.json")), ("linc.toml", "database = \"plant.db.json\"\n")],
    );
    Client::start(&root, json!({ "debounceMs": 0 }))
}

#[test]
fn diagnostics_are_linc_checks_and_clear_when_fixed() {
    let mut c = strategy("lsp-diag");
    let good = example("strategy/actions.stx");
    let bad = good.replace("TANK1.Pump := TRUE;", "TANK1.Pmp := TRUE;");
    c.open("actions.stx", &bad);
    let d = c.diagnostics("actions.stx");
    assert_snapshot!("diagnostics_unknown_field", c.show(&d));
    c.change("actions.stx", 2, &good);
    let d = c.diagnostics_at("actions.stx", 2);
    assert_eq!(d["diagnostics"], json!([]), "{d}");
    assert_eq!(d["version"], json!(2));
    c.shutdown();
}

#[test]
fn a_database_error_is_placed_in_the_json() {
    let mut c = strategy("lsp-dberr");
    let text = example("strategy/plant.json").replace("\"HighCnt\": \"INT\"", "\"HighCnt\": \"INTEGER\"");
    c.open("plant.json", &text);
    let d = c.diagnostics("plant.json");
    assert_snapshot!("diagnostics_database", c.show(&d));
    c.shutdown();
}

#[test]
fn hover_tells_blocks_fields_functions_and_steps() {
    let mut c = strategy("lsp-hover");
    let text = example("strategy/actions.stx");
    c.open("actions.stx", &text);
    let (l, ch) = pos(&text, "TANK1.Level :=", 2);
    assert_snapshot!("hover_block", c.at_shown("hover", "actions.stx", l, ch));
    let (l, ch) = pos(&text, "TANK1.Level :=", 8);
    assert_snapshot!("hover_field", c.at_shown("hover", "actions.stx", l, ch));
    let (l, ch) = pos(&text, "MAX(", 1);
    assert_snapshot!("hover_function", c.at_shown("hover", "actions.stx", l, ch));
    let (l, ch) = pos(&text, "Int1 := Int1", 1);
    assert_snapshot!("hover_own_block_field", c.at_shown("hover", "actions.stx", l, ch));
    c.shutdown();

    let mut c = sequences("lsp-hover-seq");
    let text = example("sequences/batch.sfc");
    c.open("batch.sfc", &text);
    let (l, ch) = pos(&text, "STEP Fill", 6);
    assert_snapshot!("hover_step", c.at_shown("hover", "batch.sfc", l, ch));
    c.shutdown();
}

#[test]
fn hover_without_a_database_says_so() {
    let root = workspace("lsp-nodb", &[("lone.st", "TIC_100.PV := 1.0;\n")]);
    let mut c = Client::start(&root, json!({ "debounceMs": 0 }));
    c.open("lone.st", "TIC_100.PV := 1.0;\n");
    assert_snapshot!("hover_no_database", c.at_shown("hover", "lone.st", 0, 3));
    c.shutdown();
}

#[test]
fn hover_on_an_fst_command_and_tlp() {
    let root =
        workspace("lsp-fst", &[("plant.json", &example("fst/plant.json")), ("pump.csv", &example("fst/pump.csv"))]);
    let mut c = Client::start(&root, json!({ "debounceMs": 0 }));
    let text = example("fst/pump.csv");
    c.open("pump.csv", &text);
    let (l, ch) = pos(&text, "VAL,\"AIN 2-1,EU\"", 1);
    assert_snapshot!("hover_fst_command", c.at_shown("hover", "pump.csv", l, ch));
    let (l, ch) = pos(&text, "\"AIN 2-1,EU\"", 3);
    assert_snapshot!("hover_fst_tlp", c.at_shown("hover", "pump.csv", l, ch));
    let (l, ch) = pos(&text, ",START,", 2);
    assert_snapshot!("definition_fst_label", c.at_shown("definition", "pump.csv", l, ch));
    let completion = c.clone_at("completion", "pump.csv", 3, 4);
    let labels: Vec<&Value> = completion.as_array().expect("items").iter().map(|i| &i["label"]).take(6).collect();
    assert_snapshot!("completion_fst_commands", c.show(&json!(labels)));
    // In ARGUMENT1: the points of the database, then a point's parameters.
    let (l, ch) = pos(&text, "VAL,\"AIN 2-1,EU\"", 5);
    assert_snapshot!("completion_fst_points", c.at_shown("completion", "pump.csv", l, ch));
    let (l, ch) = pos(&text, "VAL,\"AIN 2-1,EU\"", 13);
    let params = c.clone_at("completion", "pump.csv", l, ch);
    let labels: Vec<&Value> = params.as_array().expect("items").iter().map(|i| &i["label"]).take(4).collect();
    assert_snapshot!("completion_fst_parameters", c.show(&json!(labels)));
    c.shutdown();
}

#[test]
fn definitions_go_to_the_database_and_to_steps_and_actions() {
    let mut c = strategy("lsp-def");
    let text = example("strategy/actions.stx");
    c.open("actions.stx", &text);
    let (l, ch) = pos(&text, "TANK1.Level :=", 2);
    assert_snapshot!("definition_block", c.at_shown("definition", "actions.stx", l, ch));
    let (l, ch) = pos(&text, "DRAIN.Trigger", 8);
    assert_snapshot!("definition_field", c.at_shown("definition", "actions.stx", l, ch));
    let db = example("strategy/plant.json");
    c.open("plant.json", &db);
    let (l, ch) = pos(&db, "\"ActName\": \"Drain\"", 13);
    assert_snapshot!("definition_actname", c.at_shown("definition", "plant.json", l, ch));
    c.shutdown();

    let mut c = sequences("lsp-def-seq");
    let text = example("sequences/batch.sfc");
    c.open("batch.sfc", &text);
    let (l, ch) = pos(&text, "FROM Idle TO Fill", 14);
    assert_snapshot!("definition_step", c.at_shown("definition", "batch.sfc", l, ch));
    let (l, ch) = pos(&text, "FillOn(N)", 2);
    assert_snapshot!("definition_action", c.at_shown("definition", "batch.sfc", l, ch));
    c.shutdown();
}

#[test]
fn a_jump_goes_to_its_label() {
    let text = "        [a.x] -> JUMP Skip;\n        [b.x] -> (c.y);\nSkip:   [d.x] -> (e.y);\n";
    let root = workspace("lsp-label", &[("rungs.ld", text)]);
    let mut c = Client::start(&root, json!({ "debounceMs": 0 }));
    c.open("rungs.ld", text);
    assert_snapshot!("definition_label", c.at_shown("definition", "rungs.ld", 0, 24));
    c.shutdown();
}

#[test]
fn references_of_a_field_span_the_workspace() {
    let mut c = strategy("lsp-refs");
    let text = example("strategy/actions.stx");
    c.open("actions.stx", &text);
    let (l, ch) = pos(&text, "TANK1.HighCnt", 8);
    let uri = c.uri("actions.stx");
    let refs = c.request(
        "textDocument/references",
        json!({ "textDocument": { "uri": uri }, "position": { "line": l, "character": ch },
                "context": { "includeDeclaration": true } }),
    );
    assert_snapshot!("references_field", c.show(&refs));
    c.shutdown();
}

#[test]
fn completion_offers_fields_enumerations_functions_and_steps() {
    let mut c = guide("lsp-complete");
    let text = "PIC_004.Mode := \"AU\";\nTIC_100.\n";
    c.open("a.st", text);
    assert_snapshot!("completion_enum_values", c.at_shown("completion", "a.st", 0, 19));
    let fields = c.clone_at("completion", "a.st", 1, 8);
    assert_snapshot!("completion_fields", c.show(&fields));
    let names = c.clone_at("completion", "a.st", 2, 0);
    let blocks: Vec<&Value> = names.as_array().expect("items").iter().filter(|i| i["kind"] == 6).collect();
    assert_snapshot!("completion_blocks_and_aliases", c.show(&json!(blocks)));
    let all = c.clone_at("completion", "a.st", 2, 0);
    let abs: Vec<&Value> = all.as_array().expect("items").iter().filter(|i| i["label"] == "ATAN2").collect();
    assert_snapshot!("completion_function_snippet", c.show(&json!(abs)));
    c.shutdown();

    let mut c = sequences("lsp-complete-seq");
    let text = example("sequences/batch.sfc");
    c.open("batch.sfc", &text);
    let (l, _) = pos(&text, "TRANSITION FROM Idle", 0);
    let items = c.clone_at("completion", "batch.sfc", l, 0);
    let steps: Vec<&Value> = items.as_array().expect("items").iter().filter(|i| i["detail"] == "step").collect();
    assert_snapshot!("completion_steps", c.show(&json!(steps)));
    let (l, ch) = pos(&text, "Agitate.T", 8);
    assert_snapshot!("completion_step_variables", c.at_shown("completion", "batch.sfc", l, ch));
    c.shutdown();
}

#[test]
fn symbols_tokens_formatting_rename_and_fixes() {
    let mut c = sequences("lsp-symbols");
    let text = example("sequences/batch.sfc");
    c.open("batch.sfc", &text);
    let uri = c.uri("batch.sfc");
    let doc = json!({ "textDocument": { "uri": uri } });
    assert_snapshot!("document_symbols", c.request_shown("textDocument/documentSymbol", doc.clone()));
    assert_snapshot!("workspace_symbols", c.request_shown("workspace/symbol", json!({ "query": "fill" })));
    let (l, ch) = pos(&text, "STEP Heat", 6);
    let edit = c.request(
        "textDocument/rename",
        json!({ "textDocument": { "uri": uri }, "position": { "line": l, "character": ch }, "newName": "Warm" }),
    );
    assert_snapshot!("rename_step", c.show(&edit));
    c.shutdown();

    let mut c = guide("lsp-tokens");
    let text = "(* set *)\nIF PIC_004.PV > 1.5 THEN TIC_100.SL := ABS(-2); END_IF;\n";
    c.open("t.st", text);
    let uri = c.uri("t.st");
    let doc = json!({ "textDocument": { "uri": uri } });
    assert_snapshot!("semantic_tokens", c.request_shown("textDocument/semanticTokens/full", doc.clone()));
    let fmt = json!({ "textDocument": { "uri": uri }, "options": { "tabSize": 4, "insertSpaces": true } });
    assert_snapshot!("formatting", c.request_shown("textDocument/formatting", fmt));
    let bad = "PIC_004.Mode := \"AUTOMATIC\";\nTIC_100.PVV := 1.0;\n";
    c.change("t.st", 2, bad);
    let diags = c.diagnostics_at("t.st", 2);
    assert_eq!(diags["diagnostics"].as_array().map(Vec::len), Some(2), "{diags}");
    let actions = c.request(
        "textDocument/codeAction",
        json!({ "textDocument": { "uri": uri },
                "range": { "start": { "line": 0, "character": 0 }, "end": { "line": 2, "character": 0 } },
                "context": { "diagnostics": diags["diagnostics"] } }),
    );
    assert_snapshot!("code_actions", c.show(&actions));
    // After another change the fixes' offsets no longer hold: none is offered.
    c.change("t.st", 3, &format!("(* moved *)\n{bad}"));
    let stale = c.request(
        "textDocument/codeAction",
        json!({ "textDocument": { "uri": uri },
                "range": { "start": { "line": 0, "character": 0 }, "end": { "line": 2, "character": 0 } },
                "context": { "diagnostics": diags["diagnostics"] } }),
    );
    assert_eq!(stale, json!([]));
    c.shutdown();
}

#[test]
fn enumerations_complete_after_a_comparison_and_renames_are_checked() {
    let mut c = guide("lsp-compare");
    let text = "IF PIC_004.Mode <> 'MAN' THEN END_IF;
";
    c.open("c.st", text);
    let items = c.clone_at("completion", "c.st", 0, 21);
    let labels: Vec<&Value> = items.as_array().expect("items").iter().map(|i| &i["label"]).collect();
    assert_eq!(labels.len(), 8, "{items}");
    assert!(labels.contains(&&json!("MANUAL")), "{items}");
    c.shutdown();

    let mut c = sequences("lsp-rename-bad");
    let text = example("sequences/batch.sfc");
    c.open("batch.sfc", &text);
    let (l, ch) = pos(&text, "STEP Heat", 6);
    let uri = c.uri("batch.sfc");
    for bad in ["TooLongName", "9Lives", "END_IF"] {
        let e = c.answer(
            "textDocument/rename",
            json!({ "textDocument": { "uri": uri }, "position": { "line": l, "character": ch }, "newName": bad }),
        );
        assert!(e.as_ref().is_err_and(|m| m.contains(bad)), "{bad}: {e:?}");
    }
    c.shutdown();

    // A step named like a block: `Plant.N0` is the block's field, and a
    // rename of the step leaves it alone.
    let mut c = sequences("lsp-rename-shadow");
    let text = example("sequences/batch.sfc").replace("Aborted", "Plant");
    c.open("batch.sfc", &text);
    let (l, ch) = pos(&text, "STEP Plant", 6);
    let edit = c.request(
        "textDocument/rename",
        json!({ "textDocument": { "uri": c.uri("batch.sfc") }, "position": { "line": l, "character": ch }, "newName": "Halted" }),
    );
    let edits = edit["changes"][c.uri("batch.sfc").as_str()].as_array().expect("edits").clone();
    let lines: Vec<u64> = edits.iter().map(|e| e["range"]["start"]["line"].as_u64().expect("line")).collect();
    let want: Vec<u64> = text
        .lines()
        .enumerate()
        .filter(|(_, t)| t.contains("STEP Plant") || t.contains("TO Plant") || t.contains("FROM Plant"))
        .map(|(i, _)| i as u64)
        .collect();
    assert_eq!(lines, want, "{edit}");
    assert!(text.contains("Plant.N0"), "the block is still used");
    c.shutdown();
}

#[test]
fn changes_in_quick_succession_are_checked_once() {
    let root = workspace("lsp-debounce", &[("a.st", "x.y := 1;\n")]);
    let mut c = Client::start(&root, json!({ "debounceMs": 400 }));
    c.open("a.st", "x.y := 1;\n");
    assert_eq!(c.diagnostics("a.st")["version"], 1, "an opened file is checked at once");
    for v in 2..=4 {
        c.change("a.st", v, &format!("x.y := {v}\n"));
    }
    let d = c.diagnostics("a.st");
    assert_eq!(d["version"], 4, "only the last of three quick changes is checked: {d}");
    assert_eq!(d["diagnostics"][0]["code"], "W0001", "{d}");
    c.shutdown();
}

#[test]
fn hover_and_completion_work_where_the_parser_gave_up() {
    let mut c = guide("lsp-broken");
    let text = "IF TIC_100.PV > THEN\nPIC_004.Mode := \"\nTIC_100.\n";
    c.open("b.st", text);
    let d = c.diagnostics("b.st");
    assert!(!d["diagnostics"].as_array().expect("list").is_empty(), "{d}");
    let hover = c.clone_at("hover", "b.st", 0, 12);
    assert_eq!(
        hover["contents"]["value"].as_str().map(|v| v.starts_with("**TIC_100.PV** : `REAL`")),
        Some(true),
        "{hover}"
    );
    let values = c.clone_at("completion", "b.st", 1, 17);
    assert!(values.to_string().contains("\"CASCADE\""), "{values}");
    let fields = c.clone_at("completion", "b.st", 2, 8);
    assert!(fields.to_string().contains("\"TrimSP\""), "{fields}");
    c.shutdown();
}

/// What a name resolves to is kept with the document (resolving checks the
/// whole file) until its text or its database changes: each change is seen
/// by the next hover.
#[test]
fn hover_follows_changes_to_the_text_and_to_the_database() {
    let mut c = guide("lsp-hover-cache");
    c.open("c.st", "TIC_100.PV := 1.0;\n");
    let shown = |c: &mut Client| c.clone_at("hover", "c.st", 0, 9)["contents"]["value"].as_str().map(str::to_string);
    assert!(shown(&mut c).is_some_and(|v| v.starts_with("**TIC_100.PV** : `REAL`")), "{:?}", shown(&mut c));
    // The same place now holds another field.
    c.change("c.st", 2, "TIC_100.SL := 1.0;\n");
    assert!(shown(&mut c).is_some_and(|v| v.starts_with("**TIC_100.SL**")), "{:?}", shown(&mut c));
    // A database edited in the editor: TIC_100 no longer exists.
    let db = example("guide/plant.db.json").replace("\"TIC_100\"", "\"TIC_200\"");
    c.open("plant.db.json", &db);
    let after = shown(&mut c);
    assert!(!after.as_deref().is_some_and(|v| v.starts_with("**TIC_100.SL**")), "{after:?}");
    c.shutdown();
}

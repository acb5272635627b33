//! A ladder action run by an ACTION block of a strategy.
mod common;
use common::{linc, stderr, stdout, temp_dir};

#[test]
fn an_action_block_runs_a_ladder_file() {
    let dir = temp_dir("ladder-strategy");
    std::fs::copy(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/ladder/interlock.ld"), dir.join("interlock.ld"))
        .expect("copy");
    let text =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/ladder/plant.json")).expect("db");
    let mut db: serde_json::Value = serde_json::from_str(&text).expect("json");
    db["blocks"]["LAD"] = serde_json::json!({ "type": "ACTION",
        "values": { "FileName": "interlock.ld", "ActName": "interlock", "Trigger": true } });
    let plant = dir.join("plant.json");
    std::fs::write(&plant, db.to_string()).expect("write");
    let o = linc(&[
        "run",
        plant.to_str().unwrap(),
        "--for",
        "1s",
        "--set",
        "Dig_1a.In=1",
        "--set",
        "Dig_3a.In=1",
        "--show",
        "Dig_1b.Out",
        "--show",
        "Dig_3c.Out",
        "--show",
        "LAD.Active",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), "Dig_1b.Out = TRUE\nDig_3c.Out = TRUE\nLAD.Active = TRUE\n");
}

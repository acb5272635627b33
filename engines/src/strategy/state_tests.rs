//! Saved states without programs: the document, its refusals and the
//! database and clock it carries (programs are tested through the CLI,
//! which compiles them: `cli/tests/state.rs`).

use super::*;
use crate::db::Database;
use crate::errors::RuntimeError;
use crate::store::Store;
use crate::vm::{Clock, Vm};

const DB: &str = r#"{ "templates": { "TANK": { "fields": { "A0": "REAL", "N0": "INT", "Flags": "BITS16",
    "On": "BOOL", "Tag": "STRING", "Mode": { "ENUM": ["MANUAL", "AUTO"] },
    "Alarms": { "ALARMS": ["HighAbs", "LowAbs"] } } } },
    "blocks": { "T1": { "type": "TANK", "values": { "A0": 12.5, "Mode": "AUTO" } },
                "T2": { "type": "TANK" } } }"#;

fn strategy(text: &str) -> Strategy {
    let db = Database::from_json(text).expect("database");
    let vm = Vm::new(1000, Clock::new(7, 0));
    Strategy::build(Store::new(db), Vec::new(), &[], vm, 1_767_225_600.0).expect("strategy")
}

fn set(s: &mut Strategy, block: usize, field: &str, v: Cell) {
    let c = s.store.cell_of(block, field).expect("field");
    s.store.cells[c as usize] = v;
}

/// A strategy 90 s into its run with a value of every kind changed.
fn changed() -> Strategy {
    let mut s = strategy(DB);
    s.run_for(90_000_000, None);
    set(&mut s, 0, "A0", Cell::Real(f32::MAX));
    set(&mut s, 1, "A0", Cell::Real(-0.0));
    set(&mut s, 0, "N0", Cell::Int(-42));
    set(&mut s, 0, "Flags", Cell::Bits { v: 0x8001, width: 16 });
    set(&mut s, 0, "On", Cell::Bool(true));
    set(&mut s, 1, "Tag", Cell::Text(b"caf\xc3\xa9 $".to_vec()));
    set(&mut s, 1, "Mode", Cell::Enum { idx: 1 });
    let c = s.store.cell_of(0, "Alarms").expect("alarms") as usize;
    if let Cell::Alarms(a) = &mut s.store.cells[c] {
        a.active[1] = true;
        a.until[0] = f64::INFINITY;
        a.all_until = 1_767_225_700.5;
    }
    s
}

#[test]
fn a_saved_state_restores_every_value_and_the_clock() {
    let s = changed();
    let bytes = s.save_state();
    let mut t = strategy(DB);
    assert_eq!(t.restore_state(&bytes), Ok(()));
    assert_eq!(t.elapsed_us(), 90_000_000);
    assert_eq!(t.store.now, 1_767_225_690.0, "a warm start continues the same day");
    // Compare the cells' saved forms (-0.0 differs from 0.0), then the rest.
    let form = |s: &Strategy| s.store.cells.iter().map(parts::cell_json).collect::<Vec<_>>();
    assert_eq!(form(&t), form(&s));
    assert_eq!(t.store.cells[1], Cell::Int(-42));
    assert_eq!(t.save_state(), bytes, "saving a restored strategy gives the same bytes");
}

#[test]
fn the_error_status_is_retentive() {
    let mut s = strategy(DB);
    let error = RuntimeError {
        code: Code::R0003,
        message: "division by zero".into(),
        action: "Bad".into(),
        file: "a.st".into(),
        line: 3,
        col: 9,
    };
    s.error = Some(ErrorStatus { error, block: "BAD".into(), at_us: 2_000_000, double: false });
    let mut t = strategy(DB);
    assert_eq!(t.restore_state(&s.save_state()), Ok(()));
    assert_eq!(t.error(), s.error());
    assert_eq!(t.error().map(ErrorStatus::number), Some(3));
}

#[test]
fn a_file_cut_at_any_length_is_refused_and_changes_nothing() {
    let bytes = changed().save_state();
    let mut t = strategy(DB);
    let before = t.save_state();
    for n in 0..bytes.len() {
        let e = t.restore_state(&bytes[..n]).expect_err("cut short");
        assert_eq!(e.code.as_str(), "E0840", "cut at {n}: {e}");
        assert_eq!(t.save_state(), before, "cut at {n} changed the strategy");
    }
    let mut longer = bytes.clone();
    longer.push(b' ');
    assert_eq!(t.restore_state(&longer).map_err(|e| e.code.as_str()), Err("E0840"));
}

#[test]
fn a_flipped_bit_anywhere_is_refused() {
    let bytes = changed().save_state();
    let mut t = strategy(DB);
    let before = t.save_state();
    for i in 0..bytes.len() {
        for bit in [0x01u8, 0x10, 0x80] {
            let mut bad = bytes.clone();
            bad[i] ^= bit;
            let e = t.restore_state(&bad).expect_err("flipped");
            assert!(["E0840", "E0841", "E0842"].contains(&e.code.as_str()), "byte {i}: {e:?}");
        }
    }
    assert_eq!(t.save_state(), before);
}

/// A file written with another body, re-sealed with a correct header.
fn sealed(version: u64, body: &[u8]) -> Vec<u8> {
    let header = json!({"linc-state": version, "crc32": crc32(body), "length": body.len()});
    let mut out = header.to_string().into_bytes();
    out.push(b'\n');
    out.extend_from_slice(body);
    out
}

#[test]
fn another_version_is_refused_with_its_own_code() {
    let bytes = changed().save_state();
    let nl = bytes.iter().position(|&b| b == b'\n').expect("header") + 1;
    let e = strategy(DB).restore_state(&sealed(2, &bytes[nl..])).expect_err("version 2");
    assert_eq!((e.code.as_str(), e.message.contains("version 2")), ("E0841", true), "{e}");
}

#[test]
fn a_state_of_another_database_is_refused() {
    let bytes = changed().save_state();
    // One more field in the template: the same blocks, another layout.
    let other = DB.replace(r#""On": "BOOL","#, r#""On": "BOOL", "Off": "BOOL","#);
    let mut t = strategy(&other);
    let e = t.restore_state(&bytes).expect_err("another database");
    assert_eq!(e.code.as_str(), "E0842", "{e}");
    let renamed = DB.replace("\"T2\"", "\"T3\"");
    assert_eq!(strategy(&renamed).restore_state(&bytes).map_err(|e| e.code.as_str()), Err("E0842"));
}

#[test]
fn a_checksummed_body_that_does_not_fit_is_refused() {
    let s = changed();
    let mut doc = s.state_json();
    doc["cells"][0] = json!(["I", 5]);
    let body = serde_json::to_vec(&doc).expect("json");
    let e = strategy(DB).restore_state(&sealed(1, &body)).expect_err("an INT in a REAL");
    assert_eq!(e.code.as_str(), "E0842");
    assert!(e.message.contains("T1.A0"), "{e}");
    let mode = s.store.cell_of(1, "Mode").expect("mode") as usize;
    let mut doc = s.state_json();
    doc["cells"][mode] = json!(["E", 2]);
    let body = serde_json::to_vec(&doc).expect("json");
    let e = strategy(DB).restore_state(&sealed(1, &body)).expect_err("a third value of a two-value ENUM");
    assert!(e.message.contains("T2.Mode") && e.message.contains("range"), "{e}");
    let mut doc = s.state_json();
    doc["cells"] = json!([]);
    let body = serde_json::to_vec(&doc).expect("json");
    assert_eq!(strategy(DB).restore_state(&sealed(1, &body)).map_err(|e| e.code.as_str()), Err("E0842"));
}

/// What the loader refuses in a database (a REAL that is not finite, a
/// string over 65,535 bytes) is refused in a saved state too.
#[test]
fn a_value_the_loader_would_refuse_is_refused() {
    let s = changed();
    let a0 = s.store.cell_of(0, "A0").expect("A0") as usize;
    let tag = s.store.cell_of(1, "Tag").expect("Tag") as usize;
    let long = "41".repeat(crate::vm::MAX_STRING + 1);
    let cases = [
        (a0, json!(["R", f32::NAN.to_bits()])),
        (a0, json!(["R", f32::INFINITY.to_bits()])),
        (a0, json!(["R", f32::NEG_INFINITY.to_bits()])),
        (tag, json!(["T", long])),
    ];
    for (cell, value) in cases {
        let mut doc = s.state_json();
        doc["cells"][cell] = value;
        let body = serde_json::to_vec(&doc).expect("json");
        let e = strategy(DB).restore_state(&sealed(1, &body)).expect_err("refused");
        assert_eq!(e.code.as_str(), "E0842", "{e}");
        assert!(e.message.contains("range"), "{e}");
    }
    // At the limit, a string is kept.
    let mut doc = s.state_json();
    doc["cells"][tag] = json!(["T", "41".repeat(crate::vm::MAX_STRING)]);
    let body = serde_json::to_vec(&doc).expect("json");
    assert_eq!(strategy(DB).restore_state(&sealed(1, &body)), Ok(()));
}

#[test]
fn a_schedule_far_behind_the_clock_is_refused() {
    let db = DB.replace(r#""blocks""#, r#""tasks": { "1": { "period": "T#1s" } }, "blocks""#);
    let s = {
        let mut s = strategy(&db);
        s.run_for(5_000_000, None);
        s
    };
    let mut t = strategy(&db);
    assert_eq!(t.restore_state(&s.save_state()), Ok(()));
    let mut doc = s.state_json();
    doc["clock"]["tasks"][0] = json!(0);
    let body = serde_json::to_vec(&doc).expect("json");
    let e = t.restore_state(&sealed(1, &body)).expect_err("a task due 5 s ago");
    assert_eq!(e.code.as_str(), "E0842", "{e}");
}

#[test]
fn a_hostile_header_is_refused_without_allocating() {
    let huge = br#"{"linc-state":1,"crc32":0,"length":18446744073709551615}
{}"#;
    assert_eq!(strategy(DB).restore_state(huge).map_err(|e| e.code.as_str()), Err("E0840"));
    let long = [b' '; 4096];
    assert_eq!(strategy(DB).restore_state(&long).map_err(|e| e.code.as_str()), Err("E0840"));
    assert_eq!(strategy(DB).restore_state(b"").map_err(|e| e.code.as_str()), Err("E0840"));
}

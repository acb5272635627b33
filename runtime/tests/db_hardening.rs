//! The database loader refuses, with a located and coded error, every file
//! whose meaning would otherwise be silently changed: repeated keys, names
//! that clash or cannot be stored, values that cannot be written back, and
//! aliases that never end.

use linc_runtime::store::Cell;
use linc_runtime::{Database, Store};

/// The byte range of the `nth` (0-based) occurrence of `needle` in `text`.
fn span(text: &str, needle: &str, nth: usize) -> Option<(usize, usize)> {
    let at = text.match_indices(needle).nth(nth).map(|(i, _)| i).expect("needle in text");
    Some((at, at + needle.len()))
}

/// Loads `text`, expecting `code` located at the `nth` occurrence of `needle`.
fn fails(text: &str, code: &str, needle: &str, nth: usize) -> String {
    let e = Database::from_json(text).expect_err(text);
    assert_eq!((e.code.as_str(), e.span), (code, span(text, needle, nth)), "{}", e.message);
    e.message
}

#[test]
fn repeated_keys_are_located_at_the_second_one() {
    let values = r#"{ "blocks": { "REC1": { "type": "RECIPE", "values": { "A0": 1, "A0": 2 } } } }"#;
    let m = fails(values, "E0807", "\"A0\"", 1);
    assert!(m.contains("`A0` appears twice"), "{m}");
    let blocks = r#"{ "blocks": { "REC1": { "type": "RECIPE" }, "REC1": { "type": "RECIPE" } } }"#;
    fails(blocks, "E0807", "\"REC1\"", 1);
    let top = r#"{ "blocks": {}, "blocks": {} }"#;
    fails(top, "E0807", "\"blocks\"", 1);
}

#[test]
fn duplicate_names_ignoring_case() {
    let alias = r#"{ "blocks": { "REC1": { "type": "RECIPE" } }, "aliases": { "rec1": "REC1.A0" } }"#;
    let m = fails(alias, "E0806", "\"rec1\"", 0);
    assert!(m.contains("same name as block `REC1`"), "{m}");
    let templates = r#"{ "templates": { "T": { "fields": {} }, "t": { "fields": {} } } }"#;
    fails(templates, "E0806", "\"t\"", 0);
    // Overriding a built-in template is still allowed, once.
    assert!(Database::from_json(r#"{ "templates": { "pid": { "fields": { "PV": "REAL" } } } }"#).is_ok());
    let bits = r#"{ "templates": { "T": { "fields": { "B": { "BITS8": ["Run", "Stop", "RUN"] } } } } }"#;
    fails(bits, "E0806", "\"RUN\"", 0);
    let enums = r#"{ "templates": { "T": { "fields": { "M": { "ENUM": ["Auto", "Man", "auto"] } } } } }"#;
    fails(enums, "E0806", "\"auto\"", 0);
    let alarms = r#"{ "templates": { "T": { "fields": { "A": { "ALARMS": ["Hi", "HI"] } } } } }"#;
    fails(alarms, "E0806", "\"HI\"", 0);
    let values = r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "A0": 1, "a0": 2 } } } }"#;
    fails(values, "E0806", "\"a0\"", 0);
}

#[test]
fn readonly_must_be_a_boolean() {
    let text = r#"{ "templates": { "T": { "fields": { "F": { "type": "REAL", "readonly": "yes" } } } } }"#;
    fails(text, "E0814", "\"yes\"", 0);
    // A misspelt option is not silently ignored either.
    let text = r#"{ "templates": { "T": { "fields": { "F": { "type": "REAL", "readOnly": true } } } } }"#;
    fails(text, "E0802", "\"readOnly\"", 0);
}

#[test]
fn unknown_keys_in_blocks_and_templates() {
    let text = r#"{ "blocks": { "R": { "type": "RECIPE", "valeus": { "A0": 1 } } } }"#;
    fails(text, "E0801", "\"valeus\"", 0);
    let text = r#"{ "templates": { "T": { "field": { "A0": "REAL" } } } }"#;
    fails(text, "E0801", "\"field\"", 0);
}

#[test]
fn empty_names() {
    fails(r#"{ "blocks": { "": { "type": "RECIPE" } } }"#, "E0811", "\"\"", 0);
    fails(r#"{ "templates": { "": { "fields": {} } } }"#, "E0811", "\"\"", 0);
    fails(r#"{ "templates": { "T": { "fields": { "": "REAL" } } } }"#, "E0811", "\"\"", 0);
    fails(r#"{ "blocks": { "R": { "type": "RECIPE" } }, "aliases": { "": "R.A0" } }"#, "E0811", "\"\"", 0);
    fails(r#"{ "templates": { "T": { "fields": { "M": { "ENUM": ["A", ""] } } } } }"#, "E0811", "\"\"", 0);
}

#[test]
fn names_longer_than_a_u16_length() {
    let long = "X".repeat(65_536);
    let just_fits = "Y".repeat(65_535);
    let block =
        format!(r#"{{ "blocks": {{ "{long}": {{ "type": "RECIPE" }}, "{just_fits}": {{ "type": "RECIPE" }} }} }}"#);
    fails(&block, "E0812", &format!("\"{long}\""), 0);
    let ok = format!(r#"{{ "blocks": {{ "{just_fits}": {{ "type": "RECIPE" }} }} }}"#);
    assert!(Database::from_json(&ok).is_ok());
    let field = format!(r#"{{ "templates": {{ "T": {{ "fields": {{ "{long}": "REAL" }} }} }} }}"#);
    fails(&field, "E0812", &format!("\"{long}\""), 0);
    let template = format!(r#"{{ "templates": {{ "{long}": {{ }} }} }}"#);
    fails(&template, "E0812", &format!("\"{long}\""), 0);
    let alias = format!(r#"{{ "aliases": {{ "{long}": "A.B" }} }}"#);
    fails(&alias, "E0812", &format!("\"{long}\""), 0);
}

#[test]
fn enum_indices_never_wrap() {
    let list = |n: usize| (0..n).map(|i| format!("\"V{i}\"")).collect::<Vec<_>>().join(",");
    let too_many =
        format!(r#"{{ "templates": {{ "T": {{ "fields": {{ "M": {{ "ENUM": [{}] }} }} }} }} }}"#, list(65_537));
    fails(&too_many, "E0813", &format!("[{}]", list(65_537)), 0);
    let most = format!(r#"{{ "templates": {{ "T": {{ "fields": {{ "M": {{ "ENUM": [{}] }} }} }} }} }}"#, list(65_536));
    assert!(Database::from_json(&most).is_ok());
}

/// The first cell of block `R` after loading `values` into a RECIPE
/// (A0–A7 REAL, N0–N7 INT) or `template`.
fn cells(text: &str) -> Vec<Cell> {
    Store::new(Database::from_json(text).expect(text)).cells
}

#[test]
fn values_that_cannot_be_stored_are_refused() {
    let real = r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "A0": 1e300 } } } }"#;
    let m = fails(real, "E0815", "1e300", 0);
    assert!(m.contains("1e300 does not fit a REAL field"), "{m}");
    fails(r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "A1": -4e38 } } } }"#, "E0815", "-4e38", 0);
    fails(r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "A1": 1e999 } } } }"#, "E0815", "1e999", 0);
    fails(r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "N0": 2147483648 } } } }"#, "E0815", "2147483648", 0);
    fails(r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "N0": -2147483649 } } } }"#, "E0815", "-2147483649", 0);
    fails(r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "N0": 2.5 } } } }"#, "E0815", "2.5", 0);
    fails(r#"{ "blocks": { "D": { "type": "DIGIN", "values": { "Out": 256 } } } }"#, "E0815", "256", 0);
    fails(r#"{ "blocks": { "D": { "type": "DIGIN", "values": { "Out": -1 } } } }"#, "E0815", "-1", 0);
    fails(r#"{ "blocks": { "D": { "type": "DIGACT", "values": { "In": 65536 } } } }"#, "E0815", "65536", 0);
    fails(r#"{ "blocks": { "D": { "type": "DIGACT", "values": { "In": -32769 } } } }"#, "E0815", "-32769", 0);
}

#[test]
fn values_at_the_edges_are_kept_exactly() {
    let c = cells(
        r#"{ "blocks": { "R": { "type": "RECIPE", "values": { "A0": 3.4028235e38, "N0": 2147483647, "N1": -2147483648, "N2": 16777217 } } } }"#,
    );
    assert_eq!(c[0], Cell::Real(f32::MAX));
    assert_eq!(c[8..11], [Cell::Int(i32::MAX), Cell::Int(i32::MIN), Cell::Int(16_777_217)]);
    let c = cells(r#"{ "blocks": { "D": { "type": "DIGIN", "values": { "Out": 255 } } } }"#);
    assert_eq!(c[1], Cell::Bits { v: 255, width: 8 });
    let c = cells(r#"{ "blocks": { "D": { "type": "DIGACT", "values": { "In": -32768, "Out": 65535 } } } }"#);
    // DIGACT: Mode, Alarms, FileName, ActName, Trigger, Qualifier, QualTime, Active, Status, In, Out.
    assert_eq!(c[9..11], [Cell::Bits { v: 0x8000, width: 16 }, Cell::Bits { v: 0xFFFF, width: 16 }]);
}

#[test]
fn aliases_of_aliases_are_expanded() {
    let text = r#"{ "blocks": { "PID1": { "type": "PID" } },
        "aliases": { "top": "mid.HiHi", "mid": "low.Alarms", "low": "PID1" } }"#;
    let db = Database::from_json(text).expect("loads");
    let target = |a: &str| db.alias(a).map(|a| a.target.join("."));
    assert_eq!(target("top").as_deref(), Some("PID1.Alarms.HiHi"));
    assert_eq!(target("MID").as_deref(), Some("PID1.Alarms"));
    assert_eq!(target("low").as_deref(), Some("PID1"));
}

#[test]
fn alias_cycles_are_errors() {
    let two = r#"{ "aliases": { "a": "b.X", "b": "a.Y" } }"#;
    let m = fails(two, "E0816", "\"a.Y\"", 0);
    assert!(m.contains("a -> b -> a"), "{m}");
    let own = r#"{ "aliases": { "a": "A.X" } }"#;
    fails(own, "E0816", "\"A.X\"", 0);
    let three = r#"{ "aliases": { "ok": "c.Z", "c": "d", "d": "e.Q", "e": "c.R" } }"#;
    let m = fails(three, "E0816", "\"c.R\"", 0);
    assert!(m.contains("c -> d -> e -> c"), "{m}");
}

#[test]
fn alias_expansion_cannot_exhaust_memory() {
    // Ten thousand aliases of one alias with a 4 KB target would expand to
    // 40 MB; the loader refuses instead of allocating it.
    let long = "F".repeat(4_000);
    let mut text = format!(r#"{{ "aliases": {{ "base": "B.{long}""#);
    for i in 0..10_000 {
        text.push_str(&format!(r#", "a{i}": "base.X""#));
    }
    text.push_str(" } }");
    let e = Database::from_json(&text).expect_err("too big");
    assert_eq!(e.code, "E0817");
}

#[test]
fn bad_input_is_never_a_panic() {
    let deep = format!("{{\"blocks\": {}", "[".repeat(1_000_000));
    assert_eq!(Database::from_json(&deep).map_err(|e| e.code.as_str()).err(), Some("E0800"));
    for text in ["", "null", "[]", "{\"blocks\": []}", "{\"blocks\": {\"B\": 1}}", "{\"aliases\": {\"a\": 1}}"] {
        let e = Database::from_json(text).expect_err(text);
        assert!(e.span.is_some(), "{text}: {e}");
    }
}

/// A template of `fields` REAL fields and `blocks` blocks of it.
fn big_database(fields: usize, blocks: usize) -> String {
    let f: Vec<String> = (0..fields).map(|i| format!("\"F{i}\": \"REAL\"")).collect();
    let b: Vec<String> = (0..blocks).map(|i| format!("\"B{i}\": {{ \"type\": \"BIG\" }}")).collect();
    format!(
        "{{ \"templates\": {{ \"BIG\": {{ \"fields\": {{ {} }} }} }}, \"blocks\": {{ {} }} }}",
        f.join(", "),
        b.join(", ")
    )
}

/// Every field of every block is a cell of the store: the blocks of a
/// database have at most `MAX_CELLS` fields, counted before any cell is
/// made (240 million cells were declared in 562 KB).
#[test]
fn a_database_has_at_most_max_cells_fields() {
    let max = linc_runtime::db::MAX_CELLS;
    let db = Database::from_json(&big_database(1 << 12, max >> 12)).expect("exactly the limit loads");
    assert_eq!(Store::new(db).cells.len(), max);
    let text = big_database(1 << 12, (max >> 12) + 40);
    let m = fails(&text, "E0819", &format!("\"B{}\"", max >> 12), 0);
    assert!(m.contains(&format!("{} fields", max + (1 << 12))) && m.contains("at most 1048576"), "{m}");
}

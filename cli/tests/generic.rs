//! Generic sequences (guide §9.1) and resources (§9.5) from the command line.

mod common;
use common::{linc, stderr, stdout, temp_dir};
use std::fs;

const SEQ: &str = "examples/sequences/generic.sfc";
const DB: &str = "examples/sequences/generic.plant.json";
const MAP1: &str = "examples/sequences/reactor1.map.json";
const MAP2: &str = "examples/sequences/reactor2.map.json";

/// The text after the first blank line (the header comment differs).
fn body(s: &str) -> &str {
    s.split_once("\n\n").map(|(_, b)| b).unwrap_or(s)
}

#[test]
fn generic_sequence_checks_clean_with_each_map() {
    for map in [MAP1, MAP2] {
        let o = linc(&["check", SEQ, "--map", map, "--db", DB]);
        assert_eq!(o.status.code(), Some(0), "{map}: {}{}", stdout(&o), stderr(&o));
        assert_eq!(stdout(&o), "");
    }
}

#[test]
fn without_a_map_generic_names_are_unknown() {
    let o = linc(&["check", SEQ, "--db", DB, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    let out = stderr(&o);
    assert_eq!(out.matches("E0100").count(), 23, "{out}");
}

#[test]
fn specialise_gives_the_batch_and_generalise_round_trips() {
    let dir = temp_dir("generic-roundtrip");
    let specific = dir.join("tank1.sfc");
    let back = dir.join("back.sfc");
    let o = linc(&["sfc", "specialise", SEQ, "--map", MAP1, "-o", specific.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let written = fs::read_to_string(&specific).unwrap();
    let batch = fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/sequences/batch.sfc")).unwrap();
    assert_eq!(body(&written), body(&batch));
    // The header comment is kept as it was.
    assert!(written.starts_with("(* generic.sfc: batch.sfc as a generic sequence"));
    let o = linc(&["check", specific.to_str().unwrap(), "--db", DB]);
    assert_eq!((o.status.code(), stdout(&o)), (Some(0), String::new()));
    let o = linc(&["sfc", "generalise", specific.to_str().unwrap(), "--map", MAP1, "-o", back.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let generic =
        fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/sequences/generic.sfc")).unwrap();
    assert_eq!(fs::read_to_string(&back).unwrap(), generic);
}

#[test]
fn specialise_for_the_second_reactor_names_its_blocks() {
    let dir = temp_dir("generic-r2");
    let specific = dir.join("tank2.sfc");
    let o = linc(&["sfc", "specialise", SEQ, "--map", MAP2, "-o", specific.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let written = fs::read_to_string(&specific).unwrap();
    assert!(written.contains("TRANSITION FROM Idle TO Fill := Plant.N2 = 1; END_TRANSITION"), "{written}");
    assert!(written.contains("    R2.Heater := R2.Temp < 70.0;\n"), "{written}");
    assert!(!body(&written).contains("R1"), "{written}");
    let o = linc(&["check", specific.to_str().unwrap(), "--db", DB]);
    assert_eq!((o.status.code(), stdout(&o)), (Some(0), String::new()));
}

#[test]
fn map_template_lists_generic_names_in_order_of_use() {
    let o = linc(&["sfc", "map-template", SEQ, "--db", DB]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        stdout(&o),
        "{\n  \"StartCmd\": \"\",\n  \"LevelPV\": \"\",\n  \"AbortCmd\": \"\",\n  \"TempPV\": \"\",\n  \"Reactor\": \"\"\n}\n"
    );
}

fn partial_map(tag: &str) -> std::path::PathBuf {
    let dir = temp_dir(tag);
    let map = dir.join("partial.map.json");
    fs::write(&map, "{\n  \"Reactor\": \"R1\",\n  \"LevelPV\": \"R1.Level\",\n  \"TempPV\": \"\"\n}\n").unwrap();
    map
}

#[test]
fn unmapped_names_are_errors_naming_the_map() {
    let map = partial_map("generic-unmapped");
    let m = map.to_str().unwrap();
    let o = linc(&["check", SEQ, "--map", m, "--db", DB, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    let out = stderr(&o);
    let first = out.lines().next().unwrap();
    assert_eq!(first, format!("{SEQ}:12:33: error[E0250]: can't find `StartCmd` in the database or in the map `{m}`"));
    // StartCmd once, AbortCmd twice, TempPV (empty target) twice.
    assert_eq!(out.matches("error[E0250]").count(), 5, "{out}");
    assert_eq!(out.matches("E0100").count(), 0, "{out}");
}

#[test]
fn allow_unmapped_makes_them_warnings() {
    let map = partial_map("generic-allow");
    let m = map.to_str().unwrap();
    let o = linc(&["check", SEQ, "--map", m, "--db", DB, "--allow-unmapped", "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stderr(&o);
    assert_eq!(out.matches("warning[W0250]").count(), 5, "{out}");
    assert_eq!(out.matches("error").count(), 0, "{out}");
}

#[test]
fn compile_needs_a_complete_map() {
    let dir = temp_dir("generic-compile");
    let out = dir.join("r.sto");
    let o = linc(&["compile", SEQ, "--map", MAP2, "--db", DB, "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stderr(&o), stderr(&o));
    assert!(fs::metadata(&out).unwrap().len() > 0);
    let map = partial_map("generic-compile-partial");
    let out2 = dir.join("r2.sto");
    let o = linc(&["compile", SEQ, "--map", map.to_str().unwrap(), "--db", DB, "-o", out2.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0250]"), "{}", stderr(&o));
    assert!(!out2.exists());
}

/// Writes `text` as a map and checks the generic sequence with it.
fn check_with_map(tag: &str, text: &str) -> (Option<i32>, String) {
    let map = temp_dir(tag).join("m.json");
    fs::write(&map, text).unwrap();
    let o = linc(&["check", SEQ, "--map", map.to_str().unwrap(), "--db", DB, "--message-format", "short"]);
    let out = stderr(&o).replace(map.to_str().unwrap(), "m.json");
    (o.status.code(), out)
}

#[test]
fn a_map_that_is_not_json_is_located() {
    let (status, out) = check_with_map("map-notjson", "{ \"Reactor\": R1 }");
    assert_eq!(status, Some(1));
    assert!(out.starts_with("m.json:1:14: error[E0251]:"), "{out}");
}

#[test]
fn a_map_entry_that_is_not_a_string_is_located() {
    let (status, out) = check_with_map("map-number", "{ \"Reactor\": \"R1\",\n  \"LevelPV\": 12 }");
    assert_eq!(status, Some(1));
    assert!(
        out.starts_with("m.json:2:14: error[E0251]: the target of `LevelPV` must be a string, not a number"),
        "{out}"
    );
}

#[test]
fn a_map_that_is_not_an_object_is_an_error() {
    let (status, out) = check_with_map("map-array", "[\"R1\"]");
    assert_eq!(status, Some(1));
    assert!(out.starts_with("m.json:1:1: error[E0251]: a map must be a JSON object, not an array"), "{out}");
}

#[test]
fn a_target_block_the_database_lacks_is_e0252() {
    let text = "{ \"Reactor\": \"R9\", \"LevelPV\": \"R1.Level\", \"TempPV\": \"R1.Temp\",\n  \"StartCmd\": \"Plant.N0\", \"AbortCmd\": \"Plant.N1\" }";
    let (status, out) = check_with_map("map-noblock", text);
    assert_eq!(status, Some(1));
    assert!(out.starts_with("m.json:1:14: error[E0252]: the database has no block `R9`"), "{out}");
}

#[test]
fn bad_generic_names_and_targets_are_e0253_and_e0254() {
    let text = "{ \"ReactorLevelProcessValue\": \"R1.Level\", \"R2\": \"R1\", \"Reactor\": \"R1.Temp.A.B\" }";
    let (status, out) = check_with_map("map-badnames", text);
    assert_eq!(status, Some(1));
    let codes: Vec<&str> = out.lines().filter_map(|l| l.split(": ").nth(1)).take(3).collect();
    assert_eq!(codes, ["error[E0253]", "error[E0254]", "error[E0253]"], "{out}");
    assert!(out.contains("it is 24 characters long; generic names are at most 16"), "{out}");
    assert!(out.contains("`R2` can't be a generic name: the database already has a block or alias of this name"));
}

#[test]
fn resources_are_counted_against_the_small_instrument_by_default() {
    let o = linc(&["check", "--resources", "examples/sequences/batch.sfc", "--db", "examples/sequences/plant.json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        stdout(&o),
        "resources of examples/sequences/batch.sfc (small instrument):\n  steps            8 of 150\n  transitions      8 of 225\n  actions         11 of 300\n  associations    14 of 600\n  SFCs             2 of 50\n"
    );
    let o = linc(&["check", "--resources", "--instrument", "large", "examples/sequences/batch.sfc"]);
    assert!(stdout(&o).contains("(large instrument)") && stdout(&o).contains("  SFCs             2 of 130\n"));
}

#[test]
fn too_many_steps_warn_w0251() {
    let dir = temp_dir("resources-many");
    let path = dir.join("many.sfc");
    let mut src = String::from("INITIAL_STEP S0: A(N); END_STEP\n");
    for i in 1..=150 {
        src.push_str(&format!("STEP S{i}: END_STEP\nTRANSITION FROM S{} TO S{i} := TRUE; END_TRANSITION\n", i - 1));
    }
    src.push_str("ACTION A\nEND_ACTION\n");
    fs::write(&path, &src).unwrap();
    let p = path.to_str().unwrap();
    let o = linc(&["check", "--resources", p, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o) + &stderr(&o);
    assert!(out.contains("  steps          151 of 150  over the limit\n"), "{out}");
    assert!(out.contains("warning[W0251]: the sequence uses 151 steps; a small instrument loads at most 150"), "{out}");
    assert_eq!(out.matches("W0251").count(), 1, "{out}");
    let o = linc(&["check", "--resources", "--instrument", "large", p, "--message-format", "short"]);
    assert_eq!(stderr(&o).matches("W0251").count(), 0, "{}", stderr(&o));
}

#[test]
fn specialise_refuses_to_overwrite_its_input() {
    let dir = temp_dir("generic-overwrite");
    let seq = dir.join("g.sfc");
    fs::copy(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/sequences/generic.sfc"), &seq).unwrap();
    let before = fs::read(&seq).unwrap();
    let s = seq.to_str().unwrap();
    let o = linc(&["sfc", "specialise", s, "--map", MAP1, "-o", s]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("E0902"), "{}", stderr(&o));
    assert_eq!(fs::read(&seq).unwrap(), before);
}

#[test]
fn rewriting_with_a_bad_map_or_a_broken_sequence_writes_nothing() {
    let dir = temp_dir("generic-bad-rewrite");
    let out = dir.join("out.sfc");
    let map = dir.join("bad.json");
    fs::write(&map, "{ \"Reactor\": 1 }").unwrap();
    let o = linc(&["sfc", "specialise", SEQ, "--map", map.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0251]"), "{}", stderr(&o));
    assert!(!out.exists());
    let broken = dir.join("broken.sfc");
    fs::write(&broken, "INITIAL_STEP Idle: Go(N); END_STEP\nACTION Go\n    Reactor.Heater := ;\nEND_ACTION\n").unwrap();
    let o = linc(&["sfc", "generalise", broken.to_str().unwrap(), "--map", MAP1, "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0"), "{}", stderr(&o));
    assert!(!out.exists());
}

#[test]
fn long_generic_names_are_accepted_with_a_map() {
    let dir = temp_dir("generic-long");
    let seq = dir.join("long.sfc");
    let map = dir.join("long.json");
    fs::write(
        &seq,
        "INITIAL_STEP Idle: Go(N); END_STEP\nACTION Go\n    (* keep me *) WaterLevelLoFlag := ReactorHeaterOn;\nEND_ACTION\n",
    )
    .unwrap();
    fs::write(&map, "{ \"WaterLevelLoFlag\": \"R1.Alarm\", \"ReactorHeaterOn\": \"R2.Heater\" }").unwrap();
    let (s, m) = (seq.to_str().unwrap(), map.to_str().unwrap());
    let o = linc(&["check", s, "--map", m, "--db", DB]);
    assert_eq!((o.status.code(), stderr(&o)), (Some(0), String::new()));
    // Without the map the names are too long for ST.
    let o = linc(&["check", s, "--db", DB, "--message-format", "short"]);
    assert_eq!(stderr(&o).matches("error[E0005]").count(), 2, "{}", stderr(&o));
    let out = dir.join("specific.sfc");
    let o = linc(&["sfc", "specialise", s, "--map", m, "-o", out.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(
        fs::read_to_string(&out).unwrap(),
        "INITIAL_STEP Idle: Go(N); END_STEP\nACTION Go\n    (* keep me *) R1.Alarm := R2.Heater;\nEND_ACTION\n"
    );
    let o = linc(&["sfc", "map-template", s, "--db", DB]);
    assert_eq!(stdout(&o), "{\n  \"WaterLevelLoFlag\": \"\",\n  \"ReactorHeaterOn\": \"\"\n}\n");
}

#[test]
fn allow_unmapped_needs_a_map() {
    let o = linc(&["check", SEQ, "--allow-unmapped"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--map"), "{}", stderr(&o));
}

#[test]
fn resources_in_json_are_one_line() {
    let o = linc(&["check", "--resources", "examples/sequences/batch.sfc", "--message-format", "json"]);
    assert_eq!(o.status.code(), Some(0));
    let line = stdout(&o);
    let v: serde_json::Value = serde_json::from_str(line.trim()).expect("one JSON line");
    assert_eq!(v["resources"]["instrument"], "small");
    assert_eq!(v["resources"]["steps"]["used"], 8);
    assert_eq!(v["resources"]["SFCs"]["limit"], 50);
}

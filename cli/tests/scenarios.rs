//! `linc test`: the examples' scenarios pass, a broken copy fails with its
//! file, line, time and values, the JUnit report is valid against
//! docs/junit.xsd, the VCD trace reads back with a VCD parser, and serial
//! and parallel runs give the same bytes (docs/testing.md).
mod common;
use common::{linc, stderr, stdout, temp_dir};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A copy of an example directory in a fresh temporary directory.
fn copy_example(name: &str, tag: &str) -> PathBuf {
    let dir = temp_dir(&format!("scen-{tag}"));
    for entry in std::fs::read_dir(root().join("examples").join(name)).expect("example") {
        let p = entry.expect("entry").path();
        std::fs::copy(&p, dir.join(p.file_name().unwrap())).expect("copy");
    }
    dir
}

#[test]
fn every_example_scenario_passes() {
    let o = linc(&["test", "examples"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let out = stdout(&o);
    for s in ["fst/plant", "ladder/interlock", "sequences/batch", "strategy/plant"] {
        assert!(out.contains(&format!("test examples/{s}.ltest ... ok")), "{out}");
    }
    assert!(out.ends_with("test result: ok. 4 passed, 0 failed\n"), "{out}");
}

#[test]
fn a_broken_copy_fails_with_file_line_time_and_values() {
    let dir = copy_example("strategy", "broken");
    let text = std::fs::read_to_string(dir.join("plant.ltest")).unwrap();
    std::fs::write(dir.join("plant.ltest"), text.replace("HighCnt = 17", "HighCnt = 18")).unwrap();
    let file = dir.join("plant.ltest").display().to_string();
    let o = linc(&["test", &file]);
    assert_eq!(o.status.code(), Some(1));
    let out = stdout(&o);
    assert!(out.contains(&format!("test {file} ... FAILED")), "{out}");
    assert!(out.contains(&format!("{file}:7: at 10m: `TANK1.HighCnt = 18` did not hold after 10m\n")), "{out}");
    assert!(out.contains("    TANK1.HighCnt = 17\n"), "{out}");
    assert!(out.ends_with("test result: FAILED. 0 passed, 1 failed\n"), "{out}");
}

#[test]
fn bad_scenario_lines_are_reported_at_their_place() {
    let dir = copy_example("strategy", "badline");
    std::fs::write(dir.join("bad.ltest"), "strategy plant.json\nexpect within 5s TANK1.Nope\nwait 5s\n").unwrap();
    let file = dir.join("bad.ltest").display().to_string();
    let o = linc(&["test", &file]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains(&format!("{file}:3:1: error[E0503]")), "{}", stdout(&o));
    // A name that is neither a block nor a step is told as both.
    std::fs::write(dir.join("nope.ltest"), "strategy plant.json\nrun 1s\nexpect always NOPE.X\n").unwrap();
    let file = dir.join("nope.ltest").display().to_string();
    let o = linc(&["test", &file]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains(&format!("{file}:3:15: error[E0120]: no block or step `NOPE`")), "{}", stdout(&o));
}

#[test]
fn the_junit_report_is_valid_against_the_schema() {
    let dir = copy_example("strategy", "junit");
    let text = std::fs::read_to_string(dir.join("plant.ltest")).unwrap();
    std::fs::write(dir.join("bad & <broken>.ltest"), text.replace("HighCnt = 17", "HighCnt = 18")).unwrap();
    let junit = dir.join("report.xml");
    let o = linc(&["test", dir.to_str().unwrap(), "--junit", junit.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let xml = std::fs::read_to_string(&junit).expect("written");
    assert!(xml.contains("tests=\"2\" failures=\"1\""), "{xml}");
    assert!(xml.contains("bad &amp; &lt;broken&gt;.ltest"), "{xml}");
    if !common::tool("xmllint") {
        return;
    }
    // Validated by an independent tool, as the Cobertura report is.
    let xsd = root().join("docs/junit.xsd");
    let check = |file: &std::path::Path| {
        let args = ["--noout", "--nonet", "--schema", xsd.to_str().unwrap()];
        std::process::Command::new("xmllint").args(args).arg(file).output().expect("xmllint runs")
    };
    let v = check(&junit);
    assert!(v.status.success(), "{}\n{xml}", String::from_utf8_lossy(&v.stderr));
    // The validation is real: a test case without a name is refused.
    let bad = dir.join("bad.xml");
    std::fs::write(&bad, xml.replacen("<testcase name=", "<testcase nom=", 1)).unwrap();
    assert!(!check(&bad).status.success(), "a test case without a name is invalid");
}

#[test]
fn the_vcd_trace_reads_back() {
    let vcd_path = temp_dir("scen-vcd").join("plant.vcd");
    let o = linc(&["test", "examples/strategy/plant.ltest", "--vcd", vcd_path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let bytes = std::fs::read(&vcd_path).expect("written");
    let mut parser = vcd::Parser::new(&bytes[..]);
    let header = parser.parse_header().expect("a VCD header");
    let level = header.find_var(&["linc", "TANK1.Level"]).expect("TANK1.Level is traced").code;
    let count = header.find_var(&["linc", "TANK1.HighCnt"]).expect("TANK1.HighCnt is traced").code;
    let (mut time, mut last_level, mut last_count, mut first_level) = (0u64, None, None, None);
    for command in parser {
        match command.expect("a VCD command") {
            vcd::Command::Timestamp(t) => {
                assert!(t >= time, "time goes forward");
                time = t;
            }
            vcd::Command::ChangeReal(id, v) if id == level => {
                first_level.get_or_insert(v);
                last_level = Some(v);
            }
            vcd::Command::ChangeVector(id, v) if id == count => {
                last_count = Some(v.iter().fold(0u32, |n, b| n << 1 | u32::from(b == vcd::Value::V1)));
            }
            _ => {}
        }
    }
    assert_eq!(first_level, Some(20.0), "the initial level");
    assert_eq!(last_count, Some(17), "the count at the end");
    assert!(last_level.is_some_and(|l| (0.0..=100.0).contains(&l)));
    assert!(time > 590_000_000 && time <= 600_000_000, "the last change is in the last 10 s: {time}");
}

/// `n` one-hour scenarios of the example tank with different set-ups.
pub fn many(dir: &Path, n: usize) {
    for f in ["plant.json", "actions.stx", "modbus.stx"] {
        std::fs::copy(root().join("examples/strategy").join(f), dir.join(f)).expect("copy");
    }
    for i in 0..n {
        let rate = 1 + i % 7;
        let text = format!(
            "strategy plant.json\nat 0s M TANK1.Inflow={rate}.0\nexpect always TANK1.Level <= 100.0\n\
             expect within 10m TANK1.Level >= 90.0\nexpect never TANK1.HighCnt > {}\nrun 1h\n",
            40 + i % 50
        );
        std::fs::write(dir.join(format!("s{i:04}.ltest")), text).expect("write");
    }
}

#[test]
fn serial_and_parallel_runs_give_identical_reports() {
    let dir = temp_dir("scen-par");
    many(&dir, 12);
    let run = |jobs: &str, junit: &str| {
        let j = dir.join(junit);
        let o = linc(&["test", dir.to_str().unwrap(), "--jobs", jobs, "--junit", j.to_str().unwrap()]);
        (o.status.code(), stdout(&o), std::fs::read(&j).expect("junit"))
    };
    let serial = run("1", "serial.xml");
    let parallel = run("4", "parallel.xml");
    assert_eq!(serial, parallel);
    assert!(serial.1.contains("running 12 scenarios"), "{}", serial.1);
    // Scenarios that fail before they run (an action that does not
    // compile, a database that does not load, a bad expectation) report
    // inside their own outcome, in file order, for any number of threads.
    std::fs::write(dir.join("broken.stx"), "ACTION Fill\n  TANK1.Valve := ;\nEND_ACTION\n").expect("write");
    let broken = std::fs::read_to_string(dir.join("plant.json")).expect("db").replace("actions.stx", "broken.stx");
    std::fs::write(dir.join("broken.json"), broken).expect("write");
    for i in 0..6 {
        std::fs::write(dir.join(format!("s{i:04}b.ltest")), "strategy broken.json\nrun 1s\n").expect("write");
        std::fs::write(dir.join(format!("s{i:04}c.ltest")), "strategy nothing.json\nrun 1s\n").expect("write");
        std::fs::write(dir.join(format!("s{i:04}d.ltest")), "strategy plant.json\nexpect always NOPE.X\n")
            .expect("write");
    }
    let serial = run("1", "serial.xml");
    let parallel = run("4", "parallel.xml");
    assert_eq!(serial, parallel);
    assert_eq!(serial.0, Some(1));
    assert!(serial.1.contains("running 30 scenarios"), "{}", serial.1);
    assert_eq!(serial.1.matches("error[E0010]").count(), 6, "{}", serial.1);
    assert_eq!(serial.1.matches("error[E0900]").count(), 6, "{}", serial.1);
    assert_eq!(serial.1.matches("error[E0120]").count(), 6, "{}", serial.1);
}

#[test]
fn the_vcd_trace_holds_aliases_and_step_variables() {
    let dir = copy_example("sequences", "vcd-steps");
    let db = std::fs::read_to_string(dir.join("plant.json")).expect("db");
    let db = db.replacen('{', "{\n  \"aliases\": { \"Temp\": \"R1.Temp\" },", 1);
    std::fs::write(dir.join("plant.json"), db).expect("db");
    let text = "strategy plant.json\nexpect always Temp < 120.0\nexpect within 5m Heat.X\nexpect always Heat.T >= 0.0\nrun 5m\n";
    std::fs::write(dir.join("steps.ltest"), text).expect("scenario");
    let vcd_path = dir.join("steps.vcd");
    let o = linc(&["test", dir.join("steps.ltest").to_str().unwrap(), "--vcd", vcd_path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    let bytes = std::fs::read(&vcd_path).expect("written");
    let mut parser = vcd::Parser::new(&bytes[..]);
    let header = parser.parse_header().expect("a VCD header");
    let temp = header.find_var(&["linc", "Temp"]).expect("the alias is traced").code;
    let heat = header.find_var(&["linc", "Heat.X"]).expect("the step flag is traced").code;
    let heat_t = header.find_var(&["linc", "Heat.T"]).expect("the step time is traced").code;
    let (mut temps, mut heat_on, mut heat_times) = (0, false, Vec::new());
    for command in parser {
        match command.expect("a VCD command") {
            vcd::Command::ChangeReal(id, _) if id == temp => temps += 1,
            vcd::Command::ChangeScalar(id, v) if id == heat => heat_on |= v == vcd::Value::V1,
            vcd::Command::ChangeReal(id, v) if id == heat_t => heat_times.push(v),
            _ => {}
        }
    }
    assert!(temps > 1, "the alias's field changes: {temps}");
    assert!(heat_on, "Heat became active");
    assert!(heat_times.iter().any(|t| *t > 1.0), "Heat.T counts up: {heat_times:?}");
}

#[test]
fn a_vcd_that_can_not_be_written_keeps_its_own_code() {
    let dir = copy_example("strategy", "vcd-device");
    let o = linc(&["test", dir.join("plant.ltest").to_str().unwrap(), "--vcd", "/dev/null"]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(err.contains("error[E0901]") && !err.contains("E0900"), "{err}");
}

#[test]
fn a_program_scenario_runs_one_sequence_in_its_only_sfc_con_block() {
    let dir = copy_example("sequences", "program");
    // Only the sequence runs, not the SIM action that fills the vessel: the
    // batch starts filling and stays in Fill.
    let text =
        "program batch.sfc\ndb plant.json\nexpect within 5s Fill.X\nexpect after 5m Fill.X AND NOT Heat.X\nrun 5m\n";
    std::fs::write(dir.join("one.ltest"), text).unwrap();
    let file = dir.join("one.ltest").display().to_string();
    let o = linc(&["test", &file]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // A database with no SFC_CON block can't run it.
    std::fs::write(dir.join("none.json"), r#"{"blocks": {}}"#).unwrap();
    std::fs::write(dir.join("two.ltest"), "program batch.sfc\ndb none.json\nrun 1s\n").unwrap();
    let file = dir.join("two.ltest").display().to_string();
    let o = linc(&["test", &file]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stdout(&o).contains("error[E0904]: the database has no SFC_CON block to run the sequence"),
        "{}",
        stdout(&o)
    );
}

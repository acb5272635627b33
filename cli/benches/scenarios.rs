//! `cargo bench -p linc --bench scenarios`: 1,000 scenarios of one
//! simulated hour each (the example tank strategy, set up differently in
//! each), run by `linc test` serially and on every core; prints scenarios
//! per second and checks that the two reports are the same bytes.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

const SCENARIOS: usize = 1_000;

fn write_scenarios(dir: &Path) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/strategy");
    for f in ["plant.json", "actions.stx", "modbus.stx"] {
        std::fs::copy(root.join(f), dir.join(f)).expect("copy the example");
    }
    for i in 0..SCENARIOS {
        let text = format!(
            "strategy plant.json\nat 0s M TANK1.Inflow={}.0\nexpect always TANK1.Level <= 100.0\n\
             expect within 10m TANK1.Level >= 50.0\nexpect never TANK1.HighCnt > {}\nrun 1h\n",
            1 + i % 7,
            1000 + i
        );
        std::fs::write(dir.join(format!("s{i:04}.ltest")), text).expect("write a scenario");
    }
}

/// Runs `linc test` on the directory; returns seconds, stdout and the JUnit bytes.
fn run(dir: &Path, jobs: usize) -> (f64, Vec<u8>, Vec<u8>) {
    let junit = dir.join(format!("junit-{jobs}.xml"));
    let started = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(["test", dir.to_str().expect("utf-8 path"), "--jobs", &jobs.to_string(), "--junit"])
        .arg(&junit)
        .output()
        .expect("run linc test");
    let secs = started.elapsed().as_secs_f64();
    (secs, out.stdout, std::fs::read(&junit).expect("the JUnit report"))
}

fn main() {
    let dir = linc_test_support::temp_dir("bench-scenarios");
    write_scenarios(&dir);
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let (serial, out1, junit1) = run(&dir, 1);
    let (parallel, out2, junit2) = run(&dir, cores);
    assert_eq!(out1, out2, "serial and parallel reports differ");
    assert_eq!(junit1, junit2, "serial and parallel JUnit reports differ");
    let text = String::from_utf8_lossy(&out1);
    let summary = text.lines().last().unwrap_or_default();
    println!("scenarios/1h serial      {SCENARIOS} in {serial:.2} s: {:.0} scenarios/s", SCENARIOS as f64 / serial);
    println!(
        "scenarios/1h {cores} threads  {SCENARIOS} in {parallel:.2} s: {:.0} scenarios/s",
        SCENARIOS as f64 / parallel
    );
    println!("reports identical ({} bytes; {summary})", out1.len());
    let _ = std::fs::remove_dir_all(&dir);
}

//! The console's retentive state: `SAVE` then a warm start continues a
//! sequence in the same steps with the same step times; `--cold` begins at
//! the initial steps; a state file cut short is refused and the console
//! starts cold only when asked (docs/console.md, docs/state.md).
mod common;
use common::{linc_with_input, stdout, temp_dir};

const PLANT: &str = "examples/sequences/plant.json";

/// Runs the console with `script` on standard input and `args`.
fn console(args: &[&str], script: &str) -> (Option<i32>, String) {
    let o = linc_with_input(&[&["console"], args].concat(), script);
    (o.status.code(), format!("{}{}", stdout(&o), String::from_utf8_lossy(&o.stderr)))
}

#[test]
fn a_warm_start_after_save_continues_the_sequence_as_one_run_would() {
    let state = temp_dir("console-state").join("batch.state");
    let state = state.to_str().unwrap();
    let (code, out) = console(&[PLANT, "--now", "2026-01-05T06:00:00", "--state", state], "ADVANCE 72s\nP?\nSAVE\n");
    assert_eq!(code, Some(0), "{out}");
    let steps = out.lines().find(|l| l.starts_with("BATCH sequence")).expect("P? shows the sequence").to_string();
    assert!(steps.contains("RUNNING: Heat ") && steps.contains(", Agitate ") && !steps.contains(" 0s"), "{out}");
    assert!(out.contains("state saved at 2026-01-05T06:01:12.000\n"), "{out}");
    // The warm start is in the same steps with the same step times, and
    // goes on exactly as one uninterrupted run.
    let after = "P?\nADVANCE 30s\nP?\nD R1.Level, R1.Temp, R1.Stirs, R1.Batches\n";
    let (code, warm) = console(&[PLANT, "--state", state], after);
    assert_eq!(code, Some(0), "{warm}");
    assert!(warm.starts_with(&format!("SIM action task 1 running -\n{steps}\n")), "same steps, same times: {warm}");
    let (_, whole) = console(
        &[PLANT, "--now", "2026-01-05T06:00:00"],
        "ADVANCE 102s\nP?\nD R1.Level, R1.Temp, R1.Stirs, R1.Batches\n",
    );
    let tail = |s: &str| s.lines().skip_while(|l| !l.starts_with("2026")).collect::<Vec<_>>().join("\n");
    assert_eq!(tail(&warm), tail(&whole), "warm start + 30 s = one run of 102 s");
    // A cold start ignores the file: the initial step.
    let (code, cold) = console(&[PLANT, "--state", state, "--cold"], "P?\n");
    assert_eq!(code, Some(0), "{cold}");
    assert!(cold.contains("BATCH sequence task 1 running RUNNING: Idle 0s\n") || cold.contains("RESET"), "{cold}");
    assert!(!cold.contains("Heat"), "{cold}");
}

#[test]
fn a_state_file_cut_short_is_refused_unless_cold() {
    let dir = temp_dir("console-cut");
    let state = dir.join("cut.state");
    let path = state.to_str().unwrap();
    let (code, _) = console(&[PLANT, "--now", "2026-01-05T06:00:00", "--state", path], "ADVANCE 20s\nSAVE\n");
    assert_eq!(code, Some(0));
    let bytes = std::fs::read(&state).expect("saved");
    std::fs::write(&state, &bytes[..bytes.len() / 2]).expect("cut");
    let (code, out) = console(&[PLANT, "--state", path], "P?\n");
    assert_eq!(code, Some(2), "{out}");
    assert!(out.contains("error[E0840]"), "{out}");
    assert!(!out.contains("BATCH sequence"), "the console did not start: {out}");
    let (code, out) = console(&[PLANT, "--state", path, "--cold"], "NOW\n");
    assert_eq!(code, Some(0), "{out}");
}

#[test]
fn save_without_a_state_file_is_refused() {
    let (code, out) = console(&[PLANT, "--now", "2026-01-05T06:00:00"], "SAVE\nNOW\n");
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("error[C0012]"), "{out}");
    assert!(out.contains("2026-01-05T06:00:00.000"), "later commands still run: {out}");
}

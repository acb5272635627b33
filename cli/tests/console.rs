//! `linc console`: every command through `--script` (and standard input),
//! over the example strategies.
mod common;
use common::{linc, stderr, stdout, temp_dir};
use std::io::Write;
use std::process::{Command, Stdio};

const NOW: &str = "2026-01-05T06:00:00";

/// Runs `script` on the strategy `plant` (relative to the repository root
/// or absolute); the exit status and standard output.
fn console(plant: &str, tag: &str, script: &str) -> (Option<i32>, String) {
    let dir = temp_dir(&format!("console-{tag}"));
    let path = dir.join("script.txt");
    std::fs::write(&path, script).expect("script");
    let o = linc(&["console", plant, "--now", NOW, "--seed", "1", "--script", path.to_str().unwrap()]);
    assert!(stderr(&o).is_empty() || o.status.code() == Some(1), "{}", stderr(&o));
    (o.status.code(), stdout(&o))
}

/// The lines of `out` that show `field`.
fn shown<'a>(out: &'a str, field: &str) -> Vec<&'a str> {
    let prefix = format!("{field} = ");
    out.lines().filter(|l| l.starts_with(&prefix)).collect()
}

/// A copy of an example directory with `edit` applied to its plant.json.
fn example_copy(example: &str, tag: &str, edit: impl FnOnce(&mut serde_json::Value)) -> String {
    let dir = temp_dir(&format!("console-copy-{tag}"));
    let from = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples").join(example);
    for e in std::fs::read_dir(&from).expect("example") {
        let e = e.expect("entry");
        std::fs::copy(e.path(), dir.join(e.file_name())).expect("copy");
    }
    let plant = dir.join("plant.json");
    let mut db: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&plant).expect("plant")).expect("json");
    edit(&mut db);
    std::fs::write(&plant, db.to_string()).expect("write");
    plant.to_str().unwrap().to_string()
}

#[test]
fn display_modify_now_and_ranges() {
    let script =
        "NOW\nD TANK1.Level, TANK1.Valve\nM TANK1.Inflow=2.5\nDISPLAY TANK1.Level-\nSCAN\nNOW\nADVANCE 2s\nnow\n";
    let (code, out) = console("examples/strategy/plant.json", "display", script);
    assert_eq!(code, Some(0), "{out}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "2026-01-05T06:00:00.000");
    assert_eq!(&lines[1..4], ["TANK1.Level = 20.0", "TANK1.Valve = FALSE", "TANK1.Inflow = 2.5"]);
    // The range: every field of TANK1 from Level, in offset order.
    assert_eq!(
        &lines[4..10],
        [
            "TANK1.Level = 20.0",
            "TANK1.Inflow = 2.5",
            "TANK1.Outflow = 6.0",
            "TANK1.Valve = FALSE",
            "TANK1.Pump = FALSE",
            "TANK1.HighCnt = 0"
        ]
    );
    // SCAN is one period of the fastest task (100 ms).
    assert_eq!(&lines[10..12], ["2026-01-05T06:00:00.100", "2026-01-05T06:00:00.100"]);
    assert_eq!(lines[lines.len() - 1], "2026-01-05T06:00:02.100");
}

#[test]
fn forcing_an_input_seen_by_st_and_writes_to_a_forced_field_ignored() {
    // Fill opens the valve below 50 %: forced to 95 %, the level keeps it
    // shut, and Sim's writes to the level are ignored (and counted).
    let script = "F TANK1.Level=95.0\nF TANK1.Valve=1\nADVANCE 3s\nD TANK1.Level, TANK1.Valve\nF?\n\
                  F TANK1.Level=N\nM TANK1.Level=10\nADVANCE 1s\nD TANK1.Valve\nF TANK1.Valve OFF\nF?\n";
    let (code, out) = console("examples/strategy/plant.json", "force-st", script);
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(shown(&out, "TANK1.Level"), ["TANK1.Level = 95.0 (forced)", "TANK1.Level = 95.0", "TANK1.Level = 10.0"]);
    // The pump is off and the valve forced open: Sim adds the inflow to
    // the level, but the write is dropped. Fill's valve writes are dropped.
    assert_eq!(shown(&out, "TANK1.Valve")[1], "TANK1.Valve = TRUE");
    assert!(out.contains("forced TANK1.Level = 95.0\nforced TANK1.Valve = TRUE\nwrites ignored: "), "{out}");
    let ignored: u64 =
        out.lines().find_map(|l| l.strip_prefix("writes ignored: ")).and_then(|n| n.parse().ok()).expect("count");
    assert!(ignored >= 3, "{out}");
    assert!(out.contains("TANK1.Valve released = TRUE\nno forces\n"), "{out}");
}

#[test]
fn forcing_an_input_seen_by_a_ladder_program() {
    let plant = example_copy("ladder", "ladder", |db| {
        db["blocks"]["LAD"] = serde_json::json!({ "type": "ACTION",
            "values": { "FileName": "interlock.ld", "ActName": "interlock", "Trigger": true } });
    });
    let script = "SCAN\nD Dig_1b.Out\nF Dig_1a.In=1\nSCAN\nD Dig_1b.Out\nF Dig_1b.Out=FALSE\nSCAN\nD Dig_1b.Out\nF?\n";
    let (code, out) = console(&plant, "ladder", script);
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(
        shown(&out, "Dig_1b.Out"),
        ["Dig_1b.Out = FALSE", "Dig_1b.Out = TRUE", "Dig_1b.Out = FALSE (forced)", "Dig_1b.Out = FALSE"]
    );
    assert!(out.contains("writes ignored: 1\n"), "{out}");
}

#[test]
fn forcing_an_input_seen_by_a_sequence_transition() {
    // Full (Fill → Heat, Agitate) fires at R1.Level >= 80: forced there,
    // it fires on the next scan though the filling has barely begun.
    let script = "ADVANCE 2s\nP?\nF R1.Level=85\nSCAN\nSCAN\nP?\nD R1.Level\n";
    let (code, out) = console("examples/sequences/plant.json", "force-sfc", script);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("BATCH sequence task 1 running RUNNING: Fill 0s\n"), "{out}");
    assert!(out.contains("BATCH sequence task 1 running RUNNING: Heat 1s, Agitate 1s\n"), "{out}");
    assert_eq!(shown(&out, "R1.Level"), ["R1.Level = 85.0 (forced)", "R1.Level = 85.0"]);
}

#[test]
fn forcing_an_input_seen_by_an_fst_table() {
    // pump.csv starts the tank pump at SFP 2.DATA1 (80 %); alarm.csv turns
    // the sump pump on at the high alarm limit (90 %).
    let script = "F AIN 2-1.EU=85\nF AIN 3-1.EU=50\nADVANCE 2s\nD DOU 6-1.STATUS, DOU 4-1.STATUS, Level\n\
                  F AIN 3-1.EU=95\nADVANCE 1s\nD DOU 4-1.STATUS\n\
                  F DOU 4-1.STATUS=0\nADVANCE 1s\nD DOU 4-1.STATUS\nF?\n";
    let (code, out) = console("examples/fst/plant.json", "force-fst", script);
    assert_eq!(code, Some(0), "{out}");
    assert_eq!(shown(&out, "DOU 6-1.STATUS"), ["DOU 6-1.STATUS = 1"]);
    assert_eq!(shown(&out, "Level"), ["Level = 85.0"]);
    assert_eq!(
        shown(&out, "DOU 4-1.STATUS"),
        ["DOU 4-1.STATUS = 0", "DOU 4-1.STATUS = 1", "DOU 4-1.STATUS = 0 (forced)", "DOU 4-1.STATUS = 0"]
    );
    let ignored = out.lines().find_map(|l| l.strip_prefix("writes ignored: ")).expect("count");
    assert_ne!(ignored, "0", "{out}");
}

#[test]
fn programs_start_stop_and_suspend() {
    let script = "P?\nSUSPEND SIM\nPROGRAMS\nM TANK1.Valve=1\nADVANCE 2s\nD TANK1.Level\nSTART SIM\nADVANCE 1s\n\
                  D TANK1.Level\nSTOP FILL\nP?\nPSTOP COUNT\nPSTART COUNT\nP?\n";
    let (code, out) = console("examples/strategy/plant.json", "programs", script);
    assert_eq!(code, Some(0), "{out}");
    let listing = "SIM action task 2 running -\nFILL action task 1 running -\nDRAIN action task 1 running -\n\
                   COUNT action task 2 running -\nPOLL action task 2 running -\n";
    assert!(out.starts_with(listing), "{out}");
    assert!(out.contains("SIM suspended\nSIM action task 2 suspended -\n"), "{out}");
    // Suspended, Sim did not fill the tank; started again, it does.
    assert_eq!(shown(&out, "TANK1.Level"), ["TANK1.Level = 20.0", "TANK1.Level = 24.0"]);
    assert!(out.contains("FILL stopped\nSIM action task 2 running -\nFILL action task 1 inactive -\n"), "{out}");
    assert!(out.contains("COUNT stopped\nCOUNT started\n"), "{out}");
    assert!(out.ends_with("COUNT action task 2 running -\nPOLL action task 2 running -\n"), "{out}");
}

#[test]
fn fst_tables_stop_and_start() {
    let script = "PSTOP FST 3\nP?\nADVANCE 1s\nD DOU 4-1.STATUS, FST 3.RUNFLG\nSTART FST 3\nADVANCE 1s\n\
                  D DOU 4-1.STATUS, FST 3.RUNFLG\n";
    let (code, out) = console("examples/fst/plant.json", "fst-programs", script);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("FST 3 fst task 1 inactive step 0 RUNFLG 0\n"), "{out}");
    assert_eq!(shown(&out, "DOU 4-1.STATUS"), ["DOU 4-1.STATUS = 0", "DOU 4-1.STATUS = 1"]);
    assert_eq!(shown(&out, "FST 3.RUNFLG"), ["FST 3.RUNFLG = 0", "FST 3.RUNFLG = 1"]);
}

#[test]
fn each_sequence_control() {
    let script = "ADVANCE 3s\nHOLD BATCH\nADVANCE 2s\nD BATCH.Status\nRUN BATCH\nADVANCE 2s\nD BATCH.Status\n\
                  STOP BATCH\nADVANCE 2s\nD BATCH.Status\nP?\nRESET BATCH\nADVANCE 2s\nD BATCH.Status\nP?\n\
                  RUN BATCH\nHOLDSTEP BATCH Fill\nADVANCE 20s\nP?\nRELEASESTEP BATCH Fill\nADVANCE 20s\nP?\n\
                  RESET BATCH; SCAN; RUN BATCH\nFORCETRANS BATCH Full HOLD\nADVANCE 20s\nP?\n\
                  FORCETRANS BATCH Full NORMAL\nADVANCE 20s\nP?\n\
                  RESET BATCH; SCAN; RUN BATCH; FORCETRANS BATCH Full CONTINUE\nADVANCE 3s\nP?\n";
    let (code, out) = console("examples/sequences/plant.json", "sequence", script);
    assert_eq!(code, Some(0), "{out}");
    let status: Vec<&str> = shown(&out, "BATCH.Status");
    assert_eq!(
        status,
        ["BATCH.Status = 'HELD'", "BATCH.Status = 'RUNNING'", "BATCH.Status = 'STOPPED'", "BATCH.Status = 'RESET'"]
    );
    assert!(out.contains("BATCH HOLD requested (at its next scan)\n"), "{out}");
    let seq: Vec<&str> = out.lines().filter(|l| l.starts_with("BATCH sequence")).collect();
    assert_eq!(
        seq,
        [
            "BATCH sequence task 1 inactive STOPPED: Fill 5s",
            "BATCH sequence task 1 inactive RESET",
            // Held, Fill stays active though the level passed 80 %.
            "BATCH sequence task 1 running RUNNING: Fill 18s",
            "BATCH sequence task 1 running RUNNING: Heat 19s, Agitate 19s",
            // Full held: filling goes on to 100 % and stays in Fill.
            "BATCH sequence task 1 running RUNNING: Fill 18s",
            "BATCH sequence task 1 running RUNNING: Heat 19s, Agitate 19s",
            // Full forced to continue: it fires at once.
            "BATCH sequence task 1 running RUNNING: Heat 0s, Agitate 0s",
        ],
        "{out}"
    );
}

#[test]
fn errors_raised_and_cleared_run_the_error_program() {
    let plant = example_copy("strategy", "errprog", |db| {
        db["blocks"]["SYS"] = serde_json::json!({ "type": "SYSTEM", "values": { "ErrProg": "ONERR" } });
        db["blocks"]["ONERR"] = serde_json::json!({ "type": "ACTION",
            "values": { "FileName": "onerr.stx", "ActName": "OnErr" } });
    });
    let dir = std::path::Path::new(&plant).parent().expect("dir");
    std::fs::write(dir.join("onerr.stx"), "ACTION OnErr\n    TANK1.HighCnt := TANK1.HighCnt + 100;\nEND_ACTION\n")
        .expect("onerr");
    let script = "ERR?\nD TANK1.HighCnt\nERRRAISE R0001 FILL\nERROR\nD SYS.ErrNum, SYS.ErrCode, SYS.ErrBlock\n\
                  D TANK1.HighCnt\nRAISE R0005\nERRCLR\nERR?\nD SYS.ErrCode\nCLEARERROR\nRAISE R0005\nERR?\n";
    let (code, out) = console(&plant, "errors", script);
    assert_eq!(code, Some(1), "{out}");
    let expect = "no error\nTANK1.HighCnt = 0\n\
        error 1 [R0001] in FILL at 0.0s: raised by the console\n\
        error 1 [R0001] in FILL at 0.0s: raised by the console\n\
        SYS.ErrNum = 1\nSYS.ErrCode = 'R0001'\nSYS.ErrBlock = 'FILL'\n\
        TANK1.HighCnt = 100\n\
        error[C0011]: the error status already holds an error (clear it first with ERRCLR)\n\
        error cleared\nno error\nSYS.ErrCode = ''\nno error\n\
        error 5 [R0005] in (console) at 0.0s: raised by the console\n\
        error 5 [R0005] in (console) at 0.0s: raised by the console\n";
    assert_eq!(out, expect);
}

#[test]
fn bad_commands_are_errors_that_change_nothing() {
    let script = "D TANK1.Level\nFROB 1\nM TANK1.Level=high\nM TANK1.Nope=1\nM TANK1.Level\nADVANCE soon\n\
                  F TANK1.Level=N\nHOLD FILL\nSTART TANK1\nERRRAISE E0001\nHOLDSTEP BATCH Fill\nD TANK1.Level\nERR?\n\
                  M TANK1.Level=5; FROB; D TANK1.Level\nNOW\n";
    let (code, out) = console("examples/strategy/plant.json", "bad", script);
    assert_eq!(code, Some(1), "{out}");
    let expect = "TANK1.Level = 20.0\n\
        error[C0001]: unknown command `FROB`\n\
        error[C0004]: `high` is not a number\n\
        error[C0003]: `TANK1` has no field `Nope`\n\
        error[C0002]: expected `M BLOCK.FIELD=VALUE`\n";
    assert!(out.starts_with(expect), "{out}");
    for code in ["C0008", "C0009", "C0006", "C0010", "C0003"] {
        assert!(out.contains(&format!("error[{code}]: ")), "{code}: {out}");
    }
    // The failed command in the middle of a line does not stop the next one.
    // Nothing changed: the level and the error status are as they were.
    assert!(out.contains("error[C0003]: the database has no block `BATCH`\nTANK1.Level = 20.0\nno error\n"), "{out}");
    assert!(
        out.ends_with(
            "TANK1.Level = 5.0\nerror[C0001]: unknown command `FROB`\nTANK1.Level = 5.0\n2026-01-05T06:00:00.000\n"
        ),
        "{out}"
    );
}

#[test]
fn standard_input_is_a_script_and_quit_ends_it() {
    let input = "(* a comment *)\n# another\n\nD TANK1.Level; SCAN\nQUIT\nD TANK1.Nope\n";
    let o = common::linc_with_input(&["console", "examples/strategy/plant.json", "--now", NOW], input);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), "TANK1.Level = 20.0\n2026-01-05T06:00:00.100\n");
}

#[test]
fn json_errors_and_a_missing_script() {
    let dir = temp_dir("console-json");
    let path = dir.join("s.txt");
    std::fs::write(&path, "FROB\n").expect("script");
    let o = linc(&[
        "console",
        "examples/strategy/plant.json",
        "--script",
        path.to_str().unwrap(),
        "--message-format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_str(stdout(&o).trim()).expect("json");
    assert_eq!(v["code"], "C0001");
    let o = linc(&["console", "examples/strategy/plant.json", "--script", dir.join("none.txt").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn the_trace_shows_console_changes_and_dropped_writes() {
    let dir = temp_dir("console-trace");
    let script = dir.join("s.txt");
    std::fs::write(&script, "F TANK1.Valve=1\nM TANK1.Inflow=3\nADVANCE 1s\n").expect("script");
    let trace = dir.join("trace.jsonl");
    let o = linc(&[
        "console",
        "examples/strategy/plant.json",
        "--now",
        NOW,
        "--script",
        script.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let text = std::fs::read_to_string(&trace).expect("trace");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(
        &lines[..4],
        [
            r#"{"time":0.0,"task":0,"program":"(console)","field":"TANK1.Valve","old":"FALSE","new":"TRUE"}"#,
            r#"{"time":0.0,"task":0,"program":"(console)","field":"TANK1.Inflow","old":"4.0","new":"3.0"}"#,
            r#"{"time":0.0,"task":1,"program":"FILL","field":"FILL.Active","old":"FALSE","new":"TRUE"}"#,
            r#"{"time":0.0,"task":1,"program":"FILL","field":"TANK1.Valve","forced":true}"#,
        ]
    );
    // Standard output holds the replies: the trace can't go there.
    let o = linc(&["console", "examples/strategy/plant.json", "--script", script.to_str().unwrap(), "--trace", "-"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn a_terminal_gets_the_prompt() {
    // util-linux `script` gives the console a terminal; skipped without it.
    if !std::path::Path::new("/usr/bin/script").exists() {
        return;
    }
    let cmd = format!("{} console examples/strategy/plant.json", env!("CARGO_BIN_EXE_linc"));
    let mut child = Command::new("/usr/bin/script")
        .args(["-qec", &cmd, "/dev/null"])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("spawn");
    child.stdin.take().expect("stdin").write_all(b"D TANK1.Level\nQUIT\n").expect("write");
    let o = child.wait_with_output().expect("wait");
    let out = stdout(&o);
    assert!(out.contains("linc> "), "{out}");
    assert!(out.contains("TANK1.Level = 20.0"), "{out}");
}

#[test]
fn a_failed_sequence_starts_again() {
    let plant = example_copy("sequences", "seq-error", |db| {
        db["blocks"]["BATCH"]["values"]["FileName"] = serde_json::json!("boom.sfc");
    });
    let dir = std::path::Path::new(&plant).parent().expect("dir");
    let sfc = "INITIAL_STEP A: Boom(N); END_STEP\nSTEP B: END_STEP\n\
               TRANSITION FROM A TO B := R1.Batches > 2; END_TRANSITION\n\
               ACTION Boom\n    R1.Batches := R1.Batches + 10 / R1.Log;\nEND_ACTION\n";
    std::fs::write(dir.join("boom.sfc"), sfc).expect("sfc");
    let script = "ADVANCE 2s\nP?\nERR?\nM R1.Log=10\nERRCLR\nSTART BATCH\nADVANCE 5s\nP?\nD R1.Batches\n";
    let (code, out) = console(&plant, "seq-error", script);
    assert_eq!(code, Some(0), "{out}");
    assert!(out.contains("BATCH sequence task 1 inactive ERROR: A 0s\n"), "{out}");
    assert!(out.contains("error 1 [R0001] in BATCH line 5 at 0.0s"), "{out}");
    assert!(out.contains("BATCH started\n"), "{out}");
    assert!(out.ends_with("BATCH sequence task 1 running RUNNING: B 1s\nR1.Batches = 3\n"), "{out}");
}

#[test]
fn read_only_fields_unknown_steps_and_quoted_semicolons() {
    let plant = example_copy("sequences", "readonly", |db| {
        db["blocks"]["PIC1"] = serde_json::json!({ "type": "PID", "values": { "PV": 42.5 } });
    });
    let script = "M PIC1.SP=5\nF PIC1.SP=5\nD PIC1.SP, PIC1.PV\nHOLDSTEP BATCH Fil\nFORCETRANS BATCH Fulll HOLD\n\
                  HOLDSTEP SIM Fill\nM BATCH.FileName='x;y'; D BATCH.FileName\nF?\n";
    let (code, out) = console(&plant, "readonly", script);
    assert_eq!(code, Some(1), "{out}");
    let expect = "error[C0005]: PIC1.SP is read-only: the block computes it\n\
        error[C0005]: PIC1.SP is read-only: the block computes it\n\
        PIC1.SP = 0.0\nPIC1.PV = 42.5\n\
        error[C0007]: the sequence of `BATCH` has no step `Fil`\n\
        error[C0007]: the sequence of `BATCH` has no transition `Fulll`\n\
        error[C0006]: block `SIM` runs no sequence\n\
        BATCH.FileName = 'x;y'\nBATCH.FileName = 'x;y'\n\
        no forces\nwrites ignored: 0\n";
    assert_eq!(out, expect);
}

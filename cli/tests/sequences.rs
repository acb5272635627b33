//! `.sfc` sequences through the command line: check, compile, disasm, and
//! the example plant whose SFC_CON block runs `examples/sequences/batch.sfc`.
mod common;
use common::{linc, stderr, stdout, temp_dir};

const PLANT: &str = "examples/sequences/plant.json";

#[test]
fn the_example_sequence_checks_clean_and_compiles_to_a_sequence_unit() {
    let o = linc(&["check", "examples/sequences/batch.sfc", "examples/sequences/process.stx", "--db", PLANT]);
    assert_eq!((o.status.code(), stdout(&o).as_str()), (Some(0), ""), "{}", stderr(&o));
    let sto = temp_dir("seq-compile").join("batch.sto").to_string_lossy().into_owned();
    let o = linc(&["compile", "examples/sequences/batch.sfc", "-o", &sto, "--db", PLANT]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let listing = stdout(&linc(&["disasm", &sto]));
    for needle in [
        "sequence batch    ; examples/sequences/batch.sfc, 18 code blocks, 16 retained slots",
        "    step Agitate [slot 3]: Stir(L, 20 s)",
        "    transition `Full` priority 2: (Fill) -> (Heat, Agitate) when Full",
        "    action Stir: chart #1",
    ] {
        assert!(listing.contains(needle), "{needle}\n{listing}");
    }
}

#[test]
fn the_example_plant_runs_its_sequence_and_is_pinned() {
    let trace = temp_dir("seq-run").join("trace.jsonl").to_string_lossy().into_owned();
    let o = linc(&[
        "run",
        PLANT,
        "--for",
        "2m",
        "--now",
        "2026-01-05T06:00:00",
        "--trace",
        &trace,
        "--show",
        "BATCH.Status",
    ]);
    assert_eq!((o.status.code(), stdout(&o).as_str()), (Some(0), "BATCH.Status = 'RUNNING'\n"), "{}", stderr(&o));
    insta::assert_snapshot!("sequence_plant_trace_2m", std::fs::read_to_string(&trace).expect("trace"));
    let shows = ["R1.Batches", "R1.Log", "R1.Stirs", "R1.Alarm"];
    let hour = temp_dir("seq-run").join("hour.jsonl").to_string_lossy().into_owned();
    let mut args = vec!["run", PLANT, "--for", "1h", "--now", "2026-01-05T06:00:00", "--trace", &hour];
    for s in &shows {
        args.extend(["--show", s]);
    }
    let o = linc(&args);
    // 45 s a batch: 80 batches an hour, each logging once at 10 s of heat and
    // stirring 10 times (Fwd 5 s, Rev 5 s, for Agitate's first 20 s).
    assert_eq!(stdout(&o), "R1.Batches = 80\nR1.Log = 80\nR1.Stirs = 800\nR1.Alarm = FALSE\n");
    // The hour's trace (16,774 lines, 1.2 MB; each batch leaves Rev as Agitate ends)
    // is pinned by its size and CRC-32;
    // the first two minutes are pinned line by line above.
    let bytes = std::fs::read(&hour).expect("trace");
    assert_eq!((bytes.len(), bytes.iter().filter(|&&b| b == b'\n').count()), (1_206_807, 16_774));
    assert_eq!(linc_format::object::crc32(&bytes), 0x72e5_da29);
}

#[test]
fn a_broken_sequence_gets_located_errors() {
    let f = temp_dir("seq-broken").join("bad.sfc");
    let src = "INITIAL_STEP A: Go(Q); END_STEP\nTRANSITION FROM A TO B := TRUE; END_TRANSITION\nACTION Go\n  R1.Level := 1.0;\nEND_ACTION\n";
    std::fs::write(&f, src).expect("write");
    let o = linc(&["check", f.to_str().unwrap(), "--db", PLANT, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    let out = stderr(&o);
    let codes: Vec<&str> = out.lines().filter_map(|l| l.split("error[").nth(1)).map(|r| &r[..5]).collect();
    assert_eq!(codes, ["E0207", "E0204"], "{out}");
}

#[test]
fn one_sequence_runs_with_hold_force_and_step_flags() {
    let seq = "examples/sequences/batch.sfc";
    let run = |extra: &[&str]| {
        let mut args = vec!["run", seq, "--db", PLANT, "--for", "30s"];
        args.extend_from_slice(extra);
        linc(&args)
    };
    // Only the sequence runs (no process simulation): the level stays 0, so Fill stays active.
    let o =
        run(&["--period", "0.5", "--set", "R1.Level=85", "--show", "Fill.X", "--show", "Heat.X", "--show", "Heat.T"]);
    assert_eq!(stdout(&o), "Fill.X = FALSE\nHeat.X = TRUE\nHeat.T = 28.5\n", "{}", stderr(&o));
    // A held step stays active though its transition is TRUE; its timer runs.
    let o = run(&["--set", "R1.Level=85", "--hold-step", "Fill", "--show", "Fill.X", "--show", "Fill.T"]);
    assert_eq!(stdout(&o), "Fill.X = TRUE\nFill.T = 28.0\n");
    // Forced: Abort continues though Plant.N1 is 0; Full held though the level is 85.
    let o = run(&["--set", "R1.Level=85", "--force", "Abort=continue", "--force", "Full=hold", "--show", "Aborted.X"]);
    assert_eq!(stdout(&o), "Aborted.X = TRUE\n");
    let o = run(&["--force", "Nope=hold"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("error[E0903]: --force: the sequence has no transition `Nope`"), "{}", stderr(&o));
}

#[test]
fn a_sequence_action_may_be_ladder() {
    let dir = temp_dir("seq-ladder");
    let f = dir.join("lad.sfc");
    let src = "INITIAL_STEP Idle: Interlk(N); END_STEP\nSTEP Run: END_STEP\n\
        TRANSITION FROM Idle TO Run := R1.Alarm; END_TRANSITION\n\
        ACTION Interlk : LADDER\n    [R1.FillVlv] [/R1.Heater]        -> (R1.Agitator);\n\
        ([R1.Level > 50.0] | [R1.Alarm]) -> (S R1.Reverse);\n                                     -> R1.Stirs := R1.Stirs + 1;\nEND_ACTION\n";
    std::fs::write(&f, src).expect("write");
    let file = f.to_str().unwrap();
    let o = linc(&["check", file, "--db", PLANT]);
    assert_eq!((o.status.code(), stderr(&o).as_str()), (Some(0), ""), "{}", stderr(&o));
    let o = linc(&[
        "run",
        file,
        "--db",
        PLANT,
        "--for",
        "5s",
        "--set",
        "R1.FillVlv=1",
        "--set",
        "R1.Level=60",
        "--show",
        "R1.Agitator",
        "--show",
        "R1.Reverse",
        "--show",
        "R1.Stirs",
    ]);
    assert_eq!(stdout(&o), "R1.Agitator = TRUE\nR1.Reverse = TRUE\nR1.Stirs = 5\n", "{}", stderr(&o));
    // The ladder's own errors, located in the sequence file.
    let bad = dir.join("bad.sfc");
    std::fs::write(
        &bad,
        "INITIAL_STEP A: L(N); END_STEP\nACTION L : LADDER\n  [R1.Alarm] -> JUMP Nowhere;\nEND_ACTION\n",
    )
    .expect("write");
    let o = linc(&["check", bad.to_str().unwrap(), "--db", PLANT, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("bad.sfc:3:22: error[E0304]: unresolved jump"), "{}", stderr(&o));
}

#[test]
fn a_transition_may_be_one_ladder_rung() {
    let dir = temp_dir("seq-ladder-transition");
    let f = dir.join("lt.sfc");
    let src = "INITIAL_STEP Idle: END_STEP\nSTEP Run: Count(N); END_STEP\n\
        TRANSITION Go FROM Idle TO Run : LADDER ([R1.FillVlv] | [R1.Level > 50.0]) [/R1.Alarm]; END_TRANSITION\n\
        ACTION Count\n    R1.Stirs := R1.Stirs + 1;\nEND_ACTION\n";
    std::fs::write(&f, src).expect("write");
    let file = f.to_str().unwrap();
    let run = |extra: &[&str]| {
        let mut args = vec!["run", file, "--db", PLANT, "--for", "5s", "--show", "Run.X"];
        args.extend_from_slice(extra);
        stdout(&linc(&args))
    };
    assert_eq!(run(&["--set", "R1.Level=60"]), "Run.X = TRUE\n");
    assert_eq!(run(&["--set", "R1.Level=60", "--set", "R1.Alarm=1"]), "Run.X = FALSE\n", "the NC contact opens");
    assert_eq!(run(&["--set", "R1.FillVlv=1"]), "Run.X = TRUE\n", "the other branch");
    assert_eq!(run(&[]), "Run.X = FALSE\n");
    std::fs::write(&f, src.replace("[/R1.Alarm]", "[/R1.Alarm")).expect("write");
    let o = linc(&["check", file, "--db", PLANT, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("lt.sfc:3:"), "{}", stderr(&o));
}

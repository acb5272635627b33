//! `linc run … --state FILE [--cold]`: warm and cold starts (`docs/state.md`).
mod common;
use common::{linc, stderr, stdout, temp_dir};
use std::path::PathBuf;

const SEQ_PLANT: &str = "examples/sequences/plant.json";
const FST_PLANT: &str = "examples/fst/plant.json";
const NOW: &str = "2026-01-05T06:00:00";

fn temp(tag: &str, name: &str) -> String {
    common::temp_path(tag, name)
}

/// Runs a strategy for `d` with fixed clock and seed, and `more` arguments.
fn run(plant: &str, d: &str, more: &[&str]) -> std::process::Output {
    let mut args = vec!["run", plant, "--for", d, "--now", NOW, "--seed", "7"];
    args.extend_from_slice(more);
    linc(&args)
}

fn ok(o: &std::process::Output) {
    assert_eq!(o.status.code(), Some(0), "{}", stderr(o));
}

fn read(p: &str) -> Vec<u8> {
    std::fs::read(p).expect("written")
}

#[test]
fn a_warm_start_continues_a_strategy_as_one_run() {
    let (state, out) = (temp("warm", "plant.state"), temp("warm", "b.json"));
    ok(&run(SEQ_PLANT, "2m", &["--state", &state]));
    ok(&run(SEQ_PLANT, "1m", &["--state", &state, "--out", &out]));
    let (state3, out3) = (temp("warm", "three.state"), temp("warm", "c.json"));
    ok(&run(SEQ_PLANT, "3m", &["--state", &state3, "--out", &out3]));
    assert_eq!(read(&out), read(&out3), "the databases after 2m + 1m and after 3m");
    // The states hold every step's .X and .T, stored actions and the clock.
    assert_eq!(read(&state), read(&state3), "the states after 2m + 1m and after 3m");
}

/// A sequence run alone, with its step flags shown.
fn sequence(d: &str, more: &[&str]) -> String {
    let mut args: Vec<String> = ["run", "examples/sequences/batch.sfc", "--db", SEQ_PLANT, "--for", d, "--now", NOW]
        .iter()
        .chain(&["--set", "R1.Level=100"])
        .map(|s| s.to_string())
        .collect();
    for step in ["Idle", "Fill", "Heat", "Agitate", "Drain"] {
        args.extend(["--show".to_string(), format!("{step}.X"), "--show".to_string(), format!("{step}.T")]);
    }
    args.extend(more.iter().map(|s| s.to_string()));
    let o = linc(&args.iter().map(String::as_str).collect::<Vec<_>>());
    ok(&o);
    stdout(&o)
}

#[test]
fn a_warm_start_keeps_the_same_steps_and_step_times() {
    let state = temp("steps", "batch.state");
    sequence("30s", &["--state", &state]);
    let warm = sequence("15s", &["--state", &state]);
    let once = sequence("45s", &[]);
    assert_eq!(warm, once);
    assert!(warm.contains("Heat.X = TRUE\nHeat.T = 42.0\nAgitate.X = TRUE\nAgitate.T = 42.0"), "{warm}");
}

#[test]
fn a_cold_start_begins_at_the_initial_steps() {
    let state = temp("cold", "batch.state");
    sequence("30s", &["--state", &state]);
    let cold = sequence("1s", &["--state", &state, "--cold"]);
    assert_eq!(cold, sequence("1s", &[]), "a cold start is a fresh start");
    assert!(cold.contains("Idle.X = TRUE"), "{cold}");
    // The cold run saved its own state: a warm start from it is at 1s.
    let warm = sequence("44s", &["--state", &state]);
    assert_eq!(warm, sequence("45s", &[]));
}

#[test]
fn a_state_cut_short_is_refused_and_the_run_does_not_start() {
    let state = temp("cut", "plant.state");
    ok(&run(SEQ_PLANT, "2m", &["--state", &state]));
    let whole = read(&state);
    let (cut, out) = (temp("cut", "cut.state"), temp("cut", "out.json"));
    let lengths: Vec<usize> = (0..whole.len()).step_by(whole.len() / 40 + 1).chain([whole.len() - 1]).collect();
    for n in lengths {
        std::fs::write(&cut, &whole[..n]).expect("write");
        let o = run(SEQ_PLANT, "1m", &["--state", &cut, "--out", &out]);
        assert_eq!(o.status.code(), Some(2), "cut at {n}");
        assert!(stderr(&o).contains("error[E0840]"), "cut at {n}: {}", stderr(&o));
        assert!(!PathBuf::from(&out).exists(), "cut at {n}: the run started");
        assert_eq!(read(&cut), &whole[..n], "cut at {n}: the refused file was replaced");
    }
    // Asked to, the strategy starts cold and writes a good state.
    ok(&run(SEQ_PLANT, "1m", &["--state", &cut, "--cold", "--out", &out]));
    ok(&run(SEQ_PLANT, "1m", &["--state", &cut]));
}

#[test]
fn a_flipped_byte_is_refused() {
    let state = temp("flip", "plant.state");
    ok(&run(SEQ_PLANT, "2m", &["--state", &state]));
    let mut bytes = read(&state);
    let at = bytes.len() / 2;
    bytes[at] ^= 0x04;
    std::fs::write(&state, &bytes).expect("write");
    let o = run(SEQ_PLANT, "1m", &["--state", &state]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("error[E0840]") && stderr(&o).contains("checksum"), "{}", stderr(&o));
}

#[test]
fn a_state_of_another_strategy_is_refused() {
    let state = temp("other", "fst.state");
    ok(&run(FST_PLANT, "10s", &["--state", &state]));
    let o = run(SEQ_PLANT, "1m", &["--state", &state]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("error[E0842]"), "{}", stderr(&o));
}

#[test]
fn cold_without_state_is_a_usage_error() {
    let o = run(SEQ_PLANT, "1m", &["--cold"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--state"), "{}", stderr(&o));
}

#[test]
fn fst_tables_restart_at_step_0_with_their_registers_kept() {
    let (state, trace) = (temp("fst", "roc.state"), temp("fst", "warm.jsonl"));
    let o = run(FST_PLANT, "2m", &["--state", &state, "--show", "FST 4.R3"]);
    ok(&o);
    // FST 4 logs every 5 s: its last cycle began at 117.3 s and it sleeps in WT until 122.3 s.
    assert_eq!(stdout(&o), "FST 4.R3 = 24.0\n");
    ok(&run(FST_PLANT, "1s", &["--state", &state, "--trace", &trace]));
    let text = String::from_utf8(read(&trace)).expect("utf-8");
    let first: Vec<&str> = text.lines().filter(|l| l.contains("\"program\":\"FST 4\"")).take(2).collect();
    assert_eq!(
        first,
        [
            r#"{"time":120.0,"task":1,"program":"FST 4","step":0,"cmd":"VAL SFP 1,DATA1","RR":12.5,"CF":0}"#,
            r#"{"time":120.0,"task":1,"program":"FST 4","field":"FST 4.R3","old":"24.0","new":"25.0"}"#,
        ],
        "the wait is dropped, the table starts at step 0 and R3 counts on from 24"
    );
}

#[test]
fn a_restored_strategy_is_deterministic() {
    let state = temp("det", "roc.state");
    ok(&run(FST_PLANT, "90s", &["--state", &state]));
    let saved = read(&state);
    let mut outs = Vec::new();
    for tag in ["a", "b"] {
        std::fs::write(&state, &saved).expect("write");
        let out = temp("det", &format!("{tag}.json"));
        ok(&run(FST_PLANT, "5m", &["--state", &state, "--out", &out]));
        outs.push((read(&out), read(&state)));
    }
    assert_eq!(outs[0], outs[1]);
}

#[test]
fn a_stored_action_stays_stored_through_a_warm_start() {
    let dir = temp_dir("stored");
    std::fs::write(dir.join("a.st"), "ACTION Count\n  R.N0 := R.N0 + 1;\n  RUN.Trigger := FALSE;\nEND_ACTION\n")
        .expect("write");
    std::fs::write(
        dir.join("plant.json"),
        r#"{ "blocks": { "R": { "type": "RECIPE" },
              "RUN": { "type": "ACTION", "values": { "FileName": "a.st", "ActName": "Count", "Trigger": true,
                                                     "Qualifier": "S" } } } }"#,
    )
    .expect("write");
    let db = dir.join("plant.json").to_string_lossy().into_owned();
    let state = dir.join("s.state").to_string_lossy().into_owned();
    let count = |d: &str, more: &[&str]| {
        let o = run(&db, d, &[&["--show", "R.N0", "--show", "RUN.Trigger"], more].concat());
        ok(&o);
        stdout(&o)
    };
    assert_eq!(count("1s", &["--state", &state]), "R.N0 = 10\nRUN.Trigger = FALSE\n");
    // The trigger is FALSE in the saved values: only the stored S keeps the action running.
    assert_eq!(count("1s", &["--state", &state]), "R.N0 = 20\nRUN.Trigger = FALSE\n");
    assert_eq!(count("2s", &[]), "R.N0 = 20\nRUN.Trigger = FALSE\n");
}

/// Every leaf's path in a JSON document.
fn leaves(v: &serde_json::Value, path: &mut Vec<serde_json::Value>, out: &mut Vec<Vec<serde_json::Value>>) {
    match v {
        serde_json::Value::Array(a) => a.iter().enumerate().for_each(|(i, x)| {
            path.push(i.into());
            leaves(x, path, out);
            path.pop();
        }),
        serde_json::Value::Object(o) => o.iter().for_each(|(k, x)| {
            path.push(k.as_str().into());
            leaves(x, path, out);
            path.pop();
        }),
        _ => out.push(path.clone()),
    }
}

fn at<'a>(v: &'a mut serde_json::Value, path: &[serde_json::Value]) -> &'a mut serde_json::Value {
    path.iter().fold(v, |v, k| match k {
        serde_json::Value::String(s) => &mut v[s.as_str()],
        k => &mut v[k.as_u64().unwrap_or(0) as usize],
    })
}

#[test]
fn a_resealed_state_with_any_value_changed_never_panics() {
    let state = temp("reseal", "plant.state");
    ok(&run(SEQ_PLANT, "150s", &["--state", &state]));
    let bytes = read(&state);
    let nl = bytes.iter().position(|&b| b == b'\n').expect("header") + 1;
    let doc: serde_json::Value = serde_json::from_slice(&bytes[nl..]).expect("body");
    let mut paths = Vec::new();
    leaves(&doc, &mut Vec::new(), &mut paths);
    let bad = temp("reseal", "bad.state");
    let values = [serde_json::json!(null), serde_json::json!(u64::MAX), serde_json::json!("x"), serde_json::json!([])];
    for (n, path) in paths.iter().enumerate().step_by(paths.len() / 400 + 1) {
        let mut d = doc.clone();
        *at(&mut d, path) = values[n % values.len()].clone();
        let body = serde_json::to_vec(&d).expect("json");
        let header =
            serde_json::json!({"linc-state": 1, "crc32": linc_format::object::crc32(&body), "length": body.len()});
        std::fs::write(&bad, [header.to_string().as_bytes(), b"\n", &body].concat()).expect("write");
        let o = run(SEQ_PLANT, "1s", &["--state", &bad]);
        assert!(matches!(o.status.code(), Some(0 | 2)), "{path:?}: {}", stderr(&o));
        if o.status.code() == Some(2) {
            assert!(stderr(&o).contains("error[E0842]"), "{path:?}: {}", stderr(&o));
        }
    }
}

#[test]
fn the_same_plant_named_by_another_path_warm_starts() {
    // The fingerprint is of the strategy's content: `./plant.json`, an
    // absolute path and the plain name are one plant (issue 16).
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for plant in [SEQ_PLANT, FST_PLANT, "examples/strategy/plant.json"] {
        let absolute = root.join(plant).to_string_lossy().into_owned();
        let dotted = format!("./{plant}");
        let (state, out) = (temp("paths", "plant.state"), temp("paths", "warm.json"));
        ok(&run(plant, "1m", &["--state", &state, "--cold"]));
        ok(&run(&dotted, "1m", &["--state", &state]));
        ok(&run(&absolute, "1m", &["--state", &state, "--out", &out]));
        let (state3, out3) = (temp("paths", "three.state"), temp("paths", "once.json"));
        ok(&run(plant, "3m", &["--state", &state3, "--cold", "--out", &out3]));
        if plant != FST_PLANT {
            // FST tables restart at step 0 on a warm start, so only
            // strategies without them continue exactly.
            assert_eq!(read(&out), read(&out3), "{plant}: the database after 1m + 1m + 1m and after 3m");
        }
    }
}

/// A state whose program would resume inside an expression or past the end
/// of its code is refused (E0842): a run resumes only where the verified
/// code suspends (issue 16; a resealed state used to run on from there,
/// with wrong results and exit 0).
#[test]
fn a_resume_point_where_the_code_cannot_stop_is_refused() {
    for plant in [SEQ_PLANT, FST_PLANT] {
        let state = temp("resume", "plant.state");
        ok(&run(plant, "150s", &["--state", &state, "--cold"]));
        let bytes = read(&state);
        let nl = bytes.iter().position(|&b| b == b'\n').expect("header") + 1;
        let doc: serde_json::Value = serde_json::from_slice(&bytes[nl..]).expect("body");
        let members = doc["members"].as_array().expect("members").len();
        assert!(members > 0, "{plant}: no programs");
        let bad = temp("resume", "bad.state");
        for (m, at) in (0..members).flat_map(|m| [(m, 1u64), (m, 1 << 20)]) {
            let mut d = doc.clone();
            d["members"][m]["resume"] = at.into();
            let body = serde_json::to_vec(&d).expect("json");
            let header =
                serde_json::json!({"linc-state": 1, "crc32": linc_format::object::crc32(&body), "length": body.len()});
            std::fs::write(&bad, [header.to_string().as_bytes(), b"\n", &body].concat()).expect("write");
            let o = run(plant, "1s", &["--state", &bad]);
            assert_eq!(o.status.code(), Some(2), "{plant} member {m} at {at}: {}", stderr(&o));
            assert!(stderr(&o).contains("error[E0842]") && stderr(&o).contains("resume"), "{}", stderr(&o));
        }
    }
}

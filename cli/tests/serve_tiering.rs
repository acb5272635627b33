//! Issue 30: no scan waits on a translation. A generated plant of large
//! actions (40 blocks of about 1,500 instructions each, every one in a
//! loop, so every one is translated) stalls its first scans under `linc
//! serve --tier compiled`, which translates each block on the plant's
//! thread before its first run; under `--tier auto` the translations run
//! on a background thread (ADR 0023) and the plant's first minute at speed
//! 1 has no late scan.
mod common;

use std::fmt::Write as _;

const ACTIONS: usize = 40;

/// The action file: `ACTIONS` actions of about 60 statements each, inside
/// a FOR loop of two turns; the values stay small and finite.
fn actions() -> String {
    let mut src = String::new();
    for i in 0..ACTIONS {
        let _ = writeln!(src, "ACTION Big{i}\nFOR R{}.N7 := 1 TO 2 DO", i % 4);
        for s in 0..60 {
            let (j, k, r) = ((i + s) % 8, (i * 7 + s) % 8, s % 4);
            let _ = write!(
                src,
                "    IF R{r}.A{j} < {s}.5 AND R{r}.N{k} <> {i} THEN\n        R{r}.A{k} := R{r}.A{j} * 0.5 + 1.0;\n    ELSIF R{r}.N{j} > 100 THEN\n        R{r}.N{j} := 0;\n    ELSE\n        R{r}.N{k} := (R{r}.N{k} + {s}) MOD 1000;\n    END_IF;\n"
            );
        }
        src.push_str("END_FOR;\nEND_ACTION\n");
    }
    src
}

/// The plant: four register blocks and one ACTION block per action, all on
/// a 100 ms task.
fn plant_json() -> String {
    let mut blocks = String::new();
    for r in 0..4 {
        let _ = writeln!(blocks, "\"R{r}\": {{ \"type\": \"REG\" }},");
    }
    for i in 0..ACTIONS {
        let _ = writeln!(
            blocks,
            "\"ACT{i}\": {{ \"type\": \"ACTION\", \"task\": 1, \"values\": {{ \"FileName\": \"big.stx\", \"ActName\": \"Big{i}\", \"Trigger\": true, \"Qualifier\": \"N\" }} }},"
        );
    }
    let fields: Vec<String> =
        (0..8).flat_map(|n| [format!("\"N{n}\": \"INT\""), format!("\"A{n}\": \"REAL\"")]).collect();
    format!(
        "{{\n\"templates\": {{ \"REG\": {{ \"fields\": {{ {} }} }} }},\n\"tasks\": {{ \"1\": {{ \"period\": \"T#100ms\" }} }},\n\"blocks\": {{\n{blocks}\"SYS\": {{ \"type\": \"SYSTEM\" }}\n}}\n}}\n",
        fields.join(", ")
    )
}

/// Serves the plant for `duration` at speed 1 and returns (scans, late,
/// code blocks compiled, code blocks).
fn serve(plant: &str, tier: &str, duration: &str) -> [u64; 4] {
    let o = common::linc(&["serve", plant, "--http", "127.0.0.1:0", "--tier", tier, "--for", duration]);
    let out = common::stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", common::stderr(&o));
    // "stopped at TIME: N scans, L late, C of B code blocks compiled"
    let last = out.lines().last().unwrap_or("");
    let counts: Vec<u64> =
        last.rsplit(": ").next().unwrap_or("").split([' ', ',']).filter_map(|w| w.parse().ok()).collect();
    counts.try_into().unwrap_or_else(|c| panic!("four counts, not {c:?}: {out}"))
}

#[test]
fn a_plant_of_large_actions_runs_its_first_minute_with_no_late_scan() {
    let dir = common::temp_dir("serve-tiering");
    std::fs::write(dir.join("big.stx"), actions()).expect("write actions");
    let plant = dir.join("plant.json");
    std::fs::write(&plant, plant_json()).expect("write plant");
    let plant = plant.to_str().expect("a UTF-8 path");
    let check = common::linc(&["check", &dir.join("big.stx").to_string_lossy()]);
    assert_eq!(check.status.code(), Some(0), "{}", common::stderr(&check));

    // Translating every block on the plant's thread makes the first scans
    // late: the plant is large enough to show what background tiering
    // saves.
    let [scans, late, compiled, blocks] = serve(plant, "compiled", "3s");
    eprintln!("--tier compiled, 3 s: {scans} scans, {late} late, {compiled} of {blocks} blocks compiled");
    assert!(late > 0, "the plant should stall under --tier compiled");
    assert_eq!(compiled, ACTIONS as u64, "every action's block is translated");

    // Under `auto` every block is translated too, in the background,
    // and not one scan waits for it.
    let [scans, late, compiled, blocks] = serve(plant, "auto", "60s");
    eprintln!("--tier auto, 60 s: {scans} scans, {late} late, {compiled} of {blocks} blocks compiled");
    assert_eq!(late, 0, "no late scan under --tier auto ({scans} scans)");
    assert!(scans >= 600, "{scans} scans in a minute of 100 ms scans");
    assert_eq!(compiled, ACTIONS as u64, "every action's block is translated");
}

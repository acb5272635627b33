//! The generic batch sequence, specialised for each reactor with its map,
//! run side by side by two SFC_CON blocks for a simulated hour.
mod common;
use common::{linc, stderr, stdout, temp_dir};

const PLANT: &str = r#"{
  "templates": { "REACTOR": { "fields": {
      "Level": "REAL", "Temp": "REAL", "FillVlv": "BOOL", "DrainVlv": "BOOL", "Heater": "BOOL",
      "Agitator": "BOOL", "Reverse": "BOOL", "Alarm": "BOOL", "Batches": "INT", "Log": "INT", "Stirs": "INT" } } },
  "tasks": { "1": { "period": "T#1s" } },
  "blocks": {
    "R1": { "type": "REACTOR", "values": { "Temp": 20.0 } },
    "R2": { "type": "REACTOR", "values": { "Temp": 20.0 } },
    "Plant": { "type": "RECIPE", "values": { "N0": 1, "N2": 1 } },
    "SIM1": { "type": "ACTION", "values": { "FileName": "process.stx", "ActName": "Proc1", "Trigger": true } },
    "SIM2": { "type": "ACTION", "values": { "FileName": "process.stx", "ActName": "Proc2", "Trigger": true } },
    "SEQ1": { "type": "SFC_CON", "values": { "FileName": "reactor1.sfc", "Run": true } },
    "SEQ2": { "type": "SFC_CON", "values": { "FileName": "reactor2.sfc", "Run": true } } } }"#;

/// The example's process, for one reactor (R2 fills and heats more slowly).
fn process(name: &str, r: &str, fill: f32, heat: f32) -> String {
    format!(
        "ACTION {name}\n  IF {r}.FillVlv THEN {r}.Level := MIN({r}.Level + {fill:.1}, 100.0); END_IF;\n  \
         IF {r}.DrainVlv THEN {r}.Level := MAX({r}.Level - 10.0, 0.0); END_IF;\n  \
         IF {r}.Heater THEN {r}.Temp := {r}.Temp + {heat:.1}; ELSIF {r}.Temp > 20.0 THEN {r}.Temp := {r}.Temp - 0.5; END_IF;\nEND_ACTION\n"
    )
}

#[test]
fn both_specialised_reactors_run_for_an_hour() {
    let dir = temp_dir("generic-run");
    for n in [1, 2] {
        let out = dir.join(format!("reactor{n}.sfc"));
        let map = format!("examples/sequences/reactor{n}.map.json");
        let o =
            linc(&["sfc", "specialise", "examples/sequences/generic.sfc", "--map", &map, "-o", out.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    }
    std::fs::write(dir.join("process.stx"), process("Proc1", "R1", 5.0, 2.0) + &process("Proc2", "R2", 4.0, 1.5))
        .expect("write");
    let plant = dir.join("plant.json");
    std::fs::write(&plant, PLANT).expect("write");
    let trace = dir.join("hour.jsonl");
    let mut args = vec!["run", plant.to_str().unwrap(), "--for", "1h", "--now", "2026-01-05T06:00:00"];
    args.extend(["--trace", trace.to_str().unwrap()]);
    for f in ["R1.Batches", "R1.Stirs", "R2.Batches", "R2.Stirs", "SEQ1.Status", "SEQ2.Status"] {
        args.extend(["--show", f]);
    }
    let o = linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    // R1 is the example's reactor (45 s a batch); R2 fills and heats slower (about 48 s a batch).
    assert_eq!(
        stdout(&o),
        "R1.Batches = 80\nR1.Stirs = 800\nR2.Batches = 74\nR2.Stirs = 730\nSEQ1.Status = 'RUNNING'\nSEQ2.Status = 'RUNNING'\n"
    );
    let bytes = std::fs::read(&trace).expect("trace");
    let lines = bytes.iter().filter(|&&b| b == b'\n').count();
    assert_eq!(
        (lines, linc_format::object::crc32(&bytes)),
        (33_093, 0xcc32_4944),
        "the hour's trace, pinned (a chart action left deactivates its steps)"
    );
}

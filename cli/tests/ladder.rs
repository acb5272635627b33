//! `.ld` files on the command line (docs/ladder.md): check, compile, run
//! and `linc ladder to-st`, on the guide's eight rungs.

mod common;
use common::{linc, stderr, stdout};

const LD: &str = "examples/ladder/interlock.ld";
const DB: &str = "examples/ladder/plant.json";

fn temp_file(name: &str, text: &str) -> String {
    common::temp_file(&format!("ladder-{name}"), name, text)
}

#[test]
fn the_example_checks_clean() {
    let o = linc(&["check", LD, "--db", DB]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert_eq!(stdout(&o), "");
}

#[test]
fn the_example_compiles_and_disassembles_with_rung_lines() {
    let out = temp_file("interlock.sto", "");
    std::fs::remove_file(&out).expect("remove");
    let o = linc(&["compile", LD, "--db", DB, "-o", &out]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let d = linc(&["disasm", &out]);
    let text = stdout(&d);
    assert!(text.contains("action interlock"), "{text}");
    assert!(text.contains("; 2:9  [Dig_1a.In]                    -> (Dig_1b.Out);"), "{text}");
}

#[test]
fn the_example_runs_and_its_jump_skips_the_variable_outputs() {
    let show = ["--show", "Dig_1b.Out", "--show", "Dig_2c.Out", "--show", "Ana_7b.PV", "--show", "Ana_8c.PV"];
    let mut args = vec!["run", LD, "--db", DB, "--set", "Dig_1a.In=TRUE", "--set", "Dig_5b.In=TRUE"];
    args.extend(show);
    let o = linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert_eq!(stdout(&o), "Dig_1b.Out = TRUE\nDig_2c.Out = TRUE\nAna_7b.PV = 42.5\nAna_8c.PV = 8.5\n");
    let mut args = vec!["run", LD, "--db", DB, "--set", "Dig_5a.In=TRUE"];
    args.extend(show);
    let o = linc(&args);
    assert_eq!(stdout(&o), "Dig_1b.Out = FALSE\nDig_2c.Out = TRUE\nAna_7b.PV = 0.0\nAna_8c.PV = 0.0\n");
}

#[test]
fn to_st_prints_the_equivalent_st() {
    let o = linc(&["ladder", "to-st", LD, "--db", DB]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let text = stdout(&o);
    let first = "IF Dig_1a.In THEN\n    Dig_1b.Out := TRUE;\nELSE\n    Dig_1b.Out := FALSE;\nEND_IF;\n";
    let second =
        "IF Dig_2a.In AND NOT Dig_2b.In THEN\n    Dig_2c.Out := FALSE;\nELSE\n    Dig_2c.Out := TRUE;\nEND_IF;\n";
    assert!(text.starts_with(&format!("{first}{second}")), "{text}");
    assert!(text.contains("IF NOT (Dig_5a.In OR NOT Dig_5b.In) THEN\n    IF Dig_6a.In THEN\n"), "{text}");
    assert!(text.ends_with("    Ana_8c.PV := MAX(Ana_8a.PV, 8.5);\nEND_IF;\n"), "{text}");
}

#[test]
fn ladder_errors_exit_one_with_their_codes() {
    let bad =
        temp_file("bad.ld", "[Dig_1a.In] -> JUMP Top;\nTop: [Ana_8a.Count] -> (Ana_7b.PV);\n[A.In] -> JUMP Top;\n");
    let o = linc(&["check", &bad, "--db", DB, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    let text = stderr(&o);
    let codes: Vec<&str> = text.lines().filter_map(|l| l.split(['[', ']']).nth(1)).collect();
    assert_eq!(codes, ["E0306", "E0307", "E0100", "E0305"], "{text}");
    let o = linc(&["ladder", "to-st", &bad, "--db", DB]);
    assert_eq!(o.status.code(), Some(1));
}

#[test]
fn an_ld_action_and_an_st_action_share_one_namespace() {
    let st = temp_file("interlock.st", "Dig_1b.Out := TRUE;\n");
    let o = linc(&["check", LD, &st, "--db", DB, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("E0117"), "{}", stderr(&o));
}

#[test]
fn the_printed_st_runs_like_the_ladder() {
    let st = stdout(&linc(&["ladder", "to-st", LD, "--db", DB]));
    let st_path = temp_file("interlock.st", &st);
    for set in [["Dig_2a.In=TRUE", "Dig_5b.In=TRUE"], ["Dig_3a.In=TRUE", "Dig_6a.In=TRUE"]] {
        let mut outs = Vec::new();
        for file in [LD, st_path.as_str()] {
            let mut args = vec!["run", file, "--db", DB, "--set", set[0], "--set", set[1]];
            for f in ["Dig_1b.Out", "Dig_2c.Out", "Dig_3c.Out", "Dig_4c.Out", "RECIPE1.A0", "Ana_7b.PV", "Ana_8c.PV"] {
                args.extend(["--show", f]);
            }
            let o = linc(&args);
            assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
            outs.push(stdout(&o));
        }
        assert_eq!(outs[0], outs[1], "{set:?}");
    }
}

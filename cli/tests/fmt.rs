//! `linc fmt` from the command line: --check for CI, formatting in place,
//! refusing a file that does not parse, links and a missing target, and
//! the files of the strategies in the current directory.

mod common;

use common::{linc, stderr, stdout, temp_dir};
use std::path::Path;
use std::process::{Command, Output};

const MESSY: &str = "ACTION Fill\nif TANK1.Level<50.0 then TANK1.Valve:=true;end_if;\nEND_ACTION\n";
const TIDY: &str =
    "ACTION Fill\n    IF TANK1.Level < 50.0 THEN\n        TANK1.Valve := TRUE;\n    END_IF;\nEND_ACTION\n";

fn linc_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_linc")).args(args).current_dir(dir).output().expect("run linc")
}

#[test]
fn the_examples_are_formatted() {
    let o = linc(&["fmt", "--check", "examples/"]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    assert_eq!(stdout(&o), "");
}

#[test]
fn check_lists_what_would_change_and_fmt_rewrites_it() {
    let dir = temp_dir("fmt-check");
    let file = dir.join("fill.stx");
    std::fs::write(&file, MESSY).expect("write");
    let path = file.to_str().expect("path");
    let o = linc(&["fmt", "--check", dir.to_str().expect("dir")]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(stdout(&o), format!("{path}\n"));
    assert_eq!(std::fs::read_to_string(&file).expect("read"), MESSY, "--check changes nothing");
    let o = linc(&["fmt", path]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&file).expect("read"), TIDY);
    let o = linc(&["fmt", "--check", path]);
    assert_eq!((o.status.code(), stdout(&o)), (Some(0), String::new()));
}

#[test]
fn a_file_that_does_not_parse_is_reported_and_left_alone() {
    let dir = temp_dir("fmt-broken");
    let file = dir.join("broken.st");
    std::fs::write(&file, "TANK1.Level := ;\n").expect("write");
    let o = linc(&["fmt", file.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0010]"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&file).expect("read"), "TANK1.Level := ;\n");
}

#[cfg(unix)]
#[test]
fn a_link_is_not_written_through() {
    let dir = temp_dir("fmt-link");
    let target = dir.join("real.stx");
    std::fs::write(&target, MESSY).expect("write");
    let link = dir.join("link.stx");
    let _ = std::fs::remove_file(&link);
    std::os::unix::fs::symlink(&target, &link).expect("link");
    let o = linc(&["fmt", link.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("error[E0901]"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&target).expect("read"), MESSY);
}

#[test]
fn without_files_it_formats_what_the_strategies_here_run() {
    let dir = temp_dir("fmt-strategy");
    let db = r#"{ "templates": { "TANK": { "fields": { "Level": "REAL", "Valve": "BOOL" } } },
        "blocks": { "TANK1": { "type": "TANK" },
                    "FILL": { "type": "ACTION", "values": { "FileName": "fill.stx", "ActName": "Fill" } } } }"#;
    std::fs::write(dir.join("plant.json"), db).expect("db");
    std::fs::write(dir.join("fill.stx"), MESSY).expect("action");
    std::fs::write(dir.join("other.stx"), MESSY).expect("other");
    let o = linc_in(&dir, &["fmt"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(dir.join("fill.stx")).expect("read"), TIDY);
    assert_eq!(std::fs::read_to_string(dir.join("other.stx")).expect("read"), MESSY, "no strategy names it");

    let empty = temp_dir("fmt-nothing");
    let o = linc_in(&empty, &["fmt"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("error[E0903]"), "{}", stderr(&o));
}

#[test]
fn a_directory_gives_its_fst_tables_but_not_other_csv_files() {
    let dir = temp_dir("fmt-csv");
    std::fs::write(dir.join("table.csv"), "step , label,CMD,Argument 1,ARGUMENT2\n0,,END,,\n").expect("table");
    std::fs::write(dir.join("data.csv"), "time,value\n1,2\n").expect("data");
    let o = linc(&["fmt", "--check", dir.to_str().expect("dir")]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert_eq!(stdout(&o), format!("{}\n", dir.join("table.csv").display()));
}

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

/// A file with two names (a hard link) is written in place: both names
/// still show one file, formatted, and its permissions stay.
#[cfg(unix)]
#[test]
fn a_hard_link_still_shares_the_file_after_fmt() {
    use std::os::unix::fs::{MetadataExt, PermissionsExt};
    let dir = temp_dir("fmt-hard-link");
    let (file, other) = (dir.join("fill.stx"), dir.join("copy.stx"));
    std::fs::write(&file, MESSY).expect("write");
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o640)).expect("chmod");
    std::fs::hard_link(&file, &other).expect("hard link");
    let inode = std::fs::metadata(&file).expect("meta").ino();
    let o = linc(&["fmt", file.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for name in [&file, &other] {
        let meta = std::fs::metadata(name).expect("meta");
        assert_eq!((meta.ino(), meta.nlink(), meta.mode() & 0o777), (inode, 2, 0o640), "{}", name.display());
        assert_eq!(std::fs::read_to_string(name).expect("read"), TIDY);
    }
}

/// A file with one name is replaced atomically and keeps its permissions.
#[cfg(unix)]
#[test]
fn a_file_with_one_name_is_replaced_and_keeps_its_mode() {
    use std::os::unix::fs::PermissionsExt;
    let dir = temp_dir("fmt-one-name");
    let file = dir.join("fill.stx");
    std::fs::write(&file, MESSY).expect("write");
    std::fs::set_permissions(&file, std::fs::Permissions::from_mode(0o604)).expect("chmod");
    let o = linc(&["fmt", file.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&file).expect("read"), TIDY);
    assert_eq!(std::fs::metadata(&file).expect("meta").permissions().mode() & 0o777, 0o604);
    let names: Vec<_> = std::fs::read_dir(&dir).expect("list").flatten().map(|e| e.file_name()).collect();
    assert_eq!(names, [std::ffi::OsString::from("fill.stx")], "no temporary file left");
}

/// A read-only file is left as it is (content and mode), with E0900 and
/// exit status 2, even for root; the other files named are formatted.
#[cfg(unix)]
#[test]
fn a_read_only_file_is_left_alone_with_e0900() {
    use std::os::unix::fs::PermissionsExt;
    let dir = temp_dir("fmt-read-only");
    let (locked, open) = (dir.join("locked.stx"), dir.join("open.stx"));
    std::fs::write(&locked, MESSY).expect("write");
    std::fs::write(&open, MESSY).expect("write");
    std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o444)).expect("chmod");
    let o = linc(&["fmt", locked.to_str().expect("path"), open.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("error[E0900]"), "{}", stderr(&o));
    assert!(stderr(&o).contains("read-only"), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&locked).expect("read"), MESSY);
    assert_eq!(std::fs::metadata(&locked).expect("meta").permissions().mode() & 0o777, 0o444);
    assert_eq!(std::fs::read_to_string(&open).expect("read"), TIDY);
    let o = linc(&["fmt", "--check", locked.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(1), "--check still reads it: {}", stderr(&o));
}

//! The `linc` command line: exit statuses, output formats, explain.

use std::process::{Command, Output};

fn linc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run linc")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

const DB: &str = "examples/guide/plant.db.json";

/// Writes `text` to a fresh temporary file named `name` and returns its path.
fn temp_file(name: &str, text: &str) -> String {
    let dir = std::env::temp_dir().join(format!("linc-cli-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write temp file");
    path.to_string_lossy().into_owned()
}

#[test]
fn clean_files_exit_zero_and_print_nothing() {
    let o = linc(&[
        "check",
        "examples/guide/control.stx",
        "examples/guide/shift.st",
        "--db",
        DB,
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert_eq!(stdout(&o), "");
}

#[test]
fn errors_exit_one_with_short_locations() {
    let o = linc(&[
        "check",
        "examples/guide/broken.st",
        "--db",
        DB,
        "--message-format",
        "short",
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stdout(&o),
        "examples/guide/broken.st:2:24: error[E0010]: unexpected `;`\n\
         examples/guide/broken.st:3:17: error[E0104]: `AUTOMATIC` is not a value of `PIC_004.Mode`\n\
         examples/guide/broken.st:5:28: error[E0007]: `ANDB` is a name, not the operator AND\n"
    );
}

#[test]
fn human_format_renders_snippets_and_help() {
    let o = linc(&["check", "examples/guide/broken.st", "--db", DB]);
    assert_eq!(o.status.code(), Some(1));
    insta::assert_snapshot!(stdout(&o));
    assert!(String::from_utf8_lossy(&o.stderr).contains("3 errors, 0 warnings"));
}

#[test]
fn json_format_is_one_object_per_line() {
    let o = linc(&[
        "check",
        "examples/guide/broken.st",
        "--db",
        DB,
        "--message-format",
        "json",
    ]);
    assert_eq!(o.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = stdout(&o)
        .lines()
        .map(|l| serde_json::from_str(l).expect("each line is JSON"))
        .collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[1]["code"], "E0104");
    assert_eq!(lines[1]["line"], 3);
    assert_eq!(lines[1]["column"], 17);
    assert_eq!(lines[1]["file"], "examples/guide/broken.st");
    assert_eq!(lines[1]["severity"], "error");
    assert!(lines[1]["help"][0]
        .as_str()
        .unwrap_or_default()
        .contains("MANUAL"));
}

#[test]
fn without_a_database_names_are_not_resolved() {
    let o = linc(&["check", "examples/guide/shift.st"]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

#[test]
fn missing_file_is_an_io_error() {
    let o = linc(&["check", "no/such/file.st"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("E0900"));
}

#[test]
fn broken_database_is_reported_with_its_location() {
    let db = temp_file(
        "bad.json",
        "{ \"blocks\": { \"B1\": { \"type\": \"NOPE\" } } }",
    );
    let o = linc(&[
        "check",
        "examples/guide/shift.st",
        "--db",
        &db,
        "--message-format",
        "short",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stdout(&o).contains("bad.json:1:31: error[E0803]: block `B1` has unknown type `NOPE`"),
        "{}",
        stdout(&o)
    );
}

#[test]
fn usage_errors_exit_two() {
    assert_eq!(linc(&["check"]).status.code(), Some(2));
    assert_eq!(
        linc(&["check", "x.st", "--message-format", "xml"])
            .status
            .code(),
        Some(2)
    );
    assert_eq!(linc(&["frobnicate"]).status.code(), Some(2));
}

#[test]
fn tree_prints_the_grouping() {
    let f = temp_file("prec.st", "Recipe.N0 := 10 - 2 - 3;\n");
    let o = linc(&["check", &f, "--db", DB, "--tree"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        stdout(&o),
        "(action prec\n  (:= Recipe.N0 (- (- 10 2) 3))\n)\n"
    );
}

#[test]
fn transitions_are_checked_in_sequence_context() {
    let path = &temp_file(
        "t1.stt",
        "Dig_B.Out.Bit5 AND (Rec.A0<4 OR Rec.A0>5) OR step6.T>=T#4s",
    );
    assert_eq!(
        linc(&["check", path, "--db", DB, "--transition"])
            .status
            .code(),
        Some(0)
    );
    assert_eq!(linc(&["check", path, "--db", DB]).status.code(), Some(1));
}

#[test]
fn explain_prints_the_page() {
    let o = linc(&["explain", "e0104"]);
    assert_eq!(o.status.code(), Some(0));
    let page = stdout(&o);
    assert!(page.starts_with("# E0104"));
    assert!(page.contains("## Wrong") && page.contains("## Right"));
    assert_eq!(linc(&["explain", "E9999"]).status.code(), Some(2));
    let list = stdout(&linc(&["explain", "--list"]));
    assert!(list.lines().count() >= 46 && list.contains("E0001") && list.contains("W0001"));
}

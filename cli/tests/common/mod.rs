//! What the CLI test files share: running the binary from the repository
//! root, and temporary files of one test run.
#![allow(dead_code)]

use std::process::{Command, Output};

/// The guide's database, relative to the repository root.
pub const DB: &str = "examples/guide/plant.db.json";

/// Runs `linc` with `args` in the repository root.
pub fn linc(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run linc")
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh directory `tag` for this test run.
#[allow(unused_imports)]
pub use linc_test_support::temp_dir;

/// Runs `linc` with `args` in the repository root, `input` on its standard input.
pub fn linc_with_input(args: &[&str], input: &str) -> Output {
    use std::io::Write;
    let mut child = spawn(args);
    // linc may refuse its arguments and exit before it reads a line; the
    // pipe is then closed and the write fails with BrokenPipe, which is not
    // the test's failure: the exit code and output say what happened.
    match child.stdin.take().expect("stdin").write_all(input.as_bytes()) {
        Ok(()) => {}
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => {}
        Err(e) => panic!("write the input: {e}"),
    }
    child.wait_with_output().expect("linc's output")
}

/// Starts `linc` with `args` in the repository root, its standard input,
/// output and error piped.
pub fn spawn(args: &[&str]) -> std::process::Child {
    use std::process::Stdio;
    Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run linc")
}

/// Whether the independent tool `name` (xmllint, genhtml) is installed; a
/// test that needs one is skipped without it, unless `.ci/run` asks for
/// the tools (`LINC_REQUIRE_COVERAGE_TOOLS`), where it fails.
pub fn tool(name: &str) -> bool {
    let found = std::process::Command::new(name).arg("--version").output().is_ok();
    if !found {
        assert!(std::env::var_os("LINC_REQUIRE_COVERAGE_TOOLS").is_none(), "{name} is required but not installed");
        eprintln!("skipped: {name} is not installed");
    }
    found
}

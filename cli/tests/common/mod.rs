//! What the CLI test files share: running the binary from the repository
//! root, and temporary files of one test run.
#![allow(dead_code)]

use std::process::{Command, Output};

pub mod null_modem;

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

/// Waits for `child` to exit. Not a timing assertion: the minute only ends
/// a test that would otherwise hang, far beyond any load on the machine.
pub fn exited(child: &mut std::process::Child) -> std::process::ExitStatus {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    loop {
        if let Some(status) = child.try_wait().expect("wait for linc") {
            return status;
        }
        if std::time::Instant::now() > deadline {
            let _ = child.kill();
            panic!("linc did not exit within a minute");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

/// Every Rust source file under `dir`.
pub fn rust_sources(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("list").flatten() {
        let p = entry.path();
        if p.is_dir() {
            rust_sources(&p, out);
        } else if p.extension().is_some_and(|e| e == "rs") {
            out.push(p);
        }
    }
}

/// A fresh file `name` in the scratch directory `tag`, holding `bytes`; its
/// path as text, for the command line.
pub fn temp_file(tag: &str, name: &str, bytes: impl AsRef<[u8]>) -> String {
    let path = temp_dir(tag).join(name);
    std::fs::write(&path, bytes).expect("write temp file");
    path.to_string_lossy().into_owned()
}

/// The path of `name` in the scratch directory `tag` (not made), as text.
pub fn temp_path(tag: &str, name: &str) -> String {
    temp_dir(tag).join(name).to_string_lossy().into_owned()
}

//! The command line against hostile or mistaken file names and option values:
//! inputs that never end or are too large.
#![cfg(unix)]

use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
const DB: &str = "examples/guide/plant.db.json";
const SRC: &str = "examples/guide/shift.st";

/// Runs `linc` and gives up (failing the test) after `secs` seconds, so a
/// command that runs away fails instead of hanging the suite.
fn linc_within(secs: u64, args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(args)
        .current_dir(ROOT)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run linc");
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut buf = Vec::new();
            let _ = r.read_to_end(&mut buf);
            buf
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("stdout")));
    let err = drain(Box::new(child.stderr.take().expect("stderr")));
    let deadline = Instant::now() + Duration::from_secs(secs);
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait for linc") {
            break status;
        }
        if Instant::now() > deadline {
            let _ = child.kill();
            let _ = child.wait();
            panic!("`linc {}` did not finish within {secs} s", args.join(" "));
        }
        std::thread::sleep(Duration::from_millis(20));
    };
    Output { status, stdout: out.join().expect("stdout"), stderr: err.join().expect("stderr") }
}

fn linc(args: &[&str]) -> Output {
    linc_within(120, args)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The exit status and standard error, for one assertion with context.
fn status(o: &Output) -> (Option<i32>, String) {
    (o.status.code(), stderr(o) + &String::from_utf8_lossy(&o.stdout))
}

/// A fresh, empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("linc-hardening-{}-{name}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).expect("scratch dir");
    dir
}

fn s(p: &Path) -> &str {
    p.to_str().expect("utf-8 temp path")
}

fn mkfifo(p: &Path) {
    let ok = Command::new("mkfifo").arg(p).status().expect("mkfifo").success();
    assert!(ok, "mkfifo {}", p.display());
}

/// Asserts a refused command: exit 2 and `code` in its message.
fn assert_refused(o: &Output, code: &str) {
    let (status, text) = status(o);
    assert_eq!(status, Some(2), "{text}");
    assert!(text.contains(code), "expected {code}: {text}");
}

// ---- input files ----

#[test]
fn endless_inputs_fail_fast() {
    let dir = scratch("in-endless");
    let fifo = dir.join("pipe.st");
    mkfifo(&fifo);
    let sto = dir.join("a.sto");
    assert_eq!(linc(&["compile", SRC, "--db", DB, "-o", s(&sto)]).status.code(), Some(0));
    // A link to /dev/zero named `.sto`, so that `run` takes it as an object.
    let zero_sto = dir.join("zero.sto");
    let z_sto = dir.join("z.sto");
    std::os::unix::fs::symlink("/dev/zero", &zero_sto).expect("symlink");
    let cases: [&[&str]; 9] = [
        &["check", "/dev/zero"],
        &["check", s(&fifo)],
        &["check", SRC, "--db", "/dev/zero"],
        &["compile", "/dev/zero", "--db", DB, "-o", s(&z_sto)],
        &["run", "/dev/zero", "--db", DB],
        &["run", s(&zero_sto), "--db", DB],
        &["run", s(&sto), "--db", s(&fifo)],
        &["eval", "1", "--db", "/dev/zero"],
        &["disasm", "/dev/zero"],
    ];
    for args in cases {
        let o = linc_within(20, args);
        let (code, text) = status(&o);
        assert_eq!(code, Some(2), "linc {}: {text}", args.join(" "));
        assert!(text.contains("E0900") && text.contains("not a regular file"), "linc {}: {text}", args.join(" "));
    }
}

#[test]
fn inputs_over_the_size_limit_are_refused() {
    let dir = scratch("in-large");
    let big = dir.join("big.st");
    // Sparse: 256 MiB and one byte, almost nothing on disk.
    fs::File::create(&big).expect("big").set_len((256 << 20) + 1).expect("set_len");
    let o = linc_within(20, &["check", s(&big)]);
    assert_refused(&o, "E0900");
    assert!(stderr(&o).contains("256 MiB"), "{}", stderr(&o));
    let o = linc_within(20, &["run", SRC, "--db", s(&big)]);
    assert_refused(&o, "E0900");
}

#[test]
fn fifty_megabytes_of_source_are_accepted() {
    let dir = scratch("in-50mb");
    let path = dir.join("wide.st");
    let mut text = String::with_capacity(50_000_100);
    text.push_str("Counters.N0 := 1;\n");
    let line = format!("{}\n", " ".repeat(99));
    while text.len() < 50_000_000 {
        text.push_str(&line);
    }
    fs::write(&path, &text).expect("write");
    let o = linc(&["check", s(&path), "--db", DB]);
    assert_eq!(status(&o), (Some(0), String::new()));
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn disasm_does_not_hang_on_a_source_that_became_a_fifo() {
    let dir = scratch("disasm-fifo");
    let src = dir.join("a.st");
    fs::write(&src, "Counters.N0 := 1;\n").expect("source");
    let sto = dir.join("a.sto");
    assert_eq!(linc(&["compile", s(&src), "--db", DB, "-o", s(&sto)]).status.code(), Some(0));
    fs::remove_file(&src).expect("remove");
    mkfifo(&src);
    let o = linc_within(20, &["disasm", s(&sto)]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(String::from_utf8_lossy(&o.stdout).contains("action a"));
}

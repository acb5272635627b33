//! The command line against hostile or mistaken file names and option values:
//! output files that are links, devices or inputs, inputs that never end,
//! option values out of range (impossible dates, a zero period) and a
//! `--block` of the wrong type.
#![cfg(unix)]
mod common;

use common::stderr;
use std::fs;
use std::io::Read;
use std::os::unix::fs::{FileTypeExt, MetadataExt, PermissionsExt};
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

/// The exit status and standard error, for one assertion with context.
fn status(o: &Output) -> (Option<i32>, String) {
    (o.status.code(), stderr(o) + &String::from_utf8_lossy(&o.stdout))
}

/// A fresh, empty directory for one test.
fn scratch(name: &str) -> PathBuf {
    linc_test_support::fresh_dir(&format!("hardening-{name}"))
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

// ---- output files ----

#[test]
fn output_symlink_is_refused_and_left_alone() {
    let dir = scratch("out-symlink");
    let victim = dir.join("victim.txt");
    fs::write(&victim, "precious").expect("victim");
    let link = dir.join("out.sto");
    std::os::unix::fs::symlink(&victim, &link).expect("symlink");
    let o = linc(&["compile", SRC, "--db", DB, "-o", s(&link)]);
    assert_refused(&o, "E0901");
    assert!(stderr(&o).contains("symbolic link"), "{}", stderr(&o));
    let json = dir.join("out.json");
    std::os::unix::fs::symlink(&victim, &json).expect("symlink");
    assert_refused(&linc(&["run", SRC, "--db", DB, "--out", s(&json)]), "E0901");
    for l in [&link, &json] {
        assert!(fs::symlink_metadata(l).expect("link").file_type().is_symlink(), "{} replaced", l.display());
        assert_eq!(fs::read_link(l).expect("read link"), victim);
    }
    assert_eq!(fs::read_to_string(&victim).expect("victim"), "precious");
}

#[test]
fn output_fifo_device_or_directory_is_refused() {
    let dir = scratch("out-special");
    let fifo = dir.join("pipe.sto");
    mkfifo(&fifo);
    let o = linc_within(20, &["compile", SRC, "--db", DB, "-o", s(&fifo)]);
    assert_refused(&o, "E0901");
    assert!(stderr(&o).contains("FIFO"), "{}", stderr(&o));
    assert!(fs::symlink_metadata(&fifo).expect("fifo").file_type().is_fifo(), "the FIFO was replaced");
    assert_refused(&linc_within(20, &["run", SRC, "--db", DB, "--out", s(&fifo)]), "E0901");
    assert!(fs::symlink_metadata(&fifo).expect("fifo").file_type().is_fifo(), "the FIFO was replaced");

    let sub = dir.join("sub");
    fs::create_dir(&sub).expect("dir");
    assert_refused(&linc(&["compile", SRC, "--db", DB, "-o", s(&sub)]), "E0901");
    assert!(sub.is_dir());

    // A character device: a private copy of /dev/null when we may create
    // one (root), otherwise /dev/null itself (which a non-root user can't
    // replace, so the old behaviour could not harm it either).
    let dev = dir.join("null");
    let made = Command::new("mknod").arg(&dev).args(["c", "1", "3"]).status().is_ok_and(|st| st.success());
    let dev = if made {
        dev
    } else if fs::metadata(&dir).expect("dir").uid() != 0 {
        PathBuf::from("/dev/null")
    } else {
        eprintln!("skipping the device case: can't create a device node");
        return;
    };
    let o = linc(&["compile", SRC, "--db", DB, "-o", s(&dev)]);
    assert_refused(&o, "E0901");
    assert!(stderr(&o).contains("character device"), "{}", stderr(&o));
    assert!(fs::symlink_metadata(&dev).expect("device").file_type().is_char_device(), "the device was replaced");
}

#[test]
fn rewritten_output_keeps_its_permissions() {
    let dir = scratch("out-mode");
    let sto = dir.join("a.sto");
    fs::write(&sto, "old").expect("old object");
    fs::set_permissions(&sto, fs::Permissions::from_mode(0o640)).expect("chmod");
    let o = linc(&["compile", SRC, "--db", DB, "-o", s(&sto)]);
    assert_eq!(status(&o).0, Some(0), "{}", status(&o).1);
    assert_eq!(fs::metadata(&sto).expect("object").permissions().mode() & 0o7777, 0o640);
    assert_ne!(fs::read(&sto).expect("object"), b"old", "rewritten");

    let json = dir.join("a.json");
    fs::write(&json, "{}").expect("old db");
    fs::set_permissions(&json, fs::Permissions::from_mode(0o600)).expect("chmod");
    let o = linc(&["run", SRC, "--db", DB, "--out", s(&json)]);
    assert_eq!(status(&o).0, Some(0), "{}", status(&o).1);
    assert_eq!(fs::metadata(&json).expect("db").permissions().mode() & 0o7777, 0o600);

    // A new file gets the usual mode (0666 less the umask), like any file
    // this process creates, not the private mode of a temporary file.
    let fresh = dir.join("fresh.sto");
    let o = linc(&["compile", SRC, "--db", DB, "-o", s(&fresh)]);
    assert_eq!(status(&o).0, Some(0), "{}", status(&o).1);
    let reference = dir.join("reference");
    fs::write(&reference, "").expect("reference");
    let mode = |p: &Path| fs::metadata(p).expect("mode").permissions().mode() & 0o777;
    assert_eq!(mode(&fresh), mode(&reference));
}

/// A symlink planted where a predictable temporary file would go (the old
/// `.NAME.tmp-PID`) must not redirect the write.
#[test]
fn planted_temporary_file_links_are_not_followed() {
    let Some(last) = fs::read_to_string("/proc/sys/kernel/ns_last_pid").ok().and_then(|t| t.trim().parse::<u32>().ok())
    else {
        eprintln!("skipping: no /proc/sys/kernel/ns_last_pid");
        return;
    };
    let dir = scratch("out-planted");
    let victim = dir.join("victim.txt");
    fs::write(&victim, "precious").expect("victim");
    for pid in last + 1..=last + 2000 {
        std::os::unix::fs::symlink(&victim, dir.join(format!(".out.sto.tmp-{pid}"))).expect("plant");
    }
    let out = dir.join("out.sto");
    let o = linc(&["compile", SRC, "--db", DB, "-o", s(&out)]);
    assert_eq!(status(&o).0, Some(0), "{}", status(&o).1);
    assert_eq!(fs::read_to_string(&victim).expect("victim"), "precious");
    assert!(fs::symlink_metadata(&out).expect("out").file_type().is_file());
    assert_eq!(linc(&["disasm", s(&out)]).status.code(), Some(0));
    let left: Vec<String> = fs::read_dir(&dir)
        .expect("list")
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| !n.starts_with(".out.sto.tmp-") && n != "victim.txt" && n != "out.sto")
        .collect();
    assert!(left.is_empty(), "temporary files left behind: {left:?}");
    let _ = fs::remove_dir_all(&dir);
}

#[test]
fn output_that_is_an_input_is_refused() {
    let dir = scratch("out-input");
    let src = dir.join("a.st");
    let text = "Counters.N0 := Counters.N0 + 1;\n";
    fs::write(&src, text).expect("source");
    let other = dir.join("hard.st");
    fs::hard_link(&src, &other).expect("hard link");
    let respelled = format!("{}/../{}/./a.st", s(&dir), dir.file_name().and_then(|n| n.to_str()).expect("name"));
    for out in [s(&src), respelled.as_str(), s(&other)] {
        let o = linc(&["compile", s(&src), "--db", DB, "-o", out]);
        assert_refused(&o, "E0902");
        assert_eq!(fs::read_to_string(&src).expect("source"), text, "-o {out} changed the input");
    }
    let link = dir.join("link.st");
    std::os::unix::fs::symlink(&src, &link).expect("symlink");
    assert_eq!(linc(&["compile", s(&src), "--db", DB, "-o", s(&link)]).status.code(), Some(2));
    assert!(fs::symlink_metadata(&link).expect("link").file_type().is_symlink());
    assert_refused(&linc(&["compile", s(&link), "--db", DB, "-o", s(&src)]), "E0902");
    assert_eq!(fs::read_to_string(&src).expect("source"), text);

    // The database is an input too, for compile and for run.
    let db = dir.join("db.json");
    fs::copy(Path::new(ROOT).join(DB), &db).expect("copy db");
    let before = fs::read(&db).expect("db");
    assert_refused(&linc(&["compile", s(&src), "--db", s(&db), "-o", s(&db)]), "E0902");
    assert_refused(&linc(&["run", s(&src), "--db", s(&db), "--out", s(&db)]), "E0902");
    let sto = dir.join("a.sto");
    assert_eq!(linc(&["compile", s(&src), "--db", DB, "-o", s(&sto)]).status.code(), Some(0));
    let sto_before = fs::read(&sto).expect("object");
    assert_refused(&linc(&["run", s(&sto), "--db", s(&db), "--out", s(&sto)]), "E0902");
    assert_eq!(fs::read(&db).expect("db"), before);
    assert_eq!(fs::read(&sto).expect("object"), sto_before);
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

// ---- option values ----

fn run_with(extra: &[&str]) -> Output {
    let mut args = vec!["run", SRC, "--db", DB];
    args.extend_from_slice(extra);
    linc(&args)
}

#[test]
fn period_must_be_positive_and_finite() {
    for bad in ["0", "-1", "nan", "inf", "-inf", "1e999", "x", "1e-9", "0.0000009"] {
        let o = run_with(&["--period", bad]);
        assert_refused(&o, "E0903");
        assert!(stderr(&o).contains("--period") && stderr(&o).contains("0.000001"), "{bad}: {}", stderr(&o));
    }
    assert_eq!(status(&run_with(&["--period", "0.5"])).0, Some(0));
}

#[test]
fn now_must_be_a_real_date_and_time() {
    for bad in ["2023-02-29T00:00:00", "2024-04-31T00:00:00", "2024-01-01T24:00:00", "2024-1-01T00:00:00", "soon"] {
        for cmd in [&["run", SRC, "--db", DB][..], &["eval", "1"][..]] {
            let mut args = cmd.to_vec();
            args.extend_from_slice(&["--now", bad]);
            let o = linc(&args);
            assert_refused(&o, "E0903");
            assert!(stderr(&o).contains("YYYY-MM-DDTHH:MM:SS"), "{bad}: {}", stderr(&o));
        }
    }
    let o = linc(&["eval", "DATEANDTIMENOW(1)", "--now", "2024-02-29T00:00:00"]);
    assert_eq!(status(&o), (Some(0), "'29/02/2024 00:00:00'\n".to_string()));
}

#[test]
fn cycles_and_watchdog_values_are_checked() {
    let o = run_with(&["--cycles", "-1"]);
    assert_refused(&o, "E0903");
    assert!(stderr(&o).contains("--cycles"), "{}", stderr(&o));
    for bad in ["0", "-1", "many"] {
        let o = run_with(&["--watchdog", bad]);
        assert_refused(&o, "E0903");
        assert!(stderr(&o).contains("--watchdog") && stderr(&o).contains("at least 1"), "{bad}: {}", stderr(&o));
    }
    // Zero cycles: the action is linked and --set/--show/--out work, nothing runs.
    let o = run_with(&["--cycles", "0", "--set", "Block_5.Val1=7", "--show", "Block_5.Val1"]);
    assert_eq!(status(&o).0, Some(0), "{}", status(&o).1);
    assert_eq!(String::from_utf8_lossy(&o.stdout), "Block_5.Val1 = 7.0\n");
}

// ---- --block ----

#[test]
fn block_of_another_type_is_refused() {
    let dir = scratch("block-type");
    let src = dir.join("m.st");
    fs::write(&src, "ACTION m : PID\n    HR := PV + 1;\nEND_ACTION\n").expect("source");
    let o = linc(&["run", s(&src), "--db", DB, "--block", "ANIN_004", "--show", "ANIN_004.HR"]);
    assert_refused(&o, "E0904");
    let err = stderr(&o);
    assert!(err.contains("--block ANIN_004 has type ANIN") && err.contains("block of type PID"), "{err}");
    assert!(o.stdout.is_empty(), "nothing ran");
    let o = linc(&["run", s(&src), "--db", DB, "--block", "pid1", "--show", "pid1.HR"]);
    assert_eq!(status(&o).0, Some(0), "{}", status(&o).1);
}

// ---- codes ----

/// Every E09xx code the command line prints has an explanation page.
#[test]
fn every_cli_code_is_registered() {
    let src = Path::new(ROOT).join("cli/src");
    let mut seen = 0;
    for entry in fs::read_dir(src).expect("cli/src") {
        let text = fs::read_to_string(entry.expect("entry").path()).expect("source");
        for (i, _) in text.match_indices("E09") {
            let code = &text[i..i + 5];
            assert!(linc_compiler::diag::codes::lookup(code).is_some(), "{code} is printed but not registered");
            seen += 1;
        }
    }
    assert!(seen >= 5);
}

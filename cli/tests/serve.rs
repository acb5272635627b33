//! `linc serve` as a process: console lines on standard input, a stop at
//! `--for`, Ctrl-C with the state saved, and an address off loopback
//! refused without a token.
mod common;

use std::io::{BufRead, BufReader, Write};

fn serve(args: &[&str]) -> std::process::Child {
    common::spawn(&[&["serve"], args].concat())
}

#[test]
fn console_lines_run_while_serving_and_the_run_stops_at_for() {
    // Speed 100 for 5 minutes: three seconds in which the lines are run.
    let args = ["examples/sequences/plant.json", "--http", "127.0.0.1:0", "--speed", "100", "--for", "5m"];
    let mut child = serve(&[&args[..], &["--console", "--allow-writes"]].concat());
    let mut stdin = child.stdin.take().expect("stdin");
    stdin.write_all(b"M Plant.N0=0; D Plant.N0\nNOSUCH\n").expect("write");
    drop(stdin);
    let o = child.wait_with_output().expect("output");
    let out = common::stdout(&o);
    assert_eq!(o.status.code(), Some(0), "{out}{}", common::stderr(&o));
    assert!(out.starts_with("serving http://127.0.0.1:"), "{out}");
    assert!(out.contains("(controls on)"), "{out}");
    assert!(out.contains("Plant.N0 = 0\n"), "{out}");
    assert!(out.contains("error[C0001]: unknown command `NOSUCH`"), "{out}");
    let last = out.lines().last().unwrap_or("");
    assert!(
        last.starts_with("stopped at ") && last.contains(" late, ") && last.ends_with(" code blocks compiled"),
        "{out}"
    );
}

#[cfg(unix)]
#[test]
fn ctrl_c_stops_cleanly_and_saves_the_state() {
    let dir = common::temp_dir("serve-state");
    let state = dir.join("plant.state");
    let mut child = serve(&[
        "examples/sequences/plant.json",
        "--http",
        "127.0.0.1:0",
        "--speed",
        "10",
        "--state",
        state.to_str().unwrap(),
    ]);
    let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
    let first = lines.next().expect("a line").expect("text");
    assert!(first.starts_with("serving http://127.0.0.1:") && first.contains("read-only"), "{first}");
    // Ctrl-C is watched from before that line: sent at once, it stops the
    // server cleanly (it does not kill it).
    // SAFETY: signalling our own child by its pid.
    assert_eq!(unsafe { libc::kill(child.id() as libc::pid_t, libc::SIGINT) }, 0);
    let status = common::exited(&mut child);
    assert_eq!(status.code(), Some(0));
    let rest: Vec<String> = lines.map_while(Result::ok).collect();
    assert!(rest.iter().any(|l| l.starts_with("stopped at ")), "{rest:?}");
    let saved = std::fs::read(&state).expect("the state was saved");
    assert!(!saved.is_empty());
    // It starts warm from it next time (and the state file is not an error).
    let mut again = serve(&[
        "examples/sequences/plant.json",
        "--http",
        "127.0.0.1:0",
        "--speed",
        "max",
        "--for",
        "1s",
        "--state",
        state.to_str().unwrap(),
    ]);
    drop(again.stdin.take());
    let o = again.wait_with_output().expect("output");
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
}

#[test]
fn off_loopback_a_token_is_required() {
    let o = common::linc(&["serve", "examples/sequences/plant.json", "--http", "0.0.0.0:0", "--for", "1s"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("error[E0903]") && common::stderr(&o).contains("--token"));
    let o = common::linc(&["serve", "examples/sequences/plant.json", "--speed", "0"]);
    assert_eq!(o.status.code(), Some(2), "{}", common::stderr(&o));
}

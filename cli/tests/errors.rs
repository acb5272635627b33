//! One path for errors: every error of every command is a coded diagnostic
//! from the one reporter, on standard error, in the format asked for —
//! `--message-format json` included, for option errors, unreadable files,
//! refused outputs, runtime faults and clap's own refusals. Option values
//! that would be ignored or mean nothing are refused (E0903), a closed
//! standard output ends `linc` without a panic, and no source outside the
//! renderer writes `error[` by hand.

mod common;

use common::{linc, linc_with_input, stderr, stdout, temp_dir};
use std::path::Path;
use std::process::Output;

const PLANT: &str = "examples/strategy/plant.json";
const SEQ: &str = "examples/sequences/batch.sfc";
const SEQ_DB: &str = "examples/sequences/plant.json";

/// Every line of standard error is one JSON object with a code: errors,
/// and any warning or note (a summary, I0003) with its own. A failing
/// scenario's failures are in the report on standard output; its standard
/// error holds the summary note alone.
fn assert_json_errors(args: &[&str], o: &Output) {
    assert_ne!(o.status.code(), Some(0), "{args:?} should fail");
    let err = stderr(o);
    assert!(!err.trim().is_empty(), "{args:?}: nothing on standard error");
    for line in err.lines() {
        let v: serde_json::Value =
            serde_json::from_str(line).unwrap_or_else(|e| panic!("{args:?}: not JSON ({e}): {line:?}"));
        let code = v["code"].as_str().unwrap_or_default();
        let coded = code.len() == 5 && "ECRWI".contains(&code[..1]) && code[1..].chars().all(|c| c.is_ascii_digit());
        assert!(coded, "{args:?}: no code in {line}");
        let severity = v["severity"].as_str().unwrap_or_default();
        let fits = match &code[..1] {
            "I" => severity == "note",
            "W" => severity == "warning",
            _ => severity == "error",
        };
        assert!(fits, "{args:?}: {severity} with {code}: {line}");
    }
}

/// Each command's error paths: a bad option, a missing file, a database
/// that does not load, a source that does not compile, a runtime fault, a
/// failing scenario (issue 27).
fn every_command_s_error_paths(dir: &Path) -> Vec<Vec<&'static str>> {
    let leak = |p: std::path::PathBuf| -> &'static str { Box::leak(p.to_string_lossy().into_owned().into_boxed_str()) };
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).expect("write");
        leak(p)
    };
    let bad_db = write("bad.json", "{ \"blocks\": { \"A\": { \"type\": \"NOPE\" } } }");
    let missing = leak(dir.join("none.json"));
    let broken_plant = write(
        "broken.json",
        r#"{ "blocks": { "A": { "type": "ACTION", "values": { "FileName": "broken.st", "ActName": "x" } } } }"#,
    );
    std::fs::copy(abs("examples/guide/broken.st"), dir.join("broken.st")).expect("copy");
    let failing =
        write("failing.ltest", &format!("strategy {}\nrun 1s\nexpect after 0s TANK1.Level > 1000.0\n", abs(PLANT)));
    let lcov = write("junk.info", "not lcov\n");
    let cmds = write("cmds.csv", "not,a,list\n");
    let table = write("table.csv", "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n0,,NOPE,,,\n");
    vec![
        vec!["check", "--nope"],
        vec!["check", "examples/guide/shift.st", "--db", bad_db],
        vec!["compile", missing, "-o", leak(dir.join("o.sto"))],
        vec!["compile", "examples/guide/shift.st", "--db", bad_db, "-o", leak(dir.join("o.sto"))],
        vec!["run", missing, "--for", "1s"],
        vec!["run", bad_db, "--for", "1s"],
        vec!["run", broken_plant, "--for", "1s"],
        vec!["run", PLANT, "--for", "1s", "--set", "TANK1.Level=abc"],
        vec!["console", bad_db],
        vec!["console", broken_plant],
        vec!["serve", missing],
        vec!["serve", bad_db],
        vec!["serve", broken_plant],
        vec!["serve", PLANT, "--client-timeout", "soon"],
        vec!["draw", missing],
        vec!["draw", SEQ, "--db", bad_db],
        vec!["draw", SEQ, "--db", SEQ_DB, "--for", "0s"],
        vec!["draw", table],
        vec!["fst", "list", table],
        vec!["fst", "to-st", table, "--db", "examples/fst/plant.json"],
        vec!["fst", "to-sfc", missing, "--db", "examples/fst/plant.json"],
        vec!["ladder", "to-st", "examples/ladder/interlock.ld", "--db", bad_db],
        vec!["sfc", "generalise", SEQ, "--map", missing, "-o", leak(dir.join("g.sfc"))],
        vec!["eval", "1", "--db", bad_db],
        vec!["eval", "NOPE.X + 1", "--db", common::DB],
        vec!["fmt", missing],
        vec!["fmt", write("unparsed.st", "IF THEN\n")],
        vec!["test", failing],
        vec!["test", "--merge-coverage", lcov, "-o", leak(dir.join("sum.info"))],
        vec!["test", failing, "--coverage", "lcov"],
        vec!["roc", "poll", "--host", "127.0.0.1:1", "--commands", cmds],
        vec!["roc", "poll", "--host", "127.0.0.1:1", "--commands", missing, "--timeout", "soon"],
        vec!["disasm", missing],
        vec!["explain", "--nope"],
    ]
}

/// `path` (relative to the repository) made absolute.
fn abs(path: &str) -> String {
    std::fs::canonicalize(Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(path))
        .expect("example")
        .display()
        .to_string()
}

#[test]
fn every_command_reports_its_errors_as_json() {
    let dir = temp_dir("errors-json");
    let fault = dir.join("fault.st");
    std::fs::write(&fault, "Counters.N0 := 1 / Counters.N1;\n").expect("write");
    let junk = dir.join("junk.sto");
    std::fs::write(&junk, "not an object").expect("write");
    let f = fault.to_str().expect("path");
    let j = junk.to_str().expect("path");
    let missing = dir.join("missing.st");
    let m = missing.to_str().expect("path");
    let cases: Vec<Vec<&str>> = vec![
        vec!["check", "examples/guide/broken.st", "--db", common::DB],
        vec!["check", m],
        vec!["check", f, "--db", "examples/guide/broken.st"],
        vec!["compile", "examples/guide/broken.st", "--db", common::DB, "-o", "x.sto"],
        vec!["compile", f, "--db", common::DB, "-o", f],
        vec!["run", f, "--db", common::DB],
        vec!["run", f, "--db", common::DB, "--tier", "compiled"],
        vec!["run", f, "--db", common::DB, "--set", "Counters.N1=abc"],
        vec!["run", f, "--db", common::DB, "--show", "Nope.X"],
        vec!["run", f, "--db", common::DB, "--period", "0"],
        vec!["run", PLANT, "--for", "0s"],
        vec!["run", PLANT, "--for", "1s", "--cycles", "3"],
        vec!["run", SEQ, "--db", SEQ_DB, "--for", "1s", "--force", "Nope=hold"],
        vec!["run", SEQ, "--db", SEQ_DB, "--for", "1s", "--show", "Nope.X"],
        vec!["console", m],
        vec!["eval", "1 / 0"],
        vec!["eval", "1 +"],
        vec!["disasm", j],
        vec!["explain", "E9999"],
        vec!["test", m],
        vec!["fst", "list", m],
        vec!["ladder", "to-st", m],
        vec!["ladder", "show", m],
        vec!["sfc", "map-template", m],
        vec!["sfc", "specialise", SEQ, "--map", m, "-o", "x.sfc"],
        vec!["run", "--no-such-option"],
    ];
    let cases = cases.into_iter().chain(every_command_s_error_paths(&dir));
    for mut args in cases {
        args.extend(["--message-format", "json"]);
        let o = linc(&args);
        assert_json_errors(&args, &o);
    }
    // The format may also come first, as a global option.
    let o = linc(&["--message-format", "json", "run", PLANT, "--for", "garbage"]);
    assert_json_errors(&["--message-format", "json", "run"], &o);
    // A server whose address is in use, for HTTP and each wire protocol.
    let taken = std::net::TcpListener::bind("127.0.0.1:0").expect("a port");
    let addr = taken.local_addr().expect("address").to_string();
    let port = addr.rsplit(':').next().expect("port").to_string();
    for args in [
        vec!["serve", PLANT, "--http", &addr],
        vec!["serve", "examples/roc/plant.json", "--http", "127.0.0.1:0", "--roc", &port],
        vec!["serve", "examples/roc/plant.json", "--http", "127.0.0.1:0", "--modbus", &port],
    ] {
        let args = [&args[..], &["--message-format", "json", "--for", "1s"]].concat();
        assert_json_errors(&args, &linc(&args));
    }
}

/// Exit 2 and E0903 naming `flag`.
fn assert_option_refused(args: &[&str], flag: &str) {
    let o = linc(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    let err = stderr(&o);
    assert!(err.contains("error[E0903]") && err.contains(flag), "{args:?}: {err}");
    assert!(stdout(&o).is_empty(), "{args:?} ran: {}", stdout(&o));
}

#[test]
fn option_values_that_mean_nothing_are_refused() {
    for d in ["0s", "garbage", "0.0000001s", "-5s"] {
        assert_option_refused(&["run", PLANT, "--for", d], "--for");
    }
    assert_option_refused(&["run", PLANT, "--for", "1s", "--show", "NOPE.X"], "--show");
    assert_option_refused(&["run", PLANT, "--for", "1s", "--set", "X=abc"], "--set");
    assert_option_refused(&["run", PLANT, "--for", "1s", "--set", "TANK1.Level=abc"], "--set");
    assert_option_refused(&["run", PLANT, "--for", "1s", "--cold"], "--cold");
    // Each command's duration names its own option.
    let poll = ["roc", "poll", "--host", "127.0.0.1:1", "--commands", "nope.csv", "--timeout"];
    assert_option_refused(&[&poll[..], &["soon"]].concat(), "--timeout `soon`");
    assert_option_refused(&[&poll[..], &["0s"]].concat(), "--timeout `0s`");
    assert_option_refused(&["serve", PLANT, "--client-timeout", "0s"], "--client-timeout `0s`");
    // An empty token (an unset variable) is no secret; a host is a name.
    assert_option_refused(&["serve", PLANT, "--for", "1s", "--token", ""], "--token");
    assert_option_refused(&["serve", PLANT, "--for", "1s", "--token", "  "], "--token");
    assert_option_refused(&["serve", PLANT, "--for", "1s", "--allow-host", "evil.example:80"], "--allow-host");
    // Options of another form of `run` are refused, not ignored.
    assert_option_refused(&["run", PLANT, "--for", "1s", "--cycles", "3"], "--cycles");
    assert_option_refused(&["run", PLANT, "--for", "1s", "--action", "Fill"], "--action");
    assert_option_refused(&["run", PLANT, "--for", "1s", "--period", "1"], "--period");
    assert_option_refused(&["run", PLANT, "--for", "1s", "--hold-step", "Fill"], "--hold-step");
    assert_option_refused(&["run", SEQ, "--db", SEQ_DB, "--for", "1s", "--cycles", "2"], "--cycles");
    // A step that the sequence does not have prints no empty value.
    assert_option_refused(&["run", SEQ, "--db", SEQ_DB, "--for", "1s", "--show", "Nope.X"], "--show Nope.X");
    let o = linc(&["run", SEQ, "--db", SEQ_DB, "--for", "1s", "--show", "Idle.X"]);
    assert_eq!((o.status.code(), stdout(&o)), (Some(0), "Idle.X = TRUE\n".to_string()), "{}", stderr(&o));
}

#[test]
fn values_a_field_cannot_hold_are_refused_as_the_loader_refuses_them() {
    // --set: E0903, nothing runs.
    for set in ["SYS.ErrNum=5", "TANK1.HighCnt=2147483648", "TANK1.Valve=2"] {
        assert_option_refused(&["run", PLANT, "--for", "1s", "--set", set], "--set");
    }
    // The console's M: C0004 / C0005, the field unchanged.
    let dir = temp_dir("errors-field-values");
    let db = dir.join("db.json");
    let template =
        r#"{"templates": {"T": {"fields": {"S": "STRING", "N": "INT", "B": "BITS8"}}}, "blocks": {"X": {"type": "T""#;
    std::fs::write(&db, format!("{template}}}}}}}")).expect("write");
    let script = "M X.N=99999999999\nM X.B=256\nD X.N\nD X.B\n";
    let o = linc_with_input(&["console", db.to_str().expect("path")], script);
    let out = stdout(&o);
    assert!(out.contains("error[C0004]: 99999999999 does not fit a INT field"), "{out}");
    assert!(out.contains("error[C0004]: 256 does not fit a BITS8 field"), "{out}");
    assert!(out.ends_with("X.N = 0\nX.B = 0\n"), "{out}");
    // A string longer than the VM's: refused by --set (console lines are
    // shorter than that anyway).
    let long = format!("X.S='{}'", "a".repeat(70_000));
    let o = linc(&["run", db.to_str().expect("path"), "--for", "1s", "--set", &long]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("the text is 70000 bytes long"), "{}", &stderr(&o)[..300.min(stderr(&o).len())]);
    let o = linc_with_input(&["console", PLANT], "M SYS.ErrNum=5\nD SYS.ErrNum\n");
    assert!(stdout(&o).contains("error[C0005]: SYS.ErrNum is read-only"), "{}", stdout(&o));
    // The database loader says the same of a string too long.
    let text = format!(r#"{template}, "values": {{"S": "{}"}}}}}}}}"#, "a".repeat(70_000));
    std::fs::write(&db, text).expect("write");
    let o = linc(&["check", "examples/guide/shift.st", "--db", db.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("a string field holds at most 65535"), "{}", &stderr(&o)[..300.min(stderr(&o).len())]);
}

#[test]
fn a_closed_standard_output_ends_linc_without_a_panic() {
    use std::io::Read;
    use std::process::{Command, Stdio};
    for args in [vec!["explain", "--list"], vec!["run", PLANT, "--for", "10s", "--trace", "-"]] {
        let mut child = Command::new(env!("CARGO_BIN_EXE_linc"))
            .args(&args)
            .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run linc");
        let mut first = [0u8; 1];
        child.stdout.take().expect("stdout").read_exact(&mut first).expect("one byte");
        // The reading end is closed here, as `| head -c1` closes it.
        let o = child.wait_with_output().expect("wait");
        assert_ne!(o.status.code(), Some(101), "{args:?} panicked: {}", stderr(&o));
        assert!(!stderr(&o).contains("panicked"), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn console_lines_are_bounded() {
    // A line without an end is not kept whole: it is refused (C0002) once
    // it passes the limit, and the lines after it still run.
    let long = "D ".to_string() + &"X".repeat(1 << 20);
    let o = linc_with_input(&["console", PLANT], &format!("{long}\nD TANK1.HighCnt\n"));
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    assert!(out.contains("error[C0002]: a console line is at most 4096 bytes"), "{}", &out[..out.len().min(400)]);
    assert!(out.contains("TANK1.HighCnt = 0"), "{out}");
    assert!(out.len() < 1000, "the long line was echoed: {} bytes", out.len());
}

#[test]
fn byte_order_marks_are_ignored_in_databases_and_scenarios() {
    let dir = temp_dir("errors-bom");
    for f in ["plant.json", "actions.stx", "modbus.stx", "plant.ltest"] {
        let text = std::fs::read(Path::new("..").join("examples/strategy").join(f)).expect("example");
        let mut with_bom = b"\xEF\xBB\xBF".to_vec();
        with_bom.extend(text);
        std::fs::write(dir.join(f), with_bom).expect("write");
    }
    let db = dir.join("plant.json");
    let o = linc(&["run", db.to_str().expect("path"), "--for", "10s", "--show", "TANK1.HighCnt"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = linc(&["test", dir.join("plant.ltest").to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(0), "{}{}", stdout(&o), stderr(&o));
    // A database error after the mark is still located where it is.
    std::fs::write(&db, b"\xEF\xBB\xBF{ \"blocks\": { \"B1\": { \"type\": \"NOPE\" } } }").expect("write");
    let o = linc(&["run", db.to_str().expect("path"), "--for", "1s", "--message-format", "short"]);
    assert!(stderr(&o).contains("plant.json:1:31: error[E0803]"), "{}", stderr(&o));
}

#[test]
fn scenario_problems_are_located_and_coded() {
    let dir = temp_dir("errors-scenario");
    let bad = dir.join("latin1.ltest");
    std::fs::write(&bad, b"strategy plant.json\nrun 1s (* caf\xE9 *)\n").expect("write");
    let o = linc(&["test", bad.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains("latin1.ltest:2:14: error[E0017]"), "{}", stdout(&o));
    let o = linc(&["test", dir.join("nothing.ltest").to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("error[E0903]"), "{}", stderr(&o));
    // A scenario whose strategy is missing: E0900, at the database's name.
    std::fs::write(dir.join("gone.ltest"), "strategy gone.json\nrun 1s\n").expect("write");
    let o = linc(&["test", dir.join("gone.ltest").to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stdout(&o).contains("gone.json:1:1: error[E0900]: can't read"), "{}", stdout(&o));
    assert_eq!(stdout(&o).matches("error[").count(), 1, "{}", stdout(&o));
}

#[test]
fn no_source_writes_an_error_by_hand() {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let mut files = Vec::new();
    for krate in ["cli/src", "driver/src", "compiler/src", "format/src", "runtime/src", "engines/src", "stdlib/src"] {
        common::rust_sources(&root.join(krate), &mut files);
    }
    let hand: Vec<String> = files
        .iter()
        .filter(|p| !p.ends_with("compiler/src/diag/render.rs"))
        .flat_map(|p| {
            let text = std::fs::read_to_string(p).expect("read");
            // Unit tests may say what the renderer prints.
            let code = text.split("#[cfg(test)]").next().unwrap_or_default().to_string();
            code.lines()
                .enumerate()
                .filter(|(_, l)| l.contains("\"error[") || l.contains("error[{"))
                .map(|(i, l)| format!("{}:{}: {}", p.display(), i + 1, l.trim()))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(hand.is_empty(), "errors written by hand:\n{}", hand.join("\n"));
}

#[test]
fn no_output_sends_an_escape_sequence_to_the_terminal() {
    let dir = temp_dir("errors-escapes");
    let esc = "\u{1b}[2J";
    // A block name with an escape sequence (JSON allows it as \u001b).
    let db = dir.join("db.json");
    std::fs::write(&db, r#"{"blocks": {"A\u001b[2JB": {"type": "RECIPE", "values": {"A0": 1.5}}}}"#).expect("db");
    let db = db.to_str().expect("path");
    let field = format!("A{esc}B.A0");
    let table = dir.join("t.csv");
    std::fs::write(&table, format!("STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n0,,END,,,clear {esc} screen\n"))
        .expect("table");
    let named = dir.join(format!("x{esc}y.st"));
    std::fs::write(&named, "Counters.N0 := 1;\n").expect("source");
    let object = dir.join("x.sto");
    let o = linc(&["compile", named.to_str().expect("path"), "--db", common::DB, "-o", object.to_str().expect("path")]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let runs: Vec<(Vec<&str>, Option<String>)> = vec![
        (vec!["run", db, "--for", "1s", "--show", &field], None),
        (vec!["console", db], Some(format!("D {field}\nD A{esc}B.A0-\n"))),
        (vec!["eval", "'$1B[2Jx'"], None),
        (vec!["fst", "list", table.to_str().expect("path")], None),
        (vec!["disasm", object.to_str().expect("path")], None),
        (vec!["explain", esc], None),
    ];
    for (args, input) in runs {
        let o = match &input {
            Some(text) => linc_with_input(&args, text),
            None => linc(&args),
        };
        let (out, err) = (stdout(&o), stderr(&o));
        assert!(!out.contains('\u{1b}') && !err.contains('\u{1b}'), "{args:?} printed a raw escape: {out}{err}");
        let shown = out.contains("\\u{1b}") || err.contains("\\u{1b}") || out.contains("$1B");
        assert!(shown, "{args:?} dropped the text: {out}{err}");
    }
}

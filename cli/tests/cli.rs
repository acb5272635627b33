//! The `linc` command line: exit statuses, output formats, explain.
mod common;

use common::{linc, stderr, stdout};

const DB: &str = "examples/guide/plant.db.json";

/// Writes `text` to a fresh temporary file named `name` and returns its path.
fn temp_file(name: &str, text: &str) -> String {
    common::temp_file(&format!("cli-{name}"), name, text)
}

#[test]
fn clean_files_exit_zero_and_print_nothing() {
    let o = linc(&["check", "examples/guide/control.stx", "examples/guide/shift.st", "--db", DB]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    assert_eq!(stdout(&o), "");
}

#[test]
fn errors_exit_one_with_short_locations() {
    let o = linc(&["check", "examples/guide/broken.st", "--db", DB, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr(&o),
        "examples/guide/broken.st:2:24: error[E0010]: unexpected `;`\n\
         examples/guide/broken.st:3:17: error[E0104]: `AUTOMATIC` is not a value of `PIC_004.Mode`\n\
         examples/guide/broken.st:5:28: error[E0007]: `ANDB` is a name, not the operator AND\n"
    );
}

#[test]
fn human_format_renders_snippets_and_help() {
    let o = linc(&["check", "examples/guide/broken.st", "--db", DB]);
    assert_eq!(o.status.code(), Some(1));
    insta::assert_snapshot!(stderr(&o));
    assert!(String::from_utf8_lossy(&o.stderr).contains("3 errors, 0 warnings"));
}

#[test]
fn json_format_is_one_object_per_line() {
    let o = linc(&["check", "examples/guide/broken.st", "--db", DB, "--message-format", "json"]);
    assert_eq!(o.status.code(), Some(1));
    let lines: Vec<serde_json::Value> =
        stderr(&o).lines().map(|l| serde_json::from_str(l).expect("each line is JSON")).collect();
    assert_eq!(lines.len(), 3);
    assert_eq!(lines[1]["code"], "E0104");
    assert_eq!(lines[1]["line"], 3);
    assert_eq!(lines[1]["column"], 17);
    assert_eq!(lines[1]["file"], "examples/guide/broken.st");
    assert_eq!(lines[1]["severity"], "error");
    assert!(lines[1]["help"][0].as_str().unwrap_or_default().contains("MANUAL"));
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
    let db = temp_file("bad.json", "{ \"blocks\": { \"B1\": { \"type\": \"NOPE\" } } }");
    let o = linc(&["check", "examples/guide/shift.st", "--db", &db, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("bad.json:1:31: error[E0803]: block `B1` has unknown type `NOPE`"), "{}", stderr(&o));
}

#[test]
fn usage_errors_exit_two() {
    assert_eq!(linc(&["check"]).status.code(), Some(2));
    assert_eq!(linc(&["check", "x.st", "--message-format", "xml"]).status.code(), Some(2));
    assert_eq!(linc(&["frobnicate"]).status.code(), Some(2));
}

#[test]
fn tree_prints_the_grouping() {
    let f = temp_file("prec.st", "Recipe.N0 := 10 - 2 - 3;\n");
    let o = linc(&["check", &f, "--db", DB, "--tree"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(stdout(&o), "(action prec\n  (:= Recipe.N0 (- (- 10 2) 3))\n)\n");
}

#[test]
fn transitions_are_checked_in_sequence_context() {
    let path = &temp_file("t1.stt", "Dig_B.Out.Bit5 AND (Rec.A0<4 OR Rec.A0>5) OR step6.T>=T#4s");
    assert_eq!(linc(&["check", path, "--db", DB, "--transition"]).status.code(), Some(0));
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

fn eval(expr: &str) -> (Option<i32>, String, String) {
    let o = linc(&["eval", expr, "--now", "2024-02-29T13:45:07", "--seed", "42"]);
    (o.status.code(), stdout(&o), String::from_utf8_lossy(&o.stderr).into_owned())
}

#[test]
fn eval_prints_values_in_st_form() {
    let cases = [
        ("10 - 2 - 3", "5"),
        ("7 / 2", "3"),
        ("7 / 2.0", "3.5"),
        ("2 ** 10", "1024.0"),
        ("1000 / 3.0", "333.33334"),
        ("T#1h", "3600.0"),
        ("16#FF AND 16#0F", "15"),
        ("1 < 2", "TRUE"),
        ("NOT TRUE", "FALSE"),
        ("'abc' = 'ABC'", "TRUE"),
        ("'it$'s'", "'it$'s'"),
        ("CONCAT('a$0D', 'b')", "'a$0Db'"),
        ("CRC('123456789', 1, 16#8005, 16#FFFF)", "19255"),
        ("DATEANDTIMENOW(1)", "'29/02/2024 13:45:07'"),
        ("-2147483648", "-2147483648"),
        ("99999999999", "2147483647"),
    ];
    for (expr, want) in cases {
        let (code, out, err) = eval(expr);
        assert_eq!((code, out.trim_end()), (Some(0), want), "{expr}: {err}");
    }
}

/// R0005's message gives the reason: the operand rule of `**` that was
/// broken, an argument outside a function's domain, or an overflow.
#[test]
fn eval_says_why_a_power_or_a_function_failed() {
    let overflow = "overflows: the result is beyond the largest REAL (3.4028235E38)";
    for (expr, why) in [
        ("2.0**1000.0", format!("2 ** 1000 {overflow}")),
        ("10.0 ** 39", format!("10 ** 39 {overflow}")),
        ("(-2.0)**2.0", "(-2) ** 2 is undefined: A must exceed zero".to_string()),
        ("0.0**0.0", "0 ** 0 is undefined: 0 may only be raised to a power above zero".to_string()),
        ("EXP(100.0)", format!("EXP(100) {overflow}")),
        ("SQRT(-1.0)", "SQRT(-1) is undefined: the argument must not be negative".to_string()),
        ("LN(0.0)", "LN(0) is undefined: the argument must exceed zero".to_string()),
        ("ACOS(2.0)", "ACOS(2) is undefined: the argument must lie between -1 and 1".to_string()),
    ] {
        let (code, _, err) = eval(expr);
        assert_eq!(code, Some(1), "{expr}: {err}");
        assert!(err.contains(&format!("error[R0005]: in `eval`: {why}")), "{expr}: {err}");
    }
    let (code, out, err) = eval("2.0 ** -1000.0");
    assert_eq!((code, out.trim_end()), (Some(0), "0.0"), "an underflow is 0: {err}");
}

#[test]
fn eval_reads_the_database_and_reports_errors() {
    let o = linc(&["eval", "REC1.A0 * 2", "--db", DB]);
    assert_eq!((o.status.code(), stdout(&o)), (Some(0), "25.0\n".to_string()));
    let (code, _, err) = eval("1 / (2 - 2 + 0 * 1)");
    assert_eq!(code, Some(1), "{err}");
    assert!(err.contains("R0001"), "{err}");
    let (code, _, err) = eval("SQRT('x')");
    assert_eq!(code, Some(2));
    assert!(err.contains("E0112"), "{err}");
    let (a, b) = (eval("RANDOM(100)").1, eval("RANDOM(100)").1);
    assert_eq!(a, b, "--seed makes RANDOM repeatable");
}

#[test]
fn run_sets_shows_and_traces() {
    let o = linc(&[
        "run",
        "examples/guide/shift.st",
        "--db",
        DB,
        "--set",
        "Block_5.PV=42.5",
        "--show",
        "Block_5.Val8",
        "--show",
        "Block_5.Val1",
        "--trace",
    ]);
    assert_eq!(o.status.code(), Some(0));
    let out = stdout(&o);
    assert!(out.starts_with("cycle 1: Counters.N0 = 0\ncycle 1: Block_5.Val1 = 2.0\n"), "{out}");
    assert!(out.ends_with("Block_5.Val8 = 42.5\nBlock_5.Val1 = 2.0\n"), "{out}");
}

#[test]
fn run_cycles_repeat_the_action() {
    let f = temp_file("count.st", "Counters.N0 := Counters.N0 + 1;\n");
    let o = linc(&["run", &f, "--db", DB, "--cycles", "5", "--show", "Counters.N0"]);
    assert_eq!((o.status.code(), stdout(&o)), (Some(0), "Counters.N0 = 5\n".to_string()));
}

#[test]
fn runtime_error_keeps_earlier_writes_in_out() {
    let f = temp_file("fault.st", "Counters.N0 := 5;\nCounters.N1 := 1 / Counters.N3;\nCounters.N2 := 7;\n");
    let out = temp_file("fault.json", "");
    let o = linc(&["run", &f, "--db", DB, "--out", &out]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("error[R0001]: in `fault`: division by zero") && err.contains("fault.st:2:1"), "{err}");
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&out).expect("out written")).expect("json");
    assert_eq!(v["blocks"]["Counters"]["values"]["N0"], 5);
    assert_eq!(v["blocks"]["Counters"]["values"]["N2"], 0);
    assert_eq!(v["blocks"]["Counters"]["type"], "RECIPE");
    assert!(v["templates"]["VALBLK"].is_object() && v["aliases"]["avg"] == "RECORD.A7");
}

#[test]
fn watchdog_names_the_loop_line() {
    let f = temp_file("loop.st", "Counters.N0 := 0;\nWHILE 1 DO\n  Counters.N0 := Counters.N0 + 1;\nEND_WHILE;\n");
    let o = linc(&["run", &f, "--db", DB, "--watchdog", "1000"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("error[R0006]") && err.contains("loop.st:2:1") && err.contains("line 2"), "{err}");
}

#[test]
fn compile_disasm_and_run_an_object() {
    let sto = temp_file("control.sto", "");
    let o = linc(&["compile", "examples/guide/control.stx", "-o", &sto, "--db", DB]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
    let listing = stdout(&linc(&["disasm", &sto]));
    assert!(listing.contains("action Startup") && listing.contains("StoreS       PIC_004.Mode"), "{listing}");
    assert!(listing.contains("; 4:5  PIC_004.Mode := \"CASCADE\";"), "{listing}");
    let o = linc(&["run", &sto, "--db", DB, "--action", "startup", "--show", "PIC_004.Mode", "--show", "TIC_100.SL"]);
    assert_eq!(stdout(&o), "PIC_004.Mode = 'CASCADE'\nTIC_100.SL = 55.0\n");
    let o = linc(&[
        "run",
        &sto,
        "--db",
        DB,
        "--action",
        "Modbus",
        "--block",
        "Raw1",
        "--set",
        "Raw1.I1=1",
        "--show",
        "Raw1.I2",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn run_usage_and_compile_errors_exit_two() {
    assert_eq!(linc(&["run", "examples/guide/broken.st", "--db", DB]).status.code(), Some(2));
    assert_eq!(linc(&["run", "examples/guide/shift.st", "--db", DB, "--action", "nope"]).status.code(), Some(2));
    assert_eq!(linc(&["run", "examples/guide/shift.st", "--db", DB, "--set", "Block_5.PV=abc"]).status.code(), Some(2));
    assert_eq!(linc(&["run", "examples/guide/shift.st", "--db", DB, "--now", "soon"]).status.code(), Some(2));
    let bad = temp_file("bad.sto", "LINCSTO but not really");
    let o = linc(&["run", &bad, "--db", DB]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("E0700"));
}

#[test]
fn eval_calls_every_category_of_the_library() {
    let cases = [
        // Convert
        ("ABS(-3)", "3"),
        ("ROUND(2.5) + ROUND(-2.5)", "0"),
        ("TRUNC(-2.7)", "-2"),
        ("FLOAT(7) / 2", "3.5"),
        ("FORMAT('05I', -123)", "'-0123'"),
        ("FORMAT('6.F', 1000/3.0)", "'  333.'"),
        ("FORMAT('3I!', 7412)", "'!!!'"),
        ("FORMAT('10.2E', 1000/3.0)", "'  3.33E+02'"),
        ("SCAN('3I', '-4789')", "-47"),
        ("SCAN('X', MID('[M01G0DI*01C5E5$R', 4, 10))", "453"),
        ("SCAN('G', ' -1.456E-2')", "-0.01456"),
        ("IS_VALID('U', ' -4789')", "FALSE"),
        // Numeric and random
        ("SQRT(16)", "4.0"),
        ("DEG(ATAN2(1, 1))", "45.0"),
        ("RANDOM(10) < 10", "TRUE"),
        // Selector
        ("AVG(1, 2, 3, 4)", "2.5"),
        ("MAX(1, 7.5, 3)", "7.5"),
        ("MIN(4, 2, 9)", "2"),
        ("SWITCH(10, 20, 0)", "10"),
        // String basics
        ("MID('ABCDEFG', 3, 2)", "'BCD'"),
        ("FIND('ABACABA', 'AB', 2)", "5"),
        ("FIND('AAAAA', '', -1)", "6"),
        ("DELIMIT('a::bb::ccc::dddd', '::', -2)", "'ccc'"),
        ("JUSTIFY_CENTRE('ab', 5)", "' ab  '"),
        ("PURGE('abcdabcde', 'bd')", "'acace'"),
        ("LEFT('abc', 4)", "''"),
        ("STRCOMP('aa', 'aaa')", "-1"),
        ("EQUAL('abc', 'ABC')", "FALSE"),
        // Date and time (the clock is fixed by --now)
        ("DATEANDTIMENOW(0)", "'29/02/2024 13:45:07'"),
        // Extract and replace
        ("EXTRACT_INT16('$12$34', 1, 1)", "4660"),
        ("EXTRACT_UINT16(REPLACE_INT16('$00$00', 1, -2, 0), 1, 0)", "65534"),
        ("EXTRACT_REAL(REPLACE_REAL('$00$00$00$00', 1, 2.5, 3), 1, 3)", "2.5"),
        ("EXTRACT_BOOL('$80', 1, 7)", "TRUE"),
        // Bit
        ("SHL8(255, 1)", "254"),
        ("ROR16(1, 1)", "32768"),
        ("ROL32(16#40000000, 2)", "1"),
        ("BIT_INVERT(0)", "-1"),
        // Checksum
        ("CRC('123456789', 0, 16#1021, 16#FFFF)", "10673"),
        ("BCC('123456789', 0, 0)", "49"),
        ("BCC('123456789', 2, 0)", "477"),
    ];
    for (expr, want) in cases {
        let (code, out, err) = eval(expr);
        assert_eq!((code, out.trim_end()), (Some(0), want), "{expr}: {err}");
    }
}

#[test]
fn wrong_calls_name_the_expected_signature() {
    let (code, _, err) = eval("MID('abc', 1)");
    assert_eq!(code, Some(2));
    assert!(err.contains("error[E0111]") && err.contains("expected MID(BSEQ, INT, INT) : BSEQ"), "{err}");
    let (code, _, err) = eval("CRC(12, 1, 2, 3)");
    assert_eq!(code, Some(2));
    assert!(
        err.contains("error[E0112]") && err.contains("argument 1 should be a string") && err.contains("<expr>:1:5"),
        "{err}"
    );
}

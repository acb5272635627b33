//! `linc check` and `linc compile` over one compile session: they reject the
//! same inputs, deep or long code never crashes them, and source text never
//! reaches the terminal raw.

mod common;
use common::{linc, stderr, DB};

/// Writes `bytes` to `dir/name` in a fresh temporary directory of this test
/// run and returns its path.
fn temp(dir: &str, name: &str, bytes: &[u8]) -> String {
    common::temp_file(&format!("session-{dir}"), name, bytes)
}

/// Runs `check` and `compile` on the same files and database; returns the
/// two (status, short output) pairs.
fn check_and_compile(files: &[String]) -> ((Option<i32>, String), (Option<i32>, String)) {
    let mut check = vec!["check", "--db", DB, "--message-format", "short"];
    check.extend(files.iter().map(String::as_str));
    let out = temp("out", "out.sto", b"");
    let mut compile = vec!["compile", "--db", DB, "--message-format", "short", "-o", &out];
    compile.extend(files.iter().map(String::as_str));
    let (c, k) = (linc(&check), linc(&compile));
    ((c.status.code(), stderr(&c)), (k.status.code(), stderr(&k)))
}

#[test]
fn two_files_with_the_same_stem_fail_check_as_they_fail_compile() {
    let a = temp("one", "fill.st", b"Recipe.N0 := 1;\n");
    let b = temp("two", "fill.st", b"Recipe.N0 := 2;\n");
    let (check, compile) = check_and_compile(&[a, b.clone()]);
    let expected = format!("{b}:1:1: error[E0117]: action `fill` is defined twice\n");
    assert_eq!(check, (Some(1), expected.clone()));
    assert_eq!(compile, (Some(1), expected));
}

#[test]
fn limits_fail_check_as_they_fail_compile() {
    let args: Vec<String> = (1..=17).map(|i| i.to_string()).collect();
    let call = temp("limits", "call.st", format!("Recipe.A0 := MAX({});\n", args.join(", ")).as_bytes());
    let loops = temp("limits", "loops.st", "FOR Counters.N0 := 1 TO 2 DO END_FOR;\n".repeat(255).as_bytes());
    for f in [call, loops] {
        let (check, compile) = check_and_compile(std::slice::from_ref(&f));
        assert_eq!(check.0, Some(1), "{}", check.1);
        assert!(check.1.contains("error[E0132]"), "{}", check.1);
        assert_eq!(check, compile);
    }
}

/// Every command on `file` exits with status 1 and reports `code` once.
fn fails_cleanly(file: &str, code: &str) {
    let out = temp("deep", "out.sto", b"");
    for args in [vec!["check"], vec!["check", "--tree"], vec!["compile", "-o", &out]] {
        let mut full = args.clone();
        full.extend([file, "--db", DB, "--message-format", "short"]);
        let o = linc(&full);
        let text = stderr(&o);
        assert_eq!(o.status.code(), Some(1), "{args:?}: {text}");
        assert_eq!(text.matches("error[").count(), 1, "{args:?}: {}", &text[text.len().saturating_sub(500)..]);
        assert!(text.contains(&format!("error[{code}]")), "{args:?}");
    }
}

#[test]
fn deep_nesting_is_a_located_error_in_every_command() {
    let ifs = "IF Dig_A.Out.Bit0 THEN\n".repeat(5_000) + "Recipe.A0 := 1;\n" + &"END_IF;\n".repeat(5_000);
    fails_cleanly(&temp("deep", "ifs.st", ifs.as_bytes()), "E0021");
    let offsets = format!("Recipe.A0 := {}0{};\n", "Block_5.Val1{".repeat(6_000), "}".repeat(6_000));
    fails_cleanly(&temp("deep", "offsets.st", offsets.as_bytes()), "E0022");
    let sum = format!("Recipe.A0 := {};\n", vec!["1"; 12_000].join("+"));
    fails_cleanly(&temp("deep", "sum.st", sum.as_bytes()), "E0022");
}

#[test]
fn a_ten_megabyte_line_is_checked_and_compiled() {
    // One line: 10 MB of `NOT NOT ...` and a REAL constant out of range at its end.
    let line = format!("Recipe.N0 := {}1; Recipe.A0 := 1E39;", "NOT ".repeat(10 << 18));
    let f = temp("long", "line.st", line.as_bytes());
    let out = temp("long", "out.sto", b"");
    for args in [vec!["check"], vec!["check", "--tree"], vec!["compile", "-o", &out]] {
        let mut full = args.clone();
        full.extend([f.as_str(), "--db", DB]);
        let o = linc(&full);
        assert_eq!(o.status.code(), Some(1), "{args:?}");
        let text = stderr(&o);
        assert_eq!(text.matches("error[").count(), 2, "{args:?}: {}", &text[..text.len().min(2000)]);
        assert!(text.contains("error[E0022]") && text.contains("error[E0019]"), "{text}");
        assert!(text.len() < 4_000, "long lines are cut around the label: {} bytes", text.len());
    }
}

#[test]
fn escapes_and_bad_bytes_are_shown_escaped() {
    let f = temp("bytes", "esc.st", b"PIC_004.PV := '\x1b[31m'; (* 85 \xB0C \x1b[2J *) \x1b\n");
    for format in ["human", "short", "json"] {
        let o = linc(&["check", &f, "--db", DB, "--message-format", format]);
        assert_eq!(o.status.code(), Some(1));
        assert!(!o.stdout.contains(&0x1b) && !o.stderr.contains(&0x1b), "{format}: {}", stderr(&o));
        if format == "short" {
            let file = f.as_str();
            assert_eq!(
                stderr(&o),
                format!(
                    "{file}:1:15: error[E0103]: can't store a STRING value in a REAL field\n\
                     {file}:1:30: error[E0017]: byte 0xB0 is not UTF-8\n\
                     {file}:1:41: error[E0001]: unexpected character `\\u{{1b}}`\n"
                )
            );
        }
    }
    let o = linc(&["check", &f, "--db", DB, "--tree"]);
    assert!(!o.stdout.contains(&0x1b), "{}", stderr(&o));
}

#[test]
fn a_byte_order_mark_is_accepted() {
    let f = temp("bom", "bom.st", "\u{FEFF}PIC_004.PV := 1;\nPIC_004.PV := 'x';\n".as_bytes());
    let o = linc(&["check", &f, "--db", DB, "--message-format", "short"]);
    assert_eq!(stderr(&o), format!("{f}:2:15: error[E0103]: can't store a STRING value in a REAL field\n"));
}

#[test]
fn an_object_file_is_named_as_such() {
    let out = temp("object", "ok.sto", b"");
    let o = linc(&["compile", "examples/guide/shift.st", "--db", DB, "-o", &out]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = linc(&["check", &out]);
    assert_eq!(o.status.code(), Some(1));
    let text = stderr(&o);
    assert!(text.contains("error[E0018]: `") && text.contains("is a linc object file, not ST source"), "{text}");
    assert!(text.contains(&format!("run `linc disasm {out}`")), "{text}");
}

#[test]
fn junk_gives_few_errors() {
    let at = temp("junk", "at.st", &[b'@'; 2 << 20]);
    let o = linc(&["check", &at, "--message-format", "short"]);
    assert_eq!(stderr(&o), format!("{at}:1:1: error[E0001]: unexpected characters, from `@` on\n"));
    let many = temp("junk", "many.st", "xx := 1; ".repeat(1_500).as_bytes());
    let o = linc(&["check", &many, "--db", DB, "--message-format", "short"]);
    let text = stderr(&o);
    assert_eq!(text.lines().count(), 1_001, "{}", &text[text.len().saturating_sub(300)..]);
    assert!(
        text.ends_with(&format!("{many}:1:9001: error[E0023]: 500 more errors in this file not shown\n")),
        "{text}"
    );
}

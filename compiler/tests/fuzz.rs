//! Robustness: random and mutated inputs (bytes, so not always UTF-8)
//! through lexer, parser, checker, lowering and every renderer must never
//! panic, and `check` must reject exactly what `compile` rejects.
//!
//! Deterministic (a fixed-seed xorshift generator), so a failure reproduces.
//! `cargo test` runs a reduced number of inputs; set `LINC_FUZZ_CASES` for a
//! long run (the figure in the README used 200,000).

use linc_compiler::diag::render::{render, Format, SourceFiles};
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::Database;

use linc_test_support::Rng;

const CORPUS: &[&str] = &[
    include_str!("../../examples/guide/control.stx"),
    include_str!("../../examples/guide/shift.st"),
    include_str!("../../examples/guide/broken.st"),
    "IF PIC_004.PV < 10 THEN Dig_B.Out.Bit0 := 1; ELSIF a THEN b := 2; ELSE Dig_B.Out.Bit1 := 1; END_IF;",
    "FOR PIC_004.PV := 0 TO 10 BY 2 DO avg := avg+f[PIC_004.PV]; EXIT; END_FOR;",
    "REPEAT PIC_004.PV:= PIC_004.PV+1; UNTIL PIC_004.PV >= 10; END_REPEAT;",
    "[Word 1]{N/2}.Bit4{N} := [DG_CONN3.W Field2.Bit6] AND NOT (A)MOD(B) ** -2;",
    "x := T#1d12.2h + 16#FF + 2#1010 - 3.5E2 + 'a$'b$62' + \"q\" + CRC('123456789',1,16#8005,16#FFFF);",
    "ANIN_005.Alarms.HiLevel.Suppress := 3600; STEP3.T >= T#4m;",
];

const VOCAB: &[&str] = &[
    "IF ",
    "THEN ",
    "ELSIF ",
    "ELSE ",
    "END_IF",
    "FOR ",
    " TO ",
    " BY ",
    " DO ",
    "END_FOR",
    "WHILE ",
    "END_WHILE",
    "REPEAT ",
    "UNTIL ",
    "END_REPEAT",
    "EXIT",
    "ACTION ",
    "END_ACTION",
    " AND ",
    " OR ",
    " XOR ",
    "NOT ",
    " MOD ",
    ":=",
    ":",
    ";",
    ",",
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    "+",
    "-",
    "**",
    "*",
    "/",
    "=",
    "<>",
    "<",
    ">",
    "<=",
    ">=",
    ".",
    ".Bit3",
    "PIC_004.PV",
    "Dig_A.Out",
    "avg",
    "f",
    "REC1",
    "Alarms",
    ".Suppress",
    "Pulserate",
    "1A",
    "6366.MN",
    "45",
    "16#",
    "16#FG",
    "2#1",
    "3.",
    "3.6",
    "T#",
    "T#3s",
    "T#5x",
    "'",
    "\"",
    "'abc'",
    "$",
    "(*",
    "*)",
    "(* c *)",
    " ",
    "\n",
    "\t",
    "é",
    "\u{201C}",
    "\u{0}",
    "SCAN(",
    "FIND(",
    "MID(",
    "AVG(",
    "TRUE",
    "FALSE",
    "STEP1.X",
];

fn mutate(rng: &mut Rng, input: &str) -> Vec<u8> {
    let mut bytes = input.as_bytes().to_vec();
    for _ in 0..=rng.below(4) {
        let len = bytes.len();
        match rng.below(6) {
            0 if len > 0 => {
                let at = rng.below(len);
                bytes[at] = rng.next_u64() as u8;
            }
            1 if len > 0 => {
                let at = rng.below(len);
                let n = rng.below(8).min(len - at);
                bytes.drain(at..at + n);
            }
            2 => {
                let at = rng.below(len + 1);
                let w = VOCAB[rng.below(VOCAB.len())].as_bytes();
                bytes.splice(at..at, w.iter().copied());
            }
            3 if len > 0 => {
                let a = rng.below(len);
                let b = (a + rng.below(32)).min(len);
                let chunk = bytes[a..b].to_vec();
                let at = rng.below(len + 1);
                bytes.splice(at..at, chunk);
            }
            4 => bytes.truncate(rng.below(len + 1)),
            _ => {
                let other = CORPUS[rng.below(CORPUS.len())].as_bytes();
                let at = rng.below(other.len() + 1);
                bytes.extend_from_slice(&other[at..]);
            }
        }
    }
    bytes
}

fn random_tokens(rng: &mut Rng) -> String {
    (0..rng.below(40)).map(|_| VOCAB[rng.below(VOCAB.len())]).collect()
}

/// The error codes of checking `bytes`, and of checking and lowering them,
/// each in its own session against `db`; every diagnostic is rendered in
/// every format on the way.
fn check_and_compile(db: &Database, bytes: &[u8]) -> (Vec<&'static str>, Vec<&'static str>) {
    let ctx = Context::of(Some(db));
    let mut codes = Vec::new();
    for compiling in [false, true] {
        let mut s = if compiling { Session::compiling(ctx) } else { Session::new(ctx) };
        let id = s.add("fuzz.st", bytes.to_vec());
        let mut diagnostics = s.check(id, CheckOptions::default()).diagnostics;
        if compiling {
            diagnostics.extend(s.compile().err().unwrap_or_default());
        }
        for d in &diagnostics {
            assert!(d.span.start <= d.span.end && d.span.end <= bytes.len(), "span out of range: {d:?} in {bytes:?}");
            for f in [Format::Human, Format::Short, Format::Json] {
                let _ = render(s.files(), d, f);
            }
        }
        codes.push(diagnostics.iter().filter(|d| d.is_error()).map(|d| d.code.as_str()).collect());
    }
    let compiled = codes.pop().unwrap_or_default();
    (codes.pop().unwrap_or_default(), compiled)
}

fn exercise(db: &Database, bytes: &[u8]) {
    let (checked, compiled) = check_and_compile(db, bytes);
    assert_eq!(checked, compiled, "check and compile disagree on {bytes:?}");
    let src = String::from_utf8_lossy(bytes);
    let steps: &[String] = &[];
    for ctx in [Context::of(Some(db)), Context::of(Some(db)).unresolved().with_steps(steps)] {
        let report = linc_compiler::check_source(&src, "fuzz", ctx);
        let expr = linc_compiler::check_transition(&src, ctx);
        let mut files = SourceFiles::new();
        let id = files.add("fuzz.st".into(), src.to_string());
        for d in report.diagnostics.iter().chain(&expr.diagnostics) {
            assert!(d.span.start <= d.span.end && d.span.end <= src.len(), "span out of range: {d:?} in {src:?}");
            for f in [Format::Human, Format::Short, Format::Json] {
                let _ = render(&files, &d.clone().in_file(id), f);
            }
        }
        if let Some(t) = report.tree {
            let _ = linc_compiler::st::pretty::file(&t);
        }
    }
}

#[test]
fn random_and_mutated_inputs_never_panic() {
    let cases: usize = std::env::var("LINC_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(3_000);
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    let mut rng = Rng::new(0x9E37_79B9_7F4A_7C15);
    for i in 0..cases {
        let src = if i % 4 == 0 {
            random_tokens(&mut rng).into_bytes()
        } else {
            let seed = CORPUS[rng.below(CORPUS.len())];
            mutate(&mut rng, seed)
        };
        exercise(&db, &src);
    }
}

#[test]
fn corpus_checks_without_panicking() {
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("guide db");
    for src in CORPUS {
        exercise(&db, src.as_bytes());
    }
}

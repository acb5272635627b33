//! `linc fmt` keeps meaning and is idempotent (docs/style.md): over every
//! example (each already in the canonical layout, and each rebuilt from a
//! scrambled layout), over every conformance case (in the harness's `run`)
//! and over generated programs whose blanks, line breaks, comments and
//! keyword case are scrambled.

use linc_compiler::fmt::format;
use linc_compiler::source_kind::SourceKind;
use linc_compiler::st::token::Raw;
use linc_conformance::gen::Gen;
use linc_conformance::rng::Rng;
use linc_conformance::{assert_format_preserves, compiled, guide_db};
use linc_runtime::Database;
use logos::Logos;
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every source file of the examples with the database it runs against.
fn examples() -> Vec<(PathBuf, Database)> {
    let mut out = Vec::new();
    for dir in ["guide", "strategy", "sequences", "ladder", "fst"] {
        let dir = root().join("examples").join(dir);
        let db_name = if dir.ends_with("guide") { "plant.db.json" } else { "plant.json" };
        let db = Database::from_json(&std::fs::read_to_string(dir.join(db_name)).expect("database")).expect("db");
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir).expect("dir").flatten().map(|e| e.path()).collect();
        files.sort();
        for f in files {
            let ext = f.extension().and_then(|e| e.to_str()).unwrap_or("");
            if ["st", "stx", "sfc", "ld", "csv"].contains(&ext) {
                out.push((f, db.clone()));
            }
        }
    }
    out
}

/// The text with its blanks replaced at random (a run of blanks becomes
/// spaces, tabs or line breaks; in ST, a space may appear where there was
/// none between punctuation), its keywords in random case, and, when
/// `comments`, comments added between tokens.
fn scramble(src: &str, rng: &mut Rng, st: bool, comments: bool) -> String {
    // A blank line stays one (the layout keeps blank lines), and none is made.
    const BLANKS: [&str; 6] = [" ", "\t", "\n", "   ", " \n  ", "\r\n"];
    const BLANK_LINES: [&str; 3] = ["\n\n", "\n \n\t", "\r\n\r\n\n"];
    let mut out = String::new();
    let mut lexer = Raw::lexer(src);
    let mut prev_end = 0;
    let mut prev: Option<Raw> = None;
    while let Some(tok) = lexer.next() {
        let span = lexer.span();
        let gap = &src[prev_end..span.start];
        let free =
            |r: Option<Raw>| matches!(r, Some(Raw::Assign | Raw::Semi | Raw::Comma | Raw::Plus | Raw::Eq | Raw::Lt));
        if !gap.is_empty() && gap.trim().is_empty() {
            let blank_line = gap.matches('\n').count() > 1;
            out.push_str(if blank_line { BLANK_LINES[rng.below(3)] } else { BLANKS[rng.below(BLANKS.len())] });
        } else if gap.is_empty() && st && (free(prev) || free(tok.ok())) && rng.one_in(2) {
            out.push(' ');
        } else {
            out.push_str(gap);
        }
        if comments && prev.is_some() && rng.one_in(6) && (!gap.is_empty() || st) {
            out.push_str(["(* c *)", " (* note *) ", "\n(* line\n     two *)\n", "(**)"][rng.below(4)]);
        }
        let text = &src[span.clone()];
        let keyword = text.chars().all(|c| c.is_ascii_uppercase() || c == '_') && tok.is_ok_and(|t| t != Raw::Name);
        if keyword && rng.one_in(2) {
            out.push_str(
                &text.chars().map(|c| if rng.one_in(2) { c.to_ascii_lowercase() } else { c }).collect::<String>(),
            );
        } else {
            out.push_str(text);
        }
        prev_end = span.end;
        prev = tok.ok();
    }
    out.push_str(&src[prev_end..]);
    out
}

fn name_of(path: &Path) -> String {
    path.file_name().and_then(|n| n.to_str()).unwrap_or("x").to_string()
}

#[test]
fn every_example_is_in_the_canonical_layout_and_comes_back_from_a_scrambled_one() {
    let mut rng = Rng::new(18);
    for (path, db) in examples() {
        let src = std::fs::read_to_string(&path).expect("example");
        let name = name_of(&path);
        let kind = SourceKind::of_name(&name);
        if name == "broken.st" {
            assert_eq!(format(kind, &src).as_deref(), Ok(src.as_str()), "linc-fmt: skip leaves it");
            continue;
        }
        assert_eq!(format(kind, &src).as_deref(), Ok(src.as_str()), "{} is not formatted", path.display());
        if kind == SourceKind::FstTable {
            let spaced = src.replace(",,", ", ,").replace('\n', "  \n").replacen("STEP,LABEL", "step ,Label", 1);
            assert_eq!(format(kind, &spaced).as_deref(), Ok(src.as_str()), "{}", path.display());
            continue;
        }
        for round in 0..20 {
            let st = kind == SourceKind::Actions;
            let plain = scramble(&src, &mut rng, st, false);
            assert_eq!(format(kind, &plain).as_deref(), Ok(src.as_str()), "{} round {round}:\n{plain}", path.display());
            let commented = scramble(&src, &mut rng, st, true);
            assert_format_preserves(&commented, &name, &db);
            assert_eq!(compiled(&commented, &name, &db), compiled(&src, &name, &db), "scrambling changed meaning");
        }
    }
}

/// How many generated programs each run checks (`LINC_FMT_CASES` raises it).
fn cases() -> u64 {
    std::env::var("LINC_FMT_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(10_000)
}

// Two halves, so that the suite's two threads share the work.
#[test]
fn generated_programs_keep_their_meaning_and_layout_is_canonical() {
    generated_programs(0..cases() / 2);
}

#[test]
fn generated_programs_keep_their_meaning_and_layout_is_canonical_second_half() {
    generated_programs(cases() / 2..cases());
}

/// Each seed's program: its layout scrambled without comments formats to
/// the same text; with comments added, formatting is idempotent, and for
/// every eighth the object is the same before and after.
fn generated_programs(seeds: std::ops::Range<u64>) {
    let db = guide_db();
    let mut rng = Rng::new(1800 + seeds.start);
    let mut compiled_ok = 0;
    for seed in seeds {
        let mut g = Gen::new(seed);
        let n = 1 + g.rng.below(5);
        let src = g.stmts(n);
        let canonical = format(SourceKind::Actions, &src).unwrap_or_else(|e| panic!("{src}\n{e:?}"));
        let plain = scramble(&src, &mut rng, true, false);
        let again = format(SourceKind::Actions, &plain).unwrap_or_else(|e| panic!("{plain}\n{e:?}"));
        assert_eq!(again, canonical, "layout depends on the input's blanks:\n{plain}\n---");
        let commented = scramble(&src, &mut rng, true, true);
        if seed % 8 == 0 {
            assert_format_preserves(&commented, "gen.st", db);
            compiled_ok += usize::from(compiled(&commented, "gen.st", db).is_ok());
        } else {
            let f = format(SourceKind::Actions, &commented).expect("commented");
            assert_eq!(format(SourceKind::Actions, &f).as_deref(), Ok(f.as_str()), "not idempotent:\n{commented}");
        }
    }
    assert!(compiled_ok > 50, "only {compiled_ok} generated programs compiled");
}

/// Rules of docs/style.md, each as a text and its layout.
#[test]
fn the_style_pages_rules() {
    let cases: [(SourceKind, &str, &str); 4] = [
        (
            SourceKind::Actions,
            "if a.b>1 then c.d:=-(2);(* more *)\nelse c.d:=abs(3);END_IF;",
            "IF a.b > 1 THEN\n    c.d := -(2); (* more *)\nELSE\n    c.d := abs(3);\nEND_IF;\n",
        ),
        (
            SourceKind::Actions,
            "IF x.a THEN\n  y.b := 1;\n(* later *)\nEND_IF;\n",
            "IF x.a THEN\n    y.b := 1;\n    (* later *)\nEND_IF;\n",
        ),
        (
            SourceKind::Sequence,
            "STEP X: A(n); END_STEP (* first *)\nSTEP Longer: B(N); END_STEP\n",
            "STEP X:      A(N); END_STEP (* first *)\nSTEP Longer: B(N); END_STEP\n",
        ),
        (
            SourceKind::Ladder,
            "[a.x]->(b.y);\nLong_label: [a.x] [/c.z] -> (S d.w);\n",
            "            [a.x]        -> (b.y);\nLong_label: [a.x] [/c.z] -> (S d.w);\n",
        ),
    ];
    for (kind, src, want) in cases {
        assert_eq!(format(kind, src).as_deref(), Ok(want), "{src}");
        assert_eq!(format(kind, want).as_deref(), Ok(want), "idempotent: {want}");
    }
}

/// The style page's examples: each "before" block formats to the block
/// after it (a page that contradicts the formatter is a bug).
#[test]
fn the_style_pages_examples_are_what_linc_fmt_writes() {
    let page = std::fs::read_to_string(root().join("docs/style.md")).expect("style page");
    // Code blocks with the text before each.
    let mut blocks: Vec<(String, String)> = Vec::new();
    let (mut inside, mut code, mut between) = (false, String::new(), String::new());
    for line in page.lines() {
        if line.starts_with("```") {
            if inside {
                blocks.push((std::mem::take(&mut between), std::mem::take(&mut code)));
            }
            inside = !inside;
        } else if inside {
            code.push_str(line);
            code.push('\n');
        } else {
            between.push_str(line);
            between.push('\n');
        }
    }
    let mut pairs = 0;
    for w in blocks.windows(2) {
        let ((_, before), (gap, after)) = (&w[0], &w[1]);
        let gap = gap.trim();
        if !(gap.is_empty() || gap.starts_with("After")) || before.starts_with("linc ") {
            continue;
        }
        let kind = if before.contains("STEP,LABEL")
            || before.to_ascii_uppercase().starts_with("STEP") && before.contains(',')
        {
            SourceKind::FstTable
        } else if before.to_ascii_uppercase().contains("STEP ") {
            SourceKind::Sequence
        } else if before.contains("->") {
            SourceKind::Ladder
        } else {
            SourceKind::Actions
        };
        assert_eq!(format(kind, before).as_deref(), Ok(after.as_str()), "docs/style.md:\n{before}");
        pairs += 1;
    }
    assert!(pairs >= 5, "only {pairs} before/after pairs found on the style page");
}

/// Formatting time grows linearly: a long line full of comments, and a
/// sequence of many aligned steps, each at two sizes (4× the input within
/// 8× the time; quadratic work would take 16×).
#[test]
fn formatting_is_linear_in_the_input() {
    let comments = |n: usize| format!("{}\n", "x.y := 1; (* c *) ".repeat(n));
    let steps = |n: usize| (0..n).map(|i| format!("STEP S{i}: A(N); END_STEP\n")).collect::<String>();
    for (kind, make) in [
        (SourceKind::Actions, &comments as &dyn Fn(usize) -> String),
        (SourceKind::Sequence, &steps as &dyn Fn(usize) -> String),
    ] {
        let (small, large) = (make(5_000), make(20_000));
        // Processor time on this thread: how busy the machine is does not count.
        let work = |src: &str| {
            let (out, took) = linc_test_support::work::thread_cpu(|| format(kind, src).expect("formats"));
            assert!(out.len() >= src.len() / 2);
            took
        };
        let r = linc_test_support::work::growth(|big| work(if big { &large } else { &small }));
        assert!(r < 8.0, "{kind:?}: 4x the input took {r:.1}x the work");
    }
}

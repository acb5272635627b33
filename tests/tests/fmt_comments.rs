//! `linc fmt` never loses a comment (issue 28, item 3): every source file
//! of the repository — the examples, the code blocks of the documentation
//! and the conformance cases' sources — is copied once for each boundary
//! between two of its tokens, with a marked comment inserted there (in one
//! of several layouts), and once with a comment at every boundary. Each
//! copy is formatted: the comments come out in the same number and order
//! (their text the same, line by line, but for the indentation of a
//! comment's further lines), a second run changes nothing, and the object
//! it compiles to (or the errors it gives) is the same as the copy's,
//! positions aside. FST tables have no comments between tokens: their
//! COMMENT cells are marked instead.

use linc_compiler::fmt::format;
use linc_compiler::source_kind::SourceKind;
use linc_compiler::st::token::Raw;
use linc_conformance::{compiled, guide_db};
use linc_runtime::Database;
use logos::Logos;
use std::path::{Path, PathBuf};
use std::sync::Arc;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// A source file, the name it is formatted as (its extension gives the
/// language) and the database it compiles against.
struct Source {
    name: String,
    text: String,
    db: Arc<Database>,
}

fn read_db(path: &Path) -> Arc<Database> {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    Arc::new(Database::from_json(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display())))
}

fn files_in(dir: &Path, exts: &[&str]) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir).expect("dir").flatten().map(|e| e.path()).collect();
    files.retain(|f| exts.contains(&f.extension().and_then(|e| e.to_str()).unwrap_or("")));
    files.sort();
    files
}

/// Every source file of the repository, each with its database; the
/// conformance cases' sources are read from their snapshots.
fn sources() -> Vec<Source> {
    const EXTS: [&str; 5] = ["st", "stx", "sfc", "ld", "csv"];
    let guide = Arc::new(guide_db().clone());
    let mut out = Vec::new();
    for dir in ["guide", "strategy", "sequences", "ladder", "fst", "roc"] {
        let dir = root().join("examples").join(dir);
        let db = if dir.ends_with("guide") { guide.clone() } else { read_db(&dir.join("plant.json")) };
        for f in files_in(&dir, &EXTS) {
            let name = f.file_name().and_then(|n| n.to_str()).unwrap_or("x").to_string();
            out.push(Source { name, text: std::fs::read_to_string(&f).expect("example"), db: db.clone() });
        }
    }
    for f in files_in(&root().join("docs"), &["md"]) {
        for (name, text) in doc_blocks(&std::fs::read_to_string(&f).expect("page")) {
            if !out.iter().any(|s: &Source| s.text == text) {
                out.push(Source { name, text, db: guide.clone() });
            }
        }
    }
    let ladder = read_db(&root().join("examples/ladder/plant.json"));
    for f in files_in(&root().join("tests/tests/snapshots"), &["snap"]) {
        let snap = std::fs::read_to_string(&f).expect("snapshot");
        let Some((_, rest)) = snap.split_once("\n--- source\n") else { continue };
        let Some((src, _)) = rest.split_once("\n--- ") else { continue };
        let suite = f.file_name().and_then(|n| n.to_str()).and_then(|n| n.split_once("__")).map_or("", |p| p.0);
        let (name, db) = match suite {
            "ladder" => ("case.ld", ladder.clone()),
            "sequences_syntax" => ("case.sfc", guide.clone()),
            "fst_errors" | "fst_translate" => ("case.csv", guide.clone()),
            _ => ("case.st", guide.clone()),
        };
        if !out.iter().any(|s: &Source| s.text == src) {
            out.push(Source { name: name.into(), text: src.to_string(), db });
        }
    }
    out
}

/// The code blocks of a documentation page that hold a sequence, ladder
/// or ST, each with a name that gives its language (those that do not
/// parse, such as the error pages' wrong examples, are left out later).
fn doc_blocks(page: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let (mut info, mut code) = (None::<String>, String::new());
    for line in page.lines() {
        match (line.strip_prefix("```"), &info) {
            (Some(_), Some(lang)) => {
                let upper = code.to_ascii_uppercase();
                let ext = if lang == "sfc" || upper.contains("END_STEP") || upper.contains("END_TRANSITION") {
                    "sfc"
                } else if lang == "ld" || code.contains("->") {
                    "ld"
                } else {
                    "st"
                };
                if ["st", "text", "sfc", "ld", ""].contains(&lang.as_str()) && !code.trim().is_empty() {
                    out.push((format!("doc.{ext}"), std::mem::take(&mut code)));
                }
                code.clear();
                info = None;
            }
            (Some(lang), None) => info = Some(lang.trim().to_string()),
            (None, Some(_)) => {
                code.push_str(line);
                code.push('\n');
            }
            (None, None) => {}
        }
    }
    out
}

/// Where a comment may go in `src`: the start of every token (so between
/// every two tokens, and before the first), and the end of the text. In
/// ladder (a `.ld` file, a sequence's `: LADDER` action or transition) the
/// elements of a `[…]` contact are tokens too, and the `-` and `>` of a
/// rung's `->` are one; elsewhere `[…]` is a name, one token.
fn boundaries(src: &str, kind: SourceKind) -> Vec<usize> {
    let mut out = Vec::new();
    let mut ladder = kind == SourceKind::Ladder;
    let mut lexer = Raw::lexer(src);
    let mut prev: Option<(Option<Raw>, usize)> = None;
    while let Some(tok) = lexer.next() {
        let span = lexer.span();
        let arrow = tok == Ok(Raw::Gt) && prev.is_some_and(|(r, e)| r == Some(Raw::Minus) && e == span.start);
        if !arrow {
            out.push(span.start);
        }
        let word = &src[span.clone()];
        if kind == SourceKind::Sequence {
            if word.eq_ignore_ascii_case("LADDER") && prev.is_some_and(|(r, _)| r == Some(Raw::Colon)) {
                ladder = true;
            } else if tok == Ok(Raw::EndAction) || word.eq_ignore_ascii_case("END_TRANSITION") {
                ladder = false;
            }
        }
        if ladder && tok == Ok(Raw::Bracketed) {
            let inner = &src[span.start + 1..span.end - 1];
            out.extend(Raw::lexer(inner).spanned().map(|(_, r)| span.start + 1 + r.start));
            out.push(span.end - 1);
        }
        prev = Some((tok.ok(), span.end));
    }
    out.push(src.len());
    out.dedup();
    out
}

/// The comment marked `n`, in layout `style` (of six a comment can have:
/// touching the tokens, between blanks, on its own line, over two lines,
/// after a blank line, at the end of a line).
fn comment(n: usize, style: usize) -> String {
    match style % 6 {
        0 => format!("(*@{n}@*)"),
        1 => format!(" (* @{n}@ *) "),
        2 => format!("\n(*@{n}@*)\n"),
        3 => format!("(*@{n}@ first\n        and second line *)"),
        4 => format!("\n\n   (* @{n}@ *)"),
        _ => format!("(*@{n}@*)\n"),
    }
}

/// `src` with the comments `marks` (position, marker, layout) inserted.
fn with_comments(src: &str, marks: &[(usize, usize, usize)]) -> String {
    let mut out = String::with_capacity(src.len() + 24 * marks.len());
    let mut at = 0;
    for &(pos, n, style) in marks {
        out.push_str(&src[at..pos]);
        out.push_str(&comment(n, style));
        at = pos;
    }
    out.push_str(&src[at..]);
    out
}

/// The comments of a text, in order, each as its lines trimmed (a
/// comment's further lines move with its first). Strings are skipped.
fn comments_of(text: &str) -> Vec<String> {
    let b = text.as_bytes();
    let (mut out, mut i) = (Vec::new(), 0);
    while i < b.len() {
        match b[i] {
            q @ (b'\'' | b'"') => {
                i += 1;
                while i < b.len() && b[i] != q && b[i] != b'\n' {
                    i += if b[i] == b'$' { 2 } else { 1 };
                }
                i += 1;
            }
            b'(' if b.get(i + 1) == Some(&b'*') => {
                let end = text[i + 2..].find("*)").map(|k| i + 4 + k).unwrap_or(text.len());
                let lines: Vec<&str> = text[i..end].lines().map(str::trim).filter(|l| !l.is_empty()).collect();
                out.push(lines.join("\n"));
                i = end;
            }
            _ => i += 1,
        }
    }
    out
}

/// Tallies of one run.
#[derive(Default, Debug)]
struct Tally {
    files: usize,
    /// Conformance cases with a syntax error, which are not formatted.
    unparsed: usize,
    /// Boundaries between tokens that must touch, where a blank is an error.
    touching: usize,
    comments: usize,
    compiled: usize,
}

/// Formats `variant` of `s` and checks it: comments, idempotence, and the
/// object, compared with `object` (the original's) first, which is the
/// same in nearly every case and saves compiling the variant.
fn check(s: &Source, variant: &str, object: &Result<Vec<u8>, Vec<&'static str>>, t: &mut Tally) {
    let kind = SourceKind::of_name(&s.name);
    let formatted = format(kind, variant).unwrap_or_else(|e| panic!("{}: not formatted: {e:?}\n{variant}", s.name));
    let (before, after) = (comments_of(variant), comments_of(&formatted));
    assert_eq!(before, after, "{}: comments changed\n{variant}\n--- formatted:\n{formatted}", s.name);
    let again = format(kind, &formatted).expect("formatted text formats");
    assert_eq!(again, formatted, "{}: a second run changes the layout of\n{variant}", s.name);
    let obj = compiled(&formatted, &s.name, &s.db);
    if &obj != object {
        assert_eq!(obj, compiled(variant, &s.name, &s.db), "{}: meaning changed\n{variant}\n---\n{formatted}", s.name);
    }
    t.files += 1;
    t.comments += before.len();
    t.compiled += usize::from(obj.is_ok());
}

/// Every boundary of every source, three copies each, and a copy with a
/// comment at every boundary.
fn boundary_copies(sources: &[Source], t: &mut Tally) {
    for s in sources {
        let kind = SourceKind::of_name(&s.name);
        // A file marked `linc-fmt: skip` is left as it is, comments and all.
        if kind == SourceKind::FstTable || s.text.contains("linc-fmt: skip") {
            continue;
        }
        if format(kind, &s.text).is_err() {
            // Only conformance cases and documentation examples of syntax
            // errors (or of other languages) do not parse.
            assert!(s.name.starts_with("case.") || s.name.starts_with("doc."), "{} does not format", s.name);
            t.unparsed += 1;
            continue;
        }
        let object = compiled(&s.text, &s.name, &s.db);
        let mut cuts = boundaries(&s.text, kind);
        // A comment goes where a blank may go: between tokens that must
        // touch (`F{n}.Bit0`, a name's parts) is inside a token.
        cuts.retain(|&p| {
            let blank = |c: Option<char>| c.is_none_or(char::is_whitespace);
            let ok = blank(s.text[..p].chars().last())
                || blank(s.text[p..].chars().next())
                || format(kind, &format!("{} {}", &s.text[..p], &s.text[p..])).is_ok();
            t.touching += usize::from(!ok);
            ok
        });
        // Three layouts at each boundary, a different three at the next.
        for (n, &pos) in cuts.iter().enumerate() {
            for (j, style) in [n, n + 1, n + 3].into_iter().enumerate() {
                check(s, &with_comments(&s.text, &[(pos, 3 * n + j, style)]), &object, t);
            }
        }
        let all: Vec<(usize, usize, usize)> = cuts.iter().enumerate().map(|(n, &p)| (p, n, n)).collect();
        check(s, &with_comments(&s.text, &all), &object, t);
    }
}

/// An FST table's cells, row by row, trimmed, the header left out.
fn cells(text: &str) -> Vec<Vec<String>> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    let delim = linc_compiler::fst::reader::delimiter(body);
    let mut r =
        csv::ReaderBuilder::new().has_headers(false).flexible(true).delimiter(delim).from_reader(body.as_bytes());
    let mut rows: Vec<Vec<String>> =
        r.records().skip(1).map(|r| r.expect("record").iter().map(|c| c.trim().to_string()).collect()).collect();
    for row in &mut rows {
        while row.len() < 6 {
            row.push(String::new());
        }
    }
    rows
}

/// Each row of each table with a marked COMMENT cell: every cell is kept.
fn fst_copies(sources: &[Source], t: &mut Tally) {
    for s in sources.iter().filter(|s| SourceKind::of_name(&s.name) == SourceKind::FstTable) {
        let lines: Vec<&str> = s.text.lines().collect();
        let delim = if linc_compiler::fst::reader::delimiter(&s.text) == b';' { ";" } else { "," };
        for row in 1..lines.len() {
            let mut copy = lines.clone();
            let cells_now = lines[row].split(delim).count();
            if lines[row].trim().is_empty() {
                continue;
            }
            let marked = format!("{}{} @{row}@ a note", lines[row], delim.repeat(6usize.saturating_sub(cells_now)));
            copy[row] = &marked;
            let variant = copy.join("\n") + "\n";
            let Ok(formatted) = format(SourceKind::FstTable, &variant) else { continue };
            assert_eq!(cells(&variant), cells(&formatted), "{}: cells changed\n{variant}", s.name);
            assert!(formatted.contains(&format!("@{row}@")), "{}: the comment went\n{formatted}", s.name);
            t.files += 1;
            t.comments += 1;
        }
    }
}

// Two halves (the sources taken alternately), so that the suite's two
// threads share the work; each half checks more than 5,000 copies.
#[test]
fn formatting_keeps_every_comment_at_every_token_boundary() {
    every_boundary(0);
}

#[test]
fn formatting_keeps_every_comment_at_every_token_boundary_second_half() {
    every_boundary(1);
}

fn every_boundary(half: usize) {
    let sources = sources();
    assert!(sources.len() > 250, "only {} sources found", sources.len());
    let mine: Vec<Source> = sources.into_iter().skip(half).step_by(2).collect();
    let mut t = Tally::default();
    boundary_copies(&mine, &mut t);
    fst_copies(&mine, &mut t);
    eprintln!("{t:?}");
    assert!(t.files >= 5_000, "only {} copies checked", t.files);
    assert!(t.compiled > 1_000, "only {} copies compiled", t.compiled);
    assert!(t.comments > 2 * t.files, "only {} comments in {} copies", t.comments, t.files);
}

/// The comments the ladder formatter used to delete: beside a rung's
/// label (before and after its `:`), between the words of an `ACTION`
/// header, and between `END_ACTION` and its `;`.
#[test]
fn ladder_comments_beside_labels_and_in_headers_are_kept() {
    let src = "ACTION (*a*) Pumps (*b*) : (*c*) LADDER (*d*)\n\
               Start (*e*): (*f*) [Dig_1.In] -> (Dig_2.Out);\n\
               Stop:\n(*g*)\n[/Dig_1.In] -> (Dig_3.Out);\n\
               END_ACTION (*h*);\n";
    let want = "ACTION (*a*) Pumps (*b*) : (*c*) LADDER (*d*)\n\
                \x20   Start (*e*): (*f*) [Dig_1.In]  -> (Dig_2.Out);\n\
                \x20   Stop:        (*g*) [/Dig_1.In] -> (Dig_3.Out);\n\
                END_ACTION (*h*);\n";
    let got = format(SourceKind::Ladder, src).expect("formats");
    assert_eq!(got, want);
    assert_eq!(comments_of(&got), ["(*a*)", "(*b*)", "(*c*)", "(*d*)", "(*e*)", "(*f*)", "(*g*)", "(*h*)"]);
    assert_eq!(format(SourceKind::Ladder, want).as_deref(), Ok(want));
}

/// A generic sequence's names may have up to 16 characters (its map gives
/// them targets); `fmt` formats it without the map. A longer name is an
/// error in any sequence.
#[test]
fn a_generic_sequence_with_long_names_is_formatted_without_its_map() {
    let src = "INITIAL_STEP Idle: Ready(P); END_STEP\nSTEP Fill: FillOn(N); END_STEP\n\
               transition from Idle to Fill := StartCommand=1; end_transition\n\
               ACTION Ready\nReactorVessel.Batches:=ReactorVessel.Batches+1;\nEND_ACTION\n";
    let want = "INITIAL_STEP Idle: Ready(P);  END_STEP\nSTEP Fill:         FillOn(N); END_STEP\n\
                TRANSITION FROM Idle TO Fill := StartCommand = 1; END_TRANSITION\n\
                ACTION Ready\n    ReactorVessel.Batches := ReactorVessel.Batches + 1;\nEND_ACTION\n";
    assert_eq!(format(SourceKind::Sequence, src).as_deref(), Ok(want));
    let too_long = src.replace("StartCommand", "StartCommandOfReactor");
    let codes: Vec<&str> = format(SourceKind::Sequence, &too_long)
        .expect_err("a name of 21 characters")
        .iter()
        .map(|d| d.code.as_str())
        .collect();
    assert_eq!(codes, ["E0005"]);
}

/// A comment may stand before a contact's `/` as anywhere between
/// elements: the contact is still negated (it was a syntax error).
#[test]
fn a_comment_before_a_contacts_slash_keeps_it_negated() {
    let db = read_db(&root().join("examples/ladder/plant.json"));
    let plain = "[/Dig_1a.In] -> (Dig_1b.Out);\n";
    let commented = "[ (* closed *) /Dig_1a.In] -> (Dig_1b.Out);\n";
    let object = compiled(plain, "x.ld", &db);
    assert!(object.is_ok(), "{object:?}");
    assert_eq!(compiled(commented, "x.ld", &db), object);
    let want = "        [(* closed *) /Dig_1a.In] -> (Dig_1b.Out);\n";
    assert_eq!(format(SourceKind::Ladder, commented).as_deref(), Ok(want));
    assert_eq!(compiled(want, "x.ld", &db), object);
}

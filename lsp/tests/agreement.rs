//! One name resolution: over every example source, each name the compiler
//! resolves (`linc_compiler::names`, what `linc check` uses) is what the
//! language server's hover describes and where its definition goes.

mod common;

use common::{workspace, Client};
use linc_compiler::names::{Meaning, Name};
use linc_compiler::Context;
use linc_format::Database;
use serde_json::{json, Value};
use std::path::Path;

const EXAMPLES: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples");

/// Each example folder, and the database that names its sources when no
/// block does (`linc.toml`).
const FOLDERS: &[(&str, Option<&str>)] = &[
    ("strategy", None),
    ("sequences", None),
    ("ladder", None),
    ("roc", None),
    ("fst", None),
    ("guide", Some("plant.db.json")),
];

fn is_source(name: &str) -> bool {
    [".st", ".stx", ".sfc", ".ld"].iter().any(|e| name.ends_with(e))
}

/// The 0-based line and UTF-16 column of byte `at`.
fn position(text: &str, at: usize) -> (u32, u32) {
    let line = text[..at].matches('\n').count() as u32;
    let col = text[..at].rsplit('\n').next().unwrap_or("").encode_utf16().count() as u32;
    (line, col)
}

/// The text a protocol range covers.
fn covered<'t>(text: &'t str, range: &Value) -> &'t str {
    let at = |p: &Value| {
        let (line, col) = (p["line"].as_u64().unwrap() as usize, p["character"].as_u64().unwrap() as usize);
        let start: usize = text.split_inclusive('\n').take(line).map(str::len).sum();
        let row = &text[start..];
        start + row.char_indices().nth(col).map_or(row.len(), |(i, _)| i)
    };
    &text[at(&range["start"])..at(&range["end"])]
}

/// How hover's text of a meaning starts.
fn described(db: &Database, m: &Meaning) -> String {
    match m {
        Meaning::Block(b) => format!("**{}**: block of type", db.blocks[*b].name),
        Meaning::Alias(i) => format!("**{}**: alias for", db.aliases[*i].name),
        Meaning::Field { block, template, field, .. } => {
            let t = &db.templates[*template];
            let owner = block.map_or_else(|| format!("(own block, {})", t.name), |b| db.blocks[b].name.clone());
            format!("**{owner}.{}** :", t.fields[*field].name)
        }
        Meaning::Function(sig) => format!("```\n{sig}"),
        Meaning::Step(_) => "**".to_string(),
        Meaning::Action(n) => format!("**ACTION {n}**"),
        Meaning::Label(n) => format!("**{n}:**"),
    }
}

/// The names a definition of `m` may be written as: a field's own (in its
/// template or its block's values), else its block's.
fn defined_as(db: &Database, m: &Meaning) -> Vec<String> {
    match m {
        Meaning::Block(b) => vec![db.blocks[*b].name.clone()],
        Meaning::Alias(i) => vec![db.aliases[*i].name.clone()],
        Meaning::Field { template, field, block, .. } => {
            let mut names = vec![db.templates[*template].fields[*field].name.clone()];
            names.extend(block.map(|b| db.blocks[b].name.clone()));
            names
        }
        Meaning::Function(sig) => vec![sig.name.to_string()],
        Meaning::Step(n) | Meaning::Action(n) | Meaning::Label(n) => vec![n.clone()],
    }
}

/// Asks hover and definition at `name`'s start and checks both against
/// the compiler's meaning.
fn agrees(c: &mut Client, folder: &Path, file: &str, (text, db): (&str, &Database), name: &Name) {
    let (line, col) = position(text, name.span.start);
    let hover = c.at("hover", file, line, col);
    let want = described(db, &name.meaning);
    let got = hover["contents"]["value"].as_str().unwrap_or_default();
    assert!(
        got.starts_with(&want),
        "{file}:{}:{}: hover {got:?}, the compiler's {:?}",
        line + 1,
        col + 1,
        name.meaning
    );
    assert_eq!(covered(text, &hover["range"]), &text[name.span.start..name.span.end], "{file}: hover's range");
    let def = c.at("definition", file, line, col);
    if def.is_null() {
        // Functions are the library's; a field of a built-in type is defined
        // by no file of the workspace.
        let nowhere = matches!(name.meaning, Meaning::Function(_) | Meaning::Field { block: None, .. });
        assert!(nowhere, "{file}:{}:{}: no definition of {:?}", line + 1, col + 1, name.meaning);
        return;
    }
    let target = lsp_types::Url::parse(def["uri"].as_str().unwrap()).unwrap().to_file_path().unwrap();
    let target_text = std::fs::read_to_string(&target).unwrap();
    let written = covered(&target_text, &def["range"]).trim_matches('"');
    let names = defined_as(db, &name.meaning);
    assert!(names.iter().any(|n| written.eq_ignore_ascii_case(n)), "{file}: {:?} defined at `{written}`", name.meaning);
    if target.file_name() == Some(std::ffi::OsStr::new(file)) {
        // A declaration in the file: the compiler gives it the same meaning.
        let at = def["range"]["start"].clone();
        let names = linc_compiler::names::of_source(text, file, Context::of(Some(db)));
        let offset =
            target_text.split_inclusive('\n').take(at["line"].as_u64().unwrap() as usize).map(str::len).sum::<usize>()
                + at["character"].as_u64().unwrap() as usize;
        assert_eq!(names.at(offset).map(|n| &n.meaning), Some(&name.meaning), "{file}: {written}");
    }
    let _ = folder;
}

#[test]
fn hover_and_definition_agree_with_the_compiler_on_every_example_name() {
    let mut checked = 0;
    for (folder, chosen) in FOLDERS {
        let dir = Path::new(EXAMPLES).join(folder);
        let mut files: Vec<(String, String)> = std::fs::read_dir(&dir)
            .unwrap()
            .flatten()
            .map(|e| (e.file_name().to_string_lossy().into_owned(), std::fs::read_to_string(e.path()).unwrap()))
            .collect();
        files.sort();
        if let Some(db) = chosen {
            files.push(("linc.toml".into(), format!("database = \"{db}\"\n")));
        }
        let named: Vec<(&str, &str)> = files.iter().map(|(n, t)| (n.as_str(), t.as_str())).collect();
        let root = workspace(&format!("lsp-agree-{folder}"), &named);
        let mut c = Client::start(&root, json!({ "debounceMs": 0 }));
        let dbs: Vec<(String, Database)> = files
            .iter()
            .filter(|(n, t)| n.ends_with(".json") && t.contains("\"blocks\""))
            .filter_map(|(n, t)| Some((n.clone(), Database::from_json(t).ok()?)))
            .collect();
        for (file, text) in files.iter().filter(|(n, _)| is_source(n)) {
            // The database that names the file, as `linc run` would read it.
            let db = dbs.iter().find(|(n, d)| {
                Some(n.as_str()) == *chosen || d.programs().iter().any(|w| w.file.eq_ignore_ascii_case(file))
            });
            let Some((_, db)) = db else { continue };
            c.open(file, text);
            let names = linc_compiler::names::of_source(text, file, Context::of(Some(db)));
            assert!(!names.is_empty(), "{folder}/{file}: no names resolved");
            for name in names.iter() {
                agrees(&mut c, &root, file, (text, db), name);
                checked += 1;
            }
        }
        c.shutdown();
    }
    assert!(checked > 200, "only {checked} names were compared");
}

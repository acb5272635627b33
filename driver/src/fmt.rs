//! `linc fmt`: which files to format, and formatting one. The layout rules
//! are the compiler's (`linc_compiler::fmt`); this reads the files, reports
//! a file that does not parse, and finds the files of the strategies in a
//! directory when no file is named.

use linc_compiler::diag::Problems;
use linc_runtime::store::Store;
use linc_runtime::Database;
use std::path::{Path, PathBuf};

/// The extensions `linc fmt` formats when it walks a directory.
const EXTENSIONS: [&str; 5] = ["st", "stx", "sfc", "ld", "csv"];

/// The files to format: each named file, the source files under each named
/// directory (a `.csv` only when it is an FST table), or, with no name, the
/// files the strategies (databases with blocks) in `dir` run.
pub fn targets(paths: &[PathBuf], dir: &Path) -> Vec<PathBuf> {
    if paths.is_empty() {
        return strategy_files(dir);
    }
    let mut out = Vec::new();
    for p in paths {
        if p.is_dir() {
            walk(p, &mut out, 0);
        } else {
            out.push(p.clone());
        }
    }
    out
}

/// Source files under `dir`, sorted, not following links, at most 32
/// directories deep.
fn walk(dir: &Path, out: &mut Vec<PathBuf>, depth: usize) {
    let Ok(entries) = std::fs::read_dir(dir) else { return };
    let mut entries: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    entries.sort();
    for p in entries {
        let Ok(meta) = std::fs::symlink_metadata(&p) else { continue };
        if meta.is_dir() && depth < 32 {
            walk(&p, out, depth + 1);
        } else if meta.is_file() && is_source(&p) {
            out.push(p);
        }
    }
}

fn is_source(p: &Path) -> bool {
    let ext = p.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
    if !EXTENSIONS.contains(&ext.as_str()) {
        return false;
    }
    ext != "csv" || std::fs::read_to_string(p).is_ok_and(|t| linc_compiler::fst::reader::starts_with_header(&t))
}

/// The files named by `FileName` in the JSON databases with blocks in `dir`,
/// once each, in order.
fn strategy_files(dir: &Path) -> Vec<PathBuf> {
    let mut dbs: Vec<PathBuf> = std::fs::read_dir(dir)
        .map(|es| es.flatten().map(|e| e.path()).filter(|p| p.extension().is_some_and(|e| e == "json")).collect())
        .unwrap_or_default();
    dbs.sort();
    let mut out: Vec<PathBuf> = Vec::new();
    for db in dbs {
        let Ok(text) = crate::files::read_input_text(&db) else { continue };
        let Ok(parsed) = Database::from_json(&text) else { continue };
        let store = Store::new(parsed);
        for want in linc_engines::strategy::wanted(&store) {
            let file = dir.join(&want.file);
            if !want.file.is_empty() && !out.contains(&file) && file.is_file() {
                out.push(file);
            }
        }
    }
    out
}

/// A file and its text in the canonical layout.
pub struct Formatted {
    pub original: String,
    pub formatted: String,
}

/// The file formatted: `Ok(None)` when it is already in the canonical
/// layout. A file that can't be read is a refused request; one that does
/// not parse, errors found in it.
pub fn format_file(path: &Path) -> Result<Option<Formatted>, Problems> {
    let text = crate::files::read_input_text(path).map_err(|e| Problems::unreadable(path, &e))?;
    let kind = crate::source::kind(path);
    match linc_compiler::fmt::format(kind, &text) {
        Ok(formatted) if formatted == text => Ok(None),
        Ok(formatted) => Ok(Some(Formatted { original: text, formatted })),
        Err(errors) => {
            let mut files = linc_compiler::diag::SourceFiles::new();
            let id = files.add(path.display().to_string(), text);
            Err(Problems::of(files, errors.into_iter().map(|d| d.in_file(id)).collect()))
        }
    }
}

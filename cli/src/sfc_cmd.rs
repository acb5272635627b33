//! `linc sfc …`: generic sequences (guide §9.1) — `specialise` and
//! `generalise` through a map file, `map-template` listing generic names —
//! and loading a map for `check`/`compile --map`. The rewriting is the
//! compiler's (`linc_compiler::sfc::generic`); this reads, prints, writes.

use linc_compiler::diag::render::{Format, SourceFiles};
use linc_compiler::sfc::generic::{self, Map};
use linc_compiler::{sfc, Diagnostic};
use linc_driver::database::load as load_db;
use linc_driver::Reporter;
use linc_runtime::Database;
use std::path::Path;

/// A map bound to a database: the database with the map's aliases, the map
/// file's name for messages, and how many errors the map file had.
pub struct Bound {
    pub db: Database,
    pub map: generic::Named,
    pub errors: usize,
}

/// Reads `path` as a map and binds it to `db`, printing the map's errors.
/// `Err` is an I/O failure (exit 2), already printed.
pub fn load_map(path: &Path, db: &Database, resolve_blocks: bool, r: &mut Reporter) -> Result<Bound, u8> {
    let (map, text, errors) = read_map(path, r)?;
    let (bound, more) = generic::bind(&map, db, resolve_blocks);
    let file = path.display().to_string();
    let mut files = SourceFiles::new();
    let id = files.add(file.clone(), text);
    let all: Vec<Diagnostic> = errors.iter().chain(&more).map(|e| e.to_diagnostic().in_file(id)).collect();
    for d in &all {
        r.emit(&files, d);
    }
    Ok(Bound { db: bound, map: generic::Named { map, file }, errors: all.len() })
}

fn read_map(path: &Path, r: &mut Reporter) -> Result<(Map, String, Vec<generic::MapError>), u8> {
    let text = linc_driver::files::read_input_text(path).map_err(|e| {
        r.unreadable(path, &e);
        2u8
    })?;
    let (map, errors) = generic::parse_map(&text);
    Ok((map, text, errors))
}

/// Reads and parses a sequence for rewriting. A sequence that does not
/// parse is not rewritten (its references can't all be found): its
/// diagnostics are printed and `Err(1)` returned.
fn parse(path: &Path, r: &mut Reporter) -> Result<(String, sfc::ast::Sequence), u8> {
    let text = linc_driver::files::read_input_text(path).map_err(|e| {
        r.unreadable(path, &e);
        2u8
    })?;
    let (seq, diagnostics) = sfc::parser::parse(&text);
    let diagnostics = generic::allow_long_names(diagnostics, &text);
    let errors: Vec<&Diagnostic> = diagnostics.iter().filter(|d| d.is_error()).collect();
    if errors.is_empty() {
        return Ok((text, seq));
    }
    let mut files = SourceFiles::new();
    let id = files.add(path.display().to_string(), text);
    for d in errors {
        r.emit(&files, &d.clone().in_file(id));
    }
    Err(1)
}

/// Which way a rewrite goes.
#[derive(Clone, Copy)]
pub enum Direction {
    Specialise,
    Generalise,
}

/// `linc sfc specialise|generalise FILE --map MAP -o OUT`.
pub fn rewrite(dir: Direction, file: &Path, map_path: &Path, out: &Path, r: &mut Reporter) -> u8 {
    if let Err(e) = linc_driver::files::check_output(out, &[file, map_path]) {
        return crate::report::refused(r, e.diagnostic());
    }
    let (map, text, errors) = match read_map(map_path, r) {
        Ok(m) => m,
        Err(status) => return status,
    };
    if !errors.is_empty() {
        let mut files = SourceFiles::new();
        let id = files.add(map_path.display().to_string(), text);
        for e in &errors {
            r.emit(&files, &e.to_diagnostic().in_file(id));
        }
        return 1;
    }
    let (src, seq) = match parse(file, r) {
        Ok(p) => p,
        Err(status) => return status,
    };
    let written = match dir {
        Direction::Specialise => generic::specialise(&src, &seq, &map),
        Direction::Generalise => generic::generalise(&src, &seq, &map),
    };
    match linc_driver::files::write_atomic(out, written.as_bytes()) {
        Ok(()) => 0,
        Err(e) => crate::report::refused(r, e.diagnostic()),
    }
}

/// `linc sfc map-template FILE [--db DB]`: prints a map with every generic
/// name and an empty target.
pub fn map_template(file: &Path, db: Option<&Path>, r: &mut Reporter) -> u8 {
    let mut dbfiles = SourceFiles::new();
    let db = match load_db(db, &mut dbfiles, r) {
        Ok(db) => db.unwrap_or_else(Database::builtin),
        Err(status) => return status,
    };
    let (_, seq) = match parse(file, r) {
        Ok(p) => p,
        Err(status) => return status,
    };
    crate::out::print(&generic::map_template(&generic::generic_names(&seq, &db)));
    0
}

/// `--resources`: the table of what the sequence uses (or one JSON line).
pub fn print_resources(name: &str, uses: &[sfc::resources::Use], instrument: &str, format: Format) {
    if format == Format::Json {
        let fields: Vec<String> =
            uses.iter().map(|u| format!("{:?}:{{\"used\":{},\"limit\":{}}}", u.resource, u.used, u.limit)).collect();
        crate::out::line(&format!(
            "{{\"resources\":{{\"file\":{},\"instrument\":\"{instrument}\",{}}}}}",
            serde_json::Value::String(name.to_string()),
            fields.join(",")
        ));
        return;
    }
    crate::out::line(&format!("resources of {name} ({instrument} instrument):"));
    for u in uses {
        let mark = if u.used > u.limit { "  over the limit" } else { "" };
        crate::out::line(&format!("  {:<13}{:>5} of {}{mark}", u.resource, u.used, u.limit));
    }
}

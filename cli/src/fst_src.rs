//! FST tables (`.csv`, as ROCLINK 800 exports them) on the command line:
//! read, checked and compiled by the compiler's FST front end, diagnostics
//! printed through the renderer, and `linc fst list`.

use linc_compiler::fst;
use linc_compiler::render::SourceFiles;
use linc_driver::Reporter;
use linc_runtime::{Database, ObjectFile};
use std::path::Path;

/// Whether a path names an FST table.
pub fn is_fst(path: &Path) -> bool {
    path.extension().and_then(|e| e.to_str()).is_some_and(|e| e.eq_ignore_ascii_case("csv"))
}

/// What checking one table gave.
pub struct Checked {
    pub errors: usize,
    pub warnings: usize,
    pub object: Option<ObjectFile>,
}

/// The table's text, or the located E0017 for bytes that are not UTF-8
/// (already printed). `Err` is an I/O failure, reported.
fn read(path: &Path, files: &mut SourceFiles, r: &mut Reporter) -> Result<Option<String>, ()> {
    let bytes = linc_driver::files::read_input(path).map_err(|e| r.unreadable(path, &e))?;
    let (text, invalid) = linc_compiler::files::decode(bytes);
    let id = files.add_decoded(path.display().to_string(), text.clone(), invalid.clone());
    match linc_compiler::session::SessionError::not_utf8(&invalid) {
        Some(e) => {
            r.emit(files, &e.to_diagnostic().in_file(id));
            Ok(None)
        }
        None => Ok(Some(text)),
    }
}

/// Reads, checks and (with a database, when `lower`) compiles one table,
/// printing its diagnostics.
pub fn check(path: &Path, db: Option<&Database>, lower: bool, r: &mut Reporter) -> Result<Checked, ()> {
    let mut files = SourceFiles::new();
    let Some(text) = read(path, &mut files, r)? else {
        return Ok(Checked { errors: 1, warnings: 0, object: None });
    };
    let name = path.display().to_string();
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("fst");
    let (diagnostics, object) = fst::compile(&text, stem, &name, db);
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    for d in &diagnostics {
        r.emit(&files, &d.clone().in_file(linc_compiler::span::FileId(0)));
    }
    let object = if lower { object } else { None };
    Ok(Checked { errors, warnings: diagnostics.len() - errors, object })
}

/// `linc fst list TABLE.csv [--db DB]`: the table as the FST Editor shows
/// it, with each step's instruction offset when a database lets it compile.
pub fn list(path: &Path, db: Option<&Path>, r: &mut Reporter) -> u8 {
    let mut dbfiles = SourceFiles::new();
    let db = match crate::check_cmd::load_db(db, &mut dbfiles, r) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let mut files = SourceFiles::new();
    let text = match read(path, &mut files, r) {
        Ok(Some(t)) => t,
        Ok(None) => return 1,
        Err(()) => return 2,
    };
    let (table, mut diagnostics) = fst::reader::read(&text);
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("fst");
    let (more, object) = fst::compile(&text, stem, &path.display().to_string(), db.as_ref());
    if db.is_some() {
        diagnostics = more;
    }
    for d in &diagnostics {
        r.emit(&files, &d.clone().in_file(linc_compiler::span::FileId(0)));
    }
    if diagnostics.iter().any(|d| d.is_error()) {
        return 1;
    }
    let offsets = object.as_ref().and_then(fst::offsets);
    crate::out::print(&fst::list::listing(&table, offsets.as_deref()));
    0
}

//! FST tables (`.csv`, as ROCLINK 800 exports them) for `linc check` and
//! `linc fst list`: read through the driver, checked by the compiler's FST
//! front end, diagnostics reported, the listing printed.

use linc_compiler::fst;
use linc_driver::{source, Reporter};
use linc_runtime::Database;
use std::path::Path;

/// What checking one table gave.
pub struct Checked {
    pub errors: usize,
    pub warnings: usize,
}

/// Reads and checks one table (against the database, when there is one),
/// reporting its diagnostics. `Err` is an I/O failure, reported.
pub fn check(path: &Path, db: Option<&Database>, r: &mut Reporter) -> Result<Checked, ()> {
    let (text, files, id) = source::read(path, r).map_err(|_| ())?;
    let Some(text) = text else {
        return Ok(Checked { errors: 1, warnings: 0 });
    };
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("fst");
    let (diagnostics, _) = fst::compile(&text, stem, &path.display().to_string(), db);
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    r.emit_all(&files, &diagnostics.iter().map(|d| d.clone().in_file(id)).collect::<Vec<_>>());
    Ok(Checked { errors, warnings: diagnostics.len() - errors })
}

/// `linc fst list TABLE.csv [--db DB]`: the table as the FST Editor shows
/// it, with each step's instruction offset when a database lets it compile.
pub fn list(path: &Path, db: Option<&Path>, r: &mut Reporter) -> u8 {
    let mut dbfiles = linc_compiler::render::SourceFiles::new();
    let db = match linc_driver::database::load(db, &mut dbfiles, r) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let (text, files, id) = match source::read(path, r) {
        Ok((Some(t), files, id)) => (t, files, id),
        Ok((None, ..)) => return 1,
        Err(status) => return status,
    };
    let (table, mut diagnostics) = fst::reader::read(&text);
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("fst");
    let (more, object) = fst::compile(&text, stem, &path.display().to_string(), db.as_ref());
    if db.is_some() {
        diagnostics = more;
    }
    r.emit_all(&files, &diagnostics.iter().map(|d| d.clone().in_file(id)).collect::<Vec<_>>());
    if diagnostics.iter().any(|d| d.is_error()) {
        return 1;
    }
    let offsets = object.as_ref().and_then(fst::offsets);
    crate::out::print(&fst::list::listing(&table, offsets.as_deref()));
    0
}

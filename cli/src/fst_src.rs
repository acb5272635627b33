//! `linc fst list`: an FST table (`.csv`, as ROCLINK 800 exports it) read
//! through the driver and listed as the FST Editor shows it (`linc check`
//! checks tables in the compile session like any source); `linc fst to-st`:
//! the driver's translations, printed or written.

use linc_compiler::fst;
use linc_driver::{source, Reporter};
use std::path::Path;

/// `linc fst list TABLE.csv [--db DB]`: the table as the FST Editor shows
/// it, with each step's instruction offset when a database lets it compile.
pub fn list(path: &Path, db: Option<&Path>, r: &mut Reporter) -> u8 {
    let mut dbfiles = linc_compiler::diag::render::SourceFiles::new();
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

/// `linc fst to-st` and `to-sfc`: the driver's translation `make`,
/// printed or written to `out` (never over the table or the database).
pub fn translate(
    path: &Path,
    db: &Path,
    out: Option<&Path>,
    r: &mut Reporter,
    make: impl FnOnce(&mut Reporter) -> Result<String, u8>,
) -> u8 {
    crate::out::print_or_write(out, &[path, db], r, |r| make(r).map(|text| (text, 0)))
}

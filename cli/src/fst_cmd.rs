//! `linc fst list|to-st|to-sfc`: the driver reads, lists and translates
//! FST tables; this prints or writes what it made.

use crate::report::Reporter;
use linc_compiler::diag::Problems;
use std::path::Path;

/// `linc fst list TABLE.csv [--db DB]`.
pub fn list(path: &Path, db: Option<&Path>, r: &Reporter) -> u8 {
    match linc_driver::fst::list(path, db) {
        Ok((listing, warnings)) => {
            let status = r.report(&warnings);
            crate::out::print(&listing);
            status
        }
        Err(p) => r.report(&p),
    }
}

/// `linc fst to-st` and `to-sfc`: the driver's translation `make`,
/// printed or written to `out` (never over the table or the database).
pub fn translate(
    path: &Path,
    db: &Path,
    out: Option<&Path>,
    r: &Reporter,
    make: impl FnOnce() -> Result<String, Problems>,
) -> u8 {
    crate::out::print_or_write(out, &[path, db], r, || make().map(|text| (text, Problems::new())))
}

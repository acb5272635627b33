//! `linc compile FILE... -o OUT.sto`.

use crate::build::{compile, Failed};
use crate::check_cmd::load_db;
use linc_compiler::render::{Format, SourceFiles};
use std::path::{Path, PathBuf};

pub fn run(files: &[PathBuf], out: &Path, db: Option<&Path>, format: Format) -> u8 {
    let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).chain(db).collect();
    if let Err(e) = crate::files::check_output(out, &inputs) {
        eprintln!("{e}");
        return 2;
    }
    let mut dbfiles = SourceFiles::new();
    let db = match load_db(db, &mut dbfiles, format) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let obj = match compile(files, db.as_ref(), format, 1) {
        Ok(o) => o,
        Err(Failed(status)) => return status,
    };
    let bytes = obj.to_bytes();
    match crate::files::write_atomic(out, &bytes) {
        Ok(()) => 0,
        Err(e) => {
            eprintln!("{e}");
            2
        }
    }
}

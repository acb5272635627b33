//! `linc compile FILE... -o OUT.sto`.

use crate::build::{compile, Failed};
use crate::check_cmd::load_db;
use linc_compiler::check::Context;
use linc_compiler::render::{Format, SourceFiles};
use linc_runtime::{Database, ObjectFile};
use std::path::{Path, PathBuf};

pub fn run(files: &[PathBuf], out: &Path, db: Option<&Path>, map: Option<&Path>, format: Format) -> u8 {
    let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).chain(db).chain(map).collect();
    if let Err(e) = crate::files::check_output(out, &inputs) {
        eprintln!("{e}");
        return 2;
    }
    let mut dbfiles = SourceFiles::new();
    let db = match load_db(db, &mut dbfiles, format) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let compiled = match map {
        Some(m) => compile_mapped(files, db.as_ref(), m, format),
        None => compile(files, db.as_ref(), format, 1),
    };
    let obj = match compiled {
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

/// `--map`: one generic sequence, its names resolved through the map (a
/// map is for sequences only; every generic name needs a target here).
fn compile_mapped(files: &[PathBuf], db: Option<&Database>, map: &Path, format: Format) -> Result<ObjectFile, Failed> {
    let [file] = files else {
        crate::report::usage("[E0903] --map compiles one generic sequence (.sfc) on its own");
        return Err(Failed(2));
    };
    if !crate::sequence_src::is_sequence(file) {
        crate::report::usage(format_args!("[E0903] --map is for sequences: `{}` is not a .sfc file", file.display()));
        return Err(Failed(2));
    }
    let builtin = Database::builtin();
    let resolve_blocks = db.is_some();
    let bound = crate::sfc_cmd::load_map(map, db.unwrap_or(&builtin), resolve_blocks, format).map_err(Failed)?;
    if bound.errors > 0 {
        return Err(Failed(1));
    }
    let ctx = Context { db: &bound.db, resolve_blocks, steps: None };
    let extra = crate::sequence_src::Extra { map: Some(&bound), ..Default::default() };
    let c = crate::sequence_src::check_with(file, ctx, &extra, (true, false), format).map_err(|()| Failed(2))?;
    c.object.ok_or(Failed(1))
}

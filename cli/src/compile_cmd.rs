//! `linc compile FILE... -o OUT.sto`.

use linc_compiler::diag::render::SourceFiles;
use linc_compiler::Context;
use linc_driver::build::{compile, Failed};
use linc_driver::database::load as load_db;
use linc_driver::Reporter;
use linc_runtime::{Database, ObjectFile};
use std::path::{Path, PathBuf};

pub fn run(files: &[PathBuf], out: &Path, db: Option<&Path>, map: Option<&Path>, r: &mut Reporter) -> u8 {
    let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).chain(db).chain(map).collect();
    if let Err(e) = linc_driver::files::check_output(out, &inputs) {
        return crate::report::refused(r, e.diagnostic());
    }
    let mut dbfiles = SourceFiles::new();
    let db = match load_db(db, &mut dbfiles, r) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let compiled = match map {
        Some(m) => compile_mapped(files, db.as_ref(), m, r),
        None => compile(files, db.as_ref(), r, 1),
    };
    let obj = match compiled {
        Ok(o) => o,
        Err(Failed(status)) => return status,
    };
    let bytes = obj.to_bytes();
    match linc_driver::files::write_atomic(out, &bytes) {
        Ok(()) => 0,
        Err(e) => crate::report::refused(r, e.diagnostic()),
    }
}

/// `--map`: one generic sequence, its names resolved through the map (a
/// map is for sequences only; every generic name needs a target here).
fn compile_mapped(
    files: &[PathBuf],
    db: Option<&Database>,
    map: &Path,
    r: &mut Reporter,
) -> Result<ObjectFile, Failed> {
    let [file] = files else {
        crate::report::usage(r, "--map compiles one generic sequence (.sfc) on its own");
        return Err(Failed(2));
    };
    if !linc_driver::source::is_sequence(file) {
        crate::report::usage(r, format_args!("--map is for sequences: `{}` is not a .sfc file", file.display()));
        return Err(Failed(2));
    }
    let plain = Context::of(db);
    let resolve_blocks = plain.resolve_blocks;
    let bound = crate::sfc_cmd::load_map(map, plain.db, resolve_blocks, r).map_err(Failed)?;
    if bound.errors > 0 {
        return Err(Failed(1));
    }
    let ctx = Context { db: &bound.db, resolve_blocks, steps: None };
    let extra = crate::sequence_src::Extra { map: Some(&bound), ..Default::default() };
    let c = crate::sequence_src::check_with(file, ctx, &extra, (true, false), r).map_err(|()| Failed(2))?;
    c.object.ok_or(Failed(1))
}

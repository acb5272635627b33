//! Turning source files into an object, for `compile`, `run`, the console
//! and scenarios alike, through one compile session that classifies every
//! file (`linc_compiler::source_kind`). The compiler does the work; this
//! reads the files.

use linc_compiler::diag::Problems;
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::{Database, ObjectFile, Verified};
use std::path::{Path, PathBuf};

/// An object compiled, with the warnings its files had.
pub struct Compiled {
    pub object: ObjectFile,
    pub warnings: Problems,
}

/// Checks and lowers `paths` into one object, in one compile session that
/// knows each file's kind (ST and ladder files together; a sequence or an
/// FST table alone). An unreadable file is a refused request; errors in
/// the files are errors found (with the warnings).
pub fn compile(paths: &[PathBuf], db: Option<&Database>) -> Result<Compiled, Problems> {
    let mut session = Session::compiling(Context::of(db));
    let mut found = Vec::new();
    for path in paths {
        let bytes = crate::files::read_input(path).map_err(|e| Problems::unreadable(path, &e))?;
        let id = session.add(path.display().to_string(), bytes);
        found.extend(session.check(id, CheckOptions::default()).diagnostics);
    }
    let compiled = session.compile();
    match compiled {
        Ok(object) => Ok(Compiled { object, warnings: Problems::of(session.into_files(), found) }),
        Err(errors) => {
            found.extend(errors);
            Err(Problems::of(session.into_files(), found))
        }
    }
}

/// Loads a program file: a `.sto` object as is (verified), anything else
/// compiled against `db`, with its warnings. A program that does not
/// compile or load is a refused request: it can't run.
pub fn program_object(path: &Path, db: &Database) -> Result<(Verified, Problems), Problems> {
    let name = path.display().to_string();
    let refused = |e: linc_runtime::LoadError| Problems::whole_file(&name, e.code(), e.to_string());
    if !crate::source::is_object(path) {
        let c = compile(&[path.to_path_buf()], Some(db)).map_err(Problems::refused)?;
        let mut warnings = c.warnings;
        return match linc_runtime::verify::verify(c.object) {
            Ok(v) => Ok((v, warnings)),
            Err(e) => {
                warnings.append(refused(e));
                Err(warnings)
            }
        };
    }
    let bytes = crate::files::read_input(path).map_err(|e| Problems::unreadable(path, &e))?;
    linc_runtime::load(&bytes).map(|v| (v, Problems::new())).map_err(refused)
}

/// `linc compile FILE... -o OUT [--db DB] [--map MAP]`: the files compiled
/// into one object written atomically to `out` (never over an input), or
/// with a map one generic sequence through it. The warnings; errors in the
/// files are errors found, anything else a refused request.
pub fn compile_to(files: &[PathBuf], out: &Path, db: Option<&Path>, map: Option<&Path>) -> Result<Problems, Problems> {
    let inputs: Vec<&Path> = files.iter().map(PathBuf::as_path).chain(db).chain(map).collect();
    crate::files::check_output(out, &inputs)?;
    let db = crate::database::load_opt(db)?.map(|d| d.db);
    let compiled = match map {
        Some(m) => compile_mapped(files, db.as_ref(), m)?,
        None => compile(files, db.as_ref())?,
    };
    crate::files::write_atomic(out, &compiled.object.to_bytes())?;
    Ok(compiled.warnings)
}

/// `--map`: one generic sequence, its names resolved through the map (a
/// map is for sequences only; every generic name needs a target here).
fn compile_mapped(files: &[PathBuf], db: Option<&Database>, map: &Path) -> Result<Compiled, Problems> {
    let [file] = files else {
        return Err(crate::database::usage("--map compiles one generic sequence (.sfc) on its own"));
    };
    if !crate::source::is_sequence(file) {
        let why = format!("--map is for sequences: `{}` is not a .sfc file", file.display());
        return Err(crate::database::usage(why));
    }
    let plain = Context::of(db);
    let resolve_blocks = plain.resolve_blocks;
    let mut bound = crate::sfc::load_map(map, plain.db, resolve_blocks)?;
    let mut problems = std::mem::take(&mut bound.problems);
    if problems.has_errors() {
        return Err(problems);
    }
    let ctx = Context { db: &bound.db, ..plain };
    let extra = crate::sfc::Extra { map: Some(&bound), lower: true, ..Default::default() };
    let c = crate::sfc::check(file, ctx, &extra)?;
    problems.append(c.problems);
    match c.object {
        Some(object) if !problems.has_errors() => Ok(Compiled { object, warnings: problems }),
        _ => Err(problems),
    }
}

//! Turning source files into an object, for `compile`, `run`, the console
//! and scenarios alike: ST and ladder action files through one compile
//! session, a sequence or an FST table on its own, an object loaded and
//! verified. The compiler does the work; this reads the files and reports.

use crate::report::usage;
use crate::source;
use crate::Reporter;
use linc_compiler::check::Context;
use linc_compiler::fst;
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::sfc;
use linc_runtime::{Database, ObjectFile};
use std::path::PathBuf;

/// Why a build failed (everything already printed); carries the exit status.
pub struct Failed(pub u8);

/// Checks and lowers `paths` into one object. Diagnostics are printed; any
/// error gives `Failed(errors_status)` (or 2 for I/O problems).
pub fn compile(
    paths: &[PathBuf],
    db: Option<&Database>,
    r: &mut Reporter,
    errors_status: u8,
) -> Result<ObjectFile, Failed> {
    if let Some(table) = paths.iter().find(|p| source::is_fst(p)) {
        return compile_fst(paths, table, db, r, errors_status);
    }
    let builtin;
    let (db, resolve_blocks) = match db {
        Some(d) => (d, true),
        None => {
            builtin = Database::builtin();
            (&builtin, false)
        }
    };
    let ctx = Context { db, resolve_blocks, steps: None };
    if let Some(seq) = paths.iter().find(|p| source::is_sequence(p)) {
        // A sequence is one unit of its own (its steps and actions are its).
        if paths.len() > 1 {
            usage(r, format_args!("`{}` is a sequence: compile it on its own", seq.display()));
            return Err(Failed(2));
        }
        return compile_sequence(seq, ctx, r)?.ok_or(Failed(errors_status));
    }
    let mut session = Session::compiling(ctx);
    for path in paths {
        let bytes = crate::files::read_input(path).map_err(|e| {
            r.unreadable(path, &e);
            Failed(2)
        })?;
        let id = session.add(path.display().to_string(), bytes);
        let checked = session.check(id, CheckOptions::default());
        r.emit_all(session.files(), &checked.diagnostics);
    }
    if session.has_errors() {
        return Err(Failed(errors_status));
    }
    session.compile().map_err(|errors| {
        r.emit_all(session.files(), &errors);
        Failed(errors_status)
    })
}

/// An FST table is one unit of its own, and compiling it needs the
/// database its points live in.
fn compile_fst(
    paths: &[PathBuf],
    table: &std::path::Path,
    db: Option<&Database>,
    r: &mut Reporter,
    errors_status: u8,
) -> Result<ObjectFile, Failed> {
    if paths.len() > 1 {
        usage(r, format_args!("`{}` is an FST table: compile it on its own", table.display()));
        return Err(Failed(2));
    }
    let Some(db) = db else {
        let what = format!("compiling the FST table `{}` needs its point database: pass --db", table.display());
        usage(r, what);
        return Err(Failed(2));
    };
    let (text, files, id) = source::read(table, r).map_err(Failed)?;
    let Some(text) = text else { return Err(Failed(errors_status)) };
    let stem = table.file_stem().and_then(|s| s.to_str()).unwrap_or("fst");
    let (diagnostics, object) = fst::compile(&text, stem, &table.display().to_string(), Some(db));
    r.emit_all(&files, &diagnostics.into_iter().map(|d| d.in_file(id)).collect::<Vec<_>>());
    object.ok_or(Failed(errors_status))
}

/// Reads and compiles one sequence (no map), reporting its diagnostics;
/// `Ok(None)` when it has errors.
fn compile_sequence(path: &std::path::Path, ctx: Context, r: &mut Reporter) -> Result<Option<ObjectFile>, Failed> {
    let (text, files, id) = source::read(path, r).map_err(Failed)?;
    let Some(text) = text else { return Ok(None) };
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("sequence");
    let (diagnostics, object) = sfc::compile_sequence(&text, stem, &path.display().to_string(), ctx);
    r.emit_all(&files, &diagnostics.into_iter().map(|d| d.in_file(id)).collect::<Vec<_>>());
    Ok(object)
}

//! Turning source files into an object: shared by `compile` and `run`.
//!
//! The compiler's session does the work; this only reads the files and
//! prints what the session reports.

use linc_compiler::check::Context;
use linc_compiler::session::{CheckOptions, Session};
use linc_driver::Reporter;
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
    if let Some(table) = paths.iter().find(|p| crate::fst_src::is_fst(p)) {
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
    if let Some(seq) = paths.iter().find(|p| crate::sequence_src::is_sequence(p)) {
        // A sequence is one unit of its own (its steps and actions are its).
        if paths.len() > 1 {
            crate::report::usage(r, format_args!("`{}` is a sequence: compile it on its own", seq.display()));
            return Err(Failed(2));
        }
        let c = crate::sequence_src::check(seq, ctx, true, false, r).map_err(|()| Failed(2))?;
        return c.object.ok_or(Failed(errors_status));
    }
    let mut session = Session::compiling(ctx);
    for path in paths {
        let bytes = linc_driver::files::read_input(path).map_err(|e| {
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
        crate::report::usage(r, format_args!("`{}` is an FST table: compile it on its own", table.display()));
        return Err(Failed(2));
    }
    let Some(db) = db else {
        let what = format!("compiling the FST table `{}` needs its point database: pass --db", table.display());
        crate::report::usage(r, what);
        return Err(Failed(2));
    };
    let c = crate::fst_src::check(table, Some(db), true, r).map_err(|()| Failed(2))?;
    c.object.ok_or(Failed(errors_status))
}

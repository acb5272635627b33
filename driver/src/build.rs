//! Turning source files into an object, for `compile`, `run`, the console
//! and scenarios alike, through one compile session that classifies every
//! file (`linc_compiler::source_kind`). The compiler does the work; this
//! reads the files and reports.

use crate::Reporter;
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::{Database, ObjectFile};
use std::path::PathBuf;

/// Why a build failed (everything already printed); carries the exit status.
pub struct Failed(pub u8);

/// Checks and lowers `paths` into one object, in one compile session that
/// knows each file's kind (ST and ladder files together; a sequence or an
/// FST table alone). Diagnostics are printed; any error gives
/// `Failed(errors_status)` (or 2 for I/O problems).
pub fn compile(
    paths: &[PathBuf],
    db: Option<&Database>,
    r: &mut Reporter,
    errors_status: u8,
) -> Result<ObjectFile, Failed> {
    let mut session = Session::compiling(Context::of(db));
    for path in paths {
        let bytes = crate::files::read_input(path).map_err(|e| {
            r.unreadable(path, &e);
            Failed(2)
        })?;
        let id = session.add(path.display().to_string(), bytes);
        let checked = session.check(id, CheckOptions::default());
        r.emit_all(session.files(), &checked.diagnostics);
    }
    session.compile().map_err(|errors| {
        r.emit_all(session.files(), &errors);
        Failed(errors_status)
    })
}

//! `--state FILE` and `--cold`: a strategy's retentive state kept in a file
//! between runs (`docs/state.md`). A warm start restores the file when it
//! exists; a damaged one stops the run before it starts unless `--cold`
//! asks to ignore it. The state is written atomically, so a run that dies
//! while saving leaves the last good state in place.

use crate::plant::Start;
use linc_compiler::diag::Problems;
use linc_engines::strategy::Strategy;
use std::io;
use std::path::Path;

/// Restores `path` into `s` unless `cold`; a file that can't be read or
/// does not fit the strategy is a refused request.
pub fn warm_start(path: &Path, cold: bool, s: &mut Strategy) -> Result<Start, Problems> {
    if cold {
        return Ok(Start::Cold);
    }
    let bytes = match crate::files::read_in_out(path) {
        Ok(b) => b,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Start::Cold),
        Err(e) => return Err(Problems::unreadable(path, &e)),
    };
    match s.restore_state(&bytes) {
        Ok(()) => Ok(Start::Warm),
        Err(e) => {
            let why = format!("{} (the run did not start; --cold ignores the file)", e.message);
            Err(Problems::whole_file(&path.display().to_string(), e.code, why))
        }
    }
}

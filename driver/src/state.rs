//! `--state FILE` and `--cold`: a strategy's retentive state kept in a file
//! between runs (`docs/state.md`). A warm start restores the file when it
//! exists; a damaged one stops the run before it starts unless `--cold`
//! asks to ignore it. The state is written atomically, so a run that dies
//! while saving leaves the last good state in place.

use crate::Reporter;
use linc_engines::strategy::Strategy;
use std::io;
use std::path::Path;

/// What a warm start found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Start {
    /// `--cold`, or no state file yet: the strategy begins as built.
    Cold,
    /// The file's state was restored.
    Warm,
}

/// Restores `path` into `s` unless `cold`. Errors are reported; the `u8` is
/// the exit status (2).
pub fn warm_start(path: &Path, cold: bool, s: &mut Strategy, r: &mut Reporter) -> Result<Start, u8> {
    if cold {
        return Ok(Start::Cold);
    }
    let bytes = match crate::files::read_in_out(path) {
        Ok(b) => b,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Start::Cold),
        Err(e) => {
            r.unreadable(path, &e);
            return Err(2);
        }
    };
    match s.restore_state(&bytes) {
        Ok(()) => Ok(Start::Warm),
        Err(e) => {
            let why = format!("{} (the run did not start; --cold ignores the file)", e.message);
            r.whole_file(&path.display().to_string(), e.code, why);
            Err(2)
        }
    }
}

/// Saves the strategy's state to `path`, atomically.
pub fn save(path: &Path, s: &Strategy, r: &mut Reporter) -> Result<(), u8> {
    crate::files::write_atomic(path, &s.save_state()).map_err(|e| crate::report::refused(r, e.diagnostic()))
}

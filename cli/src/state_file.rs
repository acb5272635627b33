//! `--state FILE` and `--cold`: a strategy's retentive state kept in a file
//! between runs (`docs/state.md`). A warm start restores the file when it
//! exists; a damaged one stops the run before it starts unless `--cold`
//! asks to ignore it. The state is written atomically, so a run that dies
//! while saving leaves the last good state in place.

use linc_runtime::strategy::Strategy;
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

/// Restores `path` into `s` unless `cold`. Errors are printed; the `u8` is
/// the exit status (2).
pub fn warm_start(path: &Path, cold: bool, s: &mut Strategy) -> Result<Start, u8> {
    if cold {
        return Ok(Start::Cold);
    }
    let bytes = match crate::files::read_in_out(path) {
        Ok(b) => b,
        Err(e) if e.kind() == io::ErrorKind::NotFound => return Ok(Start::Cold),
        Err(e) => {
            eprintln!("error[E0900]: can't read the state file `{}`: {e}", path.display());
            return Err(2);
        }
    };
    match s.restore_state(&bytes) {
        Ok(()) => Ok(Start::Warm),
        Err(e) => {
            eprintln!(
                "error[{}]: `{}`: {} (the run did not start; --cold ignores the file)",
                e.code,
                path.display(),
                e.message
            );
            Err(2)
        }
    }
}

/// Saves the strategy's state to `path`, atomically.
pub fn save(path: &Path, s: &Strategy) -> Result<(), u8> {
    crate::files::write_atomic(path, &s.save_state()).map_err(|e| {
        eprintln!("{e}");
        2
    })
}

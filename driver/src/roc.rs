//! The files of `linc roc poll`: the command list and the word table, read
//! with their errors located in the file, and the word table written back
//! atomically, never over an input.

use crate::files::{read_input_text, write_atomic};
use crate::Reporter;
use linc_comms::error::FileError;
use linc_comms::roc::host::{Command, Words};
use linc_compiler::{Diagnostic, Span};
use std::path::Path;

/// Reports a comms file error at its place in the file.
fn located(r: &mut Reporter, path: &Path, text: String, e: FileError) -> u8 {
    let id = r.file(path.display().to_string(), text);
    let span = e.span.map(|(s, t)| Span::new(s, t)).unwrap_or_default();
    r.emit_own(Diagnostic::error(e.code, e.message, span).label("here").in_file(id));
    2
}

/// Reads a file with `parse`; `Err` is the exit status after reporting.
fn read<T>(path: &Path, r: &mut Reporter, parse: impl Fn(&str) -> Result<T, FileError>) -> Result<T, u8> {
    let text = read_input_text(path).map_err(|e| {
        r.unreadable(path, &e);
        2u8
    })?;
    parse(&text).map_err(|e| located(r, path, text, e))
}

/// The command list (`--commands`).
pub fn commands(path: &Path, r: &mut Reporter) -> Result<Vec<Command>, u8> {
    read(path, r, linc_comms::roc::host::commands::parse)
}

/// The initial word table (`--words`), or all zeros.
pub fn words(path: Option<&Path>, r: &mut Reporter) -> Result<Words, u8> {
    match path {
        Some(p) => read(p, r, Words::parse),
        None => Ok(Words::default()),
    }
}

/// Writes the word table with each command's status (`--out`),
/// atomically (the caller has checked that `out` is not an input before
/// polling began).
pub fn write_words(out: &Path, words: &Words, status: &[u16], r: &mut Reporter) -> Result<(), u8> {
    write_atomic(out, words.to_json(Some(status)).as_bytes()).map_err(|e| crate::report::refused(r, e.diagnostic()))
}

//! Standard output: what a command was asked for. Everything printed there
//! goes through here, escaped as the renderer escapes diagnostics — a block
//! name, a string value, a listing or a drawing can hold an escape sequence
//! (from a database, an object or a source), and none may reach the
//! terminal raw. Line ends stay line ends.

use linc_compiler::render::escape_text;
use std::io::Write;

/// Prints `text` as it is (escaped).
pub fn print(text: &str) {
    // A closed standard output ends the process by SIGPIPE (see main); any
    // other failure to write is no reason to panic.
    let _ = std::io::stdout().lock().write_all(escape_text(text).as_bytes());
}

/// Prints `text` and a line end (escaped).
pub fn line(text: &str) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(escape_text(text).as_bytes());
    let _ = out.write_all(b"\n");
}

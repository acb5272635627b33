//! Errors of every stage through the one renderer (`linc_compiler::render`):
//! a `RuntimeError` knows its file, line and column, so it becomes a
//! `Diagnostic` located in that file; loader, linker and I/O errors belong
//! to a whole file and are shown at its start. All print in `human`,
//! `short` or `json` like any front-end error.

use linc_compiler::render::{self, Format, SourceFiles};
use linc_compiler::{Diagnostic, Span};
use linc_runtime::RuntimeError;

/// Byte offset of a 1-based line and column in `text` (clamped).
fn offset(text: &str, line: u32, col: u32) -> usize {
    let start: usize = text.split_inclusive('\n').take((line as usize).saturating_sub(1)).map(str::len).sum();
    (start + (col as usize).saturating_sub(1)).min(text.len())
}

/// Renders a runtime error. When its source can't be read (an object run
/// without its source), the file is stood in for by empty lines so that
/// line and column still print right.
pub fn runtime(e: &RuntimeError, format: Format) -> String {
    let text = crate::files::read_input_text(std::path::Path::new(&e.file))
        .unwrap_or_else(|_| "\n".repeat((e.line as usize).saturating_sub(1)) + &" ".repeat(e.col as usize));
    runtime_in(&e.file, text, e, format)
}

/// Renders a runtime error of a program whose source is `text` (an
/// expression of `linc eval` has no file to read back).
pub fn runtime_in(name: &str, text: String, e: &RuntimeError, format: Format) -> String {
    let at = offset(&text, e.line, e.col);
    let mut files = SourceFiles::new();
    let id = files.add(name.to_string(), text);
    let message = if e.action.is_empty() { e.message.clone() } else { format!("in `{}`: {}", e.action, e.message) };
    let d = Diagnostic::error(e.code, message, Span::new(at, at)).label("the program stopped here").in_file(id);
    render::render(&files, &d, format)
}

/// Renders an error that belongs to a whole file (a damaged object, a link
/// failure, an unreadable input), without reading the file again.
pub fn file_error(file: &str, code: &'static str, message: impl Into<String>, format: Format) -> String {
    let mut files = SourceFiles::new();
    let id = files.add(file.to_string(), String::new());
    render::render(&files, &Diagnostic::error(code, message, Span::new(0, 0)).in_file(id), format)
}

/// Prints a usage problem (exit status 2) in the one shape: a message that
/// starts with its code in brackets (`[E0903] --now …`) becomes
/// `error[E0903]: --now …`; others are `error: …`.
pub fn usage(msg: impl std::fmt::Display) -> u8 {
    let msg = msg.to_string();
    let coded = msg.strip_prefix('[').and_then(|m| m.split_once("] "));
    match coded {
        Some((code, rest)) if code.len() == 5 => eprintln!("error[{code}]: {}", render::escape(rest)),
        _ => eprintln!("error: {}", render::escape(&msg)),
    }
    2
}

//! The one place a command's problems are printed.
//!
//! Every error and warning of every stage — compile diagnostics, a database
//! that does not load, a refused object, a runtime fault, a strategy that
//! can't start, a damaged state file, a refused option — reaches the user
//! as a [`Diagnostic`] through a [`Reporter`], which owns the format
//! (`--message-format human|short|json`) and the stream. Diagnostics go to
//! standard error in every format; standard output carries only what the
//! command was asked for (values, listings, traces, reports, the console's
//! replies), so `linc run … --show X > values.txt` never mixes the two.
//! A reporter can also collect into memory (a scenario prepared on another
//! thread), so that reports come out in a fixed order.

use linc_compiler::diag::render::{self, Format, SourceFiles};
use linc_compiler::{Diagnostic, FileId, Span};
use linc_format::Code;
use linc_runtime::RuntimeError;
use std::io::Write;

enum Sink {
    Stderr,
    Memory(String),
}

/// Renders diagnostics in one format to one stream, and counts errors.
pub struct Reporter {
    format: Format,
    sink: Sink,
    /// Files of problems that were not found by a compile session (a
    /// runtime error's source, a file that could not be read).
    files: SourceFiles,
    errors: usize,
}

impl Reporter {
    /// A reporter that prints to standard error.
    pub fn new(format: Format) -> Reporter {
        Reporter { format, sink: Sink::Stderr, files: SourceFiles::new(), errors: 0 }
    }

    /// A reporter that keeps what it renders, for [`Reporter::take`].
    pub fn in_memory(format: Format) -> Reporter {
        Reporter { format, sink: Sink::Memory(String::new()), files: SourceFiles::new(), errors: 0 }
    }

    pub fn format(&self) -> Format {
        self.format
    }

    /// How many errors (not warnings) were reported.
    pub fn errors(&self) -> usize {
        self.errors
    }

    /// What an in-memory reporter has rendered so far (emptied).
    pub fn take(&mut self) -> String {
        match &mut self.sink {
            Sink::Memory(text) => std::mem::take(text),
            Sink::Stderr => String::new(),
        }
    }

    fn write(&mut self, text: &str) {
        match &mut self.sink {
            // A closed standard error is no reason to stop or panic.
            Sink::Stderr => {
                let _ = std::io::stderr().lock().write_all(text.as_bytes());
            }
            Sink::Memory(buffer) => buffer.push_str(text),
        }
    }

    /// Reports `d`, which points into one of `files`.
    pub fn emit(&mut self, files: &SourceFiles, d: &Diagnostic) {
        if d.is_error() {
            self.errors += 1;
        }
        let text = render::render(files, d, self.format);
        self.write(&text);
    }

    /// Reports every one of `ds`.
    pub fn emit_all<'a>(&mut self, files: &SourceFiles, ds: impl IntoIterator<Item = &'a Diagnostic>) {
        for d in ds {
            self.emit(files, d);
        }
    }

    /// Reports a diagnostic that points into no file or into a file the
    /// reporter added itself ([`Reporter::file`]).
    pub fn emit_own(&mut self, d: Diagnostic) {
        let files = std::mem::take(&mut self.files);
        self.emit(&files, &d);
        self.files = files;
    }

    /// Renders a file-less diagnostic in the reporter's format without
    /// writing it, for a transcript that keeps its replies and refusals in
    /// order on one stream (the console's); counted like any other.
    pub fn text(&mut self, d: Diagnostic) -> String {
        if d.is_error() {
            self.errors += 1;
        }
        render::render(&self.files, &d, self.format)
    }

    /// Adds a file the reporter's own diagnostics may point into.
    pub fn file(&mut self, name: impl Into<String>, text: String) -> FileId {
        self.files.add(name.into(), text)
    }

    /// Reports an error about the command itself (E0903, E0904 …).
    pub fn command(&mut self, code: Code, message: impl Into<String>) {
        self.emit_own(Diagnostic::command(code, message));
    }

    /// Reports an error that belongs to a whole file (an unreadable input,
    /// a damaged object), shown against the file's name without a snippet.
    pub fn whole_file(&mut self, file: &str, code: Code, message: impl Into<String>) {
        let id = self.file(file, String::new());
        self.emit_own(Diagnostic::error(code, message, Span::new(0, 0)).in_file(id));
    }

    /// Reports that `path` could not be read (E0900).
    pub fn unreadable(&mut self, path: &std::path::Path, e: &std::io::Error) {
        let name = path.display().to_string();
        self.whole_file(&name, Code::E0900, format!("can't read `{name}`: {e}"));
    }

    /// Reports a runtime fault at its place in its source. When the source
    /// can't be read (an object run without it), line and column still
    /// print right, against empty lines.
    pub fn runtime(&mut self, e: &RuntimeError) {
        let text = crate::files::read_input_text(std::path::Path::new(&e.file))
            .unwrap_or_else(|_| "\n".repeat((e.line as usize).saturating_sub(1)) + &" ".repeat(e.col as usize));
        self.runtime_in(&e.file, text, e);
    }

    /// A runtime fault rendered for a transcript (the console's), located
    /// in its source like [`Reporter::runtime`], not written.
    pub fn runtime_text(&mut self, e: &RuntimeError) -> String {
        let memory = std::mem::replace(&mut self.sink, Sink::Memory(String::new()));
        self.runtime(e);
        let text = self.take();
        self.sink = memory;
        text
    }

    /// Reports a runtime fault of a program whose source is `text` (an
    /// expression of `linc eval` has no file to read back).
    pub fn runtime_in(&mut self, name: &str, text: String, e: &RuntimeError) {
        let at = offset(&text, e.line, e.col);
        let id = self.file(name, text);
        let message = if e.action.is_empty() { e.message.clone() } else { format!("in `{}`: {}", e.action, e.message) };
        let d = Diagnostic::error(e.code, message, Span::new(at, at)).label("the program stopped here").in_file(id);
        self.emit_own(d);
    }
}

/// Reports a refused option or argument (E0903) and gives exit status 2.
pub fn usage(r: &mut Reporter, msg: impl std::fmt::Display) -> u8 {
    r.command(Code::E0903, msg.to_string());
    2
}

/// Reports a diagnostic about the command or one of its files (E0902,
/// E0904 …) and gives exit status 2.
pub fn refused(r: &mut Reporter, d: Diagnostic) -> u8 {
    r.emit_own(d);
    2
}

/// Byte offset of a 1-based line and column in `text` (clamped).
fn offset(text: &str, line: u32, col: u32) -> usize {
    let start: usize = text.split_inclusive('\n').take((line as usize).saturating_sub(1)).map(str::len).sum();
    (start + (col as usize).saturating_sub(1)).min(text.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn command_errors_have_no_location_in_any_format() {
        let mut r = Reporter::in_memory(Format::Short);
        r.command(Code::E0903, "--for `0s`: the duration must be more than 0");
        assert_eq!(r.take(), "error[E0903]: --for `0s`: the duration must be more than 0\n");
        let mut r = Reporter::in_memory(Format::Json);
        r.command(Code::E0903, "bad");
        let v: serde_json::Value = serde_json::from_str(r.take().trim()).expect("one JSON object");
        assert_eq!(v["code"], "E0903");
        assert_eq!(v["file"], serde_json::Value::Null);
        assert_eq!(v["message"], "bad");
        let mut r = Reporter::in_memory(Format::Human);
        r.command(Code::E0903, "bad\u{1b}[2J");
        let text = r.take();
        assert!(text.starts_with("error[E0903]: bad\\u{1b}[2J"), "{text}");
        assert_eq!(r.errors(), 1);
    }

    #[test]
    fn runtime_errors_point_at_their_line_and_column() {
        let mut r = Reporter::in_memory(Format::Short);
        let e = RuntimeError {
            code: Code::R0001,
            message: "division by zero".into(),
            action: "fault".into(),
            file: "rt.st".into(),
            line: 2,
            col: 3,
        };
        r.runtime_in("rt.st", "a := 1;\nb := a / 0;\n".into(), &e);
        assert_eq!(r.take(), "rt.st:2:3: error[R0001]: in `fault`: division by zero\n");
    }
}

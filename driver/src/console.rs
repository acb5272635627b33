//! A console session over a plant (`linc console`, `linc serve --console`):
//! the plant built by [`crate::plant`], console lines run on it with their
//! trace and `SAVE`, and what each line said returned as data — replies,
//! and refused commands and runtime faults as problems — for the caller to
//! render in order. Reading lines is bounded ([`bounded_lines`]).

use crate::plant::{Plant, PlantSpec};
use linc_compiler::diag::{Diagnostic, Problems};
use linc_engines::console::{Console, ConsoleError};
use linc_engines::strategy::trace::Trace;
use linc_format::Code;
use std::path::PathBuf;

/// The longest command line the console reads (its commands are short; a
/// line without an end, piped in by mistake, must not grow without bound).
pub const MAX_LINE: usize = 4096;

/// A line the console reads: its text, or how long it was when too long.
pub type ReadLine = Result<String, usize>;

/// What a console line said, in order.
pub enum Said {
    /// A command's reply (never empty).
    Reply(String),
    /// A refused command (a C code) or a runtime fault of a scan the line
    /// ran, or a state that could not be saved.
    Problem(Problems),
}

/// A running console with its trace and state file.
pub struct Session {
    pub console: Console,
    trace: Option<Trace<'static>>,
    trace_name: String,
    state: Option<PathBuf>,
    /// Whether every command so far succeeded.
    ok: bool,
}

impl Session {
    /// Builds the plant `spec` describes (a strategy) and a console over
    /// it, tracing to `trace` (a file; standard output holds the replies).
    /// The plant's warnings come back with it.
    pub fn start(spec: &PlantSpec, trace: Option<PathBuf>) -> Result<(Session, Problems), Problems> {
        if trace.as_ref().is_some_and(|p| p.as_os_str() == "-") {
            return Err(crate::database::usage(
                "--trace of the console takes a FILE (standard output holds the replies)",
            ));
        }
        let mut plant = crate::plant::build(spec)?;
        let warnings = std::mem::take(&mut plant.warnings);
        let state = spec.state.as_ref().map(|s| s.path.clone());
        let session = Session::over(plant, trace, state)?;
        Ok((session, warnings))
    }

    /// A console over a plant built already.
    pub fn over(plant: Plant, trace: Option<PathBuf>, state: Option<PathBuf>) -> Result<Session, Problems> {
        let Some(strategy) = plant.into_strategy() else {
            return Err(crate::database::usage("the console runs a strategy"));
        };
        let mut console = Console::new(strategy);
        console.can_save = state.is_some();
        let trace_name = trace.as_ref().map(|p| p.display().to_string()).unwrap_or_default();
        let trace = match &trace {
            Some(path) => Some(Trace::new(crate::run::trace_file(path)?, &console.strategy.store)),
            None => None,
        };
        Ok(Session { console, trace, trace_name, state, ok: true })
    }

    /// Runs one line: each command's reply or refusal, then the runtime
    /// faults of the scans it ran (not command failures), then a `SAVE`
    /// that could not be written.
    pub fn line(&mut self, text: &str) -> Vec<Said> {
        let mut said = Vec::new();
        for reply in self.console.execute_traced(text, self.trace.as_mut()) {
            match reply {
                Ok(reply) if reply.is_empty() => {}
                Ok(reply) => said.push(Said::Reply(reply)),
                Err(e) => {
                    self.ok = false;
                    said.push(Said::Problem(refused(&e)));
                }
            }
        }
        for e in self.console.take_failures() {
            said.push(Said::Problem(crate::run::fault(&e)));
        }
        // SAVE took the state; it is written here, atomically.
        if let (Some(bytes), Some(path)) = (self.console.take_saved(), &self.state) {
            if let Err(e) = crate::files::write_atomic(path, &bytes) {
                self.ok = false;
                said.push(Said::Problem(e.into()));
            }
        }
        said
    }

    /// A line longer than [`MAX_LINE`] (C0002).
    pub fn too_long(&mut self, length: usize) -> Said {
        self.ok = false;
        let why = format!("a console line is at most {MAX_LINE} bytes; this one has {length}");
        Said::Problem(refused(&ConsoleError { code: Code::C0002, message: why }))
    }

    /// Whether every command so far succeeded.
    pub fn ok(&self) -> bool {
        self.ok
    }

    /// Commits the trace and saves the state (as on `SAVE`).
    pub fn finish(self) -> Result<(), Problems> {
        if let Some(Err(e)) = self.trace.map(Trace::finish) {
            let name = &self.trace_name;
            return Err(Problems::usage(Code::E0900, format!("can't write the trace `{name}`: {e}")));
        }
        match &self.state {
            Some(path) => crate::plant::save_state(path, &self.console.strategy),
            None => Ok(()),
        }
    }
}

/// A refused console command, as a problem about the command.
pub fn refused(e: &ConsoleError) -> Problems {
    Problems::finding(Diagnostic::command(e.code, e.message.clone()))
}

/// Whether a script line holds no command: blank, `#` or `(*` comments.
pub fn skipped(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#') || t.starts_with("(*")
}

/// Whether a line ends the session.
pub fn is_quit(line: &str) -> bool {
    matches!(line.trim().to_ascii_uppercase().as_str(), "QUIT" | "EXIT")
}

/// Lines of `input`, each at most [`MAX_LINE`] bytes; the rest of a longer
/// line is read and dropped without being kept. Bytes that are not UTF-8
/// are replaced (the command is then refused as written wrongly).
pub fn bounded_lines(mut input: impl std::io::BufRead) -> impl Iterator<Item = ReadLine> {
    std::iter::from_fn(move || {
        let mut kept: Vec<u8> = Vec::new();
        let mut length = 0usize;
        loop {
            let buf = match input.fill_buf() {
                Ok(b) => b,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
                Err(_) => return None,
            };
            if buf.is_empty() {
                return (length > 0).then(|| finish(kept, length));
            }
            let (chunk, end) = match buf.iter().position(|&b| b == b'\n') {
                Some(at) => (&buf[..at], Some(at + 1)),
                None => (buf, None),
            };
            let room = (MAX_LINE + 1).saturating_sub(kept.len());
            kept.extend_from_slice(&chunk[..chunk.len().min(room)]);
            length += chunk.len();
            let used = end.unwrap_or(buf.len());
            input.consume(used);
            if end.is_some() {
                return Some(finish(kept, length));
            }
        }
    })
}

fn finish(mut kept: Vec<u8>, length: usize) -> ReadLine {
    if length > MAX_LINE {
        return Err(length);
    }
    if kept.last() == Some(&b'\r') {
        kept.pop();
    }
    Ok(String::from_utf8_lossy(&kept).into_owned())
}

//! `linc console PLANT.json`: a command line over a running strategy. The
//! runtime's console executes commands; this reads lines (interactively
//! with line editing and history, or from a script) and prints replies.

use crate::run_cmd::Common;
use crate::strategy_cmd::{self, Options as StrategyOptions};
use linc_driver::Reporter;
use linc_engines::console::{Console, ConsoleError};
use linc_engines::strategy::trace::Trace;
use linc_format::Code;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};

pub struct Options {
    pub db: PathBuf,
    pub script: Option<PathBuf>,
    pub common: Common,
    /// `--state FILE [--cold]`: warm start from FILE, saved on SAVE and at the end.
    pub retain: strategy_cmd::Retain,
}

/// Whether a script line holds no command: blank, `#` or `(*` comments.
fn skipped(line: &str) -> bool {
    let t = line.trim();
    t.is_empty() || t.starts_with('#') || t.starts_with("(*")
}

fn is_quit(line: &str) -> bool {
    matches!(line.trim().to_ascii_uppercase().as_str(), "QUIT" | "EXIT")
}

/// The longest command line the console reads (its commands are short; a
/// line without an end, piped in by mistake, must not grow without bound).
pub const MAX_LINE: usize = 4096;

/// A line the console reads: its text, or how long it was when too long.
type ReadLine = Result<String, usize>;

/// Lines of `input`, each at most [`MAX_LINE`] bytes; the rest of a longer
/// line is read and dropped without being kept. Bytes that are not UTF-8
/// are replaced (the command is then refused as written wrongly).
pub(crate) fn bounded_lines(mut input: impl std::io::BufRead) -> impl Iterator<Item = ReadLine> {
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

/// A refused command, as the reporter renders it, for the transcript on
/// standard output between the replies it follows.
pub(crate) fn error_text(e: &ConsoleError, r: &mut Reporter) -> String {
    r.text(linc_compiler::Diagnostic::command(e.code, e.message.clone())).trim_end().to_string()
}

/// Prints one command's reply, or its refusal as the reporter renders it
/// (also for `linc serve --console`); `true` if the command succeeded.
pub(crate) fn print_reply(reply: Result<String, ConsoleError>, r: &mut Reporter) -> bool {
    match reply {
        Ok(reply) if reply.is_empty() => true,
        Ok(reply) => {
            crate::out::line(&reply);
            true
        }
        Err(e) => {
            crate::out::line(&error_text(&e, r));
            false
        }
    }
}

/// Runs one line and prints its replies; `true` if every command succeeded.
fn line(console: &mut Console, text: &str, r: &mut Reporter, trace: Option<&mut Trace>, state: Option<&Path>) -> bool {
    let mut ok = true;
    for reply in console.execute_traced(text, trace) {
        ok &= print_reply(reply, r);
    }
    // Runtime errors of the scans a command ran follow its reply, rendered
    // like any runtime error; they are not command failures.
    for e in console.take_failures() {
        crate::out::line(r.runtime_text(&e).trim_end());
    }
    // SAVE took the state; it is written here, atomically.
    if let (Some(bytes), Some(path)) = (console.take_saved(), state) {
        if let Err(e) = linc_driver::files::write_atomic(path, &bytes) {
            crate::out::line(r.text(e.diagnostic()).trim_end());
            ok = false;
        }
    }
    ok
}

pub fn run(o: Options, r: &mut Reporter) -> u8 {
    if o.common.trace.as_ref().is_some_and(|p| p.as_os_str() == "-") {
        return crate::report::usage(r, "--trace of the console takes a FILE (standard output holds the replies)");
    }
    let trace_path = o.common.trace.clone();
    let state = o.retain.state.clone();
    let so = StrategyOptions {
        db: o.db,
        duration: String::new(),
        common: o.common,
        single: None,
        retain: o.retain,
        script: o.script.clone(),
    };
    let mut strategy = match strategy_cmd::load(&so, r) {
        Ok(s) => s,
        Err(status) => return status,
    };
    if let Some(path) = &state {
        if let Err(status) = linc_driver::state::warm_start(path, so.retain.cold, &mut strategy, r) {
            return status;
        }
    }
    let mut console = Console::new(strategy);
    console.can_save = state.is_some();
    let mut sink = match strategy_cmd::trace_sink(trace_path.as_deref(), r) {
        Ok(s) => s,
        Err(status) => return status,
    };
    let mut trace = sink.as_mut().map(|w| Trace::new(w.as_mut(), &console.strategy.store));
    let status = match &o.script {
        Some(p) => match linc_driver::files::read_input(p) {
            Ok(bytes) => script(&mut console, bounded_lines(bytes.as_slice()), r, trace.as_mut(), state.as_deref()),
            Err(e) => {
                r.unreadable(p, &e);
                return 2;
            }
        },
        None if std::io::stdin().is_terminal() => interactive(&mut console, r, trace.as_mut(), state.as_deref()),
        None => script(&mut console, bounded_lines(std::io::stdin().lock()), r, trace.as_mut(), state.as_deref()),
    };
    let traced = trace.map(Trace::finish);
    drop(sink);
    if let Some(Err(e)) = traced {
        return strategy_cmd::trace_unwritten(trace_path.as_deref(), &e, r);
    }
    // The state is kept at the end as on SAVE.
    if let Some(path) = &state {
        if let Err(status) = linc_driver::state::save(path, &console.strategy, r) {
            return status;
        }
    }
    status
}

/// Runs every line; the exit status: 1 if a command was refused.
fn script(
    console: &mut Console,
    lines: impl Iterator<Item = ReadLine>,
    r: &mut Reporter,
    mut trace: Option<&mut Trace>,
    state: Option<&Path>,
) -> u8 {
    let mut ok = true;
    for l in lines {
        let l = match l {
            Ok(l) => l,
            Err(length) => {
                let why = format!("a console line is at most {MAX_LINE} bytes; this one has {length}");
                crate::out::line(&error_text(&ConsoleError { code: Code::C0002, message: why }, r));
                ok = false;
                continue;
            }
        };
        if skipped(&l) {
            continue;
        }
        if is_quit(&l) {
            break;
        }
        ok &= line(console, &l, r, trace.as_deref_mut(), state);
    }
    u8::from(!ok)
}

/// The prompt `linc> ` with line editing and history (rustyline).
fn interactive(console: &mut Console, r: &mut Reporter, mut trace: Option<&mut Trace>, state: Option<&Path>) -> u8 {
    let mut editor = match rustyline::DefaultEditor::new() {
        Ok(e) => e,
        Err(e) => {
            r.command(Code::E0900, format!("can't open the terminal: {e}"));
            return 2;
        }
    };
    while let Ok(l) = editor.readline("linc> ") {
        if skipped(&l) {
            continue;
        }
        if is_quit(&l) {
            break;
        }
        let _ = editor.add_history_entry(l.as_str());
        line(console, &l, r, trace.as_deref_mut(), state);
    }
    0
}

//! `linc console PLANT.json`: a command line over a running strategy. The
//! runtime's console executes commands; this reads lines (interactively
//! with line editing and history, or from a script) and prints replies.

use crate::run_cmd::Common;
use crate::strategy_cmd::{self, Options as StrategyOptions};
use linc_compiler::render::Format;
use linc_runtime::console::{Console, ConsoleError};
use linc_runtime::strategy::trace::Trace;
use std::io::{BufRead, IsTerminal};
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

/// An error reply, on standard output between the replies it follows.
fn error_text(e: &ConsoleError, format: Format) -> String {
    match format {
        Format::Json => serde_json::json!({ "severity": "error", "code": e.code, "message": e.message }).to_string(),
        _ => format!("error[{}]: {}", e.code, linc_compiler::render::escape(&e.message)),
    }
}

/// Runs one line and prints its replies; `true` if every command succeeded.
fn line(console: &mut Console, text: &str, format: Format, trace: Option<&mut Trace>, state: Option<&Path>) -> bool {
    let mut ok = true;
    for reply in console.execute_traced(text, trace) {
        match reply {
            Ok(r) if r.is_empty() => {}
            Ok(r) => println!("{r}"),
            Err(e) => {
                ok = false;
                println!("{}", error_text(&e, format));
            }
        }
    }
    // Runtime errors are shown in the ADVANCE/SCAN reply; they are not
    // command failures.
    console.take_failures();
    // SAVE took the state; it is written here, atomically.
    if let (Some(bytes), Some(path)) = (console.take_saved(), state) {
        if let Err(e) = crate::files::write_atomic(path, &bytes) {
            println!("error[E0900]: {e}");
            ok = false;
        }
    }
    ok
}

pub fn run(o: Options) -> u8 {
    let format = o.common.format;
    if o.common.trace.as_ref().is_some_and(|p| p.as_os_str() == "-") {
        return crate::report::usage("--trace of the console takes a FILE (standard output holds the replies)");
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
    let mut strategy = match strategy_cmd::load(&so) {
        Ok(s) => s,
        Err(status) => return status,
    };
    if let Some(path) = &state {
        if let Err(status) = crate::state_file::warm_start(path, so.retain.cold, &mut strategy) {
            return status;
        }
    }
    let mut console = Console::new(strategy);
    console.can_save = state.is_some();
    let mut sink = match strategy_cmd::trace_sink(trace_path.as_deref()) {
        Ok(s) => s,
        Err(status) => return status,
    };
    let mut trace = sink.as_mut().map(|w| Trace::new(w.as_mut(), &console.strategy.store));
    let status = match &o.script {
        Some(p) => match crate::files::read_input_text(p) {
            Ok(text) => {
                script(&mut console, text.lines().map(str::to_string), format, trace.as_mut(), state.as_deref())
            }
            Err(e) => {
                eprintln!("error[E0900]: can't read `{}`: {e}", p.display());
                return 2;
            }
        },
        None if std::io::stdin().is_terminal() => interactive(&mut console, format, trace.as_mut(), state.as_deref()),
        None => {
            let lines = std::io::stdin().lock().lines().map_while(Result::ok);
            script(&mut console, lines, format, trace.as_mut(), state.as_deref())
        }
    };
    let traced = trace.map(Trace::finish);
    drop(sink);
    if let Some(Err(e)) = traced {
        eprintln!("error[E0900]: can't write the trace: {e}");
        return 2;
    }
    // The state is kept at the end as on SAVE.
    if let Some(path) = &state {
        if let Err(status) = crate::state_file::save(path, &console.strategy) {
            return status;
        }
    }
    status
}

/// Runs every line; the exit status: 1 if a command was refused.
fn script(
    console: &mut Console,
    lines: impl Iterator<Item = String>,
    format: Format,
    mut trace: Option<&mut Trace>,
    state: Option<&Path>,
) -> u8 {
    let mut ok = true;
    for l in lines {
        if skipped(&l) {
            continue;
        }
        if is_quit(&l) {
            break;
        }
        ok &= line(console, &l, format, trace.as_deref_mut(), state);
    }
    u8::from(!ok)
}

/// The prompt `linc> ` with line editing and history (rustyline).
fn interactive(console: &mut Console, format: Format, mut trace: Option<&mut Trace>, state: Option<&Path>) -> u8 {
    let mut editor = match rustyline::DefaultEditor::new() {
        Ok(e) => e,
        Err(e) => {
            eprintln!("error[E0900]: can't open the terminal: {e}");
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
        line(console, &l, format, trace.as_deref_mut(), state);
    }
    0
}

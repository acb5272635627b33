//! `linc console PLANT.json`: a command line over a running strategy. The
//! driver's console session runs the lines; this reads them (interactively
//! with line editing and history, or from a script) and prints what each
//! said, refusals and faults rendered in the transcript.

use crate::report::Reporter;
use linc_driver::console::{bounded_lines, is_quit, skipped, ReadLine, Said, Session};
use linc_driver::plant::PlantSpec;
use linc_format::Code;
use std::io::IsTerminal;
use std::path::PathBuf;

pub struct Options {
    pub spec: PlantSpec,
    pub script: Option<PathBuf>,
    pub trace: Option<PathBuf>,
}

/// Prints what one line said, in order; refusals and faults as the
/// reporter renders them, on standard output between the replies.
pub fn print_said(said: Vec<Said>, r: &Reporter) {
    for s in said {
        match s {
            Said::Reply(reply) => crate::out::line(&reply),
            Said::Problem(p) => crate::out::line(r.text(&p).trim_end()),
        }
    }
}

pub fn run(o: Options, r: &Reporter) -> u8 {
    let mut spec = o.spec;
    spec.inputs.extend(o.script.clone());
    let outputs = [("--trace", &o.trace), ("--state", &spec.state.as_ref().map(|s| s.path.clone()))];
    spec.outputs = outputs.iter().filter_map(|(f, p)| Some((f.to_string(), (*p).clone()?))).collect();
    let mut session = match Session::start(&spec, o.trace.clone()) {
        Ok((session, warnings)) => {
            r.report(&warnings);
            session
        }
        Err(p) => return r.report(&p),
    };
    let status = match &o.script {
        Some(p) => match linc_driver::files::read_input(p) {
            Ok(bytes) => script(&mut session, bounded_lines(bytes.as_slice()), r),
            Err(e) => return r.report(&linc_driver::Problems::unreadable(p, &e)),
        },
        None if std::io::stdin().is_terminal() => interactive(&mut session, r),
        None => script(&mut session, bounded_lines(std::io::stdin().lock()), r),
    };
    // The trace is committed and the state kept at the end as on SAVE.
    match session.finish() {
        Ok(()) => status,
        Err(p) => r.report(&p),
    }
}

/// Runs every line; the exit status: 1 if a command was refused.
fn script(session: &mut Session, lines: impl Iterator<Item = ReadLine>, r: &Reporter) -> u8 {
    for l in lines {
        let l = match l {
            Ok(l) => l,
            Err(length) => {
                print_said(vec![session.too_long(length)], r);
                continue;
            }
        };
        if skipped(&l) {
            continue;
        }
        if is_quit(&l) {
            break;
        }
        print_said(session.line(&l), r);
    }
    u8::from(!session.ok())
}

/// The prompt `linc> ` with line editing and history (rustyline). Refused
/// commands do not make an interactive session fail; a terminal that can't
/// be opened does.
fn interactive(session: &mut Session, r: &Reporter) -> u8 {
    let mut editor = match rustyline::DefaultEditor::new() {
        Ok(e) => e,
        Err(e) => {
            let p = linc_driver::Problems::usage(Code::E0900, format!("can't open the terminal: {e}"));
            return r.report(&p);
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
        print_said(session.line(&l), r);
    }
    0
}

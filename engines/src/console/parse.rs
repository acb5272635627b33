//! The console's command language: one command's text to a [`Command`].
//! Verbs are case-insensitive, with short forms in the spirit of a PLC
//! kernel's command interpreter (`D`, `M`, `F`, `P?`) and long forms that
//! read well in scripts (`DISPLAY`, `MODIFY`, `FORCE`, `PROGRAMS`).

use super::ConsoleError;
use crate::strategy::ProgramState;
use linc_format::Code;

/// An SFC_CON command, applied through the block's fields.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SeqControl {
    Reset,
    Stop,
    Hold,
    Run,
}

/// A transition forced by the monitor: held, fired when enabled, or normal.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TransForce {
    Hold,
    Continue,
    Normal,
}

/// One parsed command.
#[derive(Clone, Debug, PartialEq)]
pub enum Command {
    /// Fields; one ending in `-` is a range of 16 fields from it.
    Display(Vec<String>),
    Modify {
        path: String,
        value: String,
    },
    /// `None` releases the force.
    Force {
        path: String,
        value: Option<String>,
    },
    Forces,
    Programs,
    Program {
        block: String,
        state: ProgramState,
    },
    Sequence {
        block: String,
        control: SeqControl,
    },
    HoldStep {
        block: String,
        step: String,
        hold: bool,
    },
    ForceTrans {
        block: String,
        transition: String,
        force: TransForce,
    },
    Advance(u64),
    Scan,
    Now,
    /// Keep the retentive state now (the state file of `--state`).
    Save,
    ErrorShow,
    ErrorClear,
    ErrorRaise {
        code: String,
        block: Option<String>,
    },
}

impl Command {
    /// Whether the command only reads: a monitor that may not write (`linc
    /// serve` without `--allow-writes`) runs these and refuses the rest.
    pub fn reads_only(&self) -> bool {
        matches!(self, Command::Display(_) | Command::Forces | Command::Programs | Command::Now | Command::ErrorShow)
    }
}

/// Splits the verb from its arguments at the first space.
fn verb(text: &str) -> (String, &str) {
    let t = text.trim();
    match t.split_once(char::is_whitespace) {
        Some((v, rest)) => (v.to_ascii_uppercase(), rest.trim()),
        None => (t.to_ascii_uppercase(), ""),
    }
}

fn usage(form: &str) -> ConsoleError {
    ConsoleError::new(Code::C0002, format!("expected `{form}`"))
}

/// `PATH=VALUE`, or `PATH VALUE` when the path has no `=`.
fn assignment(args: &str, form: &str) -> Result<(String, String), ConsoleError> {
    let (p, v) = args.split_once('=').ok_or_else(|| usage(form))?;
    let (p, v) = (p.trim(), v.trim());
    if p.is_empty() || v.is_empty() {
        return Err(usage(form));
    }
    if let Some(q) = v.chars().next().filter(|c| matches!(c, '\'' | '"')) {
        if v.len() < 2 || !v.ends_with(q) {
            let why = format!("the text {v} has no closing {q}: a quoted value ends with the quote it starts with");
            return Err(ConsoleError::new(Code::C0002, why));
        }
    }
    Ok((p.to_string(), v.to_string()))
}

/// Exactly `n` space-separated words (block names with spaces are not
/// allowed here: sequence and action blocks are LIN names).
fn words<'a>(args: &'a str, n: usize, form: &str) -> Result<Vec<&'a str>, ConsoleError> {
    let w: Vec<&str> = args.split_whitespace().collect();
    if w.len() == n {
        Ok(w)
    } else {
        Err(usage(form))
    }
}

/// One program's block: everything after the verb (an FST point's name
/// has a space, `FST 1`).
fn block(args: &str, form: &str) -> Result<String, ConsoleError> {
    if args.is_empty() {
        return Err(usage(form));
    }
    Ok(args.to_string())
}

/// Parses one command (no `;`). `duration` turns `10s` into µs.
pub fn parse(text: &str, duration: &dyn Fn(&str) -> Result<u64, String>) -> Result<Command, ConsoleError> {
    let (v, args) = verb(text);
    let state = |s| Ok(Command::Program { block: block(args, &format!("{v} BLOCK"))?, state: s });
    let seq = |c| Ok(Command::Sequence { block: block(args, &format!("{v} SFC_BLOCK"))?, control: c });
    match v.as_str() {
        "D" | "DISPLAY" => {
            let paths: Vec<String> = args.split(',').map(|p| p.trim().to_string()).collect();
            if paths.iter().any(String::is_empty) {
                return Err(usage("D BLOCK.FIELD[, BLOCK.FIELD…]"));
            }
            Ok(Command::Display(paths))
        }
        "M" | "MODIFY" => {
            let (path, value) = assignment(args, "M BLOCK.FIELD=VALUE")?;
            Ok(Command::Modify { path, value })
        }
        "F?" | "FORCES" if args.is_empty() => Ok(Command::Forces),
        "F" | "FORCE" => force(args),
        "P?" | "PROGRAMS" if args.is_empty() => Ok(Command::Programs),
        "START" | "PSTART" => state(ProgramState::Running),
        "SUSPEND" | "PSUSPEND" => state(ProgramState::Suspended),
        "PSTOP" => state(ProgramState::Inactive),
        "STOP" => Ok(Command::Sequence { block: block(args, "STOP BLOCK")?, control: SeqControl::Stop }),
        "RESET" => seq(SeqControl::Reset),
        "HOLD" => seq(SeqControl::Hold),
        "RUN" => seq(SeqControl::Run),
        "HOLDSTEP" | "RELEASESTEP" => {
            let w = words(args, 2, &format!("{v} SFC_BLOCK STEP"))?;
            Ok(Command::HoldStep { block: w[0].to_string(), step: w[1].to_string(), hold: v == "HOLDSTEP" })
        }
        "FORCETRANS" => {
            let w = words(args, 3, "FORCETRANS SFC_BLOCK TRANSITION HOLD|CONTINUE|NORMAL")?;
            let force = match w[2].to_ascii_uppercase().as_str() {
                "HOLD" => TransForce::Hold,
                "CONTINUE" => TransForce::Continue,
                "NORMAL" => TransForce::Normal,
                _ => return Err(usage("FORCETRANS SFC_BLOCK TRANSITION HOLD|CONTINUE|NORMAL")),
            };
            Ok(Command::ForceTrans { block: w[0].to_string(), transition: w[1].to_string(), force })
        }
        "ADVANCE" => {
            let d = duration(args).map_err(|why| ConsoleError::new(Code::C0008, why))?;
            Ok(Command::Advance(d))
        }
        "SCAN" if args.is_empty() => Ok(Command::Scan),
        "NOW" if args.is_empty() => Ok(Command::Now),
        "SAVE" if args.is_empty() => Ok(Command::Save),
        "ERR?" | "ERROR" if args.is_empty() => Ok(Command::ErrorShow),
        "ERRCLR" | "CLEARERROR" if args.is_empty() => Ok(Command::ErrorClear),
        "ERRRAISE" | "RAISE" => {
            let (code, rest) = verb(args);
            if code.is_empty() {
                return Err(usage("ERRRAISE CODE [BLOCK]"));
            }
            Ok(Command::ErrorRaise { code, block: (!rest.is_empty()).then(|| rest.to_string()) })
        }
        "QUIT" | "EXIT" if args.is_empty() => Err(ConsoleError::new(
            Code::C0001,
            format!("`{v}` ends an interactive `linc console`; it is not a command of a served plant or a scenario"),
        )),
        "F?" | "FORCES" | "P?" | "PROGRAMS" | "SCAN" | "NOW" | "SAVE" | "ERR?" | "ERROR" | "ERRCLR" | "CLEARERROR"
        | "QUIT" | "EXIT" => Err(ConsoleError::new(Code::C0002, format!("`{v}` takes no arguments"))),
        _ => Err(ConsoleError::new(Code::C0001, format!("unknown command `{v}`"))),
    }
}

/// `F PATH=VALUE`, `F PATH=N` (release) or `F PATH OFF` (release).
fn force(args: &str) -> Result<Command, ConsoleError> {
    let form = "F BLOCK.FIELD=VALUE, F BLOCK.FIELD=N or FORCE BLOCK.FIELD OFF";
    if let Some(path) = args.strip_suffix(" OFF").or_else(|| args.strip_suffix(" off")) {
        return Ok(Command::Force { path: path.trim().to_string(), value: None });
    }
    let (path, value) = assignment(args, form)?;
    let value = (!value.eq_ignore_ascii_case("N")).then_some(value);
    Ok(Command::Force { path, value })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn secs(t: &str) -> Result<u64, String> {
        t.strip_suffix('s').and_then(|n| n.parse::<u64>().ok()).map(|n| n * 1_000_000).ok_or_else(|| "bad".into())
    }

    fn p(t: &str) -> Result<Command, ConsoleError> {
        parse(t, &secs)
    }

    #[test]
    fn short_and_long_forms_are_the_same_command() {
        assert_eq!(p("d PIC1.PV, REC1.A0-"), p("DISPLAY PIC1.PV,REC1.A0-"));
        assert_eq!(p("D PIC1.PV, REC1.A0-"), Ok(Command::Display(vec!["PIC1.PV".into(), "REC1.A0-".into()])));
        assert_eq!(p("m PIC1.SL = 5.0"), Ok(Command::Modify { path: "PIC1.SL".into(), value: "5.0".into() }));
        assert_eq!(p("P?"), p("programs"));
        assert_eq!(p("ERR?"), Ok(Command::ErrorShow));
        assert_eq!(p("clearerror"), Ok(Command::ErrorClear));
    }

    #[test]
    fn quit_with_words_after_it_and_unclosed_quotes_are_written_wrongly() {
        let code = |t: &str| p(t).map_err(|e| (e.code, e.message)).unwrap_err();
        let (c, m) = code("QUIT now");
        assert_eq!((c, m.as_str()), (Code::C0002, "`QUIT` takes no arguments"));
        assert_eq!(code("exit 1").0, Code::C0002);
        assert!(code("QUIT").1.contains("interactive"), "QUIT alone, where it does not end anything");
        for t in ["M X.S='unterminated", "M X.S=\"open", "M X.S='", "F X.S='a\""] {
            let (c, m) = code(t);
            assert_eq!(c, Code::C0002, "{t}");
            assert!(m.contains("no closing"), "{t}: {m}");
        }
        assert_eq!(p("M X.S='a;b'"), Ok(Command::Modify { path: "X.S".into(), value: "'a;b'".into() }));
    }

    #[test]
    fn forces_set_and_release() {
        assert_eq!(p("F DIG1.In=1"), Ok(Command::Force { path: "DIG1.In".into(), value: Some("1".into()) }));
        assert_eq!(p("F DIG1.In=n"), Ok(Command::Force { path: "DIG1.In".into(), value: None }));
        assert_eq!(p("FORCE AIN 2-1.EU OFF"), Ok(Command::Force { path: "AIN 2-1.EU".into(), value: None }));
        assert_eq!(p("F?"), Ok(Command::Forces));
    }

    #[test]
    fn programs_and_sequences() {
        let block = "FST 1".to_string();
        assert_eq!(p("start FST 1"), Ok(Command::Program { block: block.clone(), state: ProgramState::Running }));
        assert_eq!(p("PSTOP FST 1"), Ok(Command::Program { block, state: ProgramState::Inactive }));
        assert_eq!(p("hold SFC1"), Ok(Command::Sequence { block: "SFC1".into(), control: SeqControl::Hold }));
        assert_eq!(
            p("FORCETRANS SFC1 T1 continue"),
            Ok(Command::ForceTrans { block: "SFC1".into(), transition: "T1".into(), force: TransForce::Continue })
        );
        assert_eq!(
            p("RELEASESTEP SFC1 Fill"),
            Ok(Command::HoldStep { block: "SFC1".into(), step: "Fill".into(), hold: false })
        );
    }

    #[test]
    fn time_and_errors() {
        assert_eq!(p("ADVANCE 10s"), Ok(Command::Advance(10_000_000)));
        assert_eq!(p("advance soon").map_err(|e| e.code.as_str()), Err("C0008"));
        assert_eq!(p("RAISE R0001 PUMP"), Ok(Command::ErrorRaise { code: "R0001".into(), block: Some("PUMP".into()) }));
    }

    #[test]
    fn mistakes_have_codes() {
        assert_eq!(p("FROB X").map_err(|e| e.code.as_str()), Err("C0001"));
        assert_eq!(p("M PIC1.SL").map_err(|e| e.code.as_str()), Err("C0002"));
        assert_eq!(p("D ").map_err(|e| e.code.as_str()), Err("C0002"));
        assert_eq!(p("NOW later").map_err(|e| e.code.as_str()), Err("C0002"));
        assert_eq!(p("FORCETRANS SFC1 T1 maybe").map_err(|e| e.code.as_str()), Err("C0002"));
        assert_eq!(p("START").map_err(|e| e.code.as_str()), Err("C0002"));
    }
}

//! Scenario files (`.ltest`, `docs/testing.md`): what to run, console
//! commands at simulated times, and expectations written in ST.
//!
//! ```text
//! strategy ../examples/sequences/plant.json
//! at 0s     M Plant.Start=1
//! expect within 5m   Fill.X
//! expect always      TIC.PV < 120.0
//! run 1h
//! ```
//!
//! The file is read line by line; an expectation's expression is checked
//! and lowered later (`linc_compiler::compile_expectation`), once the
//! strategy it runs against is known (its database and its sequences'
//! steps).

use linc_compiler::diag::{Diagnostic, Span};
use linc_format::Code;

/// What a scenario runs.
#[derive(Clone, Debug, PartialEq)]
pub enum Target {
    /// A strategy's database (`strategy PLANT.json`).
    Strategy(String),
    /// One program and a database (`program batch.sfc` and `db plant.json`).
    Program { file: String, db: String },
}

/// When an expectation must hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum How {
    /// True at some scan within this many µs from the line's time.
    Within(u64),
    /// True at the scan this many µs after the line's time.
    After(u64),
    /// True at every scan from the line's time to the end.
    Always,
    /// False at every scan from the line's time to the end.
    Never,
}

/// One line that does something.
#[derive(Clone, Debug, PartialEq)]
pub enum Action {
    /// Run until this scenario time (µs), then give the console this line.
    At { at_us: u64, command: String },
    /// An expectation from the current time; `expr` is ST.
    Expect { how: How, expr: String, span: Span },
    /// Run this long from the current time.
    Run { for_us: u64 },
}

/// A line of the file and what it does.
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// 1-based line number.
    pub line: u32,
    pub action: Action,
}

/// A scenario as read.
#[derive(Clone, Debug, PartialEq)]
pub struct Scenario {
    pub target: Option<Target>,
    /// `state FILE`: the retentive state the run starts from (only read).
    pub state: Option<(String, Span)>,
    /// `set BLOCK.FIELD=VALUE`: applied after the state, as `--set` is.
    pub sets: Vec<(String, Span)>,
    pub lines: Vec<Line>,
}

/// A duration or time like `5m`, `1h30m`, `2.5s`, `T#100ms`, in µs.
pub fn duration(text: &str) -> Result<u64, String> {
    let secs = linc_format::db::duration_seconds(text)
        .map_err(|why| format!("`{text}` is not a time like 10s, 5m or 1h30m: {why}"))?;
    if !secs.is_finite() || !(0.0..=366.0 * 86_400.0).contains(&secs) {
        return Err(format!("`{text}`: times are from 0 to 366 days"));
    }
    Ok((secs * 1e6).round() as u64)
}

fn error(code: Code, message: impl Into<String>, span: Span, label: &str) -> Diagnostic {
    Diagnostic::error(code, message, span).label(label)
}

/// Where `part`, a slice of `text`, lies in it (so a span always falls on
/// character boundaries, whatever was trimmed around it).
fn span_of(text: &str, part: &str) -> Span {
    let start = (part.as_ptr() as usize).saturating_sub(text.as_ptr() as usize).min(text.len());
    Span::new(start, (start + part.len()).min(text.len()))
}

/// The first word of `s` and the rest (both trimmed; slices of `s`).
fn word(s: &str) -> (&str, &str) {
    let s = s.trim_start();
    let end = s.find(char::is_whitespace).unwrap_or(s.len());
    (&s[..end], s[end..].trim())
}

/// `text` with every `(* … *)` comment (which may span lines) blanked out,
/// keeping line breaks and byte offsets; the start of a comment left open.
fn blank_comments(text: &str) -> (String, Option<usize>) {
    let mut out = String::with_capacity(text.len());
    let mut open = None;
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        if open.is_none() && c == '(' && chars.peek().is_some_and(|&(_, n)| n == '*') {
            open = Some(i);
        }
        if let Some(start) = open {
            if c == ')' && i > start + 1 && text[..i].ends_with('*') {
                open = None;
            }
            out.extend(std::iter::repeat_n(
                if c == '\n' { '\n' } else { ' ' },
                if c == '\n' { 1 } else { c.len_utf8() },
            ));
        } else {
            out.push(c);
        }
    }
    (out, open)
}

/// Reads a scenario. Every line is checked; an error does not stop the
/// reading, so one run reports them all. Comments are ST's `(* … *)`, and
/// `#` starts a comment line.
pub fn parse(text: &str) -> (Scenario, Vec<Diagnostic>) {
    let mut s = Scenario { target: None, state: None, sets: Vec::new(), lines: Vec::new() };
    let mut diags = Vec::new();
    let (blanked, unclosed) = blank_comments(text);
    if let Some(at) = unclosed {
        diags.push(
            error(Code::E0503, "a comment is not closed", Span::new(at, at + 2), "opened here")
                .help("close it with `*)`"),
        );
    }
    let text = blanked.as_str();
    let mut offset = 0usize;
    let mut db: Option<String> = None;
    let mut program: Option<(String, Span)> = None;
    for (i, raw) in text.split_inclusive('\n').enumerate() {
        let start = offset;
        offset += raw.len();
        let line = raw.trim_end_matches(['\n', '\r']);
        let trimmed = line.trim_start();
        let at = start + (line.len() - trimmed.len());
        let span = Span::new(at, at + trimmed.len());
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let (keyword, rest) = word(trimmed);
        let number = i as u32 + 1;
        let rest_span = span_of(text, rest);
        match keyword.to_ascii_lowercase().as_str() {
            "strategy" | "db" | "program" if rest.is_empty() => {
                diags.push(error(Code::E0500, format!("`{keyword}` names a file"), span, "no file given"));
            }
            "strategy" => set_target(&mut s, Target::Strategy(rest.to_string()), span, &mut diags),
            "db" => db = Some(rest.to_string()),
            "state" | "set" => start_line(&mut s, keyword, (rest, rest_span), span, &mut diags),
            "program" => program = Some((rest.to_string(), span)),
            "at" => {
                let (time, command) = word(rest);
                match duration(time) {
                    Ok(at_us) if !command.is_empty() => s.lines.push(Line {
                        line: number,
                        action: Action::At { at_us, command: command.trim_end().to_string() },
                    }),
                    Ok(_) => {
                        diags.push(error(Code::E0501, "`at` needs a time and a console command", span, "no command"))
                    }
                    Err(why) => diags.push(error(Code::E0502, why, rest_span, "not a time")),
                }
            }
            "run" => match duration(rest) {
                Ok(for_us) => s.lines.push(Line { line: number, action: Action::Run { for_us } }),
                Err(why) => diags.push(error(Code::E0502, why, rest_span, "not a time")),
            },
            "expect" => match expect(text, rest) {
                Ok(action) => s.lines.push(Line { line: number, action }),
                Err(d) => diags.push(*d),
            },
            _ => diags.push(
                error(Code::E0503, format!("`{keyword}` does not start a scenario line"), span, "unknown line")
                    .help("a line is `strategy`, `program`, `db`, `state`, `set`, `at TIME COMMAND`, `expect …` or `run TIME`"),
            ),
        }
    }
    match (program, db) {
        (Some((file, _)), Some(db)) => {
            let span = Span::new(0, 0);
            set_target(&mut s, Target::Program { file, db }, span, &mut diags);
        }
        (Some((_, span)), None) => {
            diags.push(error(Code::E0500, "`program` needs a `db` line naming its database", span, "no database"))
        }
        _ => {}
    }
    if s.target.is_none() && diags.is_empty() {
        let d = error(Code::E0500, "the scenario names nothing to run", Span::new(0, 0), "no `strategy` line")
            .help("start with `strategy PLANT.json`, or `program FILE` and `db DB.json`");
        diags.push(d);
    }
    (s, diags)
}

/// `state FILE` (once) and `set BLOCK.FIELD=VALUE`: how the plant starts.
fn start_line(s: &mut Scenario, keyword: &str, (rest, at): (&str, Span), span: Span, diags: &mut Vec<Diagnostic>) {
    let refuse = |message: &str, label: &str| error(Code::E0505, message, span, label);
    if keyword.eq_ignore_ascii_case("set") {
        match rest.split_once('=') {
            Some((field, value)) if field.contains('.') && !value.trim().is_empty() => {
                s.sets.push((rest.to_string(), at));
            }
            _ => diags.push(refuse("`set` writes BLOCK.FIELD=VALUE", "not BLOCK.FIELD=VALUE")),
        }
    } else if rest.is_empty() {
        diags.push(refuse("`state` names a state file", "no file given"));
    } else if s.state.is_some() {
        diags.push(refuse("a scenario starts from one state", "second state"));
    } else {
        s.state = Some((rest.to_string(), at));
    }
}

fn set_target(s: &mut Scenario, t: Target, span: Span, diags: &mut Vec<Diagnostic>) {
    if s.target.is_some() {
        diags.push(error(Code::E0500, "a scenario runs one strategy or program", span, "second target"));
    } else {
        s.target = Some(t);
    }
}

/// `within D EXPR`, `after D EXPR`, `always EXPR`, `never EXPR`.
fn expect(text: &str, rest: &str) -> Result<Action, Box<Diagnostic>> {
    let span = span_of(text, rest);
    let (how, tail) = word(rest);
    let timed = |make: fn(u64) -> How| -> Result<(How, &str), Box<Diagnostic>> {
        let (time, expr) = word(tail);
        let d = duration(time).map_err(|why| Box::new(error(Code::E0502, why, span, "not a time")))?;
        Ok((make(d), expr))
    };
    let (how, expr) = match how.to_ascii_lowercase().as_str() {
        "within" => timed(How::Within)?,
        "after" => timed(How::After)?,
        "always" => (How::Always, tail),
        "never" => (How::Never, tail),
        _ => {
            let hint =
                "write `expect within 5m EXPR`, `expect after 10s EXPR`, `expect always EXPR` or `expect never EXPR`";
            let e = error(Code::E0504, format!("`expect {how}` is not a kind of expectation"), span, "unknown kind");
            return Err(Box::new(e.help(hint)));
        }
    };
    if expr.is_empty() {
        return Err(Box::new(error(Code::E0504, "the expectation has no expression", span, "nothing to check")));
    }
    Ok(Action::Expect { how, expr: expr.to_string(), span: span_of(text, expr) })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_issue_example_reads() {
        let text = "strategy ../examples/sequences/plant.json\nat 0s     M Plant.Start=1\n\
                    expect within 5m   Fill.X\nat 10m    F TANK.Level=95.0\n\
                    expect within 2s   Heat.X AND Agitate.X\n\
                    expect always      TIC.PV < 120.0          (* checked at every scan *)\nrun 1h\n";
        let (s, d) = parse(text);
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(s.target, Some(Target::Strategy("../examples/sequences/plant.json".into())));
        assert_eq!(s.lines.len(), 6);
        assert_eq!(s.lines[0].action, Action::At { at_us: 0, command: "M Plant.Start=1".into() });
        match &s.lines[1].action {
            Action::Expect { how: How::Within(us), expr, span } => {
                assert_eq!((*us, expr.as_str()), (300_000_000, "Fill.X"));
                assert_eq!(&text[span.start..span.end], "Fill.X");
            }
            other => panic!("{other:?}"),
        }
        assert_eq!(s.lines[5], Line { line: 7, action: Action::Run { for_us: 3_600_000_000 } });
    }

    #[test]
    fn comments_may_span_lines() {
        let (s, d) = parse("(* a\n   scenario *)\nstrategy p.json (* the plant *)\nrun 1s (* one *)\n");
        assert!(d.is_empty(), "{d:?}");
        assert_eq!(s.target, Some(Target::Strategy("p.json".into())));
        assert_eq!(s.lines, vec![Line { line: 4, action: Action::Run { for_us: 1_000_000 } }]);
        let (_, d) = parse("strategy p.json\n(* open\nrun 1s\n");
        assert_eq!(d[0].code, "E0503");
    }

    #[test]
    fn bad_lines_are_located_and_reading_goes_on() {
        let (_, d) = parse("strategy p.json\nat soon M A.B=1\nexpect sometimes X\nwait 5s\nrun 1x\n");
        let codes: Vec<_> = d.iter().map(|d| d.code).collect();
        assert_eq!(codes, ["E0502", "E0504", "E0503", "E0502"]);
        let (_, d) = parse("at 0s NOW\n");
        assert_eq!(d[0].code, "E0500", "nothing to run");
        let (_, d) = parse("program x.sfc\n");
        assert_eq!(d[0].code, "E0500", "a program needs its database");
    }
}

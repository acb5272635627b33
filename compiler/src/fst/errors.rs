//! Diagnostics of the FST front end (codes E0400–E0449, W0400–W0449), built
//! in one place so that every code and its wording live next to each other
//! (`docs/errors/E04xx.md` explains each).

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::Code;

/// The header row is missing or is not the FST Editor's.
pub fn bad_header(span: Span, found: &str) -> Diagnostic {
    Diagnostic::error(Code::E0400, "the table does not start with the FST header row", span)
        .label(if found.is_empty() { "expected the header here".to_string() } else { format!("found `{found}`") })
        .help("the first line must be `STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT` (COMMENT may be left out)")
}

/// A row the CSV reader cannot split into the table's columns.
pub fn malformed_row(span: Span, why: String) -> Diagnostic {
    Diagnostic::error(Code::E0401, "malformed CSV row", span).label(why)
}

/// A cell with a line break inside its quotes (RFC 4180 allows it, ROCLINK
/// never writes one): refused, so that a row is always one line.
pub fn line_break_in_cell(span: Span) -> Diagnostic {
    malformed_row(span, "a line break inside a cell".to_string())
        .help("an FST row is one line: put the cell's text on one line (ROCLINK writes no line breaks in cells)")
}

/// A STEP cell that is not the next step number.
pub fn bad_step(span: Span, found: &str, expected: usize) -> Diagnostic {
    Diagnostic::error(Code::E0402, format!("step number `{found}` where step {expected} was expected"), span)
        .label(format!("expected {expected}"))
        .help("steps are numbered 0, 1, 2 … in order, without gaps")
}

/// A CMD cell that is no command of Table B-9.
pub fn unknown_command(span: Span, found: &str, suggestion: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(Code::E0403, format!("unknown FST command `{found}`"), span).label("not a command");
    match suggestion {
        Some(s) => d.help(format!("did you mean `{s}`?")),
        None => d.help("`linc explain E0403` lists the commands"),
    }
}

/// Rows after the first blank command are not part of the program.
pub fn rows_after_end(span: Span, blank_line: u32) -> Diagnostic {
    Diagnostic::warning(Code::W0400, "rows after a blank command are ignored", span)
        .label("ignored")
        .help(format!("the program ends at line {blank_line}, the first row without a command"))
}

/// A label that is not 1–6 letters and digits.
pub fn bad_label(span: Span, label: &str) -> Diagnostic {
    Diagnostic::error(Code::E0404, format!("invalid label `{label}`"), span)
        .label("not a label")
        .help("a label is up to six letters and digits (B.1.2)")
}

/// A label spelt like a command.
pub fn label_is_command(span: Span, label: &str) -> Diagnostic {
    Diagnostic::error(Code::E0405, format!("label `{label}` is the name of a command"), span)
        .label("a command name")
        .help("B.1.2: do not use the names of commands as labels")
}

pub fn duplicate_label(span: Span, label: &str, first: Span) -> Diagnostic {
    Diagnostic::error(Code::E0406, format!("label `{label}` is defined twice"), span)
        .label("defined again here")
        .with(first, "first defined here")
}

/// A branch to a label no step has.
pub fn unknown_label(span: Span, label: &str, suggestion: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(Code::E0407, format!("no step has the label `{label}`"), span).label("unknown label");
    match suggestion {
        Some(s) => d.help(format!("did you mean `{s}`?")),
        None => d,
    }
}

pub fn second_end(span: Span, first: Span) -> Diagnostic {
    Diagnostic::error(Code::E0408, "a table has only one END", span)
        .label("second END")
        .with(first, "the table ends here")
        .help("branch to the END step's label instead, or use GO")
}

/// An argument cell filled where the command takes nothing.
pub fn unexpected_argument(span: Span, cmd: &str, which: u8) -> Diagnostic {
    Diagnostic::error(Code::E0409, format!("`{cmd}` takes no ARGUMENT{which}"), span)
        .label("not used by this command")
        .help("leave the cell empty; put remarks in the COMMENT column")
}

/// A required argument left empty.
pub fn missing_argument(span: Span, cmd: &str, which: u8, what: &str) -> Diagnostic {
    Diagnostic::error(Code::E0410, format!("`{cmd}` needs ARGUMENT{which}"), span)
        .label(format!("ARGUMENT{which} is empty"))
        .help(format!("ARGUMENT{which} of `{cmd}` is {what}"))
}

/// A value where a branch target (label) is expected.
pub fn value_for_label(span: Span, cmd: &str, found: &str) -> Diagnostic {
    Diagnostic::error(Code::E0411, format!("`{found}` is not a label"), span)
        .label("a label is expected here")
        .help(format!("`{cmd}` branches to a step: write that step's label"))
}

/// A label where a value is expected.
pub fn label_for_value(span: Span, found: &str) -> Diagnostic {
    Diagnostic::error(Code::E0412, format!("label `{found}` used as a value"), span)
        .label("a number or a parameter is expected here")
        .help("labels are branch targets (GO, CT, the comparisons' ARGUMENT2), not values")
}

/// A constant where only a database parameter will do.
pub fn constant_for_param(span: Span, cmd: &str, what: &str) -> Diagnostic {
    Diagnostic::error(Code::E0413, format!("`{cmd}` needs {what} here, not a constant"), span)
        .label("a constant")
        .help("write a point and parameter, e.g. `SFP 1,DATA1`, or a numeric TLP such as `98,0,2`")
}

/// A parameter that is not a number (text, enumeration …).
pub fn not_numeric(span: Span, written: &str, ty: &str) -> Diagnostic {
    Diagnostic::error(Code::E0414, format!("parameter `{written}` is {ty}, not a number"), span)
        .label("not numeric")
        .help("FST commands read and write REAL, INT, BOOL and bit-field parameters")
}

/// A write to a read-only parameter (SAV, or an index WDB/WTM/RDB advance).
pub fn readonly(span: Span, written: &str, cmd: &str) -> Diagnostic {
    Diagnostic::error(Code::E0415, format!("parameter `{written}` is read-only"), span)
        .label(format!("`{cmd}` writes it"))
        .help("the device computes this parameter itself; save to a soft point (SFP) or an FST register instead")
}

/// A timer argument that is no timer.
pub fn bad_timer(span: Span, written: &str) -> Diagnostic {
    Diagnostic::error(Code::E0416, format!("`{written}` is not a timer"), span)
        .label("timers are 1 to 4")
        .help("write 1, 2, 3 or 4 for this FST's timers, or `FST n,TMR1` … `FST n,TMR4`")
}

/// A constant outside what its command accepts.
pub fn out_of_range(span: Span, cmd: &str, value: &str, range: &str) -> Diagnostic {
    Diagnostic::error(Code::E0417, format!("`{value}` is out of range for `{cmd}`"), span)
        .label(format!("expected {range}"))
}

/// A month/day constant that is not a date.
pub fn bad_month_day(span: Span, value: &str) -> Diagnostic {
    Diagnostic::error(Code::E0418, format!("`{value}` is not a month and day"), span)
        .label("expected month × 100 + day")
        .help("write the date as MMDD: 1123 is November 23 (month 1–12, day 1–31)")
}

/// A number the device cannot hold.
pub fn bad_number(span: Span, text: &str) -> Diagnostic {
    Diagnostic::error(Code::E0419, format!("number `{text}` is out of the REAL range"), span)
        .label("not a finite single-precision number")
        .help("FST constants are 32-bit floating point: at most about 3.4e38 in size")
}

/// An argument that is neither a number, a TLP nor a point.
pub fn bad_argument(span: Span, text: &str, why: &str) -> Diagnostic {
    Diagnostic::error(Code::E0420, format!("cannot read argument `{text}`"), span)
        .label(why.to_string())
        .help("write a number, a numeric TLP `T,L,P` or a point and parameter `POINT,PARAM`")
}

pub fn unknown_point(span: Span, point: &str, suggestion: Option<&str>) -> Diagnostic {
    let d = Diagnostic::error(Code::E0421, format!("the database has no point `{point}`"), span).label("unknown point");
    match suggestion {
        Some(s) => d.help(format!("did you mean `{s}`?")),
        None => d,
    }
}

pub fn unknown_param(span: Span, param: &str, point: &str, template: &str, known: &str) -> Diagnostic {
    Diagnostic::error(Code::E0422, format!("point `{point}` ({template}) has no parameter `{param}`"), span)
        .label("unknown parameter")
        .help(format!("{template} parameters: {known}"))
}

/// A point written without a parameter whose template has no default.
pub fn needs_param(span: Span, point: &str, template: &str) -> Diagnostic {
    Diagnostic::error(Code::E0423, format!("point `{point}` needs a parameter"), span)
        .label(format!("{template} points have no default parameter"))
        .help(format!("write `{point},PARAM`; only AIN/AOU (EU) and DIN/DOU (STATUS) have a default"))
}

/// A numeric TLP whose point type is not one of this device family's.
pub fn tlp_no_type(span: Span, t: u16, family: &str) -> Diagnostic {
    Diagnostic::error(Code::E0424, format!("no point type {t} on a {family}"), span)
        .label(format!("T = {t}"))
        .help(format!("the database's device family is {family}; point type numbers differ between families"))
}

/// A numeric TLP whose logical number is past the points of its type.
pub fn tlp_no_logical(span: Span, l: u16, template: &str, count: usize) -> Diagnostic {
    Diagnostic::error(Code::E0425, format!("no {template} point with logical number {l}"), span)
        .label(format!("L = {l}"))
        .help(format!("the database has {count} {template} point(s), numbered from 0"))
}

/// A numeric TLP whose parameter number is past its template's fields.
pub fn tlp_no_param(span: Span, p: u16, template: &str, count: usize) -> Diagnostic {
    Diagnostic::error(Code::E0426, format!("{template} points have no parameter {p}"), span)
        .label(format!("P = {p}"))
        .help(format!("{template} parameters are numbered 0 to {}", count.saturating_sub(1)))
}

/// AO/DO/TDO on a point of another template.
pub fn wrong_point_type(span: Span, cmd: &str, point: &str, found: &str, expected: &str) -> Diagnostic {
    Diagnostic::error(Code::E0427, format!("`{cmd}` drives {expected} points, and `{point}` is of type {found}"), span)
        .label(format!("type {found}, not {expected}"))
}

/// Message text longer than the device keeps.
pub fn text_truncated(span: Span, cmd: &str, keep: usize) -> Diagnostic {
    Diagnostic::warning(Code::W0401, format!("`{cmd}` keeps only the first {keep} characters"), span)
        .label("the rest is cut off")
}

/// A table with more steps than one FST unit holds (E0132, the code of the
/// object format's other limits), at the first step over it.
pub fn too_many_steps(span: Span, limit: usize, appended: bool) -> Diagnostic {
    let d = Diagnostic::error(Code::E0132, format!("too many steps: a table has at most {limit}"), span)
        .label(if appended { "the END appended after this step is over the limit" } else { "step over the limit" });
    if appended {
        d.help(
            "the table has no END, so one is appended after its last step; make one of its steps END, or remove a step",
        )
    } else {
        d.help(format!("split the table between FST blocks: each runs a table of up to {limit} steps"))
    }
}

/// What is over the error cap is counted once.
pub fn omitted(span: Span, count: usize) -> Diagnostic {
    Diagnostic::error(Code::E0023, format!("{count} more errors in this file not shown"), span)
        .label("the first of them")
}

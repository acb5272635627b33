//! Errors of name resolution and type checking, as plain data.

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::Code;

#[derive(Clone, Debug, PartialEq)]
pub enum CheckError {
    UnknownName {
        span: Span,
        name: String,
        /// A block or alias with a close name.
        suggestion: Option<String>,
    },
    UnknownField {
        span: Span,
        field: String,
        owner: String,
        template: String,
        known: Vec<String>,
    },
    UnknownSubField {
        span: Span,
        sub: String,
        field: String,
        field_type: &'static str,
    },
    /// A value of the wrong kind stored into a field (`expected`/`found` are type names).
    AssignType {
        span: Span,
        target: Span,
        expected: String,
        found: String,
    },
    BadEnumValue {
        span: Span,
        value: String,
        field: String,
        values: Vec<String>,
    },
    ModNotInteger {
        span: Span,
        found: String,
    },
    ForByNotLiteral {
        span: Span,
    },
    ExitOutsideLoop {
        span: Span,
    },
    NotWritable {
        span: Span,
        what: String,
        why: &'static str,
    },
    BadOffsetBase {
        span: Span,
        base: String,
        why: String,
    },
    UnknownFunction {
        span: Span,
        name: String,
        suggestion: Option<String>,
    },
    WrongArity {
        span: Span,
        name: String,
        found: usize,
        signature: String,
    },
    WrongArgType {
        span: Span,
        index: usize,
        found: String,
        expected: String,
        signature: String,
    },
    StepOutsideSequence {
        span: Span,
        name: String,
    },
    OperandTypes {
        span: Span,
        op: String,
        left: String,
        right: Option<String>,
        help: &'static str,
    },
    NotAValue {
        span: Span,
        what: String,
    },
    UnknownBlockType {
        span: Span,
        name: String,
    },
    /// Over a limit of the object format (see `limits.rs`).
    TooMany {
        span: Span,
        what: &'static str,
        limit: &'static str,
    },
    /// `BY 0`, or a REAL step that is 0 in the loop variable's type.
    ForStepZero {
        span: Span,
        rounded: bool,
    },
    OffsetNotNumber {
        span: Span,
        found: String,
    },
    ConditionType {
        span: Span,
        found: String,
    },
    UnknownStep {
        span: Span,
        name: String,
    },
}

impl CheckError {
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            CheckError::UnknownName { span, name, suggestion } => {
                let d = Diagnostic::error(Code::E0100, format!("can't find `{name}`"), *span)
                    .label("not a block, alias or field of this action's block");
                match suggestion {
                    Some(s) => d.help(format!("did you mean `{s}`?")).fix(*span, s.clone()),
                    None => {
                        d.help("names ignore case; check the spelling, or pass the database that defines it with --db")
                    }
                }
            }
            CheckError::UnknownField { span, field, owner, template, known } => {
                let d = Diagnostic::error(Code::E0101, format!("`{owner}` has no field `{field}`"), *span)
                    .label(format!("not a field of block type {template}"));
                if known.is_empty() {
                    return d;
                }
                let d = d.help(format!("fields of {template}: {}", known.join(", ")));
                match closest(field, known) {
                    Some(best) => d.fix(*span, best),
                    None => d,
                }
            }
            CheckError::UnknownSubField { span, sub, field, field_type } => {
                let d = Diagnostic::error(Code::E0102, format!("`{field}` has no sub-field `{sub}`"), *span)
                    .label(format!("`{field}` is a {field_type} field"));
                match *field_type {
                    "BITS8" => d.help("the bits of an 8-bit bitfield are Bit0 to Bit7"),
                    "BITS16" => d.help("the bits of a 16-bit bitfield are Bit0 to Bit15"),
                    "ALARMS" => d.help("write Alarms.<alarm name>, Alarms.<alarm name>.Suppress or Alarms.Suppress"),
                    _ => d,
                }
            }
            CheckError::AssignType { span, target, expected, found } => {
                Diagnostic::error(Code::E0103, format!("can't store a {found} value in a {expected} field"), *span)
                    .label(format!("this is {found}"))
                    .with(*target, format!("this field is {expected}"))
                    .help(match (expected.as_str(), found.as_str()) {
                        ("REAL" | "INT" | "BOOL", _) => "use SCAN to turn a string into a number",
                        (_, "REAL" | "INT" | "BOOL") => "use FORMAT to turn a number into a string",
                        _ => "the value and the field must both be numbers or both be strings",
                    })
            }
            CheckError::BadEnumValue { span, value, field, values } => {
                let d = Diagnostic::error(Code::E0104, format!("`{value}` is not a value of `{field}`"), *span)
                    .label("unknown enumeration value")
                    .help(format!("`{field}` takes one of: {} (case does not matter)", values.join(", ")));
                match closest(value, values) {
                    // The span is the whole constant, quotes included.
                    Some(best) => {
                        d.fix(Span::new(span.start + 1, span.end.saturating_sub(1).max(span.start + 1)), best)
                    }
                    None => d,
                }
            }
            CheckError::ModNotInteger { span, found } => {
                Diagnostic::error(Code::E0105, format!("MOD needs integer operands, found {found}"), *span)
                    .label("not an integer")
                    .help("use TRUNC or ROUND to make an integer first")
            }
            CheckError::ForByNotLiteral { span } => {
                Diagnostic::error(Code::E0106, "the step of a FOR loop must be a constant", *span)
                    .label("not a literal")
                    .help("write `BY 2` or `BY -1`; the step is fixed when the loop is compiled (§12.4.3)")
            }
            CheckError::ExitOutsideLoop { span } => Diagnostic::error(Code::E0107, "EXIT outside a loop", *span)
                .label("there is no FOR, WHILE or REPEAT around this")
                .help("EXIT ends the innermost loop; to end an action early, wrap its rest in IF"),
            CheckError::NotWritable { span, what, why } => {
                Diagnostic::error(Code::E0108, format!("can't assign to `{what}`"), *span).label(*why)
            }
            CheckError::BadOffsetBase { span, base, why } => {
                Diagnostic::error(Code::E0109, format!("`{base}` can't be the base of an offset"), *span)
                    .label(why.clone())
                    .help("the base must be followed, in template order, by fields (or bits) of the same type (§12.12)")
            }
            CheckError::UnknownFunction { span, name, suggestion } => {
                let d = Diagnostic::error(Code::E0110, format!("`{name}` is not an ST function"), *span)
                    .label("unknown function");
                match suggestion {
                    Some(s) => d.help(format!("did you mean `{s}`?")).fix(*span, s.clone()),
                    None => d.help("see `linc explain E0110` for the function table"),
                }
            }
            CheckError::WrongArity { span, name, found, signature } => Diagnostic::error(
                Code::E0111,
                format!("`{name}` called with {found} argument{}", if *found == 1 { "" } else { "s" }),
                *span,
            )
            .label("wrong number of arguments")
            .help(format!("expected {signature}")),
            CheckError::WrongArgType { span, index, found, expected, signature } => Diagnostic::error(
                Code::E0112,
                format!("argument {} should be {expected}, found {found}", index + 1),
                *span,
            )
            .label(format!("this is {found}"))
            .help(format!("expected {signature}")),
            CheckError::StepOutsideSequence { span, name } => {
                Diagnostic::error(Code::E0113, format!("step variable `{name}` outside a sequence"), *span)
                    .label("`.X` and `.T` of a step exist only in sequence actions and transitions")
            }
            CheckError::OperandTypes { span, op, left, right, help } => {
                let msg = match right {
                    Some(r) => format!("can't apply `{op}` to {left} and {r}"),
                    None => format!("can't apply `{op}` to {left}"),
                };
                Diagnostic::error(Code::E0114, msg, *span).label("operand types do not fit").help(*help)
            }
            CheckError::NotAValue { span, what } => {
                Diagnostic::error(Code::E0115, format!("`{what}` is not a value"), *span)
                    .label("name a field, bit or alarm")
            }
            CheckError::UnknownBlockType { span, name } => {
                Diagnostic::error(Code::E0116, format!("unknown block type `{name}`"), *span)
                    .label("not a built-in template nor one in the database")
            }
            CheckError::TooMany { span, what, limit } => {
                Diagnostic::error(Code::E0132, format!("too many {what}"), *span)
                    .label("limit reached here")
                    .help(*limit)
            }
            CheckError::ForStepZero { span, rounded } => {
                let d = Diagnostic::error(Code::E0121, "the step of this FOR loop is 0", *span);
                let d = if *rounded {
                    d.label("this is 0 once converted to the loop variable's type")
                } else {
                    d.label("a step of 0 never reaches the limit")
                };
                d.help("the step is added to the loop variable after each pass (§12.4.3); use a step of at least 1 for an INT loop")
            }
            CheckError::OffsetNotNumber { span, found } => {
                Diagnostic::error(Code::E0118, format!("an offset must be a number, found {found}"), *span)
                    .label("not a number")
            }
            CheckError::ConditionType { span, found } => {
                Diagnostic::error(Code::E0119, format!("a condition must be BOOL or INT, found {found}"), *span)
                    .label("not a truth value")
                    .help("compare it with something, e.g. `X.PV > 0.5`")
            }
            CheckError::UnknownStep { span, name } => {
                // `Name.X` reads as a step variable only because no block
                // is called `Name`: the engineer may have meant either.
                Diagnostic::error(Code::E0120, format!("no block or step `{name}`"), *span)
                    .label("neither a block of the database nor a step")
            }
        }
    }
}

/// The candidate closest to `word` (ignoring case), if it is at most half
/// as long as the word away and nearer than any other.
fn closest(word: &str, candidates: &[String]) -> Option<String> {
    let word = word.to_ascii_uppercase();
    let mut scored: Vec<(usize, &String)> =
        candidates.iter().map(|c| (super::expr::distance(&word, &c.to_ascii_uppercase()), c)).collect();
    scored.sort_by_key(|s| s.0);
    match scored.as_slice() {
        [(d, best), rest @ ..] if *d <= word.len().div_ceil(2).max(1) && rest.first().is_none_or(|r| r.0 > *d) => {
            Some((*best).clone())
        }
        _ => None,
    }
}

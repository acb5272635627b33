//! Errors of the lexer and the parser, as plain data.

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::Code;

/// Lexical errors. The lexer repairs what it reports, so one mistake gives
/// one error.
#[derive(Clone, Debug, PartialEq)]
pub enum LexError {
    /// One character, or a run of them, that starts no token; `ch` is the first.
    UnexpectedChar {
        span: Span,
        ch: char,
    },
    UnclosedString {
        span: Span,
    },
    UnclosedComment {
        span: Span,
    },
    /// A space inside a name, operator or constant (§12.2.2).
    IllegalSpace {
        span: Span,
        what: &'static str,
        fixed: &'static str,
    },
    BadNumber {
        span: Span,
        text: String,
    },
    BadTime {
        span: Span,
        text: String,
    },
    StrayDot {
        span: Span,
    },
    UnclosedBracket {
        span: Span,
    },
    /// A REAL constant beyond the range of a 32-bit REAL.
    RealOutOfRange {
        span: Span,
        text: String,
    },
    /// A time constant longer than [`crate::st::lexer::MAX_TIME_SECONDS`].
    TimeOutOfRange {
        span: Span,
        text: String,
    },
}

impl LexError {
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            LexError::UnexpectedChar { span, ch } => {
                // A run of such characters is one error, named by its first.
                let message = if span.end - span.start > ch.len_utf8() {
                    format!("unexpected characters, from `{ch}` on")
                } else {
                    format!("unexpected character `{ch}`")
                };
                let d = Diagnostic::error(Code::E0001, message, *span).label("not part of any ST token");
                match ch {
                    '\u{2018}' | '\u{2019}' | '\u{201C}' | '\u{201D}' => {
                        d.help("typographic quotes are not ST quotes: write strings in ' or \"")
                    }
                    _ => d,
                }
            }
            LexError::UnclosedString { span } => Diagnostic::error(Code::E0002, "string constant is not closed", *span)
                .label("this string has no closing quote on its line")
                .help("close it with the quote that opened it; write a quote inside as $' or $\""),
            LexError::UnclosedComment { span } => Diagnostic::error(Code::E0003, "comment is not closed", *span)
                .label("this comment runs to the end of the file")
                .help("close comments with *)"),
            LexError::IllegalSpace { span, what, fixed } => {
                let d = Diagnostic::error(Code::E0004, format!("space inside {what}"), *span)
                    .label("remove this space")
                    .help(
                        "spaces are not allowed inside operators, database names, identifiers or constants (§12.2.2)",
                    );
                if fixed.is_empty() {
                    d
                } else {
                    d.help(format!("write `{fixed}`"))
                }
            }
            LexError::BadNumber { span, text } => {
                Diagnostic::error(Code::E0008, format!("`{text}` is not a valid integer constant"), *span)
                    .label("bad digit for this base")
                    .help("based integers are 16#hexdigits or 2#binarydigits, e.g. 16#03E8, 2#1100")
            }
            LexError::BadTime { span, text } => {
                Diagnostic::error(Code::E0009, format!("`{text}` is not a valid time constant"), *span)
                    .label("expected numbers each followed by a unit d, h, m or s")
                    .help("examples: T#3s, T#4m13.0s, T#5.6h, T#1d12.2h")
            }
            LexError::StrayDot { span } => Diagnostic::error(Code::E0012, "a `.` that does not join a name", *span)
                .label("expected a name on both sides of this dot, with no spaces")
                .help("names that are not valid identifiers can be written in square brackets, e.g. [6366.MN]"),
            LexError::UnclosedBracket { span } => Diagnostic::error(Code::E0013, "`[` is not closed", *span)
                .label("this bracketed name has no `]` on its line"),
            LexError::RealOutOfRange { span, text } => {
                Diagnostic::error(Code::E0019, format!("`{text}` is out of the range of a REAL"), *span)
                    .label("does not fit a 32-bit REAL")
                    .help("a REAL is at most 3.4028235E38 in magnitude")
            }
            LexError::TimeOutOfRange { span, text } => {
                Diagnostic::error(Code::E0020, format!("`{text}` is too long a time"), *span)
                    .label("more than 2147483647 seconds")
                    .help("a time constant is at most 2147483647 s (about 68 years), the largest INT number of seconds")
            }
        }
    }
}

/// Errors found while parsing.
#[derive(Clone, Debug, PartialEq)]
pub enum SyntaxError {
    Unexpected {
        span: Span,
        found: String,
        expected: Vec<String>,
    },
    UnexpectedEof {
        span: Span,
        expected: Vec<String>,
    },
    NameTooLong {
        span: Span,
        name: String,
    },
    InvalidName {
        span: Span,
        name: String,
        why: &'static str,
    },
    GluedWordOperator {
        span: Span,
        op: &'static str,
        name: String,
    },
    BadActionName {
        span: Span,
        name: String,
    },
    DoubleOffset {
        span: Span,
    },
    StatementOutsideAction {
        span: Span,
    },
    /// The last statement of an action has no `;` (accepted, with a warning).
    MissingFinalSemicolon {
        span: Span,
    },
    /// Statements nested deeper than [`crate::st::parse_support::MAX_NESTING`].
    NestedTooDeep {
        span: Span,
        keyword: &'static str,
    },
    /// An expression deeper than [`crate::st::parse_support::MAX_EXPR_DEPTH`].
    ExprTooDeep {
        span: Span,
    },
    /// The parser stopped reading the file at `span`, having recovered from
    /// [`crate::diag::MAX_ERRORS`] syntax errors.
    Stopped {
        span: Span,
    },
}

impl SyntaxError {
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            SyntaxError::Unexpected { span, found, expected } => {
                let d = Diagnostic::error(Code::E0010, format!("unexpected {found}"), *span).label(expected_text(expected));
                if expected.iter().any(|e| e == "`;`") {
                    d.help("every statement ends with `;`")
                } else {
                    d
                }
            }
            SyntaxError::UnexpectedEof { span, expected } => {
                Diagnostic::error(Code::E0011, "unexpected end of file", *span).label(expected_text(expected))
            }
            SyntaxError::NameTooLong { span, name } => Diagnostic::error(
                Code::E0005,
                format!("identifier `{name}` is {} characters long; the limit is 8", name.chars().count()),
                *span,
            )
            .label("too long")
            .help(format!("if the database really has this name, enclose the whole variable in brackets: [{name}...]")),
            SyntaxError::InvalidName { span, name, why } => {
                Diagnostic::error(Code::E0006, format!("`{name}` is not a valid identifier"), *span)
                    .label(*why)
                    .help("an identifier is a letter or `_` followed by letters, digits or `_`; enclose other names in brackets, e.g. [6366.MN]")
            }
            SyntaxError::GluedWordOperator { span, op, name } => {
                Diagnostic::error(Code::E0007, format!("`{name}` is a name, not the operator {op}"), *span)
                    .label(format!("`{op}` must be separated from its operands"))
                    .help(format!("put a space or a bracket between {op} and its operand (§12.2.1)"))
            }
            SyntaxError::BadActionName { span, name } => {
                Diagnostic::error(Code::E0014, format!("`{name}` is not a valid action name"), *span)
                    .label("action names have up to 8 characters a-z, A-Z, 0-9 or _, do not start with a digit and are not keywords")
            }
            SyntaxError::DoubleOffset { span } => {
                Diagnostic::error(Code::E0015, "a name part can carry only one offset", *span)
                    .label("second offset")
                    .help("add the offsets instead: X{a + b}")
            }
            SyntaxError::StatementOutsideAction { span } => {
                Diagnostic::error(Code::E0016, "statement outside an action", *span)
                    .label("this file has ACTION headers, so every statement must be inside one")
            }
            SyntaxError::MissingFinalSemicolon { span } => {
                Diagnostic::warning(Code::W0001, "the last statement has no `;`", *span)
                    .label("`;` expected here")
                    .help("statements must be terminated by a semicolon (§12.4); it is accepted at the end of an action")
            }
            SyntaxError::NestedTooDeep { span, keyword } => Diagnostic::error(
                Code::E0021,
                format!("statements nested more than {} deep", crate::st::parse_support::MAX_NESTING),
                *span,
            )
            .label(format!("this {keyword} goes over the limit"))
            .help("move the inner part into a separate action, or test conditions in sequence instead of nesting"),
            SyntaxError::ExprTooDeep { span } => Diagnostic::error(
                Code::E0022,
                format!("expression nested more than {} deep", crate::st::parse_support::MAX_EXPR_DEPTH),
                *span,
            )
            .label("this part is too deep")
            .help("compute the expression in parts, storing each part in a field, then combine the parts"),
            SyntaxError::Stopped { span } => {
                Diagnostic::error(Code::E0023, "too many syntax errors: the rest of the file is not read", *span)
                    .label("reading stopped here")
                    .help(format!(
                        "linc reads on through at most {} syntax errors of a file; fix these and check again",
                        crate::diag::MAX_ERRORS
                    ))
            }
        }
    }
}

fn expected_text(expected: &[String]) -> String {
    match expected.len() {
        0 => "not expected here".to_string(),
        1 => format!("expected {}", expected[0]),
        n if n <= 6 => format!("expected {} or {}", expected[..n - 1].join(", "), expected[n - 1]),
        _ => format!("expected one of {}, ...", expected[..5].join(", ")),
    }
}

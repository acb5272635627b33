//! Errors of the sequence front end, as plain data (codes E0200–E0249,
//! W0200–W0249).

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::Code;

#[derive(Clone, Debug, PartialEq)]
pub enum SfcError {
    /// A token the sequence grammar does not allow here.
    Unexpected {
        span: Span,
        found: String,
        expected: &'static str,
    },
    /// The file ends inside a step, transition or action.
    UnexpectedEof {
        span: Span,
        expected: &'static str,
    },
    /// A chart (the root chart or a chart action) with no `INITIAL_STEP`.
    NoInitialStep {
        span: Span,
        chart: String,
    },
    /// A step name used twice in one sequence (nested charts included).
    DuplicateStep {
        span: Span,
        name: String,
        first: Span,
    },
    /// A transition from or to a step its chart does not have.
    UnknownStep {
        span: Span,
        name: String,
        other_chart: Option<String>,
    },
    /// An association naming an action the sequence does not define.
    UnknownAction {
        span: Span,
        name: String,
    },
    DuplicateAction {
        span: Span,
        name: String,
        first: Span,
    },
    /// A qualifier that is neither LIN's nor IEC's.
    UnknownQualifier {
        span: Span,
        text: String,
    },
    /// An IEC 61131-3 qualifier LIN does not have (P0 P1 SD DS SL).
    IecQualifier {
        span: Span,
        text: String,
        lin: Option<&'static str>,
    },
    /// L, D or E without a time.
    MissingTime {
        span: Span,
        qualifier: String,
    },
    /// P, N, F, S or R with a time.
    ExtraTime {
        span: Span,
        qualifier: String,
    },
    DuplicateTransition {
        span: Span,
        name: String,
        first: Span,
    },
    /// An action no step names (a warning: it never runs).
    UnusedAction {
        span: Span,
        name: String,
    },
    /// A step no transition can reach from the initial steps (a warning).
    UnreachableStep {
        span: Span,
        name: String,
    },
    /// A chart action whose chart runs it, directly or through others.
    ChartRunsItself {
        span: Span,
        chart: String,
        action: String,
    },
    /// A transition that can activate a step that is still active (a warning).
    Unsafe {
        span: Span,
        transition: String,
        step: String,
    },
    /// A chart action whose chart is deeper below the root than the loader
    /// allows (at least `depth` levels).
    ChartsTooDeep {
        span: Span,
        action: String,
        depth: usize,
        limit: usize,
    },
    /// More steps than retained slots can hold.
    TooManySteps {
        span: Span,
        limit: usize,
    },
    /// More charts or code blocks, once chart actions are written out for
    /// each use, than an object's unit can name.
    TooLarge {
        span: Span,
        what: &'static str,
        count: usize,
        limit: usize,
    },
}

impl SfcError {
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            SfcError::Unexpected { span, found, expected } => {
                Diagnostic::error(Code::E0200, format!("unexpected {found} in a sequence"), *span)
                    .label(format!("expected {expected}"))
            }
            SfcError::UnexpectedEof { span, expected } => {
                Diagnostic::error(Code::E0201, "unexpected end of file in a sequence", *span)
                    .label(format!("expected {expected}"))
            }
            SfcError::NoInitialStep { span, chart } => {
                Diagnostic::error(Code::E0202, format!("{chart} has no initial step"), *span)
                    .label("no INITIAL_STEP")
                    .help("a chart starts at its initial steps: write `INITIAL_STEP name: … END_STEP` for one of them")
            }
            SfcError::DuplicateStep { span, name, first } => {
                Diagnostic::error(Code::E0203, format!("step `{name}` is defined twice"), *span)
                    .label("second definition")
                    .with(*first, "first defined here")
                    .help("step names are unique in the whole sequence, nested charts included, ignoring case")
            }
            SfcError::UnknownStep { span, name, other_chart } => {
                let d =
                    Diagnostic::error(Code::E0204, format!("the chart has no step `{name}`"), *span).label("unknown step");
                match other_chart {
                    Some(c) => d.help(format!("`{name}` is a step of {c}: a transition joins steps of one chart")),
                    None => d,
                }
            }
            SfcError::UnknownAction { span, name } => {
                Diagnostic::error(Code::E0205, format!("the sequence has no action `{name}`"), *span)
                    .label("unknown action")
                    .help("define it after the chart: `ACTION name … END_ACTION`")
            }
            SfcError::DuplicateAction { span, name, first } => {
                Diagnostic::error(Code::E0206, format!("action `{name}` is defined twice in the sequence"), *span)
                    .label("second definition")
                    .with(*first, "first defined here")
            }
            SfcError::UnknownQualifier { span, text } => {
                Diagnostic::error(Code::E0207, format!("`{text}` is not an action qualifier"), *span)
                    .label("unknown qualifier")
                    .help("LIN's qualifiers are P N L D E F S R (§20.5.5)")
            }
            SfcError::IecQualifier { span, text, lin } => {
                let d = Diagnostic::error(Code::E0208, format!("LIN has no qualifier `{text}`"), *span)
                    .label("IEC 61131-3 qualifier");
                match lin {
                    Some(q) => d.help(format!("write `{q}`, LIN's qualifier for this")),
                    None => d.help("LIN has no equivalent; its qualifiers are P N L D E F S R (§20.5.5)"),
                }
            }
            SfcError::MissingTime { span, qualifier } => {
                Diagnostic::error(Code::E0209, format!("qualifier `{qualifier}` needs a time"), *span)
                    .label("no time given")
                    .help(format!("write it after the qualifier, e.g. `Act({qualifier}, T#10s)`"))
            }
            SfcError::ExtraTime { span, qualifier } => {
                Diagnostic::error(Code::E0210, format!("qualifier `{qualifier}` takes no time"), *span)
                    .label("remove this time")
                    .help("only L, D and E take a time")
            }
            SfcError::DuplicateTransition { span, name, first } => {
                Diagnostic::error(Code::E0211, format!("transition `{name}` is defined twice"), *span)
                    .label("second definition")
                    .with(*first, "first defined here")
            }
            SfcError::UnusedAction { span, name } => {
                Diagnostic::warning(Code::W0200, format!("action `{name}` is never used"), *span)
                    .label("no step names this action")
            }
            SfcError::UnreachableStep { span, name } => {
                Diagnostic::warning(Code::W0201, format!("step `{name}` can never become active"), *span)
                    .label("unreachable")
                    .help("it is not an initial step and no transition from a reachable step leads to it")
            }
            SfcError::Unsafe { span, transition, step } => unsafe_chart(*span, transition, step),
            SfcError::ChartRunsItself { span, chart, action } => runs_itself(*span, chart, action),
            SfcError::ChartsTooDeep { span, action, depth, limit } => {
                Diagnostic::error(Code::E0213, format!("chart actions nest more than {limit} deep"), *span)
                    .label(format!("`{action}` puts a chart {depth} levels below the sequence's chart"))
                    .help("run some of the nested charts' steps in the chart above them, or split the sequence")
            }
            SfcError::TooManySteps { span, limit } => {
                Diagnostic::error(Code::E0214, format!("more than {limit} steps in one sequence"), *span)
                    .label(format!("step {}", limit + 1))
                    .help("each step keeps `.X` and `.T` in two of the sequence's 65,535 retained slots; split the sequence")
            }
            SfcError::TooLarge { span, what, count, limit } => {
                Diagnostic::error(Code::E0215, format!("the sequence needs {count} {what}; an object holds at most {limit}"), *span)
                    .label("the limit is passed here")
                    .help("a chart action's chart is written out once for each chart that uses it, with a code block for each of its transitions; use shared chart actions in fewer charts")
            }
        }
    }
}

/// W0202, whose message needs the most words.
fn unsafe_chart(span: Span, transition: &str, step: &str) -> Diagnostic {
    Diagnostic::warning(
        Code::W0202,
        format!("unsafe chart: transition `{transition}` can activate step `{step}` while it is active"),
        span,
    )
    .label(format!("`{step}` may still be active here"))
    .help("leaving one branch of a simultaneous divergence, or branches that never converge, leaves steps active")
    .help("join the parallel branches with one transition `FROM (a, b, …)`")
}

/// E0212, naming the loop.
fn runs_itself(span: Span, chart: &str, action: &str) -> Diagnostic {
    let label = if chart.eq_ignore_ascii_case(action) {
        format!("the chart of `{chart}` runs `{action}` itself")
    } else {
        format!("the chart of `{chart}` runs `{action}`, which leads back to `{chart}`")
    };
    Diagnostic::error(Code::E0212, format!("chart action `{action}` runs itself"), span)
        .label(label)
        .help("a chart action's chart cannot run the action it belongs to: charts would nest without end")
}

impl From<SfcError> for Diagnostic {
    fn from(e: SfcError) -> Diagnostic {
        e.to_diagnostic()
    }
}

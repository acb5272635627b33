//! The syntax tree of a `.sfc` sequence.
//!
//! A sequence is its root chart and the actions its steps name. A chart is
//! steps and transitions; an action holds ST statements (the ST tree of
//! [`crate::st::ast`]) or a nested chart. Every name keeps its span so that each
//! check can point at what it is about.

use crate::diag::span::Span;
use crate::st::ast::{Action as StAction, Expr, Ident};

/// One `.sfc` file: the root chart, then the actions.
#[derive(Clone, Debug, PartialEq)]
pub struct Sequence {
    pub chart: Chart,
    pub actions: Vec<Action>,
}

/// Steps and transitions, in source order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Chart {
    pub steps: Vec<Step>,
    pub transitions: Vec<Transition>,
    /// A transition of this chart did not parse (already reported): the
    /// checks that follow every transition (reachability, safety) are
    /// skipped, as they would only report what the broken one hides.
    pub broken: bool,
}

/// `[INITIAL_]STEP name: associations END_STEP`.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub name: Ident,
    pub initial: bool,
    pub assocs: Vec<Assoc>,
    pub span: Span,
}

/// `Action(Q)` or `Action(Q, T#…)` inside a step (§20.5.5).
#[derive(Clone, Debug, PartialEq)]
pub struct Assoc {
    pub action: Ident,
    /// The qualifier as written; checked against LIN's P N L D E F S R.
    pub qualifier: Ident,
    /// Seconds, and where the time constant is.
    pub time: Option<(f64, Span)>,
    pub span: Span,
}

/// `TRANSITION [name] [(PRIORITY := n)] FROM steps TO steps := cond; END_TRANSITION`.
#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    /// Boxed, as are `priority` and `ladder`: few transitions have one, and
    /// a sequence of 100,000 steps holds as many transitions (issue 30).
    pub name: Option<Box<Ident>>,
    pub priority: Option<Box<(i64, Span)>>,
    pub from: Vec<Ident>,
    pub to: Vec<Ident>,
    /// `None` when the condition did not parse (already reported).
    pub cond: Option<Expr>,
    /// Where the rung of a `: LADDER` condition is (§20.5.7): `cond` is
    /// the ST it stands for, this the contacts as written, for pictures.
    pub ladder: Option<Box<Span>>,
    pub span: Span,
}

impl Transition {
    /// The name the guide gives a transition: its own, or "A to B" for an
    /// unnamed one with a single source and target (§20.5, "STEP1 to STEP2").
    pub fn display_name(&self) -> String {
        if let Some(n) = &self.name {
            return n.text.to_string();
        }
        let list = |v: &[Ident]| match v {
            [one] => one.text.to_string(),
            many => format!("({})", many.iter().map(|i| i.text.as_str()).collect::<Vec<_>>().join(", ")),
        };
        format!("{} to {}", list(&self.from), list(&self.to))
    }
}

/// `ACTION name … END_ACTION` or `ACTION name : CHART … END_ACTION`.
#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub name: Ident,
    pub body: ActionBody,
    pub span: Span,
}

#[derive(Clone, Debug, PartialEq)]
pub enum ActionBody {
    /// ST statements, as the ST parser read them (header included).
    St(StAction),
    /// A chart action (§10.2.2).
    Chart(Chart),
}

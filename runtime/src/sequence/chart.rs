//! The shape of a sequence: a chart of steps, transitions and actions.
//!
//! Conditions and code actions are named by a `code` number that the host
//! running the chart understands (a code block of the sequence's unit once
//! compiled); the engine itself decides only *when* they run.

use crate::strategy::qualifier::Qualifier;

/// A chart: the sequence's ROOT chart, or the chart of a chart action.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Chart {
    pub steps: Vec<Step>,
    pub transitions: Vec<Transition>,
    pub actions: Vec<Action>,
}

/// A step and its action associations, in the order they are listed.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    pub name: String,
    pub initial: bool,
    pub assocs: Vec<Assoc>,
}

/// `Action(Q)` or `Action(Q, T#…)`: an action of the same chart, by index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Assoc {
    pub action: usize,
    pub qualifier: Qualifier,
    /// The time of L, D and E, in µs.
    pub time_us: u64,
}

/// A transition from all of `from` to all of `to` (simultaneous divergence
/// and convergence when there are several).
#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    pub name: String,
    pub from: Vec<usize>,
    pub to: Vec<usize>,
    /// Lowest fires first among those leaving one step; `None` after every
    /// numbered one, in source order.
    pub priority: Option<u32>,
    /// The host's number for the condition.
    pub code: usize,
}

/// An action: ST (or ladder) code the host runs, or a chart of its own.
#[derive(Clone, Debug, PartialEq)]
pub struct Action {
    pub name: String,
    pub body: Body,
}

#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    Code(usize),
    Chart(Box<Chart>),
}

impl Chart {
    pub fn step(&self, name: &str) -> Option<usize> {
        self.steps.iter().position(|s| s.name.eq_ignore_ascii_case(name))
    }

    pub fn transition(&self, name: &str) -> Option<usize> {
        self.transitions.iter().position(|t| t.name.eq_ignore_ascii_case(name))
    }

    /// Transitions in the order they are tried: by priority, then as written.
    pub fn firing_order(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.transitions.len()).collect();
        order.sort_by_key(|&t| (self.transitions[t].priority.unwrap_or(u32::MAX), t));
        order
    }
}

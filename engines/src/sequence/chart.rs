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
    /// The step's number in the whole sequence: code reads its `.X` and
    /// `.T` from retained slots `2 × slot` and `2 × slot + 1`.
    pub slot: usize,
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

    /// Whether this chart or a chart action's chart has a step `name`.
    pub fn has_step(&self, name: &str) -> bool {
        self.step(name).is_some() || self.sub_charts().any(|c| c.has_step(name))
    }

    /// Whether this chart or a chart action's chart has a transition `name`.
    pub fn has_transition(&self, name: &str) -> bool {
        self.transition(name).is_some() || self.sub_charts().any(|c| c.has_transition(name))
    }

    fn sub_charts(&self) -> impl Iterator<Item = &Chart> {
        self.actions.iter().filter_map(|a| match &a.body {
            Body::Chart(c) => Some(c.as_ref()),
            Body::Code(_) => None,
        })
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

impl Chart {
    /// Chart `index` of a verified sequence unit (the ROOT chart is 0).
    /// The verifier has checked every index, so nothing here can fail.
    pub fn from_unit(unit: &crate::object::Unit, index: usize) -> Chart {
        let Some(c) = unit.charts.get(index) else { return Chart::default() };
        let steps = c
            .steps
            .iter()
            .map(|s| Step {
                name: s.name.clone(),
                initial: s.initial != 0,
                slot: usize::from(s.slot),
                assocs: s
                    .assocs
                    .iter()
                    .map(|a| Assoc {
                        action: usize::from(a.action),
                        qualifier: qualifier_of(a.qualifier).unwrap_or(Qualifier::N),
                        time_us: a.time_us,
                    })
                    .collect(),
            })
            .collect();
        let transitions = c
            .transitions
            .iter()
            .map(|t| Transition {
                name: t.name.clone(),
                from: t.from.iter().map(|&s| usize::from(s)).collect(),
                to: t.to.iter().map(|&s| usize::from(s)).collect(),
                priority: (t.priority != u32::MAX).then_some(t.priority),
                code: usize::from(t.block),
            })
            .collect();
        let actions = c
            .actions
            .iter()
            .map(|a| Action {
                name: a.name.clone(),
                body: match a.kind {
                    1 => Body::Chart(Box::new(Chart::from_unit(unit, usize::from(a.index)))),
                    _ => Body::Code(usize::from(a.index)),
                },
            })
            .collect();
        Chart { steps, transitions, actions }
    }
}

/// A qualifier from its letter as stored in an object.
pub fn qualifier_of(letter: u8) -> Option<Qualifier> {
    std::str::from_utf8(&[letter]).ok().and_then(Qualifier::parse)
}

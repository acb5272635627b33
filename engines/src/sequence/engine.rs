//! One scan of a chart: transitions, then actions (docs/sequences.md).
//!
//! 1. Each transition whose source steps were all active before this scan,
//!    none of them held, is evaluated against the database as it stands;
//!    a forced one counts as its forced value. In firing order (priority,
//!    then as written) a TRUE transition fires unless an earlier one in
//!    this scan already took one of its source steps, so only the first
//!    TRUE transition leaving a step fires. All firing transitions fire
//!    together: sources deactivate, targets activate with `.T` = 0.
//! 2. Actions run, steps in order, associations as listed (P N L D E F S R),
//!    then every stored action; an action runs at most once per scan. A
//!    chart action scans its chart once per scan in which it runs; when it
//!    stops, its chart is reset.

use super::chart::{Body, Chart};
use crate::errors::RuntimeError;
use crate::strategy::qualifier::Qualifier;
use std::collections::{HashMap, HashSet};

/// What the engine asks of whoever runs the code.
pub trait Host {
    /// Evaluates transition condition `code` (a truth value).
    fn condition(&mut self, code: usize) -> Result<bool, RuntimeError>;
    /// Runs code action `code` once.
    fn action(&mut self, code: usize) -> Result<(), RuntimeError>;
    /// Something happened, for the trace.
    fn event(&mut self, _e: Event) {}
    /// A step's `.X` or `.T` changed (`slot` as in [`super::chart::Step`]).
    fn step_flags(&mut self, _slot: usize, _x: bool, _t_us: u64) {}
}

/// A change the engine reports (names are unique in a whole sequence).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Event<'a> {
    Activated(&'a str),
    Deactivated(&'a str),
    Fired(&'a str),
    Ran(&'a str),
}

/// The monitor's controls (guide §20.6.2), by name.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Monitor {
    /// Held steps: active and held, they stay active whatever their
    /// outgoing transitions say.
    pub held: HashSet<String>,
    /// Forced transitions: TRUE is "continue", FALSE is "hold".
    pub forced: HashMap<String, bool>,
}

impl Monitor {
    fn is_held(&self, step: &str) -> bool {
        self.held.iter().any(|h| h.eq_ignore_ascii_case(step))
    }

    fn forced(&self, transition: &str) -> Option<bool> {
        self.forced.iter().find(|(n, _)| n.eq_ignore_ascii_case(transition)).map(|(_, v)| *v)
    }
}

/// The live state of one chart.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ChartState {
    pub active: Vec<bool>,
    /// `.T` of each step in µs: time active, kept after it deactivates.
    pub elapsed: Vec<u64>,
    /// E associations that fired since their step activated, per step.
    pub(crate) e_fired: Vec<Vec<bool>>,
    pub(crate) stored: Vec<bool>,
    /// The state of each chart action's chart while the action runs.
    pub(crate) children: Vec<Option<ChartState>>,
    /// The initial steps are activated at the next scan.
    pub(crate) pending_start: bool,
    /// Per-scan working sets, kept to be reused: a scan allocates nothing.
    scratch: Scratch,
}

#[derive(Clone, Debug, Default, PartialEq)]
struct Scratch {
    activating: Vec<bool>,
    deactivating: Vec<bool>,
    truth: Vec<bool>,
    taken: Vec<bool>,
    firing: Vec<usize>,
    ran: Vec<bool>,
    /// The chart's firing order, computed once.
    order: Vec<usize>,
}

impl Scratch {
    fn clear(&mut self, chart: &Chart) {
        for (v, n) in [
            (&mut self.activating, chart.steps.len()),
            (&mut self.deactivating, chart.steps.len()),
            (&mut self.truth, chart.transitions.len()),
            (&mut self.taken, chart.steps.len()),
            (&mut self.ran, chart.actions.len()),
        ] {
            v.clear();
            v.resize(n, false);
        }
        self.firing.clear();
        self.firing.reserve(chart.transitions.len());
        if self.order.len() != chart.transitions.len() {
            self.order = chart.firing_order();
        }
    }
}

/// What a scan does apart from running code.
pub struct Scan<'m> {
    /// µs since the last scan (the step timers advance by it).
    pub dt_us: u64,
    /// Transitions are disabled (SFC_CON Hold).
    pub hold: bool,
    pub monitor: &'m Monitor,
}

impl ChartState {
    /// A chart that starts at its initial steps at its next scan.
    pub fn start(chart: &Chart) -> ChartState {
        ChartState {
            active: vec![false; chart.steps.len()],
            elapsed: vec![0; chart.steps.len()],
            e_fired: chart.steps.iter().map(|s| vec![false; s.assocs.len()]).collect(),
            stored: vec![false; chart.actions.len()],
            children: vec![None; chart.actions.len()],
            pending_start: true,
            scratch: Scratch::default(),
        }
    }

    /// No step active, no action stored, timers at 0 (SFC_CON Reset).
    pub fn reset(&mut self, chart: &Chart) {
        *self = ChartState::start(chart);
        self.pending_start = false;
    }

    /// The state of chart action `a`'s chart while the action runs.
    pub fn child(&self, a: usize) -> Option<&ChartState> {
        self.children.get(a).and_then(Option::as_ref)
    }

    /// Whether the chart is at rest (no step active and none to start).
    pub fn is_idle(&self) -> bool {
        !self.pending_start && !self.active.iter().any(|&a| a)
    }

    /// Starts again from the initial steps at the next scan.
    pub fn restart(&mut self, chart: &Chart) {
        *self = ChartState::start(chart);
    }

    /// One scan of `chart`. Errors stop the scan where they happen.
    pub fn scan(&mut self, chart: &Chart, scan: &Scan, host: &mut dyn Host) -> Result<(), RuntimeError> {
        let mut k = std::mem::take(&mut self.scratch);
        k.clear(chart);
        let result = self.scan_with(chart, scan, host, &mut k);
        self.scratch = k;
        result
    }

    fn scan_with(
        &mut self,
        chart: &Chart,
        scan: &Scan,
        host: &mut dyn Host,
        k: &mut Scratch,
    ) -> Result<(), RuntimeError> {
        for (s, on) in self.active.iter().enumerate() {
            if *on && scan.dt_us > 0 {
                self.elapsed[s] = self.elapsed[s].saturating_add(scan.dt_us);
                host.step_flags(chart.steps[s].slot, true, self.elapsed[s]);
            }
        }
        if std::mem::take(&mut self.pending_start) {
            for (s, step) in chart.steps.iter().enumerate().filter(|(_, st)| st.initial) {
                self.activate(s, &mut k.activating);
                host.event(Event::Activated(&step.name));
                host.step_flags(step.slot, true, 0);
            }
        } else if !scan.hold {
            self.transitions(chart, scan.monitor, host, k)?;
        }
        self.actions(chart, scan, host, k)
    }

    fn activate(&mut self, s: usize, activating: &mut [bool]) {
        self.active[s] = true;
        self.elapsed[s] = 0;
        self.e_fired[s].fill(false);
        activating[s] = true;
    }

    fn transitions(
        &mut self,
        chart: &Chart,
        monitor: &Monitor,
        host: &mut dyn Host,
        k: &mut Scratch,
    ) -> Result<(), RuntimeError> {
        // Every condition is evaluated before any transition fires.
        let truth = &mut k.truth;
        for (i, t) in chart.transitions.iter().enumerate() {
            let enabled = t.from.iter().all(|&s| self.active[s] && !monitor.is_held(&chart.steps[s].name));
            if enabled {
                truth[i] = match monitor.forced(&t.name) {
                    Some(v) => v,
                    None => host.condition(t.code)?,
                };
            }
        }
        let (taken, firing) = (&mut k.taken, &mut k.firing);
        for &i in &k.order {
            let t = &chart.transitions[i];
            if truth[i] && t.from.iter().all(|&s| !taken[s]) {
                t.from.iter().for_each(|&s| taken[s] = true);
                firing.push(i);
            }
        }
        for &i in firing.iter() {
            let t = &chart.transitions[i];
            host.event(Event::Fired(&t.name));
            for &s in &t.from {
                self.active[s] = false;
                k.deactivating[s] = true;
                host.event(Event::Deactivated(&chart.steps[s].name));
                host.step_flags(chart.steps[s].slot, false, self.elapsed[s]);
            }
        }
        for &i in firing.iter() {
            for &s in &chart.transitions[i].to {
                self.activate(s, &mut k.activating);
                host.event(Event::Activated(&chart.steps[s].name));
                host.step_flags(chart.steps[s].slot, true, 0);
            }
        }
        Ok(())
    }

    /// Whether association `k` of step `s` runs its action in this scan;
    /// S and R change what is stored.
    fn association_runs(&mut self, chart: &Chart, s: usize, k: usize, activating: bool, deactivating: bool) -> bool {
        let a = chart.steps[s].assocs[k];
        let (on, t) = (self.active[s], self.elapsed[s]);
        match a.qualifier {
            Qualifier::P => activating && on,
            Qualifier::N => on,
            Qualifier::L => on && t < a.time_us,
            Qualifier::D => on && t >= a.time_us,
            Qualifier::E => {
                let run = on && t >= a.time_us && !self.e_fired[s][k];
                self.e_fired[s][k] |= run;
                run
            }
            Qualifier::F => deactivating,
            Qualifier::S | Qualifier::R => {
                if activating {
                    self.stored[a.action] = a.qualifier == Qualifier::S;
                }
                false
            }
        }
    }

    fn actions(
        &mut self,
        chart: &Chart,
        scan: &Scan,
        host: &mut dyn Host,
        k: &mut Scratch,
    ) -> Result<(), RuntimeError> {
        let ran = &mut k.ran;
        for s in 0..chart.steps.len() {
            for n in 0..chart.steps[s].assocs.len() {
                let a = chart.steps[s].assocs[n].action;
                if self.association_runs(chart, s, n, k.activating[s], k.deactivating[s]) && !ran[a] {
                    ran[a] = true;
                    self.run_action(chart, a, scan, host)?;
                }
            }
        }
        for (a, done) in ran.iter_mut().enumerate() {
            if self.stored[a] && !*done {
                *done = true;
                self.run_action(chart, a, scan, host)?;
            }
        }
        // A chart action that did not run is reset, to start afresh; the
        // steps it had active are left (a trace says so).
        for ((child, done), action) in self.children.iter_mut().zip(ran.iter()).zip(&chart.actions) {
            if *done {
                continue;
            }
            if let (Some(child), Body::Chart(sub)) = (child.take(), &action.body) {
                child.leave(sub, host);
            }
        }
        Ok(())
    }

    /// Tells the host that every active step of this chart, and of its
    /// running chart actions, is left: the chart is being dropped.
    fn leave(&self, chart: &Chart, host: &mut dyn Host) {
        for (s, on) in self.active.iter().enumerate() {
            if *on {
                host.event(Event::Deactivated(&chart.steps[s].name));
            }
        }
        for (a, child) in self.children.iter().enumerate() {
            if let (Some(c), Body::Chart(sub)) = (child, &chart.actions[a].body) {
                c.leave(sub, host);
            }
        }
    }

    fn run_action(&mut self, chart: &Chart, a: usize, scan: &Scan, host: &mut dyn Host) -> Result<(), RuntimeError> {
        let action = &chart.actions[a];
        host.event(Event::Ran(&action.name));
        match &action.body {
            Body::Code(code) => host.action(*code),
            Body::Chart(sub) => {
                let child = self.children[a].get_or_insert_with(|| ChartState::start(sub));
                child.scan(sub, scan, host)
            }
        }
    }
}

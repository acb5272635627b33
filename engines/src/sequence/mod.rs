//! Sequences (SFC): the engine an SFC_CON block runs (guide chapter 9,
//! §20.5–20.6; the rules are in docs/sequences.md).
//!
//! A [`Sequence`] is a chart, its live state, the SFC_CON status and the
//! monitor's controls. Each [`Sequence::scan`] is one run of the SFC_CON
//! block's task. The engine decides when transitions are evaluated and
//! actions run; a [`engine::Host`] evaluates and runs the code.

pub mod chart;
pub mod engine;
pub mod host;

use chart::Chart;
use engine::{ChartState, Host, Monitor, Scan};

use crate::errors::RuntimeError;

fn find_step(chart: &Chart, state: Option<&ChartState>, name: &str) -> Option<(bool, u64)> {
    if let Some(s) = chart.step(name) {
        return Some(state.map_or((false, 0), |st| (st.active[s], st.elapsed[s])));
    }
    chart.actions.iter().enumerate().find_map(|(a, action)| match &action.body {
        chart::Body::Chart(sub) => find_step(sub, state.and_then(|st| st.child(a)), name),
        chart::Body::Code(_) => None,
    })
}

/// SFC_CON's `Status` (§20.6.3).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// No step active; `Run` starts from the initial steps.
    Reset,
    Running,
    /// Transitions disabled; steps, timers and actions go on.
    Held,
    /// Actions halted and timers frozen; steps stay active.
    Stopped,
    /// A runtime error stopped the sequence; `Reset` clears it.
    Error,
}

impl Status {
    /// The status as SFC_CON's `Status` field, the console and state files name it.
    pub fn name(self) -> &'static str {
        match self {
            Status::Reset => "RESET",
            Status::Running => "RUNNING",
            Status::Held => "HELD",
            Status::Stopped => "STOPPED",
            Status::Error => "ERROR",
        }
    }
}

/// SFC_CON's commands. A command written in a scan takes effect at the
/// start of the next one: the caller applies it before [`Sequence::scan`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Command {
    Run,
    Hold,
    Stop,
    Reset,
}

/// A sequence and everything that survives from scan to scan.
#[derive(Clone, Debug)]
pub struct Sequence {
    pub chart: Chart,
    pub state: ChartState,
    pub status: Status,
    pub monitor: Monitor,
    pub(crate) last_us: Option<u64>,
}

impl Sequence {
    /// A sequence at rest (Reset): nothing runs until `Run`.
    pub fn new(chart: Chart) -> Sequence {
        let mut state = ChartState::start(&chart);
        state.reset(&chart);
        Sequence { chart, state, status: Status::Reset, monitor: Monitor::default(), last_us: None }
    }

    /// Applies an SFC_CON command.
    pub fn command(&mut self, c: Command) {
        let was_scanning = matches!(self.status, Status::Running | Status::Held);
        self.status = match (c, self.status) {
            (Command::Reset, _) => {
                self.state.reset(&self.chart);
                Status::Reset
            }
            // An error stands until the sequence is reset.
            (_, Status::Error) => Status::Error,
            (Command::Run, Status::Reset) => {
                self.state.restart(&self.chart);
                Status::Running
            }
            (Command::Run, _) => Status::Running,
            (Command::Hold, Status::Reset) => Status::Reset,
            (Command::Hold, _) => Status::Held,
            (Command::Stop, Status::Reset) => Status::Reset,
            (Command::Stop, _) => Status::Stopped,
        };
        // Time spent stopped does not count: the first scan after a Run
        // adds nothing to the step timers.
        if !was_scanning {
            self.last_us = None;
        }
    }

    /// One scan at simulated time `now_us`. Stopped, reset or failed
    /// sequences do nothing, and their timers do not advance.
    pub fn scan(&mut self, now_us: u64, host: &mut dyn Host) -> Result<(), RuntimeError> {
        let dt_us = self.last_us.map_or(0, |last| now_us.saturating_sub(last));
        self.last_us = Some(now_us);
        let hold = match self.status {
            Status::Running => false,
            Status::Held => true,
            Status::Reset | Status::Stopped | Status::Error => return Ok(()),
        };
        let scan = Scan { dt_us, hold, monitor: &self.monitor };
        let result = self.state.scan(&self.chart, &scan, host);
        if result.is_err() {
            self.status = Status::Error;
        }
        result
    }

    /// `.X` and `.T` (µs) of a step, in the ROOT chart or a chart action's
    /// chart (a chart that is not running has every step inactive at 0).
    pub fn step(&self, name: &str) -> Option<(bool, u64)> {
        find_step(&self.chart, Some(&self.state), name)
    }

    /// How many steps of the ROOT chart are active (SFC_CON's `Steps`).
    pub fn active_count(&self) -> usize {
        self.state.active.iter().filter(|&&on| on).count()
    }

    /// The names of the active steps of the ROOT chart, in order.
    pub fn active_steps(&self) -> Vec<&str> {
        self.chart.steps.iter().zip(&self.state.active).filter(|(_, &on)| on).map(|(s, _)| s.name.as_str()).collect()
    }
}

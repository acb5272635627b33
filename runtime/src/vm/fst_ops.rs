//! The FST-only instructions (ADR 0010): step budget, pauses for WT and
//! BRK, the device clock, the alarm and event logs and the history
//! archives. The verifier lets them appear only in FST units.

use super::{Running, Vm};
use crate::errors::Fault;
use crate::isa::Op;
use crate::roc::{day_of_week, minutes_since_midnight, HistFn, LogEntry};
use crate::store::Store;
use crate::vm::Activation;
use linc_stdlib::Env;

/// What the dispatch loop does after an FST instruction.
pub(super) enum FstFlow {
    Go,
    /// The step budget is spent: the next run begins this step.
    SuspendHere,
    /// WT or BRK: the next run goes on after this instruction.
    SuspendAfter,
}

fn halt(e: crate::roc::HistError) -> Fault {
    Fault::new(e.code, e.message)
}

impl Vm {
    pub(super) fn fst_op(
        &mut self,
        op: Op,
        l: &Running,
        act: &mut Activation,
        store: &mut Store,
    ) -> Result<FstFlow, Fault> {
        match op {
            Op::Step { n } => {
                if act.steps_left == 0 {
                    return Ok(FstFlow::SuspendHere);
                }
                act.steps_left -= 1;
                act.step = n;
            }
            Op::Pause { why } => {
                act.pause = Some((why, self.pop_r()));
                return Ok(FstFlow::SuspendAfter);
            }
            Op::DayTime { what } => {
                let now = self.clock.local_time();
                self.push_r(if what == 0 { day_of_week(now) } else { minutes_since_midnight(now) });
            }
            Op::Log { which } => {
                let text = self.pop_s();
                let value = self.pop_r();
                let source = l.prog.own.map(|b| store.db.blocks[b].name.clone()).unwrap_or_default();
                let text = String::from_utf8_lossy(&text).chars().take(10).collect();
                let entry = LogEntry { time: self.clock.local_time(), text, value, source };
                let log = if which == 0 { &mut store.roc.alarms } else { &mut store.roc.events };
                log.push(entry);
            }
            Op::HistWrite { time } => {
                let idx = self.pop_r();
                let hp = self.pop_r();
                let value = self.pop_r();
                let value = (time == 0).then_some(value);
                let next = store.roc.history.write(hp, idx, value, self.clock.local_time()).map_err(halt)?;
                self.push_r(next);
            }
            Op::HistRead { f } => {
                let a2 = self.pop_r();
                let a1 = self.pop_r();
                let f = HistFn::from_u8(f).ok_or_else(super::corrupt)?;
                let (v, next) = store.roc.history.read(f, a1, a2).map_err(halt)?;
                self.push_r(v);
                self.push_r(next);
            }
            _ => {}
        }
        Ok(FstFlow::Go)
    }
}

//! The host that runs a verified, linked sequence unit's code in the VM:
//! a transition's condition is a code block that returns a truth value, a
//! code action is a code block, and the engine's step flags go into the
//! unit's retained slots where compiled code reads `Step.X` and `Step.T`.

use super::engine::{Event, Host};
use crate::errors::RuntimeError;
use crate::link::Linked;
use crate::store::Store;
use crate::strategy::trace::Trace;
use crate::vm::{Activation, Vm};
use linc_stdlib::Value;

/// Where a sequence's events and field writes are traced.
pub struct Traced<'a, 'w> {
    pub trace: &'a mut Trace<'w>,
    pub now_us: u64,
    pub task: u8,
    pub program: &'a str,
}

/// Runs the code of one sequence program.
pub struct VmHost<'a, 'w> {
    pub vm: &'a mut Vm,
    pub linked: &'a Linked,
    /// The program's one activation: its retained slots hold the step flags.
    pub act: &'a mut Activation,
    pub store: &'a mut Store,
    pub trace: Option<Traced<'a, 'w>>,
}

impl VmHost<'_, '_> {
    fn run(&mut self, block: usize) -> Result<Option<Value>, RuntimeError> {
        self.act.block = block;
        let result = match self.trace.as_mut() {
            Some(t) => {
                let mut note = |s: &Store, cell: u32| t.trace.write(s, t.now_us, t.task, t.program, cell);
                self.vm.run(self.linked, self.act, self.store, Some(&mut note))
            }
            None => self.vm.run(self.linked, self.act, self.store, None),
        };
        result?;
        Ok(self.act.result.take())
    }
}

impl Host for VmHost<'_, '_> {
    fn condition(&mut self, code: usize) -> Result<bool, RuntimeError> {
        // The verifier proved a condition block returns a truth value.
        Ok(matches!(self.run(code)?, Some(Value::Bool(true))))
    }

    fn action(&mut self, code: usize) -> Result<(), RuntimeError> {
        self.run(code).map(|_| ())
    }

    fn event(&mut self, e: Event) {
        if let Some(c) = self.linked.coverage() {
            let unit = self.linked.program(self.act.program).map_or(usize::MAX, |p| p.unit);
            match e {
                Event::Activated(step) => c.entered(unit, step),
                Event::Fired(transition) => c.fired(unit, transition),
                Event::Deactivated(_) | Event::Ran(_) => {}
            }
        }
        if let Some(t) = self.trace.as_mut() {
            t.trace.sequence_event(e, t.now_us, t.task, t.program);
        }
    }

    fn step_flags(&mut self, slot: usize, x: bool, t_us: u64) {
        let seconds = (t_us as f64 / 1e6) as f32;
        if let Some(pair) = self.act.retained.get_mut(2 * slot..2 * slot + 2) {
            pair[0] = u32::from(x);
            pair[1] = seconds.to_bits();
        }
    }
}

//! The host that runs a verified, linked sequence unit's code in the VM:
//! a transition's condition is a code block that returns a truth value, a
//! code action is a code block, and the engine's step flags go into the
//! unit's retained slots where compiled code reads `Step.X` and `Step.T`.

use super::engine::{Event, Host};
use crate::errors::RuntimeError;
use crate::link::Linked;
use crate::store::Store;
use crate::vm::{Activation, Vm};
use linc_stdlib::Value;

/// Runs the code of one sequence program; events go to `on_event`.
pub struct VmHost<'a> {
    pub vm: &'a mut Vm,
    pub linked: &'a Linked,
    /// The program's one activation: its retained slots hold the step flags.
    pub act: &'a mut Activation,
    pub store: &'a mut Store,
    pub on_event: Option<&'a mut dyn FnMut(Event)>,
}

impl VmHost<'_> {
    fn run(&mut self, block: usize) -> Result<Option<Value>, RuntimeError> {
        self.act.block = block;
        self.vm.run(self.linked, self.act, self.store, None)?;
        Ok(self.act.result.take())
    }
}

impl Host for VmHost<'_> {
    fn condition(&mut self, code: usize) -> Result<bool, RuntimeError> {
        // The verifier proved a condition block returns a truth value.
        Ok(matches!(self.run(code)?, Some(Value::Bool(true))))
    }

    fn action(&mut self, code: usize) -> Result<(), RuntimeError> {
        self.run(code).map(|_| ())
    }

    fn event(&mut self, e: Event) {
        if let Some(f) = self.on_event.as_mut() {
            f(e);
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

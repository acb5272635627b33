//! Coverage counting in compiled code (ADR 0020). A count is kept in a
//! Cranelift variable (a register in a loop) from the block's entry and
//! added to its counter in memory at each exit, with the promoted cells: a
//! load, add and store at every statement of a tight loop made it more
//! than twice as slow. A block with more counts than [`MAX_IN_VARIABLES`]
//! adds to memory at each count instead, so that the exits, which write
//! every variable back, stay small.

use super::Emitter;
use cranelift_codegen::ir::{types, InstBuilder, MemFlags, Value};
use cranelift_frontend::Variable;
use std::collections::HashMap;

/// The most counts a block keeps in variables.
const MAX_IN_VARIABLES: usize = 128;

/// The counts kept in variables: (instruction, whether it is the taken
/// count, variable), in the order the exits write them back.
#[derive(Default)]
pub(super) struct CounterVars {
    vars: Vec<(usize, bool, Variable)>,
    index: HashMap<(usize, bool), usize>,
}

impl Emitter<'_, '_> {
    /// Declares the block's count variables, each 0 at entry (the builder
    /// is in the entry block).
    pub(super) fn declare_counters(&mut self) {
        let Some(points) = self.s.points else { return };
        let mut wanted: Vec<(usize, bool)> = Vec::new();
        for (pc, op) in self.s.ops.iter().enumerate() {
            if points.get(pc).copied().unwrap_or(false) {
                wanted.push((pc, false));
            }
            if crate::cover::is_decision(op) {
                wanted.push((pc, true));
            }
        }
        if wanted.len() > MAX_IN_VARIABLES {
            return;
        }
        let zero = self.b.ins().iconst(types::I64, 0);
        for (i, key) in wanted.into_iter().enumerate() {
            let var = self.b.declare_var(types::I64);
            self.b.def_var(var, zero);
            self.counter_vars.vars.push((key.0, key.1, var));
            self.counter_vars.index.insert(key, i);
        }
    }

    /// One more run of instruction `pc`, if it is counted.
    pub(super) fn count_hit(&mut self, pc: usize) {
        if self.s.points.and_then(|p| p.get(pc).copied()) == Some(true) {
            self.count(pc, false, None);
        }
    }

    /// `by` (an I64 of 0 or 1) more jumps of the conditional jump at `pc`.
    pub(super) fn count_taken(&mut self, pc: usize, by: Value) {
        self.count(pc, true, Some(by));
    }

    fn count(&mut self, pc: usize, taken: bool, by: Option<Value>) {
        if self.counters.is_none() {
            return;
        }
        match self.counter_vars.index.get(&(pc, taken)) {
            Some(&i) => {
                let var = self.counter_vars.vars[i].2;
                let old = self.b.use_var(var);
                let new = self.plus(old, by);
                self.b.def_var(var, new);
            }
            None => self.add_to_counter(pc, taken, by),
        }
    }

    /// `old` plus `by`, or plus one.
    fn plus(&mut self, old: Value, by: Option<Value>) -> Value {
        match by {
            Some(v) => self.b.ins().iadd(old, v),
            None => self.b.ins().iadd_imm(old, 1),
        }
    }

    /// Adds `by`, or one, to the counter in memory of instruction `pc`
    /// (its taken count if `taken`).
    fn add_to_counter(&mut self, pc: usize, taken: bool, by: Option<Value>) {
        let Some((hits, takens)) = self.counters else { return };
        let (base, off) = (if taken { takens } else { hits }, (pc * 8) as i32);
        let old = self.b.ins().load(types::I64, MemFlags::trusted(), base, off);
        let new = self.plus(old, by);
        self.b.ins().store(MemFlags::trusted(), new, base, off);
    }

    /// The counts kept in variables, as an exit passes them on.
    pub(super) fn counter_values(&mut self, vals: &mut Vec<Value>) {
        for i in 0..self.counter_vars.vars.len() {
            let var = self.counter_vars.vars[i].2;
            vals.push(self.b.use_var(var));
        }
    }

    /// Adds the next values, one per count variable, to their counters.
    pub(super) fn flush_counters(&mut self, vals: &mut impl Iterator<Item = Value>) {
        for i in 0..self.counter_vars.vars.len() {
            let Some(v) = vals.next() else { return };
            let (pc, taken, _) = self.counter_vars.vars[i];
            self.add_to_counter(pc, taken, Some(v));
        }
    }
}

//! The cold exits of compiled code: a bail-out that hands the
//! interpreter its state before an instruction, and the exit after a
//! runtime service faulted.
//!
//! The exits of one kind from one basic block share one exit block; each
//! branch to it passes its pc and what the exit writes back (stack, locals,
//! promoted cells, reference, budget) as arguments. Two costs are avoided:
//! - an exit block of its own per check wrote every promoted cell, so the
//!   code grew by (checks × cells) stores;
//! - worse, a value read only inside an exit is computed only there:
//!   Cranelift's optimiser rebuilt the whole chain of updates of a cell in
//!   every exit that wrote it back (an exit block with one predecessor has
//!   its parameters folded away again), which made translating a long
//!   block quadratic (400 statements `N1 := N1 + N0 / k MOD 7`: 20,490
//!   instructions became 247,203 and took 3.4 s). A value that differs
//!   between the branches to an exit block stays an argument, computed on
//!   the main path where the code needs it anyway; one that is the same in
//!   all of them (a constant, a cell not written in the block) is folded
//!   into the exit block and costs the main path nothing.

use super::{frame_off, Emitter, Ty};
use crate::jit::Frame;
use cranelift_codegen::ir::{types, Block, BlockArg, InstBuilder, MemFlags, Value};
use std::mem::offset_of;

/// Where a cold exit leaves to.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Exit {
    /// Back to the interpreter at the start of the basic block, whose
    /// instructions were not charged to the budget: the budget would run
    /// out inside the block, or the code ran off its end.
    Budget,
    /// Back to the interpreter before an instruction of the block, which
    /// has been charged for all its instructions: the ones not run are
    /// refunded.
    Check,
    /// After a runtime service faulted: only the cells go back.
    Fault,
}

/// Which shared exit block an exit uses: the basic block it leaves from
/// (its leader), the kind of exit, and the stack shape of a bail-out.
pub(super) type ExitKey = (usize, Exit, Vec<Ty>);

impl Emitter<'_, '_> {
    /// The values an exit writes back, in the order of its block's
    /// parameters after the pc: for a bail-out the stack before `pc`, the
    /// locals, the promoted cells, the reference and the budget; for a
    /// fault (`None`) the promoted cells.
    fn exit_values(&mut self, bail_at: Option<usize>) -> Vec<Value> {
        let mut vals = Vec::new();
        if let Some(pc) = bail_at {
            let st = self.s.states.get(pc).cloned().flatten().unwrap_or_default();
            for (d, &ty) in st.iter().enumerate() {
                vals.push(self.b.use_var(self.var(d, ty)));
            }
            for i in 0..self.locals.len() {
                vals.push(self.b.use_var(self.locals[i]));
            }
        }
        for slot in 0..self.slots.len() {
            if let Some(var) = self.slots[slot] {
                vals.push(self.b.use_var(var));
            }
        }
        self.counter_values(&mut vals);
        if let Some(pc) = bail_at {
            let r = if self.ref_live.get(pc).copied().unwrap_or(true) {
                self.b.use_var(self.ref_slot)
            } else {
                match self.no_ref {
                    Some(v) => v,
                    None => self.b.ins().iconst(types::I32, -1),
                }
            };
            vals.push(r);
            vals.push(self.b.use_var(self.budget));
        }
        vals
    }

    /// The exit block for leaving through `exit` before `pc`, and the
    /// arguments of a branch to it from here.
    fn exit_target(&mut self, exit: Exit, pc: usize) -> (Block, Vec<BlockArg>) {
        let pc_value = self.b.ins().iconst(types::I32, pc as i64);
        self.exit_target_at(exit, pc, pc_value)
    }

    /// [`Emitter::exit_target`] with the pc reported computed at run time
    /// (`pc_value`; a fault inside a run of string instructions).
    fn exit_target_at(&mut self, exit: Exit, pc: usize, pc_value: Value) -> (Block, Vec<BlockArg>) {
        let bail_at = (exit != Exit::Fault).then_some(pc);
        let shape = bail_at.and_then(|pc| self.s.states.get(pc).cloned().flatten()).unwrap_or_default();
        let mut vals = vec![pc_value];
        vals.extend(self.exit_values(bail_at));
        let key = (self.leader, exit, shape);
        let block = match self.exits.get(&key) {
            Some(b) => *b,
            None => {
                let b = self.b.create_block();
                self.b.set_cold_block(b);
                for &v in &vals {
                    let ty = self.b.func.dfg.value_type(v);
                    self.b.append_block_param(b, ty);
                }
                self.exits.insert(key.clone(), b);
                self.exit_order.push((key, b));
                b
            }
        };
        (block, vals.into_iter().map(BlockArg::Value).collect())
    }

    /// Leaves through `exit` before `pc` when `cond` holds, else goes on in
    /// a new block.
    pub(super) fn exit_if(&mut self, cond: Value, exit: Exit, pc: usize) {
        let target = self.exit_target(exit, pc);
        self.branch_out(cond, target);
    }

    /// Leaves through the fault exit, reporting the fault at instruction
    /// `pc_value`, when `cond` holds.
    pub(super) fn fault_if_at(&mut self, cond: Value, pc_value: Value) {
        let target = self.exit_target_at(Exit::Fault, 0, pc_value);
        self.branch_out(cond, target);
    }

    /// Branches to the exit `(out, args)` when `cond` holds, else goes on
    /// in a new block.
    fn branch_out(&mut self, cond: Value, (out, args): (Block, Vec<BlockArg>)) {
        let cont = self.b.create_block();
        self.b.ins().brif(cond, out, &args, cont, &[]);
        self.b.switch_to_block(cont);
    }

    /// Leaves through `exit` before `pc`.
    pub(super) fn exit_now(&mut self, exit: Exit, pc: usize) {
        let (out, args) = self.exit_target(exit, pc);
        self.b.ins().jump(out, &args);
    }

    /// Bails out before `pc` when `fault` is true.
    pub(super) fn check(&mut self, pc: usize, fault: Value) {
        self.exit_if(fault, Exit::Check, pc);
    }

    /// Emits the shared exit blocks: each writes its arguments to the
    /// frame and returns status 1 (bail) or 2 (fault).
    pub(super) fn exit_blocks(&mut self) {
        for ((leader, exit, shape), block) in std::mem::take(&mut self.exit_order) {
            self.b.switch_to_block(block);
            let params = self.b.block_params(block).to_vec();
            let mut vals = params.iter().copied();
            let Some(pc) = vals.next() else { continue };
            let f = self.frame();
            self.b.ins().store(MemFlags::trusted(), pc, f, frame_off(offset_of!(Frame, pc)));
            if exit == Exit::Fault {
                self.flush_values(&mut vals);
                let two = self.b.ins().iconst(types::I32, 2);
                self.b.ins().return_(&[two]);
                continue;
            }
            let stack = self.load_ptr(offset_of!(Frame, stack));
            for (d, v) in vals.by_ref().take(shape.len()).enumerate() {
                self.b.ins().store(MemFlags::trusted(), v, stack, (d * 4) as i32);
            }
            let locals = self.load_ptr(offset_of!(Frame, locals));
            for (i, v) in vals.by_ref().take(self.locals.len()).enumerate() {
                self.b.ins().store(MemFlags::trusted(), v, locals, (i * 4) as i32);
            }
            self.flush_values(&mut vals);
            if let (Some(r), Some(bud)) = (vals.next(), vals.next()) {
                self.b.ins().store(MemFlags::trusted(), r, f, frame_off(offset_of!(Frame, ref_slot)));
                let bud = match exit {
                    // The block charged ends[leader] - leader; the
                    // instructions from pc on did not run.
                    Exit::Check => {
                        let end = self.b.ins().iconst(types::I32, self.ends[leader] as i64);
                        let refund = self.b.ins().isub(end, pc);
                        let refund = self.b.ins().uextend(types::I64, refund);
                        self.b.ins().iadd(bud, refund)
                    }
                    _ => bud,
                };
                self.b.ins().store(MemFlags::trusted(), bud, f, frame_off(offset_of!(Frame, budget)));
            }
            let depth = self.b.ins().iconst(types::I32, shape.len() as i64);
            self.b.ins().store(MemFlags::trusted(), depth, f, frame_off(offset_of!(Frame, depth)));
            let one = self.b.ins().iconst(types::I32, 1);
            self.b.ins().return_(&[one]);
        }
    }

    /// Stores the promoted cells back to memory (at every exit).
    pub(super) fn flush(&mut self) {
        let vals = self.exit_values(None);
        self.flush_values(&mut vals.into_iter());
    }

    /// Stores the next values, one per promoted slot, to their slots, then
    /// adds the counts kept in variables to their counters.
    fn flush_values(&mut self, vals: &mut impl Iterator<Item = Value>) {
        let Some(mem) = self.mem else { return };
        for slot in 0..self.slots.len() {
            if self.slots[slot].is_some() {
                let Some(v) = vals.next() else { return };
                self.b.ins().store(MemFlags::trusted(), v, mem, (slot * 4) as i32);
            }
        }
        self.flush_counters(vals);
    }
}

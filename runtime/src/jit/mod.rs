//! The compiling tier: code blocks translated to machine code with
//! Cranelift (ADR 0011).
//!
//! Only blocks whose every instruction is in the numeric subset compile;
//! anything else is left to the interpreter, which stays the reference. The
//! compiled code works on a scratch copy of the program's cells and, where
//! the interpreter could fault or the watchdog could fire, it stops and
//! hands its exact state (pc, stack, locals, reference, budget) back to the
//! interpreter, which finishes the run. Faults and their positions are
//! therefore the interpreter's own by construction.

mod emit;
mod host;
mod plan;

use crate::isa::{Kind, Op};
use crate::link::Linked;
use crate::store::{Cell, Store};
use crate::vm::Vm;
use crate::wire::Bytes;
use cranelift_jit::JITModule;
use std::sync::{Arc, OnceLock};

pub(crate) use plan::{Plan, BOOL, INT, READONLY, REAL};

/// The largest block the tier translates, in instructions; a larger one
/// stays on the interpreter. Translating costs about 5–30 µs per
/// instruction (Cranelift's optimiser and register allocator), so a block
/// at this limit takes up to about 100 ms, which is the most `--tier auto`
/// spends on one block before running it; a 2.5 MB action (400,000
/// instructions in one loop) took 28 s and 730 MB to translate before there
/// was a limit (`docs/adr/0011-compiling-tier.md`).
pub const MAX_BLOCK_OPS: usize = 2_048;

/// The most Cranelift instructions a block may translate to (a second
/// bound, for instructions that expand to many, such as calls and string
/// services); translation stops as soon as it is passed.
pub(crate) const MAX_BLOCK_IR: usize = 8 * MAX_BLOCK_OPS;

/// The state handed between the VM and compiled code; the layout is read
/// by the generated code at fixed offsets.
#[repr(C)]
pub(crate) struct Frame {
    pub mem: *mut u32,
    pub kinds: *const u8,
    pub retained: *mut u32,
    pub stack: *mut u32,
    pub locals: *mut u32,
    pub budget: u64,
    pub pc: u32,
    pub depth: u32,
    pub ref_slot: u32,
    /// A numeric result of a runtime service ([`host`]).
    pub ret: u32,
    pub vm: *mut Vm,
    pub store: *mut Store,
    pub consts: *const Bytes,
    pub nconsts: usize,
    /// The run's tracer (`*mut Tracer`), for traced code.
    pub trace: *mut std::ffi::c_void,
    /// The code running, whose plan the trace service copies out.
    pub code: *const Compiled,
    pub mem_len: usize,
}

type Entry = unsafe extern "C" fn(*mut Frame) -> u32;

/// One compiled code block.
pub struct Compiled {
    entry: Entry,
    /// Kept so that the code's memory can be freed with the block.
    module: Option<JITModule>,
    plan: Plan,
    /// Numeric stack capacity a bail-out may need.
    max_depth: usize,
    locals: usize,
    retained: usize,
}

// SAFETY: the module is only touched when the `Compiled` is dropped, and
// the code it holds is immutable once finalised; calling it from several
// threads at once is safe because each call brings its own `Frame`.
unsafe impl Send for Compiled {}
unsafe impl Sync for Compiled {}

impl Drop for Compiled {
    fn drop(&mut self) {
        if let Some(m) = self.module.take() {
            // SAFETY: no pointer into the code outlives `self`.
            unsafe { m.free_memory() };
        }
    }
}

/// A block's compiled code once tried (`None`: not in the subset), and the
/// instructions the interpreter has run of it so far; clones of a `Linked`
/// share it.
#[derive(Default)]
pub(crate) struct SlotState {
    code: OnceLock<Option<Arc<Compiled>>>,
    /// The same block compiled to report its writes (for traced runs).
    traced: OnceLock<Option<Arc<Compiled>>>,
    interpreted: std::sync::atomic::AtomicU64,
    /// Whether the block has a backward jump (a loop), once looked at.
    looping: OnceLock<bool>,
}

type Slot = Arc<SlotState>;

/// Compiled code per (program, block), made on first use.
#[derive(Clone, Default)]
pub struct Cache {
    blocks: Vec<Vec<Slot>>,
}

impl std::fmt::Debug for Cache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Cache({} programs)", self.blocks.len())
    }
}

impl Cache {
    pub(crate) fn new(blocks_per_program: impl Iterator<Item = usize>) -> Cache {
        Cache { blocks: blocks_per_program.map(|n| (0..n).map(|_| Arc::default()).collect()).collect() }
    }

    /// The compiled code of a block with a loop, or of a straight block once
    /// the interpreter has run `after` instructions of it (0: at once),
    /// compiling it then. Compiling takes about 2 ms, so a straight block is
    /// compiled only when it has run about as long: short one-off programs
    /// stay on the interpreter.
    pub(crate) fn get(
        &self,
        linked: &Linked,
        store: &Store,
        (program, block): (usize, usize),
        after: u64,
        traced: bool,
    ) -> Option<Arc<Compiled>> {
        let slot = self.blocks.get(program)?.get(block)?;
        let cell = if traced { &slot.traced } else { &slot.code };
        if let Some(code) = cell.get() {
            return code.clone();
        }
        // A loop is where a run spends its time, and one run may be long
        // (a whole `linc run`): a block with a loop is compiled at once.
        let looping = *slot.looping.get_or_init(|| {
            linked
                .ops(program, block)
                .is_some_and(|ops| ops.iter().enumerate().any(|(i, op)| op.target().is_some_and(|t| (t as usize) <= i)))
        });
        if !looping && slot.interpreted.load(std::sync::atomic::Ordering::Relaxed) < after {
            return None;
        }
        cell.get_or_init(|| compile_as(linked, store, (program, block), traced).map(Arc::new)).clone()
    }

    /// Whether a block has been compiled (for tests and listings).
    pub fn is_compiled(&self, (program, block): (usize, usize)) -> bool {
        self.blocks.get(program).and_then(|p| p.get(block)).is_some_and(|s| s.code.get().is_some_and(Option::is_some))
    }

    /// Whether a block's traced variant has been compiled (for tests).
    pub fn is_compiled_traced(&self, (program, block): (usize, usize)) -> bool {
        self.blocks.get(program).and_then(|p| p.get(block)).is_some_and(|s| s.traced.get().is_some_and(Option::is_some))
    }

    /// Counts instructions the interpreter ran of a block not yet compiled.
    pub(crate) fn note_interpreted(&self, (program, block): (usize, usize), instructions: u64) {
        if let Some(slot) = self.blocks.get(program).and_then(|p| p.get(block)) {
            if slot.code.get().is_none() || slot.traced.get().is_none() {
                slot.interpreted.fetch_add(instructions, std::sync::atomic::Ordering::Relaxed);
            }
        }
    }
}

/// Compiles block `block` of `program`, or `None` when it uses anything
/// outside the subset or is larger than [`MAX_BLOCK_OPS`] (the interpreter
/// then runs it).
pub fn compile(linked: &Linked, store: &Store, program: usize, block: usize) -> Option<Compiled> {
    compile_as(linked, store, (program, block), false)
}

/// Compiles a block; `traced` code reports every write to the run's
/// tracer as the interpreter does.
fn compile_as(linked: &Linked, store: &Store, (program, block): (usize, usize), traced: bool) -> Option<Compiled> {
    let prog = linked.program(program)?;
    let unit = linked.unit(program)?;
    let ops = linked.ops(program, block)?;
    let code = unit.blocks.get(block)?;
    if ops.len() > MAX_BLOCK_OPS || !ops.iter().all(in_subset) {
        return None;
    }
    let plan = Plan::new(ops, &prog.targets, store, traced)?;
    let locals = usize::from(code.locals);
    let retained = usize::from(unit.retained);
    let (entry, module, max_depth) = emit::emit(ops, &plan, (locals, retained), traced)?;
    Some(Compiled { entry, module: Some(module), plan, max_depth, locals, retained })
}

/// Whether the compiled tier translates this instruction (the table's
/// `Compiled` flag; a `Return` only of a numeric value).
fn in_subset(op: &Op) -> bool {
    match op {
        Op::Return { kind } => Kind::from_bits(u32::from(*kind)) != Kind::Bytes,
        _ => op.has(crate::isa::Flag::Compiled),
    }
}

/// How a compiled run ended.
pub(crate) enum JitRun {
    /// Ran to `Ret`; the store holds the results.
    Done,
    /// Ran to `Return`: the value.
    Returned(linc_stdlib::Value),
    /// Stopped before instruction `pc`: the interpreter goes on from there
    /// with the stack and locals left in the VM's buffers.
    Bail { pc: usize, ref_cell: u32, budget: u64 },
    /// Instruction `pc` faulted in a runtime service (the fault is in
    /// `Vm::jit_fault`); what ran before it is in the store.
    Fault { pc: usize },
    /// Not used for this run (a forced cell, a store that does not match).
    Refused,
}

/// The VM's buffers a compiled run uses: scratch cells, and the numeric
/// stack and locals that a bail-out hands to the interpreter.
pub(crate) struct Buffers<'a> {
    pub mem: &'a mut Vec<u32>,
    pub stack: &'a mut Vec<u32>,
    pub locals: &'a mut Vec<u32>,
}

/// What the runtime services a compiled run calls use: the VM's string
/// stack and budgets, the object's constants and the run's tracer.
pub(crate) struct Services<'a, 't> {
    pub vm: &'a mut Vm,
    pub consts: &'a [Bytes],
    pub trace: &'a mut crate::vm::Tracer<'t>,
}

impl Compiled {
    /// Runs the code against `store`.
    pub(crate) fn run(
        &self,
        store: &mut Store,
        retained: &mut [u32],
        budget: u64,
        buf: Buffers<'_>,
        services: Services<'_, '_>,
    ) -> JitRun {
        let Buffers { mem, stack, locals } = buf;
        let Services { vm, consts, trace } = services;
        if retained.len() != self.retained || !self.copy_in(store, mem) {
            return JitRun::Refused;
        }
        stack.clear();
        stack.resize(self.max_depth.max(1), 0);
        locals.clear();
        locals.resize(self.locals.max(1), 0);
        let mut frame = Frame {
            mem: mem.as_mut_ptr(),
            kinds: self.plan.kinds.as_ptr(),
            retained: retained.as_mut_ptr(),
            stack: stack.as_mut_ptr(),
            locals: locals.as_mut_ptr(),
            budget,
            pc: 0,
            depth: 0,
            ref_slot: u32::MAX,
            ret: 0,
            vm,
            store,
            consts: consts.as_ptr(),
            nconsts: consts.len(),
            trace: (trace as *mut crate::vm::Tracer<'_>).cast(),
            code: self,
            mem_len: mem.len(),
        };
        // SAFETY: the code only touches `mem` below the plan's slot count
        // (it checks every computed slot), `kinds` likewise, `retained`
        // below `self.retained`, `stack` below `max_depth` and `locals`
        // below `self.locals`: all sized above. The services reach the VM
        // and the store only through the frame while the code runs.
        let status = unsafe { (self.entry)(&mut frame) };
        self.copy_out(store, mem);
        locals.truncate(self.locals);
        match status {
            0 => JitRun::Done,
            4 => JitRun::Returned(linc_stdlib::Value::Int(frame.ret as i32)),
            5 => JitRun::Returned(linc_stdlib::Value::Real(f32::from_bits(frame.ret))),
            6 => JitRun::Returned(linc_stdlib::Value::Bool(frame.ret != 0)),
            1 => {
                stack.truncate(frame.depth as usize);
                let ref_cell = self.plan.cells.get(frame.ref_slot as usize).copied().unwrap_or(0);
                JitRun::Bail { pc: frame.pc as usize, ref_cell, budget: frame.budget }
            }
            _ => JitRun::Fault { pc: frame.pc as usize },
        }
    }

    /// Copies the program's cells into `mem`; false when a cell is forced
    /// or does not have the kind the code was compiled for.
    fn copy_in(&self, store: &Store, mem: &mut Vec<u32>) -> bool {
        mem.clear();
        mem.reserve(self.plan.cells.len());
        for (&c, &k) in self.plan.cells.iter().zip(&self.plan.kinds) {
            if store.is_forced(c) || store.is_readonly(c) != (k & READONLY != 0) {
                return false;
            }
            let v = match (store.cells.get(c as usize), k & 3) {
                (Some(Cell::Int(i)), INT) => *i as u32,
                (Some(Cell::Bool(b)), BOOL) => u32::from(*b),
                (Some(Cell::Real(r)), REAL) => r.to_bits(),
                _ => return false,
            };
            mem.push(v);
        }
        true
    }

    /// The store cell of scratch slot `slot`.
    pub(crate) fn cell_of_slot(&self, slot: u32) -> Option<u32> {
        self.plan.cells.get(slot as usize).copied()
    }

    pub(crate) fn copy_out(&self, store: &mut Store, mem: &[u32]) {
        for (&c, &v) in self.plan.cells.iter().zip(mem) {
            match store.cells.get_mut(c as usize) {
                Some(Cell::Int(i)) => *i = v as i32,
                Some(Cell::Bool(b)) => *b = v != 0,
                Some(Cell::Real(r)) => *r = f32::from_bits(v),
                _ => {}
            }
        }
    }
}

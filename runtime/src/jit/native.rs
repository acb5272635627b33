//! The compiling tier's machine code (feature `jit`): a block translated
//! by Cranelift ([`super::emit`]), and running it against the store.

use super::plan::{Plan, BOOL, INT, READONLY, REAL};
use super::{emit, Buffers, JitRun, Mode, Services, MAX_BLOCK_OPS};
use crate::isa::{Kind, Op};
use crate::link::Linked;
use crate::store::{Cell, Store};
use crate::vm::Vm;
use crate::wire::Bytes;
use cranelift_jit::JITModule;

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
    /// The block's coverage counters by instruction (covered code only).
    pub hits: *mut u64,
    pub taken: *mut u64,
}

pub(crate) type Entry = unsafe extern "C" fn(*mut Frame) -> u32;

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
    /// Whether the code counts into the block's coverage counters.
    covered: bool,
    /// The runs of string instructions the code hands to
    /// [`host::str_run`](super::host::str_run) by index.
    pub(crate) str_runs: Vec<Box<[crate::vm::str_run::Step]>>,
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

/// What translating a block needs, copied out of the program and the store
/// by the thread that runs the block, so that the translation itself (the
/// slow part) can run on another thread without the program or the store:
/// at most [`MAX_BLOCK_OPS`] instructions, their label shapes, the cell
/// layout and the coverage points.
pub(crate) struct Prepared {
    ops: Vec<Op>,
    shapes: Vec<(u32, crate::verify::Shape)>,
    plan: Plan,
    locals: usize,
    retained: usize,
    traced: bool,
    points: Option<Vec<bool>>,
}

/// Looks at a block: `None` when it uses anything outside the subset, is
/// larger than [`MAX_BLOCK_OPS`] or meets a cell the tier leaves alone, so
/// that a refusal costs no translation and no trip to another thread.
pub(super) fn prepare(
    linked: &Linked,
    store: &Store,
    (program, block): (usize, usize),
    Mode { traced, covered }: Mode,
) -> Option<Prepared> {
    let prog = linked.program(program)?;
    let unit = linked.unit(program)?;
    let ops = linked.ops(program, block)?;
    let code = unit.blocks.get(block)?;
    if ops.len() > MAX_BLOCK_OPS || !ops.iter().all(in_subset) {
        return None;
    }
    let plan = Plan::new(ops, &prog.targets, store, traced)?;
    // The counters' own points: a bail-out takes back the count of exactly
    // these (`Vm::run`).
    let points = match covered {
        true => Some(linked.cover_block(program, block)?.points().to_vec()),
        false => None,
    };
    Some(Prepared {
        ops: ops.to_vec(),
        shapes: linked.shapes(program, block).to_vec(),
        plan,
        locals: usize::from(code.locals),
        retained: usize::from(unit.retained),
        traced,
        points,
    })
}

impl Prepared {
    /// Translates the block; traced code reports every write to the run's
    /// tracer as the interpreter does, covered code counts as the
    /// interpreter does.
    pub(super) fn compile(self) -> Option<Compiled> {
        let Prepared { ops, shapes, plan, locals, retained, traced, points } = self;
        let e = emit::emit((&ops, &shapes), &plan, (locals, retained), (traced, points.as_deref()))?;
        let (module, covered) = (Some(e.module), points.is_some());
        let (entry, max_depth, str_runs) = (e.entry, e.max_depth, e.str_runs);
        Some(Compiled { entry, module, plan, max_depth, locals, retained, covered, str_runs })
    }
}

/// Compiles a block on the calling thread.
pub(super) fn compile_as(linked: &Linked, store: &Store, at: (usize, usize), mode: Mode) -> Option<Compiled> {
    prepare(linked, store, at, mode)?.compile()
}

/// Whether the compiled tier translates this instruction (the table's
/// `Compiled` flag; a `Return` only of a numeric value).
fn in_subset(op: &Op) -> bool {
    match op {
        Op::Return { kind } => Kind::from_bits(u32::from(*kind)) != Kind::Bytes,
        _ => op.has(crate::isa::Flag::Compiled),
    }
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
        let Services { vm, consts, trace, cover } = services;
        let (hits, taken) = match cover {
            Some(c) if self.covered => c.bases(),
            None if !self.covered => (std::ptr::null_mut(), std::ptr::null_mut()),
            _ => return JitRun::Refused,
        };
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
            hits,
            taken,
        };
        // SAFETY: the code only touches `mem` below the plan's slot count
        // (it checks every computed slot), `kinds` likewise, `retained`
        // below `self.retained`, `stack` below `max_depth` and `locals`
        // below `self.locals`: all sized above; covered code adds to
        // `hits` and `taken` below the block's length, which is what the
        // counters were made for. The services reach the VM
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

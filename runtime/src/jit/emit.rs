//! Translating a numeric code block to Cranelift IR.
//!
//! The operand stack lives in Cranelift variables (one per depth and type,
//! so REAL arithmetic stays in float registers); its shape before every
//! instruction follows from the verifier's shapes at labels. Every point where
//! the interpreter could fault, and every loop header where the watchdog
//! budget could run out before the next one ([`budget`]), leads to a cold *bail-out* that
//! writes the stack, locals, promoted cells, reference and budget into the
//! [`Frame`] and returns 1, so the interpreter resumes at that instruction.

use super::plan::{Plan, BOOL, REAL};
use super::{Entry, Frame};
use crate::isa::Op;
use crate::verify::Shape as LabelShape;
use cranelift_codegen::ir::condcodes::IntCC;
use cranelift_codegen::ir::{types, AbiParam, Block, InstBuilder, MemFlags, Type, Value};
use cranelift_codegen::isa::CallConv;
use cranelift_codegen::settings::{self, Configurable};
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext, Variable};
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{default_libcall_names, Linkage, Module};
use std::mem::offset_of;

/// The type of a stack entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(super) enum Ty {
    I,
    F,
}

/// Deepest numeric stack the tier compiles.
const MAX_DEPTH: usize = 256;

/// Whether control never falls through to the next instruction.
pub(super) fn ends_block(op: &Op) -> bool {
    matches!(op, Op::Jump { .. } | Op::JumpIfFalse { .. } | Op::JumpIfTrue { .. } | Op::Ret {} | Op::Return { .. })
}

/// The basic blocks of a code block, as every pass of the emitter sees them.
pub(super) struct Blocks {
    /// Whether each instruction starts a basic block (index `ops.len()`
    /// too: the end).
    pub leader: Vec<bool>,
    /// For each leader, the index just past its basic block.
    pub ends: Vec<usize>,
    /// Whether each instruction is the target of a jump back: a loop head.
    pub head: Vec<bool>,
}

pub(super) fn blocks_of(ops: &[Op]) -> Blocks {
    let n = ops.len();
    let mut leader = vec![false; n + 1];
    let mut head = vec![false; n + 1];
    leader[0] = true;
    leader[n] = true;
    for (pc, op) in ops.iter().enumerate() {
        if let Some(to) = op.target().map(|t| t as usize).filter(|&t| t <= n) {
            leader[to] = true;
            head[to] |= to <= pc;
        }
        if ends_block(op) {
            leader[pc + 1] = true;
        }
    }
    let mut ends = vec![n; n + 1];
    let mut next = n;
    for pc in (0..n).rev() {
        ends[pc] = next;
        if leader[pc] {
            next = pc;
        }
    }
    Blocks { leader, ends, head }
}

/// The stack types before each instruction (`None`: unreachable); index
/// `ops.len()` is "ran off the end". Where paths meet (at labels) the types
/// are the verifier's (`shapes`, sorted by instruction), and straight code
/// follows from them, so the tier does no flow analysis of its own. `None`
/// overall when the verifier found different types meeting at a label (or
/// a stack deeper than it types there), or the stack grows past
/// [`MAX_DEPTH`].
fn stack_types(ops: &[Op], shapes: &[(u32, LabelShape)]) -> Option<Vec<Option<Vec<Ty>>>> {
    let mut states: Vec<Option<Vec<Ty>>> = Vec::with_capacity(ops.len() + 1);
    let mut at = shapes.iter().peekable();
    let mut cur = Some(Vec::new());
    for (pc, op) in ops.iter().enumerate() {
        if let Some(&(_, shape)) = at.next_if(|(p, _)| *p as usize == pc) {
            if !shape.known {
                return None;
            }
            cur = Some((0..shape.depth).map(|i| if shape.reals >> i & 1 == 1 { Ty::F } else { Ty::I }).collect());
        }
        states.push(cur.clone());
        let Some(mut st) = cur.take() else { continue };
        let e = op.effect();
        st.truncate(st.len().checked_sub(e.num_pop as usize)?);
        if e.num_push == 1 {
            st.push(if op.pushes_real() { Ty::F } else { Ty::I });
        }
        if st.len() > MAX_DEPTH {
            return None;
        }
        // Only a jump or a return never falls through.
        if !matches!(op, Op::Jump { .. } | Op::Ret {} | Op::Return { .. }) {
            cur = Some(st);
        }
    }
    states.push(cur);
    Some(states)
}

fn new_module() -> Option<JITModule> {
    let mut flags = settings::builder();
    flags.set("opt_level", "speed").ok()?;
    flags.set("use_colocated_libcalls", "false").ok()?;
    flags.set("is_pic", "false").ok()?;
    // Cranelift's IR verifier took a sixth of a small run's instructions
    // (a third of translating); it checks the emitter, which the debug
    // builds of the tests run with it on.
    flags.set("enable_verifier", if cfg!(debug_assertions) { "true" } else { "false" }).ok()?;
    let isa = cranelift_native::builder().ok()?.finish(settings::Flags::new(flags)).ok()?;
    Some(JITModule::new(JITBuilder::with_isa(isa, default_libcall_names())))
}

/// What translating a block made: the entry point, the module owning its
/// code, the deepest stack a bail-out can write and the runs of string
/// instructions the code hands over by index ([`str_runs`]).
pub(super) struct Emitted {
    pub entry: Entry,
    pub module: JITModule,
    pub max_depth: usize,
    pub str_runs: Vec<Box<[crate::vm::str_run::Step]>>,
}

/// Compiles `ops`.
pub(super) fn emit(
    (ops, shapes): (&[Op], &[(u32, LabelShape)]),
    plan: &Plan,
    (locals, retained): (usize, usize),
    (traced, points): (bool, Option<&[bool]>),
) -> Option<Emitted> {
    let states = stack_types(ops, shapes)?;
    let max_depth = states.iter().flatten().map(Vec::len).max().unwrap_or(0);
    let mut module = new_module()?;
    let ptr = module.target_config().pointer_type();
    let call_conv = module.isa().default_call_conv();
    let mut ctx = module.make_context();
    ctx.func.signature.params.push(AbiParam::new(ptr));
    ctx.func.signature.returns.push(AbiParam::new(types::I32));
    let mut fbc = FunctionBuilderContext::new();
    let str_runs = {
        let b = FunctionBuilder::new(&mut ctx.func, &mut fbc);
        let shape = Shape { ops, plan, traced, points, states: &states, locals, retained, max_depth, ptr, call_conv };
        let mut e = Emitter::new(b, shape);
        e.body()?;
        e.b.seal_all_blocks();
        e.b.finalize();
        e.str_runs
    };
    let id = module.declare_function("block", Linkage::Local, &ctx.func.signature).ok()?;
    module.define_function(id, &mut ctx).ok()?;
    module.clear_context(&mut ctx);
    module.finalize_definitions().ok()?;
    let code = module.get_finalized_function(id);
    // SAFETY: the function was declared with exactly `Entry`'s signature
    // in the platform's default calling convention.
    let entry = unsafe { std::mem::transmute::<*const u8, Entry>(code) };
    Some(Emitted { entry, module, max_depth, str_runs })
}

/// The REAL-to-INT conversion, called from compiled code so that it is
/// the interpreter's own rounding.
extern "C" fn real_to_int(v: f32) -> i32 {
    linc_stdlib::value::round_to_i32(v)
}

/// What the emitter translates.
struct Shape<'a> {
    ops: &'a [Op],
    plan: &'a Plan,
    /// Whether every write is reported to the run's tracer.
    traced: bool,
    /// In covered code, the instructions counted (ADR 0020).
    points: Option<&'a [bool]>,
    states: &'a [Option<Vec<Ty>>],
    locals: usize,
    retained: usize,
    max_depth: usize,
    ptr: Type,
    call_conv: CallConv,
}

struct Emitter<'a, 'f> {
    b: FunctionBuilder<'f>,
    s: Shape<'a>,
    /// The Cranelift block starting at each reachable leader.
    blocks: Vec<Option<Block>>,
    /// For each leader, the index just past its block.
    ends: Vec<usize>,
    vi: Vec<Variable>,
    vf: Vec<Variable>,
    locals: Vec<Variable>,
    /// Variables of promoted slots.
    slots: Vec<Option<Variable>>,
    ref_slot: Variable,
    budget: Variable,
    frame: Option<Value>,
    mem: Option<Value>,
    kinds: Option<Value>,
    retained: Option<Value>,
    /// Covered code: the frame's hit and taken counter bases, and the
    /// counts kept in variables until an exit ([`cover`]).
    counters: Option<(Value, Value)>,
    counter_vars: cover::CounterVars,
    /// Stack types at the instruction being translated.
    stack: Vec<Ty>,
    /// Whether each stack entry is a REAL known to be finite: read from a
    /// REAL cell, which only ever holds finite values (every writer, the
    /// interpreter, the console, the wire servers and a restored state,
    /// refuses a non-finite one), or a finite constant. Storing it again
    /// needs no check (a shift register's moves).
    finite: Vec<bool>,
    block_end: usize,
    /// The shared exit blocks made so far ([`exits`]), and in the order
    /// made (the order they are emitted in).
    exits: std::collections::HashMap<ExitKey, Block>,
    exit_order: Vec<(ExitKey, Block)>,
    /// The first instruction of the basic block being translated.
    leader: usize,
    /// The watchdog checkpoints and their bounds, by leader ([`budget`]).
    checks: Vec<Option<u64>>,
    /// Before each instruction, whether the reference may still be read
    /// ([`liveness`]): an exit where it cannot hands over none.
    ref_live: Vec<bool>,
    /// For each `RefOff`, the range its index is known to lie in
    /// ([`ranges`]).
    offsets: Vec<Option<ranges::Iv>>,
    /// The slots the reference can hold, when a `Ref` or `RefOff` earlier
    /// in the same basic block set it (its range already checked there).
    ref_known: Option<(u32, u32)>,
    /// The "no reference" constant, made once at entry: exits where the
    /// reference is dead all pass this one value, which Cranelift then
    /// folds into the shared exit block instead of materialising a -1 on
    /// the main path before every check.
    no_ref: Option<Value>,
    /// The runs of string instructions translated, which the code names by
    /// index ([`str_runs`]).
    str_runs: Vec<Box<[crate::vm::str_run::Step]>>,
}

fn frame_off(off: usize) -> i32 {
    off as i32
}

impl<'a, 'f> Emitter<'a, 'f> {
    fn new(mut b: FunctionBuilder<'f>, s: Shape<'a>) -> Emitter<'a, 'f> {
        let vi = (0..s.max_depth).map(|_| b.declare_var(types::I32)).collect();
        let vf = (0..s.max_depth).map(|_| b.declare_var(types::F32)).collect();
        let locals = (0..s.locals).map(|_| b.declare_var(types::I32)).collect();
        let slots = s
            .plan
            .promoted
            .iter()
            .zip(&s.plan.kinds)
            .map(|(&p, &k)| p.then(|| b.declare_var(if k & 3 == REAL { types::F32 } else { types::I32 })))
            .collect();
        let ref_slot = b.declare_var(types::I32);
        let budget = b.declare_var(types::I64);
        Emitter {
            b,
            s,
            blocks: Vec::new(),
            ends: Vec::new(),
            vi,
            vf,
            locals,
            slots,
            ref_slot,
            budget,
            frame: None,
            mem: None,
            kinds: None,
            retained: None,
            counters: None,
            counter_vars: cover::CounterVars::default(),
            stack: Vec::new(),
            finite: Vec::new(),
            block_end: 0,
            exits: Default::default(),
            exit_order: Vec::new(),
            leader: 0,
            checks: Vec::new(),
            ref_live: Vec::new(),
            offsets: Vec::new(),
            ref_known: None,
            no_ref: None,
            str_runs: Vec::new(),
        }
    }

    fn frame(&self) -> Value {
        self.frame.unwrap_or_else(|| unreachable!("set at entry"))
    }

    fn load_ptr(&mut self, off: usize) -> Value {
        let f = self.frame();
        self.b.ins().load(self.s.ptr, MemFlags::trusted(), f, frame_off(off))
    }

    /// Marks the leaders and creates their blocks.
    fn layout(&mut self) {
        let n = self.s.ops.len();
        let blocks = blocks_of(self.s.ops);
        let leader = &blocks.leader;
        self.ends = blocks.ends.clone();
        self.blocks =
            (0..=n).map(|pc| (leader[pc] && self.s.states[pc].is_some()).then(|| self.b.create_block())).collect();
        self.checks = budget::checkpoints(self.s.ops, &blocks);
        self.ref_live = liveness::reference_live(self.s.ops);
        let plan = self.s.plan;
        let tracked: Vec<bool> =
            self.slots.iter().zip(&plan.kinds).map(|(v, k)| v.is_some() && k & 3 != REAL).collect();
        let bools: Vec<bool> = plan.kinds.iter().map(|k| k & 3 == BOOL).collect();
        let slot_of = |sym: u16| plan.slot(sym).map(|s| s as usize);
        self.offsets = ranges::offset_ranges(self.s.ops, (&tracked, &bools), slot_of, self.s.locals, &blocks);
    }

    fn body(&mut self) -> Option<()> {
        self.layout();
        let entry = self.b.create_block();
        self.b.append_block_params_for_function_params(entry);
        self.b.switch_to_block(entry);
        self.frame = Some(self.b.block_params(entry)[0]);
        self.mem = Some(self.load_ptr(offset_of!(Frame, mem)));
        self.kinds = Some(self.load_ptr(offset_of!(Frame, kinds)));
        self.retained = Some(self.load_ptr(offset_of!(Frame, retained)));
        if self.s.points.is_some() {
            self.counters = Some((self.load_ptr(offset_of!(Frame, hits)), self.load_ptr(offset_of!(Frame, taken))));
            self.declare_counters();
        }
        let f = self.frame();
        let budget = self.b.ins().load(types::I64, MemFlags::trusted(), f, frame_off(offset_of!(Frame, budget)));
        self.b.def_var(self.budget, budget);
        let none = self.b.ins().iconst(types::I32, -1);
        self.b.def_var(self.ref_slot, none);
        self.no_ref = Some(none);
        let zero = self.b.ins().iconst(types::I32, 0);
        for &l in &self.locals {
            self.b.def_var(l, zero);
        }
        let mem = self.mem?;
        for (slot, var) in self.slots.iter().enumerate() {
            if let Some(var) = *var {
                let ty = if self.s.plan.kinds[slot] & 3 == REAL { types::F32 } else { types::I32 };
                let v = self.b.ins().load(ty, MemFlags::trusted(), mem, (slot * 4) as i32);
                self.b.def_var(var, v);
            }
        }
        let first = self.blocks[0]?;
        self.b.ins().jump(first, &[]);
        for pc in 0..=self.s.ops.len() {
            if let Some(blk) = self.blocks[pc] {
                self.b.switch_to_block(blk);
                self.block(pc)?;
            }
        }
        self.exit_blocks();
        Some(())
    }

    /// One basic block: the budget check, then its instructions.
    fn block(&mut self, start: usize) -> Option<()> {
        self.stack = self.s.states[start].clone()?;
        self.finite = vec![false; self.stack.len()];
        self.leader = start;
        self.ref_known = None;
        if start == self.s.ops.len() {
            // Ran off the end: the interpreter reports it.
            self.exit_now(Exit::Budget, start);
            return Some(());
        }
        let end = self.ends[start];
        self.block_end = end;
        // Counted before the budget check: a bail-out at an instruction has
        // always counted it, and the interpreter takes that count back.
        self.count_hit(start);
        let n = (end - start) as i64;
        let bud = self.b.use_var(self.budget);
        if let Some(bound) = self.checks.get(start).copied().flatten() {
            let short = self.b.ins().icmp_imm(IntCC::UnsignedLessThan, bud, bound as i64);
            self.exit_if(short, Exit::Budget, start);
        }
        let left = self.b.ins().iadd_imm(bud, -n);
        self.b.def_var(self.budget, left);
        let mut pc = start;
        while pc < end {
            if pc != start {
                self.count_hit(pc);
            }
            pc = match self.string_run(pc) {
                Some(next) => next,
                None => {
                    self.op(pc)?;
                    pc + 1
                }
            };
            if self.b.func.dfg.num_insts() > super::MAX_BLOCK_IR {
                return None;
            }
        }
        let last = self.s.ops.get(end - 1)?;
        if !ends_block(last) {
            let next = self.blocks.get(end).copied().flatten()?;
            self.b.ins().jump(next, &[]);
        }
        Some(())
    }

    fn var(&self, d: usize, ty: Ty) -> Variable {
        match ty {
            Ty::I => self.vi[d],
            Ty::F => self.vf[d],
        }
    }

    fn push(&mut self, ty: Ty, v: Value) {
        let var = self.var(self.stack.len(), ty);
        self.b.def_var(var, v);
        self.stack.push(ty);
        self.finite.push(false);
    }

    /// [`Emitter::push`] of a REAL known to be finite.
    fn push_finite(&mut self, v: Value) {
        self.push(Ty::F, v);
        if let Some(f) = self.finite.last_mut() {
            *f = true;
        }
    }

    /// Whether the top entry is a REAL known to be finite.
    fn top_is_finite(&self) -> bool {
        self.stack.last() == Some(&Ty::F) && self.finite.last() == Some(&true)
    }

    /// Pops the top entry as `want`, reinterpreting the bits if it was
    /// pushed as the other type (locals and retained slots are untyped).
    fn pop(&mut self, want: Ty) -> Option<Value> {
        let ty = self.stack.pop()?;
        self.finite.pop();
        let v = self.b.use_var(self.var(self.stack.len(), ty));
        Some(match (ty, want) {
            (Ty::I, Ty::F) => self.b.ins().bitcast(types::F32, MemFlags::new(), v),
            (Ty::F, Ty::I) => self.b.ins().bitcast(types::I32, MemFlags::new(), v),
            _ => v,
        })
    }

    fn bool32(&mut self, c: Value) -> Value {
        self.b.ins().uextend(types::I32, c)
    }

    fn non_finite(&mut self, v: Value) -> Value {
        let bits = self.b.ins().bitcast(types::I32, MemFlags::new(), v);
        let e = self.b.ins().band_imm(bits, 0x7f80_0000);
        self.b.ins().icmp_imm(IntCC::Equal, e, 0x7f80_0000)
    }

    fn op(&mut self, pc: usize) -> Option<()> {
        let op = *self.s.ops.get(pc)?;
        match op {
            Op::PushI { v } => {
                let c = self.b.ins().iconst(types::I32, i64::from(v));
                self.push(Ty::I, c);
            }
            Op::PushR { v } => {
                let c = self.b.ins().f32const(v);
                if v.is_finite() {
                    self.push_finite(c);
                } else {
                    self.push(Ty::F, c);
                }
            }
            Op::LoadLoc { .. } | Op::StoreLoc { .. } | Op::LoadRet { .. } | Op::StoreRet { .. } => self.local(op)?,
            Op::LoadI { .. } | Op::LoadR { .. } | Op::StoreI { .. } | Op::StoreR { .. } => self.direct(pc, op)?,
            Op::Ref { .. } | Op::RefOff { .. } => self.reference(pc, op)?,
            Op::LoadRefI { .. } | Op::LoadRefR { .. } | Op::StoreRefI { .. } | Op::StoreRefR { .. } => {
                self.through_ref(pc, op)?
            }
            Op::Jump { .. } | Op::JumpIfFalse { .. } | Op::JumpIfTrue { .. } | Op::Ret {} | Op::Return { .. } => {
                self.flow(pc, op)?
            }
            Op::PushS { .. }
            | Op::LoadS { .. }
            | Op::StoreS { .. }
            | Op::AppendS { .. }
            | Op::Decode {}
            | Op::EqS {}
            | Op::NeS {}
            | Op::LtS {}
            | Op::GtS {}
            | Op::LeS {}
            | Op::GeS {} => self.string(pc, op)?,
            Op::Call { .. } => self.call(pc, op)?,
            _ => self.arith(pc, op)?,
        }
        Some(())
    }
}

mod budget;
mod cover;
mod exits;
mod liveness;
mod ops;
mod ranges;
mod services;
mod str_runs;

use exits::{Exit, ExitKey};

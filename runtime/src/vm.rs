//! The virtual machine: runs one verified, linked action against the store.
//!
//! A match-dispatched stack machine over decoded instructions. Numeric cells
//! are raw 32-bit words whose type the compiler fixed; strings live on their
//! own stack. Stacks are sized by the verifier before the run, so an action
//! that touches no strings allocates nothing. Faults are values: the run
//! stops at the failing statement with a located [`RuntimeError`], and what
//! it wrote before stays written.

mod cells;
mod fst_ops;
#[cfg(feature = "jit")]
pub(crate) mod str_run;
mod str_stack;
mod strings;

use crate::cover::{BlockCounters, Counter};
use crate::errors::{Fault, RuntimeError};
use crate::isa::{Kind, Op};
use crate::jit::{Buffers, JitRun, Mode, Services};
use crate::link::{Linked, LinkedBlock, LinkedProgram};
use crate::object::{CodeBlock, Unit};
use crate::store::{Cell, Store};
use cells::{cell, corrupt, load_bit, load_int, locate, note, store_bit, store_int, target, writable};
use fst_ops::FstFlow;
use linc_format::Code;
use linc_stdlib::value::round_to_i32;
use linc_stdlib::{Env, FnError, Value};
use std::mem::take;
use str_stack::StrStack;

/// `?` for the dispatch loop: a fault leaves the loop, so the program
/// counter is written back.
macro_rules! tri {
    ($e:expr) => {
        match $e {
            Ok(v) => v,
            Err(f) => break Err(f),
        }
    };
}

/// Default instruction budget per run: far beyond any sane action, reached
/// by a runaway loop in well under a second.
pub const DEFAULT_WATCHDOG: u64 = 10_000_000;

/// Instructions a block runs on the interpreter before the compiling tier
/// compiles it: about as long as compiling takes (ADR 0011).
pub const JIT_AFTER: u64 = 1_000_000;

/// Which tier runs code blocks (ADR 0011; `linc run --tier`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Tier {
    /// A block with a loop due for compilation at its first run, a straight
    /// block once it has run [`JIT_AFTER`] instructions on the interpreter;
    /// a due block is translated in the background and runs on the
    /// interpreter until its code is ready (ADR 0023), so no run waits.
    #[default]
    Auto,
    /// Every block translated before its first run, on the running thread
    /// (those the tier translates): for benchmarks.
    Compiled,
    /// The interpreter alone.
    Interpreter,
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Outcome {
    Done,
    /// Stopped at a suspension point; the next run of the same activation
    /// resumes after it, with its locals as they were.
    Suspended,
}

/// One running instance of a program: where it resumes and the state that
/// survives from one run to the next. The caller owns it (a strategy keeps
/// one per block), so the VM itself holds no program state.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Activation {
    pub program: usize,
    pub block: usize,
    /// Resume point when suspended.
    resume: Option<u32>,
    locals: Vec<u32>,
    /// Retained slots: kept from run to run until the activation is reset.
    pub retained: Vec<u32>,
    /// The value of the last `Return` (linc eval).
    pub result: Option<Value>,
    /// FST: steps the next run may begin (the engine sets it before a run).
    pub steps_left: u32,
    /// FST: the step that ran last (`Step`).
    pub step: u16,
    /// FST: why the last run paused (`Pause`): 0 WT seconds, 1 BRK intervals.
    pub pause: Option<(u8, f32)>,
}

impl Activation {
    /// An activation of block `block` of `program`, at its start.
    pub fn new(linked: &Linked, program: usize, block: usize) -> Activation {
        let retained = linked.unit(program).map_or(0, |u| usize::from(u.retained));
        Activation {
            program,
            block,
            resume: None,
            locals: Vec::new(),
            retained: vec![0; retained],
            result: None,
            steps_left: 0,
            step: 0,
            pause: None,
        }
    }

    pub fn is_suspended(&self) -> bool {
        self.resume.is_some()
    }

    /// The resume point and the locals kept with it (a saved state).
    pub fn resume_point(&self) -> (Option<u32>, &[u32]) {
        (self.resume, &self.locals)
    }

    /// Resumes at `at` with `locals` at the next run (a restored state).
    pub fn set_resume_point(&mut self, at: Option<u32>, locals: Vec<u32>) {
        self.resume = at;
        self.locals = locals;
    }

    /// Back to the start: no resume point, retained slots cleared.
    pub fn reset(&mut self) {
        self.resume = None;
        self.retained.fill(0);
        self.result = None;
        self.step = 0;
        self.pause = None;
    }
}

/// Whether a run of `ops` may resume at `at`: at a `Step` (an FST run that
/// spent its step budget resumes at the step) or after a `Yield` or a
/// `Pause`. Those are the only places a run suspends, and the verifier
/// checks that both stacks are empty there (a restored state is checked
/// against this).
pub fn can_resume_at(ops: &[Op], at: usize) -> bool {
    matches!(ops.get(at), Some(Op::Step { .. }))
        || at.checked_sub(1).and_then(|p| ops.get(p)).is_some_and(|op| matches!(op, Op::Yield {} | Op::Pause { .. }))
}

/// Adds one to counter `i`, if there is one (coverage).
#[inline(always)]
fn count(counters: &[Counter], i: usize) {
    if let Some(c) = counters.get(i) {
        c.bump();
    }
}

/// The code an activation runs, looked up once per run.
struct Running<'a> {
    linked: &'a Linked,
    prog: &'a LinkedProgram,
    block: &'a LinkedBlock,
    /// The instructions the block runs.
    ops: &'a [Op],
    /// The object's block, for its tables.
    code: &'a CodeBlock,
    unit: &'a Unit,
}

impl<'a> Running<'a> {
    fn of(linked: &'a Linked, act: &Activation) -> Option<Running<'a>> {
        let prog = linked.program(act.program)?;
        let unit = linked.unit(act.program)?;
        let (block, code) = (prog.blocks.get(act.block)?, unit.blocks.get(act.block)?);
        Some(Running { linked, prog, block, ops: block.ops_or(code), code, unit })
    }
}

/// What a run reports as it writes, for `--trace`.
pub type Tracer<'t> = Option<&'t mut dyn FnMut(&Store, u32)>;

pub use linc_format::MAX_STRING;

/// Default bytes of string values one run may produce.
pub const DEFAULT_STRING_BUDGET: usize = 16 << 20;

/// The random generator and clock the library sees.
#[derive(Clone, Debug)]
pub struct Clock {
    pub state: u64,
    /// Seconds to add to system time for local time.
    pub utc_offset: i64,
    now: f64,
}

impl Clock {
    pub fn new(seed: u64, utc_offset: i64) -> Clock {
        Clock { state: seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1, utc_offset, now: 0.0 }
    }
}

impl Env for Clock {
    fn random(&mut self) -> f64 {
        self.state ^= self.state >> 12;
        self.state ^= self.state << 25;
        self.state ^= self.state >> 27;
        let x = self.state.wrapping_mul(0x2545_F491_4F6C_DD1D);
        (x >> 11) as f64 / (1u64 << 53) as f64
    }
    fn local_time(&self) -> i64 {
        self.now.floor() as i64 + self.utc_offset
    }
    fn system_time(&self) -> i64 {
        self.now.floor() as i64
    }
}

/// The machine: scratch stacks reused from run to run, the watchdog and
/// string budgets, and the library's clock. It keeps no program state.
#[derive(Debug)]
pub struct Vm {
    num: Vec<u32>,
    strs: StrStack,
    /// Buffers kept from earlier string arguments and results of library
    /// calls for later ones, so that a loop building a string does not
    /// allocate at every pass.
    spare: Vec<Vec<u8>>,
    locals: Vec<u32>,
    args: Vec<Value>,
    /// Instructions one run may execute.
    pub watchdog: u64,
    /// Bytes of string values one run may produce.
    pub string_budget: usize,
    string_used: usize,
    result: Option<Value>,
    pub clock: Clock,
    /// Runs blocks through the compiling tier (ADR 0011) when set (the
    /// default; a run touching a forced cell uses the interpreter).
    pub jit: bool,
    /// Instructions a block runs on the interpreter before it is due for
    /// compilation; a due block is translated on a background thread while
    /// the interpreter goes on running it (ADR 0023). 0: every block is
    /// translated before its first run, on the running thread
    /// (`Tier::Compiled`).
    pub jit_after: u64,
    /// The compiled tier's scratch copy of the cells.
    jit_mem: Vec<u32>,
    /// The budget the last interpreted run left (how much it ran, for the tier).
    budget_left: u64,
    /// A fault of a runtime service called by compiled code.
    pub(crate) jit_fault: Option<Fault>,
}

impl Vm {
    pub fn new(watchdog: u64, clock: Clock) -> Vm {
        Vm {
            num: Vec::new(),
            strs: StrStack::default(),
            spare: Vec::new(),
            locals: Vec::new(),
            args: Vec::new(),
            watchdog,
            string_budget: DEFAULT_STRING_BUDGET,
            string_used: 0,
            result: None,
            clock,
            jit: true,
            jit_after: JIT_AFTER,
            jit_mem: Vec::new(),
            budget_left: 0,
            jit_fault: None,
        }
    }

    /// Chooses the tier that runs this machine's code blocks.
    pub fn set_tier(&mut self, tier: Tier) {
        (self.jit, self.jit_after) = match tier {
            Tier::Auto => (true, JIT_AFTER),
            Tier::Compiled => (true, 0),
            Tier::Interpreter => (false, JIT_AFTER),
        };
    }

    fn pop(&mut self) -> u32 {
        self.num.pop().unwrap_or(0)
    }

    fn pop_i(&mut self) -> i32 {
        self.pop() as i32
    }

    fn pop_r(&mut self) -> f32 {
        f32::from_bits(self.pop())
    }

    fn push_i(&mut self, v: i32) {
        self.num.push(v as u32);
    }

    fn push_r(&mut self, v: f32) {
        self.num.push(v.to_bits());
    }

    /// Runs an activation from its start or its resume point. A fault stops
    /// it (the activation is back at its start; writes made stay).
    pub fn run(
        &mut self,
        linked: &Linked,
        act: &mut Activation,
        store: &mut Store,
        mut trace: Tracer,
    ) -> Result<Outcome, RuntimeError> {
        let Some(l) = Running::of(linked, act) else {
            let f = Fault::new(Code::E0708, format!("no block {} in program {}", act.block, act.program));
            return Err(RuntimeError::unlocated(f));
        };
        self.num.clear();
        self.clear_strs();
        self.num.reserve(l.block.limits.max_num);
        self.strs.reserve(l.block.limits.max_str);
        self.string_used = 0;
        self.result = None;
        let mut pc = match act.resume.take() {
            Some(at) => {
                std::mem::swap(&mut self.locals, &mut act.locals);
                at as usize
            }
            None => {
                self.locals.clear();
                self.locals.resize(usize::from(l.code.locals), 0);
                0
            }
        };
        self.clock.now = store.now;
        let (mut budget, mut ref_cell) = (self.watchdog, 0);
        let interpreted_from = budget;
        let cover = linked.cover_block(act.program, act.block);
        if self.jit && pc == 0 {
            let mode = Mode { traced: trace.is_some(), covered: cover.is_some() };
            if let Some(c) = linked.jit.get(linked, store, (act.program, act.block), self.jit_after, mode) {
                let (mut mem, mut stack, mut locals) =
                    (take(&mut self.jit_mem), take(&mut self.num), take(&mut self.locals));
                let buf = Buffers { mem: &mut mem, stack: &mut stack, locals: &mut locals };
                let consts = &linked.object().strings;
                let services = Services { vm: self, consts, trace: &mut trace, cover };
                let ran = c.run(store, &mut act.retained, budget, buf, services);
                (self.jit_mem, self.num, self.locals) = (mem, stack, locals);
                match ran {
                    JitRun::Done => {
                        act.result = None;
                        return Ok(Outcome::Done);
                    }
                    JitRun::Returned(v) => {
                        act.result = Some(v);
                        return Ok(Outcome::Done);
                    }
                    JitRun::Bail { pc: at, ref_cell: r, budget: b } => {
                        // Compiled code counted the instruction it stopped
                        // at; the interpreter is about to count it.
                        if let Some(c) = cover.filter(|c| c.is_point(at)) {
                            c.hits[at].unbump();
                        }
                        (pc, ref_cell, budget) = (at, r, b);
                    }
                    JitRun::Fault { pc: at } => {
                        act.result = None;
                        let f = self.jit_fault.take().unwrap_or_else(corrupt);
                        return Err(locate(&l, at, f));
                    }
                    JitRun::Refused => {}
                }
            }
        }
        let result = match cover {
            // Two copies of the loop: the one that runs without coverage
            // has no counting in it at all (ADR 0020).
            None => self.exec::<false>(&l, act, store, &mut pc, &mut trace, (budget, ref_cell), None),
            Some(c) => self.exec::<true>(&l, act, store, &mut pc, &mut trace, (budget, ref_cell), Some(c)),
        };
        if self.jit {
            linked.jit.note_interpreted((act.program, act.block), interpreted_from.saturating_sub(self.budget_left));
        }
        act.result = self.result.take();
        match result {
            Ok(Outcome::Suspended) => {
                act.resume = Some(pc as u32);
                std::mem::swap(&mut self.locals, &mut act.locals);
                Ok(Outcome::Suspended)
            }
            Ok(Outcome::Done) => Ok(Outcome::Done),
            Err(f) => Err(locate(&l, pc.saturating_sub(1), f)),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn exec<const COVER: bool>(
        &mut self,
        l: &Running,
        act: &mut Activation,
        store: &mut Store,
        pc_out: &mut usize,
        trace: &mut Tracer,
        (mut budget, mut ref_cell): (u64, u32),
        cover: Option<&BlockCounters>,
    ) -> Result<Outcome, Fault> {
        let ops = l.ops;
        let (hits, taken): (&[Counter], &[Counter]) = cover.map_or((&[], &[]), |c| (&c.hits, &c.taken));
        let mut ref_bit = 0u8;
        // The program counter and budget live in locals (registers) and are
        // written back only when the run stops. A run the compiled tier
        // handed back starts with its pc, budget, reference and stack.
        let mut pc = *pc_out;
        let result = loop {
            let Some(&op) = ops.get(pc) else {
                break Err(Fault::new(Code::E0708, "ran past the end of the code"));
            };
            if budget == 0 {
                // Point past the instruction that did not run, so the fault
                // is located at it (faults are reported at `pc - 1`).
                pc += 1;
                break Err(Fault::new(
                    Code::R0006,
                    format!("watchdog: more than {} instructions in one run", self.watchdog),
                ));
            }
            budget -= 1;
            if COVER {
                count(hits, pc);
            }
            pc += 1;
            match op {
                Op::PushI { v } => self.push_i(v),
                Op::PushR { v } => self.push_r(v),
                Op::PushS { k } => tri!(self.push_const(&l.linked.object().strings, k)),
                Op::LoadRet { n } => {
                    let v = act.retained.get(usize::from(n)).copied().unwrap_or(0);
                    self.num.push(v);
                }
                Op::StoreRet { n } => {
                    let v = self.pop();
                    if let Some(slot) = act.retained.get_mut(usize::from(n)) {
                        *slot = v;
                    }
                }
                Op::LoadLoc { n } => {
                    let v = self.locals.get(usize::from(n)).copied().unwrap_or(0);
                    self.num.push(v);
                }
                Op::StoreLoc { n } => {
                    let v = self.pop();
                    if let Some(slot) = self.locals.get_mut(usize::from(n)) {
                        *slot = v;
                    }
                }
                Op::LoadI { sym } | Op::LoadRefI { sym } => {
                    let c = if matches!(op, Op::LoadI { .. }) { cell(l, sym) } else { ref_cell };
                    let v = tri!(load_int(store, c));
                    self.push_i(v);
                }
                Op::LoadR { sym } | Op::LoadRefR { sym } => {
                    let c = if matches!(op, Op::LoadR { .. }) { cell(l, sym) } else { ref_cell };
                    match store.cells.get(c as usize) {
                        Some(Cell::Real(r)) => self.push_r(*r),
                        _ => break Err(corrupt()),
                    }
                }
                Op::LoadS { sym } | Op::LoadRefS { sym } => {
                    let c = if matches!(op, Op::LoadS { .. }) { cell(l, sym) } else { ref_cell };
                    tri!(self.load_s(store, c));
                }
                Op::LoadBit { sym, bit } => {
                    let v = tri!(load_bit(store, cell(l, sym), bit));
                    self.push_i(v);
                }
                Op::LoadRefBit { .. } => {
                    let v = tri!(load_bit(store, ref_cell, ref_bit));
                    self.push_i(v);
                }
                Op::LoadAlarm { sym } => {
                    let t = target(l, sym);
                    let v = match store.cells.get(t.cell as usize) {
                        // A suppressed alarm reads FALSE (§18.4).
                        Some(Cell::Alarms(a)) => {
                            let i = usize::from(t.alarm);
                            let until = a.until.get(i).copied().unwrap_or(0.0).max(a.all_until);
                            a.active.get(i).copied().unwrap_or(false) && until <= store.now
                        }
                        _ => break Err(corrupt()),
                    };
                    self.push_i(i32::from(v));
                }
                Op::LoadSuppress { sym } => {
                    let t = target(l, sym);
                    let until = match store.cells.get(t.cell as usize) {
                        Some(Cell::Alarms(a)) if t.alarm == u16::MAX => a.all_until,
                        Some(Cell::Alarms(a)) => a.until.get(usize::from(t.alarm)).copied().unwrap_or(0.0),
                        _ => break Err(corrupt()),
                    };
                    let v = store.suppress_remaining(until);
                    self.push_i(v);
                }
                Op::StoreI { sym } | Op::StoreRefI { sym } => {
                    let c =
                        if matches!(op, Op::StoreI { .. }) { cell(l, sym) } else { tri!(writable(store, ref_cell)) };
                    let v = self.pop_i();
                    tri!(store_int(store, c, v));
                    note(trace, store, c);
                }
                Op::StoreR { sym } | Op::StoreRefR { sym } => {
                    let c =
                        if matches!(op, Op::StoreR { .. }) { cell(l, sym) } else { tri!(writable(store, ref_cell)) };
                    let v = self.pop_r();
                    if !v.is_finite() {
                        break Err(Fault::new(Code::R0005, format!("the result is {v}, which can't be stored")));
                    }
                    if store.refuse_forced(c) {
                        continue;
                    }
                    match store.cells.get_mut(c as usize) {
                        Some(Cell::Real(r)) => *r = v,
                        _ => break Err(corrupt()),
                    }
                    note(trace, store, c);
                }
                Op::StoreS { sym } | Op::StoreRefS { sym } => {
                    let c =
                        if matches!(op, Op::StoreS { .. }) { cell(l, sym) } else { tri!(writable(store, ref_cell)) };
                    tri!(self.store_s(store, c));
                    note(trace, store, c);
                }
                Op::AppendS { sym } => {
                    let c = cell(l, sym);
                    tri!(self.append_s(store, c));
                    note(trace, store, c);
                }
                Op::StoreBit { sym, bit } => {
                    let v = self.pop_i();
                    let c = cell(l, sym);
                    tri!(store_bit(store, c, bit, v));
                    note(trace, store, c);
                }
                Op::StoreRefBit { .. } => {
                    let v = self.pop_i();
                    tri!(writable(store, ref_cell));
                    tri!(store_bit(store, ref_cell, ref_bit, v));
                    note(trace, store, ref_cell);
                }
                Op::StoreRKeep { sym } => {
                    let v = self.pop_r();
                    let c = cell(l, sym);
                    if v.is_finite() && !store.refuse_forced(c) {
                        match store.cells.get_mut(c as usize) {
                            Some(Cell::Real(r)) => *r = v,
                            _ => break Err(corrupt()),
                        }
                        note(trace, store, c);
                    }
                }
                Op::StoreSuppress { sym } => {
                    let t = target(l, sym);
                    let secs = self.pop_i();
                    if let Some(deadline) = store.suppress_deadline(secs) {
                        match store.cells.get_mut(t.cell as usize) {
                            Some(Cell::Alarms(a)) if t.alarm == u16::MAX => a.all_until = deadline,
                            Some(Cell::Alarms(a)) => {
                                if let Some(u) = a.until.get_mut(usize::from(t.alarm)) {
                                    *u = deadline;
                                }
                            }
                            _ => break Err(corrupt()),
                        }
                        note(trace, store, t.cell);
                    }
                }
                Op::Ref { sym } => {
                    ref_cell = cell(l, sym);
                    ref_bit = 0;
                }
                Op::RefOff { sym } => {
                    let n = self.pop_i();
                    let t = target(l, sym);
                    let room = t.run_end.saturating_sub(t.cell);
                    if n < 0 || n as u32 > room {
                        break Err(Fault::new(
                            Code::R0003,
                            format!(
                                "offset {n} from {} leaves its run of {} same-typed fields",
                                store.describe(t.cell),
                                room + 1
                            ),
                        ));
                    }
                    ref_cell = t.cell + n as u32;
                    ref_bit = 0;
                }
                Op::RefBit { bit } => ref_bit = bit,
                Op::RefBitOff { bit } => {
                    let n = self.pop_i();
                    let width = match store.cells.get(ref_cell as usize) {
                        Some(Cell::Bits { width, .. }) => i64::from(*width),
                        _ => break Err(corrupt()),
                    };
                    let b = i64::from(bit) + i64::from(n);
                    if n < 0 || b >= width {
                        break Err(Fault::new(
                            Code::R0003,
                            format!(
                                "bit offset {n} from Bit{bit} of {} is beyond Bit{}",
                                store.describe(ref_cell),
                                width - 1
                            ),
                        ));
                    }
                    ref_bit = b as u8;
                }
                Op::IToR {} => {
                    let v = self.pop_i();
                    self.push_r(v as f32);
                }
                Op::RToI {} => {
                    let v = self.pop_r();
                    if !v.is_finite() {
                        break Err(Fault::new(Code::R0005, format!("{v} can't be converted to an integer")));
                    }
                    self.push_i(round_to_i32(v));
                }
                Op::Decode {} => tri!(self.decode()),
                Op::Truth {} => {
                    let v = self.pop_i();
                    self.push_i(i32::from(v != 0));
                }
                Op::Clamp { hi, .. } => {
                    let v = self.pop_i();
                    self.push_i(v.clamp(0, hi.max(0)));
                }
                Op::TruncR {} => {
                    let v = self.pop_r();
                    self.push_r(v.trunc());
                }
                Op::AddI {} => self.int2(i32::wrapping_add),
                Op::SubI {} => self.int2(i32::wrapping_sub),
                Op::MulI {} => self.int2(i32::wrapping_mul),
                Op::DivI {} | Op::ModI {} => {
                    let b = self.pop_i();
                    let a = self.pop_i();
                    if b == 0 {
                        let what = if matches!(op, Op::DivI {}) { "division" } else { "MOD" };
                        break Err(Fault::new(
                            if what == "MOD" { Code::R0002 } else { Code::R0001 },
                            format!("{what} by zero"),
                        ));
                    }
                    self.push_i(if matches!(op, Op::DivI {}) { a.wrapping_div(b) } else { a.wrapping_rem(b) });
                }
                Op::NegI {} => {
                    let v = self.pop_i();
                    self.push_i(v.wrapping_neg());
                }
                Op::AddR {} => self.real2(|a, b| a + b),
                Op::SubR {} => self.real2(|a, b| a - b),
                Op::MulR {} => self.real2(|a, b| a * b),
                Op::DivR {} => {
                    let b = self.pop_r();
                    let a = self.pop_r();
                    if b == 0.0 {
                        break Err(Fault::new(Code::R0001, "division by zero"));
                    }
                    self.push_r(a / b);
                }
                Op::PowR {} => {
                    let b = self.pop_r();
                    let a = self.pop_r();
                    // The library's message says why: which rule A or B breaks, or an overflow.
                    let r = linc_stdlib::power(a, b).map_err(|FnError::Domain(why)| Fault::new(Code::R0005, why));
                    let r = tri!(r);
                    self.push_r(r);
                }
                Op::PowRKeep {} => {
                    let b = self.pop_r();
                    let a = self.pop_r();
                    self.push_r(linc_stdlib::power(a, b).unwrap_or(f32::NAN));
                }
                Op::NegR {} => {
                    let v = self.pop_r();
                    self.push_r(-v);
                }
                Op::EqI {} => self.cmp_i(|a, b| a == b),
                Op::NeI {} => self.cmp_i(|a, b| a != b),
                Op::LtI {} => self.cmp_i(|a, b| a < b),
                Op::GtI {} => self.cmp_i(|a, b| a > b),
                Op::LeI {} => self.cmp_i(|a, b| a <= b),
                Op::GeI {} => self.cmp_i(|a, b| a >= b),
                Op::EqR {} => self.cmp_r(|a, b| a == b),
                Op::NeR {} => self.cmp_r(|a, b| a != b),
                Op::LtR {} => self.cmp_r(|a, b| a < b),
                Op::GtR {} => self.cmp_r(|a, b| a > b),
                Op::LeR {} => self.cmp_r(|a, b| a <= b),
                Op::GeR {} => self.cmp_r(|a, b| a >= b),
                Op::EqS {} | Op::NeS {} | Op::LtS {} | Op::GtS {} | Op::LeS {} | Op::GeS {} => {
                    let v = self.compare_s(op);
                    self.push_i(v);
                }
                Op::And {} => self.int2(|a, b| i32::from((a & b) as i16)),
                Op::Or {} => self.int2(|a, b| i32::from((a | b) as i16)),
                Op::Xor {} => self.int2(|a, b| i32::from((a ^ b) as i16)),
                Op::Not {} => {
                    let v = self.pop_i();
                    self.push_i(i32::from(v == 0));
                }
                Op::Jump { to } => pc = to as usize,
                Op::JumpIfFalse { to } => {
                    if self.pop() == 0 {
                        if COVER {
                            count(taken, pc - 1);
                        }
                        pc = to as usize;
                    }
                }
                Op::JumpIfTrue { to } => {
                    if self.pop() != 0 {
                        if COVER {
                            count(taken, pc - 1);
                        }
                        pc = to as usize;
                    }
                }
                Op::Yield {} => break Ok(Outcome::Suspended),
                Op::Step { .. }
                | Op::Pause { .. }
                | Op::DayTime { .. }
                | Op::Log { .. }
                | Op::HistWrite { .. }
                | Op::HistRead { .. } => match tri!(self.fst_op(op, l, act, store)) {
                    FstFlow::Go => {}
                    FstFlow::SuspendHere => {
                        // Resume at this instruction, not after it.
                        pc -= 1;
                        break Ok(Outcome::Suspended);
                    }
                    FstFlow::SuspendAfter => break Ok(Outcome::Suspended),
                },
                Op::Ret {} => break Ok(Outcome::Done),
                Op::Return { kind } => {
                    self.result = Some(match Kind::from_bits(u32::from(kind)) {
                        Kind::Int => Value::Int(self.pop_i()),
                        Kind::Real => Value::Real(self.pop_r()),
                        Kind::Bool => Value::Bool(self.pop() != 0),
                        Kind::Bytes => Value::Bytes(self.pop_s()),
                    });
                    break Ok(Outcome::Done);
                }
                Op::Call { func, argc, ret, types } => {
                    if let Some(v) = tri!(self.call(func, argc, ret, types, Vm::pop)) {
                        self.num.push(v);
                    }
                }
            }
        };
        *pc_out = pc;
        self.budget_left = budget;
        result
    }

    fn int2(&mut self, f: impl Fn(i32, i32) -> i32) {
        let b = self.pop_i();
        let a = self.pop_i();
        self.push_i(f(a, b));
    }

    fn real2(&mut self, f: impl Fn(f32, f32) -> f32) {
        let b = self.pop_r();
        let a = self.pop_r();
        self.push_r(f(a, b));
    }

    fn cmp_i(&mut self, f: impl Fn(i32, i32) -> bool) {
        let b = self.pop_i();
        let a = self.pop_i();
        self.push_i(i32::from(f(a, b)));
    }

    fn cmp_r(&mut self, f: impl Fn(f32, f32) -> bool) {
        let b = self.pop_r();
        let a = self.pop_r();
        self.push_i(i32::from(f(a, b)));
    }
}

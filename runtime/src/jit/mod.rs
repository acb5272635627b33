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

mod background;
#[cfg(feature = "jit")]
mod emit;
#[cfg(feature = "jit")]
mod host;
#[cfg(feature = "jit")]
mod native;
#[cfg(not(feature = "jit"))]
mod off;
#[cfg(feature = "jit")]
mod plan;

#[doc(hidden)]
pub use background::{hold, Hold};
#[cfg(feature = "jit")]
pub use native::Compiled;
#[cfg(feature = "jit")]
use native::{compile_as, prepare, Prepared};
#[cfg(feature = "jit")]
pub(crate) use native::{Entry, Frame};
#[cfg(not(feature = "jit"))]
pub use off::Compiled;
#[cfg(not(feature = "jit"))]
use off::{compile_as, prepare, Prepared};

use crate::link::Linked;
use crate::store::Store;
use crate::vm::Vm;
use crate::wire::Bytes;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::mpsc::TrySendError;
use std::sync::{Arc, OnceLock};

/// The largest block the tier translates, in instructions; a larger one
/// stays on the interpreter. Translating costs about 5–30 µs per
/// instruction (Cranelift's optimiser and register allocator), so a block
/// at this limit takes up to about 100 ms of the translation thread (of the
/// running thread under `--tier compiled`); a 2.5 MB action (400,000
/// instructions in one loop) took 28 s and 730 MB to translate before there
/// was a limit (`docs/adr/0011-compiling-tier.md`).
pub const MAX_BLOCK_OPS: usize = 2_048;

/// The most Cranelift instructions a block may translate to (a second
/// bound, for instructions that expand to many, such as calls and string
/// services); translation stops as soon as it is passed.
#[cfg(feature = "jit")]
pub(crate) const MAX_BLOCK_IR: usize = 8 * MAX_BLOCK_OPS;

/// Which variant of a block's code a run needs.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Mode {
    /// Every write is reported to the run's tracer.
    pub traced: bool,
    /// Statement starts and decisions are counted (ADR 0020).
    pub covered: bool,
}

impl Mode {
    fn index(self) -> usize {
        usize::from(self.traced) | usize::from(self.covered) << 1
    }
}

/// A block's compiled code once tried, per [`Mode`] (`None`: not in the
/// subset), and the instructions the interpreter has run of it so far;
/// clones of a `Linked` share it.
#[derive(Default)]
pub(crate) struct SlotState {
    variants: [OnceLock<Option<Arc<Compiled>>>; 4],
    /// Per variant: handed to the translation thread (at most once, so a
    /// block is never translated twice).
    queued: [AtomicBool; 4],
    interpreted: AtomicU64,
    /// Runs that began on the interpreter while their translation was
    /// pending: what shows that no run waited for one.
    behind: AtomicU64,
    /// Whether the block has a backward jump (a loop), once looked at.
    looping: OnceLock<bool>,
}

impl SlotState {
    /// Whether a variant that is `traced` or not has been compiled.
    fn compiled(&self, traced: bool) -> bool {
        [false, true]
            .into_iter()
            .any(|covered| self.variants[Mode { traced, covered }.index()].get().is_some_and(Option::is_some))
    }

    /// Whether a variant is queued and not translated yet.
    fn pending(&self) -> bool {
        self.queued.iter().zip(&self.variants).any(|(q, v)| q.load(Ordering::Acquire) && v.get().is_none())
    }

    /// Whether the block is due for compilation: a loop at once, since
    /// that is where a run spends its time and one run may be long (a
    /// whole `linc run`); a straight block once it has run `after`
    /// instructions on the interpreter (compiling takes about 2 ms, so
    /// short one-off programs stay on the interpreter).
    fn due(&self, linked: &Linked, (program, block): (usize, usize), after: u64) -> bool {
        let looping = *self.looping.get_or_init(|| {
            linked
                .ops(program, block)
                .is_some_and(|ops| ops.iter().enumerate().any(|(i, op)| op.target().is_some_and(|t| (t as usize) <= i)))
        });
        looping || self.interpreted.load(Ordering::Relaxed) >= after
    }
}

type Slot = Arc<SlotState>;

/// Compiled code per (program, block), made once a block is due.
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

    /// The compiled code of a block, once it is due ([`SlotState::due`]).
    /// With `after` 0 (`--tier compiled`) a block is translated here, before
    /// its first run, as a benchmark wants; otherwise it is queued for the
    /// translation thread and this run, like every run until the code is
    /// ready, is the interpreter's.
    pub(crate) fn get(
        &self,
        linked: &Linked,
        store: &Store,
        at: (usize, usize),
        after: u64,
        mode: Mode,
    ) -> Option<Arc<Compiled>> {
        let slot = self.slot(at)?;
        let cell = &slot.variants[mode.index()];
        if let Some(code) = cell.get() {
            return code.clone();
        }
        if !slot.due(linked, at, after) {
            return None;
        }
        if after == 0 {
            return cell.get_or_init(|| compile_as(linked, store, at, mode).map(Arc::new)).clone();
        }
        Self::queue(slot, linked, store, at, mode);
        None
    }

    /// Hands a due variant to the translation thread, once. What the thread
    /// needs is copied out now ([`Prepared`]): a block the tier refuses is
    /// settled here, without a trip there.
    fn queue(slot: &Slot, linked: &Linked, store: &Store, at: (usize, usize), mode: Mode) {
        let variant = mode.index();
        if slot.queued[variant].swap(true, Ordering::AcqRel) {
            slot.behind.fetch_add(1, Ordering::Relaxed);
            return;
        }
        let Some(work) = prepare(linked, store, at, mode) else {
            let _ = slot.variants[variant].set(None);
            return;
        };
        match background::submit(background::Job { slot: Arc::downgrade(slot), variant, work: Box::new(work) }) {
            Ok(()) => {
                slot.behind.fetch_add(1, Ordering::Relaxed);
            }
            // Offered again at the block's next run.
            Err(TrySendError::Full(_)) => slot.queued[variant].store(false, Ordering::Release),
            // No thread could be started: translate here, as before.
            Err(TrySendError::Disconnected(job)) => {
                let _ = slot.variants[variant].set(job.work.compile().map(Arc::new));
            }
        }
    }

    fn slot(&self, (program, block): (usize, usize)) -> Option<&Slot> {
        self.blocks.get(program).and_then(|p| p.get(block))
    }

    /// Whether a block has been compiled (for tests and listings).
    pub fn is_compiled(&self, at: (usize, usize)) -> bool {
        self.slot(at).is_some_and(|s| s.compiled(false))
    }

    /// Whether a block's traced variant has been compiled (for tests).
    pub fn is_compiled_traced(&self, at: (usize, usize)) -> bool {
        self.slot(at).is_some_and(|s| s.compiled(true))
    }

    /// Runs of a block that began on the interpreter because its
    /// translation was still pending (for tests).
    pub fn runs_behind(&self, at: (usize, usize)) -> u64 {
        self.slot(at).map_or(0, |s| s.behind.load(Ordering::Relaxed))
    }

    /// Waits until every translation queued for these programs has ended,
    /// so that a test can say which code the next run uses; runs never
    /// call it.
    pub fn settle(&self) {
        background::settle(|| self.blocks.iter().flatten().any(|s| s.pending()));
    }

    /// Counts instructions the interpreter ran of a block not yet compiled.
    pub(crate) fn note_interpreted(&self, at: (usize, usize), instructions: u64) {
        if let Some(slot) = self.slot(at) {
            if slot.variants.iter().any(|v| v.get().is_none()) {
                slot.interpreted.fetch_add(instructions, Ordering::Relaxed);
            }
        }
    }
}

/// Compiles block `block` of `program`, or `None` when it uses anything
/// outside the subset or is larger than [`MAX_BLOCK_OPS`] (the interpreter
/// then runs it).
pub fn compile(linked: &Linked, store: &Store, program: usize, block: usize) -> Option<Compiled> {
    compile_as(linked, store, (program, block), Mode::default())
}

/// How a compiled run ended.
#[cfg_attr(not(feature = "jit"), allow(dead_code))]
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
#[cfg_attr(not(feature = "jit"), allow(dead_code))]
pub(crate) struct Buffers<'a> {
    pub mem: &'a mut Vec<u32>,
    pub stack: &'a mut Vec<u32>,
    pub locals: &'a mut Vec<u32>,
}

/// What the runtime services a compiled run calls use: the VM's string
/// stack and budgets, the object's constants and the run's tracer; and the
/// block's coverage counters, which covered code adds to.
#[cfg_attr(not(feature = "jit"), allow(dead_code))]
pub(crate) struct Services<'a, 't> {
    pub vm: &'a mut Vm,
    pub consts: &'a [Bytes],
    pub trace: &'a mut crate::vm::Tracer<'t>,
    pub cover: Option<&'a crate::cover::BlockCounters>,
}

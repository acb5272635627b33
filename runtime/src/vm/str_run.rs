//! Runs of string instructions that compiled code hands over in one call.
//!
//! A statement such as `T := CONCAT(LEFT(U, 4), 'ab')` is six instructions,
//! each of which compiled code would hand to a runtime service of its own:
//! the calls cost more than the string work. The compiling tier gives such
//! a run to [`Vm::run_strs`] as a list of [`Step`]s, with the INT constants
//! of LEFT, RIGHT and MID folded in and a value that is read only to be cut
//! or measured never copied whole, and a value stored and read straight
//! back left where it is. Each step does what its instructions do on the
//! interpreter, in the same order: the same values, the same counts against
//! the string budget, the same faults, reported at the instruction that
//! faults (`Step::at`).

use super::cells::{cell_text, corrupt, store_str};
use super::Vm;
use crate::errors::Fault;
use crate::isa::Op;
use crate::store::{Cell, Store};
use crate::wire::Bytes;
use linc_stdlib::call::InPlace;
use linc_stdlib::functions::strings::len as int_len;

/// A value a step reads; `cell`s are store cells, `k` a constant's index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Piece {
    /// `LoadS`.
    Field { cell: u32 },
    /// `LoadS`, then `PushI` of the INT arguments and a `Call` of LEFT,
    /// RIGHT or MID: only the bytes kept are copied.
    Cut { cell: u32, how: InPlace, ints: [i32; 2] },
    /// `PushS`.
    Const { k: u32 },
}

impl Piece {
    /// How many instructions the piece is.
    pub(crate) fn len(self) -> u32 {
        match self {
            Piece::Cut { how, .. } => 2 + cut_args(how),
            _ => 1,
        }
    }
}

/// How many INT arguments a LEFT, RIGHT or MID takes.
fn cut_args(how: InPlace) -> u32 {
    if how == InPlace::Mid {
        2
    } else {
        1
    }
}

/// What a step does.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum StrOp {
    /// A piece pushed.
    Push(Piece),
    /// A piece pushed and joined to the value below it (`Call CONCAT`):
    /// appended where that value ends.
    JoinWith(Piece),
    /// `LoadS`, `Call LEN`: nothing is copied; the run's INT result.
    LoadLen { cell: u32 },
    /// `PushI` of the INT arguments and a `Call` of LEFT, RIGHT or MID.
    Cut { how: InPlace, ints: [i32; 2] },
    /// `Call CONCAT`.
    Join,
    /// `Call LEN`: the run's INT result.
    Len,
    /// `StoreS`.
    Store { cell: u32 },
    /// `StoreS`, then `LoadS` of the same cell: the value stays where it is
    /// on the stack when the cell took it as it is (a string field not
    /// forced).
    StoreLoad { cell: u32 },
    /// `AppendS`.
    Append { cell: u32 },
    /// `EqS` … `GeS`: the run's INT result.
    Compare { op: Op },
}

/// A step and where its first instruction is, counted from the run's
/// first; and the store that follows a step making a value (`StoreS`, or
/// `StoreS` and `LoadS` of the same field, at `then_at`), which runs with
/// it: the end of every string assignment, taken without a dispatch of its
/// own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Step {
    pub op: StrOp,
    pub at: u32,
    pub then: Then,
    pub then_at: u32,
}

/// What follows a step ([`Step::then`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Then {
    Nothing,
    Store { cell: u32 },
    StoreLoad { cell: u32 },
}

impl Step {
    pub(crate) fn new(op: StrOp, at: u32) -> Step {
        Step { op, at, then: Then::Nothing, then_at: 0 }
    }
}

impl StrOp {
    /// How many instructions after its first the step's last is: the
    /// `Call` of a cut or LEN, the `LoadS` after a `StoreS`; a fault of
    /// that instruction is reported there.
    pub(crate) fn later(self) -> u32 {
        match self {
            StrOp::Push(p) => p.len() - 1,
            StrOp::JoinWith(p) => p.len(),
            StrOp::LoadLen { .. } | StrOp::StoreLoad { .. } => 1,
            StrOp::Cut { how, .. } => cut_args(how),
            _ => 0,
        }
    }
}

/// Whether cell `c` takes a stored string as it is: a string field (not
/// enumerated) that is not forced.
fn plain(store: &Store, c: u32) -> bool {
    matches!(store.cells.get(c as usize), Some(Cell::Text(_) | Cell::Bseq(_) | Cell::Wstr(_))) && !store.is_forced(c)
}

/// The string budget while a run's steps run: kept in registers, not in
/// the VM, whose every field the compiler reloads after each byte a step
/// writes (a write through a byte pointer may alias anything).
struct Budget {
    used: usize,
    limit: usize,
}

impl Budget {
    /// [`Vm::fits`], on the run's copy.
    #[inline(always)]
    fn fits(&mut self, len: usize) -> bool {
        super::strings::fits(&mut self.used, self.limit, len)
    }
}

impl Vm {
    /// Runs the steps; the INT result of the last (LEN or a comparison),
    /// else 0. On a fault, the offset of its instruction in the run, the
    /// fault being left in `jit_fault`, where compiled code leaves faults.
    pub(crate) fn run_strs(&mut self, store: &mut Store, consts: &[Bytes], steps: &[Step]) -> Result<u32, u32> {
        let mut b = Budget { used: self.string_used, limit: self.string_budget };
        let ran = self.steps(store, consts, steps, &mut b);
        self.string_used = b.used;
        ran
    }

    #[inline(always)]
    fn steps(&mut self, store: &mut Store, consts: &[Bytes], steps: &[Step], b: &mut Budget) -> Result<u32, u32> {
        let mut result = 0;
        for s in steps {
            if let Err(off) = self.step(store, consts, s.op, (&mut result, b)) {
                return Err(s.at + off);
            }
            let then = match s.then {
                Then::Nothing => continue,
                Then::Store { cell } => self.step(store, consts, StrOp::Store { cell }, (&mut result, b)),
                Then::StoreLoad { cell } => self.step(store, consts, StrOp::StoreLoad { cell }, (&mut result, b)),
            };
            then.map_err(|off| s.then_at + off)?;
        }
        Ok(result)
    }

    /// Runs one step, leaving an INT result (LEN or a comparison) in
    /// `result`. On a fault, which is left in `jit_fault` (where compiled
    /// code leaves faults), the offset in the step of the instruction that
    /// faulted.
    #[inline(always)]
    fn step(
        &mut self,
        store: &mut Store,
        consts: &[Bytes],
        op: StrOp,
        (result, b): (&mut u32, &mut Budget),
    ) -> Result<(), u32> {
        match op {
            StrOp::Push(p) => {
                let text = self.piece(store, consts, p, b)?;
                self.strs.push(text);
            }
            StrOp::JoinWith(p) => self.join_piece(store, consts, p, b)?,
            StrOp::LoadLen { cell } => {
                let text = cell_text(store, cell).ok_or_else(|| self.fail(0, corrupt()))?;
                if !b.fits(text.len()) {
                    return Err(self.fail_count(0, text.len()));
                }
                *result = int_len(text) as u32;
            }
            StrOp::Cut { how, ints } => {
                self.strs.at_least(1);
                let len = self.strs.cut(how, ints);
                if !b.fits(len) {
                    return Err(self.fail_count(op.later(), len));
                }
            }
            StrOp::Join => {
                self.strs.at_least(2);
                let len = self.strs.join();
                if !b.fits(len) {
                    return Err(self.fail_count(0, len));
                }
            }
            StrOp::Len => {
                *result = int_len(self.strs.top()) as u32;
                self.strs.drop_top();
            }
            StrOp::Store { cell } => {
                let stored = store_str(store, cell, self.strs.top());
                self.strs.drop_top();
                stored.map_err(|f| self.fail(0, f))?;
            }
            StrOp::StoreLoad { cell } => {
                let plain = plain(store, cell);
                store_str(store, cell, self.strs.top()).map_err(|f| self.fail(0, f))?;
                if plain {
                    let len = self.strs.top().len();
                    if !b.fits(len) {
                        return Err(self.fail_count(op.later(), len));
                    }
                } else {
                    self.strs.drop_top();
                    self.string_used = b.used;
                    let loaded = self.load_s(store, cell);
                    b.used = self.string_used;
                    loaded.map_err(|f| self.fail(op.later(), f))?;
                }
            }
            StrOp::Append { cell } => {
                self.string_used = b.used;
                let appended = self.append_s(store, cell);
                b.used = self.string_used;
                appended.map_err(|f| self.fail(0, f))?;
            }
            StrOp::Compare { op } => *result = self.compare_s(op) as u32,
        }
        Ok(())
    }

    /// A piece appended to the value below it, as `Call CONCAT` after it.
    #[inline(always)]
    fn join_piece(&mut self, store: &Store, consts: &[Bytes], p: Piece, b: &mut Budget) -> Result<(), u32> {
        let text = self.piece(store, consts, p, b)?;
        self.strs.extend_top(text);
        let len = self.strs.top().len();
        if !b.fits(len) {
            return Err(self.fail_count(p.len(), len));
        }
        Ok(())
    }

    /// The bytes of a piece, counted as the instructions that push it count
    /// them.
    #[inline(always)]
    fn piece<'a>(&mut self, store: &'a Store, consts: &'a [Bytes], p: Piece, b: &mut Budget) -> Result<&'a [u8], u32> {
        let text = match p {
            Piece::Field { cell } | Piece::Cut { cell, .. } => {
                cell_text(store, cell).ok_or_else(|| self.fail(0, corrupt()))?
            }
            Piece::Const { k } => consts.get(k as usize).map_or(&[][..], |b| &b.0[..]),
        };
        if !b.fits(text.len()) {
            return Err(self.fail_count(0, text.len()));
        }
        let Piece::Cut { how, ints, .. } = p else { return Ok(text) };
        let kept = text.get(how.keep(text.len(), ints)).unwrap_or_default();
        if !b.fits(kept.len()) {
            return Err(self.fail_count(p.len() - 1, kept.len()));
        }
        Ok(kept)
    }

    /// Leaves `fault` for the compiled code to report at offset `at`.
    #[cold]
    fn fail(&mut self, at: u32, fault: Fault) -> u32 {
        self.jit_fault = Some(fault);
        at
    }

    /// [`Vm::fail`] for a string of `len` bytes over a limit.
    #[cold]
    fn fail_count(&mut self, at: u32, len: usize) -> u32 {
        let fault = self.over(len);
        self.fail(at, fault)
    }
}

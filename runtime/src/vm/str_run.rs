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

use super::cells::{corrupt, store_str};
use super::Vm;
use crate::errors::Fault;
use crate::isa::Op;
use crate::store::{Cell, Store};
use crate::wire::Bytes;
use linc_stdlib::call::InPlace;
use linc_stdlib::functions::strings::len as int_len;

/// What a step does; `cell`s are store cells, `k` a constant's index.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum StrOp {
    /// `LoadS`.
    Load { cell: u32 },
    /// `LoadS`, then `PushI` of the INT arguments and a `Call` of LEFT,
    /// RIGHT or MID: only the bytes kept are copied.
    LoadCut { cell: u32, how: InPlace, ints: [i32; 2] },
    /// `LoadS`, `Call LEN`: nothing is copied; the run's INT result.
    LoadLen { cell: u32 },
    /// `PushS`.
    Const { k: u32 },
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
/// first.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Step {
    pub op: StrOp,
    pub at: u32,
}

impl StrOp {
    /// How many instructions after its first the step's last is: the
    /// `Call` of a cut or LEN, the `LoadS` after a `StoreS`; a fault of
    /// that instruction is reported there.
    pub(crate) fn later(self) -> u32 {
        match self {
            StrOp::LoadCut { how: InPlace::Mid, .. } => 3,
            StrOp::LoadCut { .. } => 2,
            StrOp::LoadLen { .. } | StrOp::StoreLoad { .. } => 1,
            StrOp::Cut { how: InPlace::Mid, .. } => 2,
            StrOp::Cut { .. } => 1,
            _ => 0,
        }
    }
}

/// The value of string cell `c` as `LoadS` reads it (`None`: not a string
/// cell, which the verifier rules out).
#[inline(always)]
fn cell_text(store: &Store, c: u32) -> Option<&[u8]> {
    match store.cells.get(c as usize)? {
        Cell::Text(t) | Cell::Bseq(t) | Cell::Wstr(t) => Some(&t[..]),
        Cell::Enum { idx } => Some(store.enum_names(c).get(usize::from(*idx)).map_or(&[][..], |n| n.as_bytes())),
        _ => None,
    }
}

/// Whether cell `c` takes a stored string as it is: a string field (not
/// enumerated) that is not forced.
fn plain(store: &Store, c: u32) -> bool {
    matches!(store.cells.get(c as usize), Some(Cell::Text(_) | Cell::Bseq(_) | Cell::Wstr(_))) && !store.is_forced(c)
}

impl Vm {
    /// Runs the steps; the INT result of the last (LEN or a comparison),
    /// else 0. On a fault, the offset of its instruction in the run, the
    /// fault being left in `jit_fault`, where compiled code leaves faults.
    pub(crate) fn run_strs(&mut self, store: &mut Store, consts: &[Bytes], steps: &[Step]) -> Result<u32, u32> {
        let mut result = 0;
        for s in steps {
            if let Err(off) = self.step(store, consts, s.op, &mut result) {
                return Err(s.at + off);
            }
        }
        Ok(result)
    }

    /// Runs one step, leaving an INT result (LEN or a comparison) in
    /// `result`. On a fault, which is left in `jit_fault` (where compiled
    /// code leaves faults), the offset in the step of the instruction that
    /// faulted.
    #[inline(always)]
    fn step(&mut self, store: &mut Store, consts: &[Bytes], op: StrOp, result: &mut u32) -> Result<(), u32> {
        match op {
            StrOp::Load { cell } => {
                let text = cell_text(store, cell).ok_or_else(|| self.fail(0, corrupt()))?;
                if !self.fits(text.len()) {
                    return Err(self.fail_count(0, text.len()));
                }
                self.strs.push(text);
            }
            StrOp::LoadCut { cell, how, ints } => {
                let text = cell_text(store, cell).ok_or_else(|| self.fail(0, corrupt()))?;
                if !self.fits(text.len()) {
                    return Err(self.fail_count(0, text.len()));
                }
                let keep = how.keep(text.len(), ints);
                let len = keep.len();
                self.strs.push(&text[keep]);
                if !self.fits(len) {
                    return Err(self.fail_count(op.later(), len));
                }
            }
            StrOp::LoadLen { cell } => {
                let text = cell_text(store, cell).ok_or_else(|| self.fail(0, corrupt()))?;
                if !self.fits(text.len()) {
                    return Err(self.fail_count(0, text.len()));
                }
                *result = int_len(text) as u32;
            }
            StrOp::Const { k } => {
                let text = consts.get(k as usize).map_or(&[][..], |b| &b.0[..]);
                if !self.fits(text.len()) {
                    return Err(self.fail_count(0, text.len()));
                }
                self.strs.push(text);
            }
            StrOp::Cut { how, ints } => {
                self.strs.at_least(1);
                let len = self.strs.cut(how, ints);
                if !self.fits(len) {
                    return Err(self.fail_count(op.later(), len));
                }
            }
            StrOp::Join => {
                self.strs.at_least(2);
                let len = self.strs.join();
                if !self.fits(len) {
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
                    if !self.fits(len) {
                        return Err(self.fail_count(op.later(), len));
                    }
                } else {
                    self.strs.drop_top();
                    self.load_s(store, cell).map_err(|f| self.fail(op.later(), f))?;
                }
            }
            StrOp::Append { cell } => self.append_s(store, cell).map_err(|f| self.fail(0, f))?,
            StrOp::Compare { op } => *result = self.compare_s(op) as u32,
        }
        Ok(())
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

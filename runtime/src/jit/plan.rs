//! Where each cell a compiled block touches lives in its scratch memory.
//!
//! Cells named directly are single slots; cells reached through `Ref` or
//! `RefOff` bring their whole run, so an offset is a slot index plus `n`.
//! Overlapping ranges share slots. Slots outside every referenced range are
//! *promoted*: the compiled code keeps them in registers between its entry
//! and its exits, since no computed index can reach them.

use crate::isa::Op;
use crate::link::Target;
use crate::store::{Cell, Store};

pub(crate) const INT: u8 = 0;
pub(crate) const BOOL: u8 = 1;
pub(crate) const REAL: u8 = 2;
/// Added to a kind: programs may not write the cell (offsets are checked).
pub(crate) const READONLY: u8 = 4;

/// Most slots kept in registers; the rest stay in memory.
const MAX_PROMOTED: usize = 48;

/// Promoted slots times instructions, at most. Every exit of the code (a
/// check that may bail out, a block's budget check) hands every promoted
/// slot back, and a block has about as many exits as instructions: without
/// a bound, translating a long block with many cells spent most of its
/// time moving promoted slots to exits (1,000 instructions of `IF`s over
/// 58 cells: 110 µs per instruction). Blocks of up to 256 instructions,
/// where a loop's speed matters, keep all 48.
const PROMOTION_BUDGET: usize = MAX_PROMOTED * 256;

pub(crate) struct Plan {
    /// Store cell of each slot.
    pub cells: Vec<u32>,
    /// Kind of each slot (`INT`, `BOOL`, `REAL`, plus `READONLY`).
    pub kinds: Vec<u8>,
    /// Whether the slot lives in a register.
    pub promoted: Vec<bool>,
    /// Slot of each symbol's cell (`u32::MAX` when not used).
    pub sym_slot: Vec<u32>,
    /// Cells after each symbol's cell in its run (for `RefOff`).
    pub sym_room: Vec<u32>,
    /// Each symbol's store cell (for strings, which have no slot).
    pub sym_cell: Vec<u32>,
}

impl Plan {
    /// The layout for `ops`, or `None` when a cell is absent or of a kind
    /// the compiled tier does not handle, or an instruction meets a cell of
    /// the wrong kind (the interpreter reports those).
    pub fn new(ops: &[Op], targets: &[Target], store: &Store, traced: bool) -> Option<Plan> {
        let mut ranges: Vec<(u32, u32, bool)> = Vec::new();
        for op in ops {
            let Some(sym) = op.symbol() else { continue };
            let t = targets.get(usize::from(sym))?;
            if t.is_absent() {
                return None;
            }
            if matches!(op, Op::LoadS { .. } | Op::StoreS { .. } | Op::AppendS { .. }) {
                // Strings stay in the store; the runtime services reach them.
                if !is_string(store, t.cell) {
                    return None;
                }
                continue;
            }
            let kind = kind_of(store, t.cell)?;
            match op {
                Op::LoadI { .. } | Op::StoreI { .. } if kind & 3 == REAL => return None,
                Op::LoadR { .. } | Op::StoreR { .. } if kind & 3 != REAL => return None,
                Op::LoadI { .. } | Op::StoreI { .. } | Op::LoadR { .. } | Op::StoreR { .. } => {
                    ranges.push((t.cell, t.cell, false))
                }
                Op::Ref { .. } => ranges.push((t.cell, t.cell, true)),
                Op::RefOff { .. } => ranges.push((t.cell, t.run_end.max(t.cell), true)),
                _ => {}
            }
        }
        ranges.sort_unstable();
        let mut merged: Vec<(u32, u32, bool)> = Vec::new();
        for (a, b, r) in ranges {
            match merged.last_mut() {
                Some(m) if a <= m.1 => {
                    m.1 = m.1.max(b);
                    m.2 |= r;
                }
                _ => merged.push((a, b, r)),
            }
        }
        let mut plan = Plan {
            cells: Vec::new(),
            kinds: Vec::new(),
            promoted: Vec::new(),
            sym_slot: Vec::new(),
            sym_room: Vec::new(),
            sym_cell: targets.iter().map(|t| t.cell).collect(),
        };
        let mut promoted = 0;
        let max_promoted = (PROMOTION_BUDGET / ops.len().max(1)).min(MAX_PROMOTED);
        for (a, b, r) in merged {
            for c in a..=b {
                plan.cells.push(c);
                plan.kinds.push(kind_of(store, c)?);
                // Traced code keeps every cell in memory, where the trace
                // reads it after each write.
                plan.promoted.push(!r && !traced && promoted < max_promoted);
                promoted += usize::from(!r);
            }
        }
        plan.sym_slot =
            targets.iter().map(|t| plan.cells.binary_search(&t.cell).map_or(u32::MAX, |s| s as u32)).collect();
        plan.sym_room = targets.iter().map(room).collect();
        Some(plan)
    }

    /// The slot of symbol `sym`'s cell.
    pub fn slot(&self, sym: u16) -> Option<u32> {
        self.sym_slot.get(usize::from(sym)).copied().filter(|&s| s != u32::MAX)
    }
}

/// The slot kind of a cell, or `None` for kinds the tier leaves alone.
fn kind_of(store: &Store, c: u32) -> Option<u8> {
    let k = match store.cells.get(c as usize)? {
        Cell::Int(_) => INT,
        Cell::Bool(_) => BOOL,
        Cell::Real(_) => REAL,
        _ => return None,
    };
    Some(k | if store.is_readonly(c) { READONLY } else { 0 })
}

/// Whether cell `c` holds a string (or an enumeration, read by name).
fn is_string(store: &Store, c: u32) -> bool {
    matches!(store.cells.get(c as usize), Some(Cell::Text(_) | Cell::Bseq(_) | Cell::Wstr(_) | Cell::Enum { .. }))
}

/// Room after the cell of `t` in its run (for `RefOff`).
fn room(t: &Target) -> u32 {
    t.run_end.saturating_sub(t.cell)
}

//! The ranges INT values can take, so that an offset whose index is a
//! loop variable with known bounds needs no range check.
//!
//! An abstract interpretation of the block over intervals: the cells kept
//! in registers (promoted slots: no offset can reach them, so only their
//! own `StoreI` changes them), the locals (a FOR loop's limit) and the
//! stack. A comparison remembers what it compared, so that the jump
//! testing it narrows the variables on each way out (`FOR N0 := 7 TO 1 BY
//! -1` leaves `N0` within 1..7 in the body). Arithmetic that could wrap
//! gives "any INT". A loop head widened after a few passes reaches a
//! fixed point at once. The result is, for each `RefOff`, the range of
//! the index it pops on every path, which the emitter compares with the
//! run's room ([`super::Emitter::reference`]); everything here is an
//! over-approximation, so a check is only ever left out where it cannot
//! fail.

use super::Blocks;
use crate::isa::Op;

/// Passes through a loop head before its ranges are widened (each pass
/// after that moves a bound to the next constant, so a loop head is
/// visited at most a few times per constant of the block).
const WIDEN_AFTER: u32 = 3;

/// A closed interval of INT values.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Iv {
    pub lo: i64,
    pub hi: i64,
}

const ANY: Iv = Iv { lo: i32::MIN as i64, hi: i32::MAX as i64 };

impl Iv {
    fn at(v: i64) -> Iv {
        Iv { lo: v, hi: v }
    }

    fn join(self, o: Iv) -> Iv {
        Iv { lo: self.lo.min(o.lo), hi: self.hi.max(o.hi) }
    }

    /// An exact result, or any INT where it could wrap.
    fn wrapped(lo: i64, hi: i64) -> Iv {
        if lo < ANY.lo || hi > ANY.hi {
            ANY
        } else {
            Iv { lo, hi }
        }
    }
}

/// What a stack entry was read from, so that a test of it narrows it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Var {
    /// A tracked slot, by its index in the state.
    Slot(usize),
    Local(usize),
}

/// A comparison and its two operands (their ranges and variables).
type Cond = (Op, (Iv, Option<Var>), (Iv, Option<Var>));

#[derive(Clone, Copy, Debug, PartialEq)]
struct Entry {
    iv: Iv,
    var: Option<Var>,
    /// For a comparison's result: the comparison and its two operands.
    cond: Option<Cond>,
}

impl Entry {
    fn plain(iv: Iv) -> Entry {
        Entry { iv, var: None, cond: None }
    }
}

#[derive(Clone, Debug, PartialEq)]
struct State {
    slots: Vec<Iv>,
    locals: Vec<Iv>,
    stack: Vec<Entry>,
}

impl State {
    fn get(&self, v: Var) -> Iv {
        match v {
            Var::Slot(i) => self.slots[i],
            Var::Local(i) => self.locals[i],
        }
    }

    fn set(&mut self, v: Var, iv: Iv) {
        match v {
            Var::Slot(i) => self.slots[i] = iv,
            Var::Local(i) => self.locals[i] = iv,
        }
        // Entries read from the variable before keep their value but no
        // longer stand for it.
        for e in &mut self.stack {
            if e.var == Some(v) {
                e.var = None;
            }
            if e.cond.is_some_and(|(_, a, b)| a.1 == Some(v) || b.1 == Some(v)) {
                e.cond = None;
            }
        }
    }

    /// One instruction of straight code (not a jump, a return or a
    /// `RefOff`); `slot` maps a symbol to its tracked slot.
    fn step(&mut self, op: Op, slot: &impl Fn(u16) -> Option<usize>, bools: &[bool]) {
        match op {
            Op::PushI { v } => self.stack.push(Entry::plain(Iv::at(i64::from(v)))),
            Op::LoadI { sym } => {
                let e = match slot(sym) {
                    Some(i) => Entry { iv: self.slots[i], var: Some(Var::Slot(i)), cond: None },
                    None => Entry::plain(ANY),
                };
                self.stack.push(e);
            }
            Op::StoreI { sym } => {
                let iv = self.stack.pop().map_or(ANY, |e| e.iv);
                if let Some(i) = slot(sym) {
                    let iv = if bools[i] { bool_of(iv) } else { iv };
                    self.set(Var::Slot(i), iv);
                }
            }
            Op::LoadLoc { n: l } => {
                let l = usize::from(l);
                let e = match self.locals.get(l) {
                    Some(&iv) => Entry { iv, var: Some(Var::Local(l)), cond: None },
                    None => Entry::plain(Iv::at(0)),
                };
                self.stack.push(e);
            }
            Op::StoreLoc { n: l } => {
                let iv = self.stack.pop().map_or(ANY, |e| e.iv);
                if usize::from(l) < self.locals.len() {
                    self.set(Var::Local(usize::from(l)), iv);
                }
            }
            Op::AddI {} | Op::SubI {} => {
                let (b, a) = (self.stack.pop().map_or(ANY, |e| e.iv), self.stack.pop().map_or(ANY, |e| e.iv));
                let iv = match op {
                    Op::AddI {} => Iv::wrapped(a.lo + b.lo, a.hi + b.hi),
                    _ => Iv::wrapped(a.lo - b.hi, a.hi - b.lo),
                };
                self.stack.push(Entry::plain(iv));
            }
            Op::EqI {} | Op::NeI {} | Op::LtI {} | Op::GtI {} | Op::LeI {} | Op::GeI {} => {
                let b = self.stack.pop().unwrap_or(Entry::plain(ANY));
                let a = self.stack.pop().unwrap_or(Entry::plain(ANY));
                let cond = Some((op, (a.iv, a.var), (b.iv, b.var)));
                self.stack.push(Entry { iv: Iv { lo: 0, hi: 1 }, var: None, cond });
            }
            _ => {
                let e = op.effect();
                let keep = self.stack.len().saturating_sub(e.num_pop as usize);
                self.stack.truncate(keep);
                for _ in 0..e.num_push {
                    self.stack.push(Entry::plain(ANY));
                }
            }
        }
    }

    /// Joins `o` in, widened to the next of `steps` when `widen`; whether
    /// anything grew.
    fn absorb(&mut self, o: &State, widen: Option<&[i64]>) -> bool {
        let grow = |a: &mut Iv, b: Iv| {
            let j = a.join(b);
            let j = match widen {
                Some(steps) => Iv {
                    lo: if j.lo < a.lo {
                        steps.iter().rev().find(|&&t| t <= j.lo).copied().unwrap_or(ANY.lo)
                    } else {
                        j.lo
                    },
                    hi: if j.hi > a.hi { steps.iter().find(|&&t| t >= j.hi).copied().unwrap_or(ANY.hi) } else { j.hi },
                },
                None => j,
            };
            let changed = j != *a;
            *a = j;
            changed
        };
        let mut changed = false;
        for (a, b) in self.slots.iter_mut().zip(&o.slots).chain(self.locals.iter_mut().zip(&o.locals)) {
            changed |= grow(a, *b);
        }
        for (a, b) in self.stack.iter_mut().zip(&o.stack) {
            changed |= grow(&mut a.iv, b.iv);
            if a.var != b.var || a.cond != b.cond {
                changed |= a.var.is_some() || a.cond.is_some();
                (a.var, a.cond) = (None, None);
            }
        }
        changed
    }

    /// The state on the way out where the comparison `cond` was `holds`;
    /// `None` where it cannot be.
    fn narrowed(&self, cond: Option<Cond>, holds: bool) -> Option<State> {
        let mut s = self.clone();
        let Some((op, (a, va), (b, vb))) = cond else { return Some(s) };
        // Normalise to a < b, a <= b, a = b or a <> b holding.
        let (op, a, va, b, vb) = match (op, holds) {
            (Op::LtI {}, true) | (Op::GeI {}, false) => (0, a, va, b, vb),
            (Op::LeI {}, true) | (Op::GtI {}, false) => (1, a, va, b, vb),
            (Op::GtI {}, true) | (Op::LeI {}, false) => (0, b, vb, a, va),
            (Op::GeI {}, true) | (Op::LtI {}, false) => (1, b, vb, a, va),
            (Op::EqI {}, true) | (Op::NeI {}, false) => (2, a, va, b, vb),
            _ => return Some(s),
        };
        let (na, nb) = match op {
            0 => (Iv { lo: a.lo, hi: a.hi.min(b.hi - 1) }, Iv { lo: b.lo.max(a.lo + 1), hi: b.hi }),
            1 => (Iv { lo: a.lo, hi: a.hi.min(b.hi) }, Iv { lo: b.lo.max(a.lo), hi: b.hi }),
            _ => {
                let both = Iv { lo: a.lo.max(b.lo), hi: a.hi.min(b.hi) };
                (both, both)
            }
        };
        if na.lo > na.hi || nb.lo > nb.hi {
            return None;
        }
        for (v, iv) in [(va, na), (vb, nb)] {
            if let Some(v) = v {
                let cur = s.get(v);
                s.set(v, Iv { lo: cur.lo.max(iv.lo), hi: cur.hi.min(iv.hi) });
            }
        }
        Some(s)
    }
}

/// For each instruction, the range of the index a `RefOff` there pops on
/// every path (`None` elsewhere, or where the code is unreachable).
/// `tracked[slot]` says which slots are INT cells kept in registers,
/// `bools[slot]` which of them are BOOL.
pub(super) fn offset_ranges(
    ops: &[Op],
    (tracked, bools): (&[bool], &[bool]),
    slot_of: impl Fn(u16) -> Option<usize>,
    locals: usize,
    blocks: &Blocks,
) -> Vec<Option<Iv>> {
    // Instructions interpreted, at most: a block of many loops and many
    // constants could otherwise take long to settle; past this nothing is
    // known (every check stays), so translation stays linear.
    settle(ops, (tracked, bools), slot_of, locals, blocks, 32 * ops.len() + 256)
}

/// [`offset_ranges`] within `budget` instructions interpreted.
fn settle(
    ops: &[Op],
    (tracked, bools): (&[bool], &[bool]),
    slot_of: impl Fn(u16) -> Option<usize>,
    locals: usize,
    blocks: &Blocks,
    mut budget: usize,
) -> Vec<Option<Iv>> {
    let n = ops.len();
    let entry = State { slots: vec![ANY; tracked.len()], locals: vec![Iv::at(0); locals], stack: Vec::new() };
    let mut at: Vec<Option<State>> = vec![None; n + 1];
    let mut passes = vec![0u32; n + 1];
    let (steps, head, ends) = (steps_of(ops), &blocks.head, &blocks.ends);
    let mut found: Vec<Option<Iv>> = vec![None; n];
    at[0] = Some(entry);
    let mut work = vec![0usize];
    let slot = |sym: u16| slot_of(sym).filter(|&s| tracked.get(s).copied().unwrap_or(false));
    while let Some(start) = work.pop() {
        let Some(mut s) = at[start].clone() else { continue };
        let end = ends.get(start).copied().unwrap_or(n).min(n);
        budget = match budget.checked_sub(end.saturating_sub(start)) {
            Some(b) => b,
            None => return vec![None; n],
        };
        let mut outs: Vec<(usize, State)> = Vec::new();
        for pc in start..end {
            let op = ops[pc];
            match op {
                Op::RefOff { .. } => {
                    let iv = s.stack.pop().map_or(ANY, |e| e.iv);
                    found[pc] = Some(found[pc].map_or(iv, |f| f.join(iv)));
                }
                Op::JumpIfTrue { to } | Op::JumpIfFalse { to } => {
                    let c = s.stack.pop().and_then(|e| e.cond);
                    let jumps_if = matches!(op, Op::JumpIfTrue { .. });
                    if let Some(t) = s.narrowed(c, jumps_if) {
                        outs.push((to as usize, t));
                    }
                    match s.narrowed(c, !jumps_if) {
                        Some(f) => s = f,
                        None => break,
                    }
                }
                Op::Jump { to } => {
                    outs.push((to as usize, s.clone()));
                    break;
                }
                Op::Ret {} | Op::Return { .. } => break,
                _ => s.step(op, &slot, bools),
            }
            if pc + 1 == end && !matches!(op, Op::Jump { .. } | Op::Ret {} | Op::Return { .. }) {
                outs.push((end, s.clone()));
            }
        }
        for (to, st) in outs {
            if to > n {
                continue;
            }
            let changed = match &mut at[to] {
                Some(old) => {
                    passes[to] += 1;
                    old.absorb(&st, (head[to] && passes[to] > WIDEN_AFTER).then_some(&steps[..]))
                }
                none => {
                    *none = Some(st);
                    true
                }
            };
            if changed && to < n {
                work.push(to);
            }
        }
    }
    found
}

/// Where loop heads widen to: the code's constants and one either side
/// (a FOR limit and the step past it), before any INT. Only loop heads
/// (targets of a jump back) are widened: elsewhere a narrowing test must
/// be able to shrink what it was given, and an outer loop's variable keeps
/// its limit.
fn steps_of(ops: &[Op]) -> Vec<i64> {
    let mut steps: Vec<i64> = ops
        .iter()
        .filter_map(|op| if let Op::PushI { v } = op { Some(i64::from(*v)) } else { None })
        .flat_map(|v| [v - 1, v, v + 1])
        .chain([0])
        .filter(|v| (ANY.lo..=ANY.hi).contains(v))
        .collect();
    steps.sort_unstable();
    steps.dedup();
    steps
}

/// What a BOOL cell holds after storing a value of range `iv`.
fn bool_of(iv: Iv) -> Iv {
    if iv.lo == 0 && iv.hi == 0 {
        Iv::at(0)
    } else if iv.lo > 0 || iv.hi < 0 {
        Iv::at(1)
    } else {
        Iv { lo: 0, hi: 1 }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn blocks(ops: &[Op]) -> Blocks {
        super::super::blocks_of(ops)
    }

    /// The shift register as `linc compile` writes it: slot 0 is N1, slot 1
    /// N0 (promoted INT cells), symbol 2 the offset array.
    fn shift() -> Vec<Op> {
        vec![
            Op::PushI { v: 1 },
            Op::StoreI { sym: 0 },
            Op::PushI { v: 10_000_000 },
            Op::StoreLoc { n: 0 },
            Op::LoadI { sym: 0 }, // 4: L0
            Op::LoadLoc { n: 0 },
            Op::GtI {},
            Op::JumpIfTrue { to: 40 },
            Op::PushI { v: 7 },
            Op::StoreI { sym: 1 },
            Op::PushI { v: 1 },
            Op::StoreLoc { n: 1 },
            Op::LoadI { sym: 1 }, // 12: L1
            Op::LoadLoc { n: 1 },
            Op::LtI {},
            Op::JumpIfTrue { to: 29 },
            Op::LoadI { sym: 1 },
            Op::PushI { v: 1 },
            Op::SubI {},
            Op::RefOff { sym: 2 }, // 19
            Op::LoadRefR { sym: 2 },
            Op::LoadI { sym: 1 },
            Op::RefOff { sym: 2 }, // 22
            Op::StoreRefR { sym: 2 },
            Op::LoadI { sym: 1 },
            Op::PushI { v: -1 },
            Op::AddI {},
            Op::StoreI { sym: 1 },
            Op::Jump { to: 12 },
            Op::LoadR { sym: 3 }, // 29: L2
            Op::PushR { v: 0.5 },
            Op::MulR {},
            Op::PushR { v: 1.0 },
            Op::AddR {},
            Op::StoreR { sym: 2 },
            Op::LoadI { sym: 0 },
            Op::PushI { v: 1 },
            Op::AddI {},
            Op::StoreI { sym: 0 },
            Op::Jump { to: 4 },
            Op::Ret {}, // 40: L3
        ]
    }

    fn ranges_of(ops: &[Op]) -> Vec<Option<Iv>> {
        let slot_of = |sym: u16| Some(usize::from(sym));
        offset_ranges(ops, (&[true, true, false, false], &[false; 4]), slot_of, 2, &blocks(ops))
    }

    #[test]
    fn a_counting_down_loop_bounds_its_offsets() {
        let r = ranges_of(&shift());
        assert_eq!(r[19], Some(Iv { lo: 0, hi: 6 }));
        assert_eq!(r[22], Some(Iv { lo: 1, hi: 7 }));
        assert_eq!(r.iter().filter(|x| x.is_some()).count(), 2);
    }

    #[test]
    fn past_its_budget_the_analysis_knows_nothing() {
        let ops = shift();
        let slot_of = |sym: u16| Some(usize::from(sym));
        let r = settle(&ops, (&[true, true, false, false], &[false; 4]), slot_of, 2, &blocks(&ops), 40);
        assert!(r.iter().all(Option::is_none), "{r:?}");
    }

    #[test]
    fn a_variable_changed_in_the_body_or_untracked_is_not_bounded() {
        // N0 (slot 1) is not a register cell: any INT.
        let ops = shift();
        let slot_of = |sym: u16| Some(usize::from(sym));
        let r = offset_ranges(&ops, (&[true, false, false, false], &[false; 4]), slot_of, 2, &blocks(&ops));
        assert_eq!(r[22], Some(ANY));
        // A store to N0 between the test and the offset: unknown again.
        let mut ops = shift();
        ops[16] = Op::LoadI { sym: 0 };
        let r = ranges_of(&ops);
        assert_eq!(r[19].map(|iv| iv.hi), Some(i64::from(10_000_000 - 1)));
    }
}

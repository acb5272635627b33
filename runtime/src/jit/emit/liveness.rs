//! Where the reference register is still needed.
//!
//! Every exit hands the interpreter the reference (the cell a `Ref` or
//! `RefOff` chose), so the reference was a value carried round every loop
//! that used an offset, moved between registers at each turn, although a
//! loop's next offset always sets it again before it is read. An exit
//! before an instruction from which no path reads the reference before
//! setting it hands over "no reference" instead, which the interpreter
//! never reads; the register then lives only from a `RefOff` to its load
//! or store.

use crate::isa::Op;

/// For each instruction (and the end), whether the reference may be read
/// on some path from there before a `Ref` or `RefOff` sets it.
pub(super) fn reference_live(ops: &[Op]) -> Vec<bool> {
    let n = ops.len();
    let mut live = vec![false; n + 1];
    // Backward flow to a fixed point; loops need more than one pass (at
    // most one per nested loop level, in practice two or three).
    loop {
        let mut changed = false;
        for pc in (0..n).rev() {
            let op = &ops[pc];
            let now = match op {
                Op::LoadRefI { .. } | Op::LoadRefR { .. } | Op::StoreRefI { .. } | Op::StoreRefR { .. } => true,
                Op::Ref { .. } | Op::RefOff { .. } | Op::Ret {} | Op::Return { .. } => false,
                _ => {
                    let falls = !matches!(op, Op::Jump { .. });
                    let to = op.target().map(|t| t as usize).filter(|&t| t <= n);
                    (falls && live[pc + 1]) || to.is_some_and(|t| live[t])
                }
            };
            if now != live[pc] {
                live[pc] = now;
                changed = true;
            }
        }
        if !changed {
            return live;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loop_that_sets_the_reference_before_reading_it_never_needs_it_at_its_head() {
        // 0: LoadI | 1: JumpIfTrue 7 | 2: PushI; 3: RefOff; 4: LoadRefR;
        // 5: StoreR | 6: Jump 0 | 7: Ret
        let ops = [
            Op::LoadI { sym: 0 },
            Op::JumpIfTrue { to: 7 },
            Op::PushI { v: 1 },
            Op::RefOff { sym: 1 },
            Op::LoadRefR { sym: 1 },
            Op::StoreR { sym: 2 },
            Op::Jump { to: 0 },
            Op::Ret {},
        ];
        let live = reference_live(&ops);
        assert_eq!(live, [false, false, false, false, true, false, false, false, false]);
    }

    #[test]
    fn a_read_reached_round_a_loop_keeps_it_live_everywhere_on_the_way() {
        // 0: Ref | 1: LoadRefI; 2: JumpIfFalse 1 | 3: Ret: the read at 1
        // is reached again from 2 without a new Ref.
        let ops = [Op::Ref { sym: 0 }, Op::LoadRefI { sym: 0 }, Op::JumpIfFalse { to: 1 }, Op::Ret {}];
        assert_eq!(reference_live(&ops), [false, true, true, false, false]);
    }
}

//! Where compiled code checks the watchdog budget.
//!
//! The interpreter charges every instruction; compiled code charges a
//! basic block's instructions at its start. Checking the budget at every
//! block cost a compare and a branch per block (two per turn of a small
//! loop). Instead it is checked only at *checkpoints* — the entry and every
//! target of a backward jump, so that every loop passes one — against the
//! most instructions any path from there can run before the next
//! checkpoint or the end. Paths between checkpoints only go forward, so
//! that bound is a longest path in an acyclic graph. Every block still
//! subtracts its own length at its start, so the budget is exact wherever
//! code leaves; when a checkpoint finds too little budget for the longest
//! path, the code leaves there and the interpreter runs on to the exact
//! instruction where the watchdog fires.

use super::{ends_block, Blocks};
use crate::isa::Op;

/// For each block leader: `Some(bound)` when the block is a checkpoint,
/// `None` otherwise.
pub(super) fn checkpoints(ops: &[Op], blocks: &Blocks) -> Vec<Option<u64>> {
    let n = ops.len();
    let (leaders, ends) = (&blocks.leader, &blocks.ends);
    let mut is_check = blocks.head.clone();
    is_check[0] = true;
    // cost[pc]: the most instructions from the start of the block at pc to
    // the next checkpoint (or the end), over every forward path.
    let mut cost = vec![0u64; n + 1];
    for pc in (0..n).rev() {
        if !leaders[pc] {
            continue;
        }
        let end = ends[pc];
        let after = |to: usize| if to >= n || is_check[to] { 0 } else { cost[to] };
        let last = &ops[end - 1];
        let mut next = 0;
        if !matches!(last, Op::Jump { .. } | Op::Ret {} | Op::Return { .. }) {
            next = after(end);
        }
        if let Some(to) = last.target().map(|t| t as usize) {
            if ends_block(last) && to > pc {
                next = next.max(after(to));
            }
        }
        cost[pc] = (end - pc) as u64 + next;
    }
    (0..=n).map(|pc| (pc < n && leaders[pc] && is_check[pc]).then_some(cost[pc])).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_loop_header_bounds_the_longest_way_round() {
        // 0: PushI; 1: JumpIfFalse 4 | 2: PushI; 3: Jump 0 | 4: Ret
        let ops = [Op::PushI { v: 1 }, Op::JumpIfFalse { to: 4 }, Op::PushI { v: 2 }, Op::Jump { to: 0 }, Op::Ret {}];
        let c = checkpoints(&ops, &super::super::blocks_of(&ops));
        // From 0: two instructions, then either the body (two more, back
        // to the checkpoint) or the return (one): at most four.
        assert_eq!(c[0], Some(4));
        assert_eq!(c[2], None);
        assert_eq!(c[4], None);
    }

    #[test]
    fn a_backward_target_inside_straight_code_is_a_checkpoint() {
        // 0: PushI | 1: PushI; 2: JumpIfTrue 1 | 3: Ret
        let ops = [Op::PushI { v: 1 }, Op::PushI { v: 2 }, Op::JumpIfTrue { to: 1 }, Op::Ret {}];
        let c = checkpoints(&ops, &super::super::blocks_of(&ops));
        assert_eq!(c[0], Some(1));
        assert_eq!(c[1], Some(3));
        assert_eq!(c[3], None);
    }
}

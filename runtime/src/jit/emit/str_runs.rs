//! Runs of string instructions handed to the runtime in one service call
//! ([`crate::vm::str_run`]): a statement that builds or tests a string
//! costs one call instead of one per instruction. (A direct call of a
//! service per step, with no dispatch, ran the string kernel at half the
//! speed: each call saves and restores as much as the dispatch costs.)
//!
//! A run lies inside one basic block, starts at a string instruction and
//! takes the instructions after it while each is one [`StrOp`] can do:
//! `LoadS`, `PushS`, `StoreS`, `AppendS`, CONCAT, and LEN, LEFT, RIGHT and
//! MID whose INT arguments are `PushI` constants just before the `Call`.
//! LEN and the comparisons end it with their INT result. In covered code a
//! run stops before an instruction that is counted; traced code, which
//! reports every store on its own, has none.

use super::{Emitter, Ty};
use crate::isa::Op;
use crate::jit::host;
use crate::vm::str_run::{Piece, Step, StrOp, Then};
use crate::vm::Vm;
use cranelift_codegen::ir::{types, InstBuilder};
use linc_stdlib::call::InPlace;

/// A run found at an instruction: its steps, the instruction after it,
/// whether it leaves an INT result and the numeric instructions inside it
/// that are translated after its call ([`transparent`]).
#[derive(Debug, PartialEq)]
pub(crate) struct Run {
    pub steps: Vec<Step>,
    pub end: usize,
    pub int_result: bool,
    pub moved: Vec<usize>,
}

/// The in-place string function `Call`ed at `pc`, and how many INT
/// arguments it takes.
fn in_place_at(ops: &[Op], pc: usize) -> Option<(InPlace, usize)> {
    match ops.get(pc)? {
        Op::Call { func, argc, ret, types } => Vm::in_place_of(*func, *argc, *ret, *types),
        _ => None,
    }
}

/// A LEFT, RIGHT or MID (or, with no INT arguments, LEN) at `pc` after
/// `PushI` of each of its INT arguments: the function, its arguments and
/// the instruction after the call.
fn cut_at(ops: &[Op], pc: usize, open: impl Fn(usize) -> bool) -> Option<(InPlace, [i32; 2], usize)> {
    let mut ints = [0; 2];
    let mut n = 0;
    while let Some(Op::PushI { v }) = ops.get(pc + n) {
        if n == 2 {
            return None;
        }
        ints[n] = *v;
        n += 1;
    }
    let (how, want) = in_place_at(ops, pc + n)?;
    let fits = want == n && matches!(how, InPlace::Left | InPlace::Right | InPlace::Mid | InPlace::Len);
    (fits && (pc..=pc + n).all(open)).then_some((how, ints, pc + n + 1))
}

/// The run starting at `start` and ending by `end` (the basic block's
/// end), if it saves at least one service call. `cell_of` gives a string
/// symbol's store cell; `open(pc)` says whether instruction `pc` may be
/// inside a run (not counted in covered code).
pub(crate) fn run_at(
    ops: &[Op],
    start: usize,
    end: usize,
    cell_of: impl Fn(u16) -> Option<u32>,
    open: impl Fn(usize) -> bool + Copy,
) -> Option<Run> {
    let mut steps = Vec::new();
    let (mut moved, mut pending) = (Vec::new(), Vec::new());
    let mut pc = start;
    let mut calls = 0;
    let mut int_result = false;
    while pc < end && (pc == start || open(pc)) && !int_result {
        if pc > start && transparent(&ops[pc]) && cut_at(ops, pc, open).is_none() {
            pending.push(pc);
            pc += 1;
            continue;
        }
        let (op, next, saved) = match *ops.get(pc)? {
            Op::LoadS { sym } => {
                let cell = cell_of(sym)?;
                match cut_at(ops, pc + 1, open).filter(|c| c.2 <= end) {
                    Some((InPlace::Len, _, next)) => (StrOp::LoadLen { cell }, next, 2),
                    Some((how, ints, next)) => (StrOp::Push(Piece::Cut { cell, how, ints }), next, 2),
                    None => (StrOp::Push(Piece::Field { cell }), pc + 1, 1),
                }
            }
            Op::PushS { k } => (StrOp::Push(Piece::Const { k }), pc + 1, 1),
            Op::StoreS { sym } => match ops.get(pc + 1) {
                Some(Op::LoadS { sym: again }) if *again == sym && pc + 1 < end && open(pc + 1) => {
                    (StrOp::StoreLoad { cell: cell_of(sym)? }, pc + 2, 2)
                }
                _ => (StrOp::Store { cell: cell_of(sym)? }, pc + 1, 1),
            },
            Op::AppendS { sym } => (StrOp::Append { cell: cell_of(sym)? }, pc + 1, 1),
            Op::EqS {} | Op::NeS {} | Op::LtS {} | Op::GtS {} | Op::LeS {} | Op::GeS {} => {
                (StrOp::Compare { op: ops[pc] }, pc + 1, 1)
            }
            Op::PushI { .. } | Op::Call { .. } => match cut_at(ops, pc, open).filter(|c| c.2 <= end) {
                Some((InPlace::Len, _, next)) => (StrOp::Len, next, 1),
                Some((how, ints, next)) => (StrOp::Cut { how, ints }, next, 1),
                None if in_place_at(ops, pc).is_some_and(|(h, _)| h == InPlace::Concat) => {
                    // A piece pushed just before is appended instead (its
                    // instructions right before the CONCAT, which the
                    // step's offsets count on).
                    let before = |s: &Step| matches!(s.op, StrOp::Push(p) if (s.at + p.len()) as usize == pc - start);
                    if let Some(Step { op: StrOp::Push(p), .. }) = steps.last().copied().filter(before) {
                        steps.pop();
                        (StrOp::JoinWith(p), pc + 1, 1)
                    } else {
                        (StrOp::Join, pc + 1, 1)
                    }
                }
                None => break,
            },
            _ => break,
        };
        int_result = matches!(op, StrOp::LoadLen { .. } | StrOp::Len | StrOp::Compare { .. });
        let at = match op {
            StrOp::JoinWith(p) => pc - start - p.len() as usize,
            _ => pc - start,
        };
        let last = steps.last_mut().filter(|s| s.then == Then::Nothing && makes_value(s.op));
        match (op, last) {
            (StrOp::Store { cell }, Some(last)) => (last.then, last.then_at) = (Then::Store { cell }, at as u32),
            (StrOp::StoreLoad { cell }, Some(last)) => {
                (last.then, last.then_at) = (Then::StoreLoad { cell }, at as u32)
            }
            _ => steps.push(Step::new(op, at as u32)),
        }
        moved.append(&mut pending);
        calls += saved;
        pc = next;
    }
    let end = pending.first().copied().unwrap_or(pc);
    (calls >= 2).then_some(Run { steps, end, int_result, moved })
}

/// Whether a step leaves a value on the stack that a store after it can
/// take (see [`Step::then`]).
fn makes_value(op: StrOp) -> bool {
    matches!(op, StrOp::Push(_) | StrOp::JoinWith(_) | StrOp::Join | StrOp::Cut { .. })
}

/// Whether an instruction only pushes a number that no string instruction
/// changes, and can neither fault nor bail out: a run goes on over it, and
/// the code for it comes after the run's call. `N := N + LEN(S)` after a
/// string statement is then one call, not two.
fn transparent(op: &Op) -> bool {
    matches!(op, Op::PushI { .. } | Op::PushR { .. } | Op::LoadI { .. } | Op::LoadR { .. } | Op::LoadLoc { .. })
}

impl Emitter<'_, '_> {
    /// Translates the run of string instructions at `pc`, if there is one
    /// worth a call of its own; the instruction after it.
    pub(super) fn string_run(&mut self, pc: usize) -> Option<usize> {
        if self.s.traced {
            return None;
        }
        let plan = self.s.plan;
        let points = self.s.points;
        let open = |at: usize| points.is_none_or(|p| !p.get(at).copied().unwrap_or(true));
        let cell_of = |sym: u16| plan.sym_cell.get(usize::from(sym)).copied();
        let run = run_at(self.s.ops, pc, self.block_end, cell_of, open)?;
        let index = u32::try_from(self.str_runs.len()).ok()?;
        self.str_runs.push(run.steps.into_boxed_slice());
        let words = [index, 0, 0].map(|w| self.b.ins().iconst(types::I32, i64::from(w)));
        let status = self.call_service(host::str_run, words)?;
        // Status k > 0: a fault at the run's (k-1)th instruction.
        let fault_pc = self.b.ins().iadd_imm(status, pc as i64 - 1);
        self.fault_if_at(status, fault_pc);
        for &at in &run.moved {
            self.op(at)?;
        }
        if run.int_result {
            let v = self.service_result(Ty::I);
            self.push(Ty::I, v);
        }
        Some(run.end)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::isa::Kind;

    /// A `Call` of library function `name` with the signature the compiler
    /// gives it.
    fn call(name: &str) -> Op {
        let func = linc_stdlib::signatures::index_of(name).unwrap() as u8;
        let s = 3u32;
        let (argc, types, ret) = match name {
            "LEN" => (1, s, Kind::Int),
            "CONCAT" => (2, s | s << 2, Kind::Bytes),
            "MID" => (3, s, Kind::Bytes),
            _ => (2, s, Kind::Bytes),
        };
        Op::Call { func, argc, ret: ret as u8, types }
    }

    fn run(ops: &[Op]) -> Option<Run> {
        run_at(ops, 0, ops.len(), |sym| Some(u32::from(sym) + 100), |_| true)
    }

    #[test]
    fn a_statement_is_one_run() {
        // T := CONCAT(LEFT(U, 4), 'ab'); N := N + LEN(T): T stays on the
        // stack for LEN, and N is read after the run's call.
        let ops = [
            Op::LoadS { sym: 1 },
            Op::PushI { v: 4 },
            call("LEFT"),
            Op::PushS { k: 0 },
            call("CONCAT"),
            Op::StoreS { sym: 2 },
            Op::LoadI { sym: 3 },
            Op::LoadS { sym: 2 },
            call("LEN"),
            Op::AddI {},
            Op::StoreI { sym: 3 },
        ];
        let r = run(&ops).unwrap();
        let ops_of: Vec<(StrOp, u32, Then, u32)> = r.steps.iter().map(|s| (s.op, s.at, s.then, s.then_at)).collect();
        assert_eq!(
            ops_of,
            [
                (StrOp::Push(Piece::Cut { cell: 101, how: InPlace::Left, ints: [4, 0] }), 0, Then::Nothing, 0),
                (StrOp::JoinWith(Piece::Const { k: 0 }), 3, Then::Store { cell: 102 }, 5),
                (StrOp::LoadLen { cell: 102 }, 7, Then::Nothing, 0),
            ]
        );
        assert_eq!((r.end, r.int_result, r.moved), (9, true, vec![6]));
        // Without the LoadI between, the value stored is read back where it
        // lies on the stack.
        let mut ops = ops.to_vec();
        ops.remove(6);
        let r = run(&ops).unwrap();
        assert_eq!(r.steps[1].then, Then::StoreLoad { cell: 102 });
        assert_eq!((r.steps[2].op, r.steps[2].at, r.end), (StrOp::Len, 7, 8));
    }

    #[test]
    fn runs_stop_where_a_step_cannot_go() {
        // LEFT(U, N): the length is not a constant.
        let ops = [Op::LoadS { sym: 1 }, Op::LoadI { sym: 5 }, call("LEFT"), Op::StoreS { sym: 2 }];
        assert_eq!(run(&ops), None, "one service call saves nothing");
        let ops = [Op::LoadS { sym: 1 }, Op::LoadS { sym: 2 }, Op::EqS {}, Op::JumpIfFalse { to: 0 }];
        let r = run(&ops).unwrap();
        assert_eq!((r.steps.len(), r.end, r.int_result), (3, 3, true));
        // A counted instruction ends a run (covered code).
        let ops = [Op::LoadS { sym: 1 }, Op::StoreS { sym: 2 }, Op::LoadS { sym: 2 }, Op::StoreS { sym: 3 }];
        let r = run_at(&ops, 0, 4, |s| Some(u32::from(s)), |pc| pc != 2).unwrap();
        assert_eq!(r.end, 2);
        // The block's end ends it, even inside a LEFT.
        let ops = [Op::PushS { k: 0 }, Op::LoadS { sym: 1 }, Op::PushI { v: 1 }, call("LEFT")];
        let r = run_at(&ops, 0, 3, |s| Some(u32::from(s)), |_| true).unwrap();
        assert_eq!(
            (r.steps.iter().map(|s| s.op).collect::<Vec<_>>(), r.end),
            (vec![StrOp::Push(Piece::Const { k: 0 }), StrOp::Push(Piece::Field { cell: 1 })], 2)
        );
        // MID takes two constants; a third PushI is not an argument.
        let ops = [Op::LoadS { sym: 1 }, Op::PushI { v: 2 }, Op::PushI { v: 3 }, call("MID"), Op::StoreS { sym: 1 }];
        let r = run(&ops).unwrap();
        assert_eq!(r.steps[0].op, StrOp::Push(Piece::Cut { cell: 101, how: InPlace::Mid, ints: [2, 3] }));
        // (It is pushed after the run: the stacks of numbers and strings are
        // apart.)
        let ops = [Op::LoadS { sym: 1 }, Op::PushI { v: 1 }, Op::PushI { v: 2 }, Op::PushI { v: 3 }, call("MID")];
        let r = run(&ops).unwrap();
        assert_eq!(
            (r.steps[1].op, r.steps[1].at, r.moved),
            (StrOp::Cut { how: InPlace::Mid, ints: [2, 3] }, 2, vec![1])
        );
        // A number pushed between a piece and its CONCAT (a hand-made
        // object) keeps them apart: the piece's offsets stay its own.
        let ops =
            [Op::LoadS { sym: 1 }, Op::LoadS { sym: 2 }, Op::LoadI { sym: 5 }, call("CONCAT"), Op::StoreS { sym: 3 }];
        let r = run(&ops).unwrap();
        let ops_of: Vec<(StrOp, u32)> = r.steps.iter().map(|s| (s.op, s.at)).collect();
        assert_eq!(ops_of[1..], [(StrOp::Push(Piece::Field { cell: 102 }), 1), (StrOp::Join, 3)]);
        // Numbers pushed after the last string step are not part of it.
        let ops = [Op::LoadS { sym: 1 }, Op::StoreS { sym: 2 }, Op::PushI { v: 1 }, Op::PushI { v: 2 }];
        assert_eq!(run(&ops).map(|r| (r.end, r.moved)), Some((2, vec![])));
    }
}

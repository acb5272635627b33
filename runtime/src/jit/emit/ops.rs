//! The translation of each instruction group, mirroring `vm.rs`.

use super::{frame_off, real_to_int, Emitter, Ty};
use crate::isa::{Kind, Op};
use crate::jit::plan::{BOOL, READONLY, REAL};
use crate::jit::Frame;
use cranelift_codegen::ir::condcodes::{FloatCC, IntCC};
use cranelift_codegen::ir::{types, AbiParam, InstBuilder, MemFlags, Signature, Value};
use std::mem::offset_of;

/// How an INT stored through the reference becomes a BOOL's 0 or 1.
#[derive(Clone, Copy, PartialEq, Eq)]
enum ToBool {
    /// No slot it can reach is a BOOL.
    Never,
    /// Every slot it can reach is.
    Always,
    /// Where the slot's kind (this value: nonzero for a BOOL) says so.
    WhereBool(Value),
}

impl Emitter<'_, '_> {
    /// Locals and retained slots: raw 32-bit words, out-of-range reads 0
    /// and out-of-range writes dropped, as in the interpreter.
    pub(super) fn local(&mut self, op: Op) -> Option<()> {
        match op {
            Op::LoadLoc { n } => {
                let v = match self.locals.get(usize::from(n)) {
                    Some(&var) => self.b.use_var(var),
                    None => self.b.ins().iconst(types::I32, 0),
                };
                self.push(Ty::I, v);
            }
            Op::StoreLoc { n } => {
                let v = self.pop(Ty::I)?;
                if let Some(&var) = self.locals.get(usize::from(n)) {
                    self.b.def_var(var, v);
                }
            }
            Op::LoadRet { n } => {
                let v = if usize::from(n) < self.s.retained {
                    let r = self.retained?;
                    self.b.ins().load(types::I32, MemFlags::trusted(), r, i32::from(n) * 4)
                } else {
                    self.b.ins().iconst(types::I32, 0)
                };
                self.push(Ty::I, v);
            }
            Op::StoreRet { n } => {
                let v = self.pop(Ty::I)?;
                if usize::from(n) < self.s.retained {
                    let r = self.retained?;
                    self.b.ins().store(MemFlags::trusted(), v, r, i32::from(n) * 4);
                }
            }
            _ => return None,
        }
        Some(())
    }

    fn slot_load(&mut self, slot: u32, ty: Ty) -> Option<Value> {
        if let Some(var) = self.slots.get(slot as usize).copied().flatten() {
            return Some(self.b.use_var(var));
        }
        let t = if ty == Ty::F { types::F32 } else { types::I32 };
        Some(self.b.ins().load(t, MemFlags::trusted(), self.mem?, (slot * 4) as i32))
    }

    fn slot_store(&mut self, slot: u32, v: Value) -> Option<()> {
        if let Some(var) = self.slots.get(slot as usize).copied().flatten() {
            self.b.def_var(var, v);
            return Some(());
        }
        self.b.ins().store(MemFlags::trusted(), v, self.mem?, (slot * 4) as i32);
        Some(())
    }

    /// Fields named directly; their kinds were checked by the plan.
    pub(super) fn direct(&mut self, pc: usize, op: Op) -> Option<()> {
        let slot = self.s.plan.slot(op.symbol()?)?;
        let kind = *self.s.plan.kinds.get(slot as usize)?;
        match op {
            Op::LoadI { .. } => {
                let v = self.slot_load(slot, Ty::I)?;
                self.push(Ty::I, v);
            }
            Op::LoadR { .. } => {
                let v = self.slot_load(slot, Ty::F)?;
                self.push_finite(v);
            }
            Op::StoreI { .. } => {
                let mut v = self.pop(Ty::I)?;
                if kind & 3 == BOOL {
                    let c = self.b.ins().icmp_imm(IntCC::NotEqual, v, 0);
                    v = self.bool32(c);
                }
                self.slot_store(slot, v)?;
                self.note_slot(pc, None, slot)?;
            }
            Op::StoreR { .. } => {
                let finite = self.top_is_finite();
                let v = self.pop(Ty::F)?;
                if !finite {
                    let bad = self.non_finite(v);
                    self.check(pc, bad);
                }
                self.slot_store(slot, v)?;
                self.note_slot(pc, None, slot)?;
            }
            _ => return None,
        }
        Some(())
    }

    pub(super) fn reference(&mut self, pc: usize, op: Op) -> Option<()> {
        let sym = op.symbol()?;
        let slot = self.s.plan.slot(sym)?;
        let (r, hi) = match op {
            Op::Ref { .. } => (self.b.ins().iconst(types::I32, i64::from(slot)), slot),
            _ => {
                let room = *self.s.plan.sym_room.get(usize::from(sym))?;
                let n = self.pop(Ty::I)?;
                // A loop variable's known range makes the check redundant.
                let known = self.offsets.get(pc).copied().flatten();
                if !known.is_some_and(|iv| iv.lo >= 0 && iv.hi <= i64::from(room)) {
                    let bad = self.b.ins().icmp_imm(IntCC::UnsignedGreaterThan, n, i64::from(room));
                    self.check(pc, bad);
                }
                (self.b.ins().iadd_imm(n, i64::from(slot)), slot.checked_add(room)?)
            }
        };
        self.b.def_var(self.ref_slot, r);
        self.ref_known = Some((slot, hi));
        Some(())
    }

    /// Loads and stores through the reference: the slot is checked against
    /// the plan and the slot's kind against the instruction (anything
    /// unexpected is left to the interpreter, which reports it). Where the
    /// reference was set in the same basic block, its slots are known at
    /// translation: the range check is already done, and a kind check that
    /// every one of them passes is left out (a shift register's offsets
    /// then cost one compare each).
    pub(super) fn through_ref(&mut self, pc: usize, op: Op) -> Option<()> {
        let slot = self.b.use_var(self.ref_slot);
        let n = self.s.plan.cells.len() as i64;
        let known = self.ref_known.and_then(|(lo, hi)| self.s.plan.kinds.get(lo as usize..=hi as usize));
        let finite = self.top_is_finite();
        let value = match op {
            Op::StoreRefI { .. } => Some(self.pop(Ty::I)?),
            Op::StoreRefR { .. } => Some(self.pop(Ty::F)?),
            _ => None,
        };
        if known.is_none() {
            let out = self.b.ins().icmp_imm(IntCC::UnsignedGreaterThanOrEqual, slot, n);
            self.check(pc, out);
        }
        let wide = self.b.ins().uextend(self.s.ptr, slot);
        let (mut bad, norm) = self.ref_kind(op, known, wide)?;
        if let (Op::StoreRefR { .. }, Some(v), false) = (op, value, finite) {
            let nf = self.non_finite(v);
            bad = Some(match bad {
                Some(b) => self.b.ins().bor(b, nf),
                None => nf,
            });
        }
        if let Some(bad) = bad {
            self.check(pc, bad);
        }
        let off = self.b.ins().ishl_imm(wide, 2);
        let addr = self.b.ins().iadd(self.mem?, off);
        match (op, value) {
            (Op::LoadRefI { .. }, _) => {
                let v = self.b.ins().load(types::I32, MemFlags::trusted(), addr, 0);
                self.push(Ty::I, v);
            }
            (Op::LoadRefR { .. }, _) => {
                // A REAL slot (the kind check above, or known): finite.
                let v = self.b.ins().load(types::F32, MemFlags::trusted(), addr, 0);
                self.push_finite(v);
            }
            (Op::StoreRefI { .. }, Some(mut v)) => {
                if norm != ToBool::Never {
                    let nz = self.b.ins().icmp_imm(IntCC::NotEqual, v, 0);
                    let nz = self.bool32(nz);
                    v = match norm {
                        ToBool::WhereBool(is_bool) => self.b.ins().select(is_bool, nz, v),
                        _ => nz,
                    };
                }
                self.b.ins().store(MemFlags::trusted(), v, addr, 0);
                self.note_slot(pc, Some(slot), 0)?;
            }
            (_, Some(v)) => {
                self.b.ins().store(MemFlags::trusted(), v, addr, 0);
                self.note_slot(pc, Some(slot), 0)?;
            }
            _ => return None,
        }
        Some(())
    }

    /// The kind check of a load or store through the reference at slot
    /// `wide` (`None` where every slot the reference can hold, `known`,
    /// passes it), and how a stored INT becomes a BOOL.
    fn ref_kind(&mut self, op: Op, known: Option<&[u8]>, wide: Value) -> Option<(Option<Value>, ToBool)> {
        let (mask, want) = match op {
            Op::LoadRefI { .. } => (REAL, 0),
            Op::StoreRefI { .. } => (REAL | READONLY, 0),
            Op::LoadRefR { .. } => (3, REAL),
            _ => (3 | READONLY, REAL),
        };
        let store_int = matches!(op, Op::StoreRefI { .. });
        let passing = known.filter(|ks| ks.iter().all(|&k| k & mask == want));
        let bools = passing.map(|ks| ks.iter().filter(|&&k| k & 3 == BOOL).count());
        match (passing, bools) {
            (Some(_), Some(b)) if !store_int || b == 0 => return Some((None, ToBool::Never)),
            (Some(ks), Some(b)) if b == ks.len() => return Some((None, ToBool::Always)),
            _ => {}
        }
        let kaddr = self.b.ins().iadd(self.kinds?, wide);
        let kind = self.b.ins().uload8(types::I32, MemFlags::trusted(), kaddr, 0);
        let bad = passing.is_none().then(|| {
            let masked = self.b.ins().band_imm(kind, i64::from(mask));
            self.b.ins().icmp_imm(IntCC::NotEqual, masked, i64::from(want))
        });
        let norm = match store_int {
            true => ToBool::WhereBool(self.b.ins().band_imm(kind, i64::from(BOOL))),
            false => ToBool::Never,
        };
        Some((bad, norm))
    }

    pub(super) fn flow(&mut self, pc: usize, op: Op) -> Option<()> {
        let target = |e: &Self, to: u32| e.blocks.get(to as usize).copied().flatten();
        match op {
            Op::Jump { to } => {
                let t = target(self, to)?;
                self.b.ins().jump(t, &[]);
            }
            Op::JumpIfFalse { to } | Op::JumpIfTrue { to } => {
                let c = self.pop(Ty::I)?;
                if self.counters.is_some() {
                    let cc = if matches!(op, Op::JumpIfTrue { .. }) { IntCC::NotEqual } else { IntCC::Equal };
                    let jumps = self.b.ins().icmp_imm(cc, c, 0);
                    let by = self.b.ins().uextend(types::I64, jumps);
                    self.count_taken(pc, by);
                }
                let t = target(self, to)?;
                let next = self.blocks.get(self.block_end).copied().flatten()?;
                if matches!(op, Op::JumpIfTrue { .. }) {
                    self.b.ins().brif(c, t, &[], next, &[]);
                } else {
                    self.b.ins().brif(c, next, &[], t, &[]);
                }
            }
            Op::Ret {} => {
                self.flush();
                let zero = self.b.ins().iconst(types::I32, 0);
                self.b.ins().return_(&[zero]);
            }
            Op::Return { kind } => {
                // The value's bits go to the frame; status 4 + kind says
                // "returned a value of this kind".
                let kind = Kind::from_bits(u32::from(kind));
                let v = self.pop(if kind == Kind::Real { Ty::F } else { Ty::I })?;
                let f = self.frame();
                self.b.ins().store(MemFlags::trusted(), v, f, frame_off(offset_of!(Frame, ret)));
                self.flush();
                let status = self.b.ins().iconst(types::I32, 4 + kind as i64);
                self.b.ins().return_(&[status]);
            }
            _ => return None,
        }
        Some(())
    }

    fn int2(&mut self) -> Option<(Value, Value)> {
        let b = self.pop(Ty::I)?;
        let a = self.pop(Ty::I)?;
        Some((a, b))
    }

    /// Whether `v` is a finite `f32const`.
    fn finite_const(&self, v: Value) -> bool {
        use cranelift_codegen::ir::{InstructionData, Opcode, ValueDef};
        let ValueDef::Result(inst, _) = self.b.func.dfg.value_def(v) else { return false };
        match self.b.func.dfg.insts[inst] {
            InstructionData::UnaryIeee32 { opcode: Opcode::F32const, imm } => f32::from_bits(imm.bits()).is_finite(),
            _ => false,
        }
    }

    fn real2(&mut self) -> Option<(Value, Value)> {
        let b = self.pop(Ty::F)?;
        let a = self.pop(Ty::F)?;
        Some((a, b))
    }

    /// A 16-bit logical result, sign-extended as `i32::from(x as i16)`.
    fn word(&mut self, v: Value) -> Value {
        let w = self.b.ins().ireduce(types::I16, v);
        self.b.ins().sextend(types::I32, w)
    }

    pub(super) fn arith(&mut self, pc: usize, op: Op) -> Option<()> {
        if let Some(cc) = int_cc(op) {
            let (a, b) = self.int2()?;
            let c = self.b.ins().icmp(cc, a, b);
            let v = self.bool32(c);
            self.push(Ty::I, v);
            return Some(());
        }
        if let Some(cc) = float_cc(op) {
            let (a, b) = self.real2()?;
            let c = self.b.ins().fcmp(cc, a, b);
            let v = self.bool32(c);
            self.push(Ty::I, v);
            return Some(());
        }
        match op {
            Op::AddI {} | Op::SubI {} | Op::MulI {} | Op::And {} | Op::Or {} | Op::Xor {} => {
                let (a, b) = self.int2()?;
                let v = match op {
                    Op::AddI {} => self.b.ins().iadd(a, b),
                    Op::SubI {} => self.b.ins().isub(a, b),
                    Op::MulI {} => self.b.ins().imul(a, b),
                    Op::And {} => self.b.ins().band(a, b),
                    Op::Or {} => self.b.ins().bor(a, b),
                    _ => self.b.ins().bxor(a, b),
                };
                let v = if matches!(op, Op::And {} | Op::Or {} | Op::Xor {}) { self.word(v) } else { v };
                self.push(Ty::I, v);
            }
            Op::DivI {} | Op::ModI {} => self.divide(pc, op)?,
            Op::AddR {} | Op::SubR {} | Op::MulR {} | Op::DivR {} => {
                let (mut a, mut b) = self.real2()?;
                // A finite constant first in a sum or product goes second,
                // where x64 takes it from memory instead of loading it into
                // a register at every turn of a loop (`1.5 * x`). IEEE
                // addition and multiplication commute, NaNs included when
                // only one operand can be one.
                if matches!(op, Op::AddR {} | Op::MulR {}) && self.finite_const(a) {
                    std::mem::swap(&mut a, &mut b);
                }
                let v = match op {
                    Op::AddR {} => self.b.ins().fadd(a, b),
                    Op::SubR {} => self.b.ins().fsub(a, b),
                    Op::MulR {} => self.b.ins().fmul(a, b),
                    _ => {
                        let zero = self.b.ins().f32const(0.0);
                        let bad = self.b.ins().fcmp(FloatCC::Equal, b, zero);
                        self.check(pc, bad);
                        self.b.ins().fdiv(a, b)
                    }
                };
                self.push(Ty::F, v);
            }
            _ => self.unary(pc, op)?,
        }
        Some(())
    }

    /// `wrapping_div` / `wrapping_rem`: a divisor of -1 is made 1 so that
    /// `i32::MIN / -1` wraps instead of trapping.
    fn divide(&mut self, pc: usize, op: Op) -> Option<()> {
        let (a, b) = self.int2()?;
        // A constant divisor (`N MOD 3`) needs neither check: Cranelift
        // folds the comparisons but kept a branch on the constant result.
        let v = match self.constant(b) {
            // Compared as 32 bits: Cranelift may keep an I32 constant's
            // immediate masked to its width.
            Some(k) if k as i32 != 0 && k as i32 != -1 => {
                if matches!(op, Op::DivI {}) {
                    self.b.ins().sdiv(a, b)
                } else {
                    self.b.ins().srem(a, b)
                }
            }
            _ => {
                let zero = self.b.ins().icmp_imm(IntCC::Equal, b, 0);
                self.check(pc, zero);
                let m1 = self.b.ins().icmp_imm(IntCC::Equal, b, -1);
                let one = self.b.ins().iconst(types::I32, 1);
                let safe = self.b.ins().select(m1, one, b);
                if matches!(op, Op::DivI {}) {
                    let q = self.b.ins().sdiv(a, safe);
                    let neg = self.b.ins().ineg(a);
                    self.b.ins().select(m1, neg, q)
                } else {
                    self.b.ins().srem(a, safe)
                }
            }
        };
        self.push(Ty::I, v);
        Some(())
    }

    /// The value of `v` when it is an integer constant of the code.
    fn constant(&self, v: Value) -> Option<i64> {
        use cranelift_codegen::ir::{InstructionData, Opcode};
        let inst = self.b.func.dfg.value_def(v).inst()?;
        match self.b.func.dfg.insts[inst] {
            InstructionData::UnaryImm { opcode: Opcode::Iconst, imm } => Some(imm.bits()),
            _ => None,
        }
    }

    fn unary(&mut self, pc: usize, op: Op) -> Option<()> {
        match op {
            Op::NegI {} | Op::Truth {} | Op::Not {} => {
                let a = self.pop(Ty::I)?;
                let v = match op {
                    Op::NegI {} => self.b.ins().ineg(a),
                    Op::Truth {} => {
                        let c = self.b.ins().icmp_imm(IntCC::NotEqual, a, 0);
                        self.bool32(c)
                    }
                    _ => {
                        let c = self.b.ins().icmp_imm(IntCC::Equal, a, 0);
                        self.bool32(c)
                    }
                };
                self.push(Ty::I, v);
            }
            Op::NegR {} => {
                let a = self.pop(Ty::F)?;
                let v = self.b.ins().fneg(a);
                self.push(Ty::F, v);
            }
            Op::IToR {} => {
                let a = self.pop(Ty::I)?;
                let v = self.b.ins().fcvt_from_sint(types::F32, a);
                self.push(Ty::F, v);
            }
            Op::RToI {} => {
                let a = self.pop(Ty::F)?;
                let bad = self.non_finite(a);
                self.check(pc, bad);
                let mut sig = Signature::new(self.s.call_conv);
                sig.params.push(AbiParam::new(types::F32));
                sig.returns.push(AbiParam::new(types::I32));
                let sig = self.b.import_signature(sig);
                let f = self.b.ins().iconst(self.s.ptr, real_to_int as *const () as usize as i64);
                let call = self.b.ins().call_indirect(sig, f, &[a]);
                let v = *self.b.inst_results(call).first()?;
                self.push(Ty::I, v);
            }
            _ => return None,
        }
        Some(())
    }
}

fn int_cc(op: Op) -> Option<IntCC> {
    Some(match op {
        Op::EqI {} => IntCC::Equal,
        Op::NeI {} => IntCC::NotEqual,
        Op::LtI {} => IntCC::SignedLessThan,
        Op::GtI {} => IntCC::SignedGreaterThan,
        Op::LeI {} => IntCC::SignedLessThanOrEqual,
        Op::GeI {} => IntCC::SignedGreaterThanOrEqual,
        _ => return None,
    })
}

fn float_cc(op: Op) -> Option<FloatCC> {
    Some(match op {
        Op::EqR {} => FloatCC::Equal,
        Op::NeR {} => FloatCC::NotEqual,
        Op::LtR {} => FloatCC::LessThan,
        Op::GtR {} => FloatCC::GreaterThan,
        Op::LeR {} => FloatCC::LessThanOrEqual,
        _ => FloatCC::GreaterThanOrEqual,
    })
    .filter(|_| matches!(op, Op::EqR {} | Op::NeR {} | Op::LtR {} | Op::GtR {} | Op::LeR {} | Op::GeR {}))
}

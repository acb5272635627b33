//! Instructions the compiled code hands to the runtime's services
//! ([`crate::jit::host`]): strings and library calls. A service that
//! faults leaves through [`Exit::Fault`]: the cells written so far go back
//! to the store, as the interpreter's writes stay when it faults.

use super::{frame_off, Emitter, Exit, Ty};
use crate::isa::{Kind, Op};
use crate::jit::host::{self, Service};
use crate::jit::Frame;
use cranelift_codegen::ir::{types, AbiParam, InstBuilder, MemFlags, Signature, Value};
use linc_stdlib::call::InPlace;
use std::mem::offset_of;

impl Emitter<'_, '_> {
    /// Calls service `f` with three immediate words; a nonzero status
    /// leaves through [`Emitter::fault_exit`] at `pc`.
    fn serve(&mut self, pc: usize, f: Service, words: [u32; 3]) -> Option<()> {
        let words = words.map(|w| self.b.ins().iconst(types::I32, i64::from(w as i32)));
        self.serve_values(pc, f, words)
    }

    /// [`Emitter::serve`] with words computed at run time.
    fn serve_values(&mut self, pc: usize, f: Service, words: [Value; 3]) -> Option<()> {
        let status = self.call_service(f, words)?;
        self.exit_if(status, Exit::Fault, pc);
        Some(())
    }

    /// Calls service `f`; its status.
    pub(super) fn call_service(&mut self, f: Service, words: [Value; 3]) -> Option<Value> {
        let mut sig = Signature::new(self.s.call_conv);
        sig.params.push(AbiParam::new(self.s.ptr));
        sig.params.extend([AbiParam::new(types::I32); 3]);
        sig.returns.push(AbiParam::new(types::I32));
        let sig = self.b.import_signature(sig);
        let callee = self.b.ins().iconst(self.s.ptr, f as usize as i64);
        let mut args = vec![self.frame()];
        args.extend(words);
        let call = self.b.ins().call_indirect(sig, callee, &args);
        self.b.inst_results(call).first().copied()
    }

    /// In traced code, reports the write to slot `dynamic` (a value) or
    /// `slot` just made by instruction `pc`.
    pub(super) fn note_slot(&mut self, pc: usize, dynamic: Option<Value>, slot: u32) -> Option<()> {
        if !self.s.traced {
            return Some(());
        }
        let what = match dynamic {
            Some(v) => v,
            None => self.b.ins().iconst(types::I32, i64::from(slot as i32)),
        };
        let (one, zero) = (self.b.ins().iconst(types::I32, 1), self.b.ins().iconst(types::I32, 0));
        self.serve_values(pc, host::note, [what, one, zero])
    }

    /// In traced code, reports the write to store cell `cell`.
    fn note_cell(&mut self, pc: usize, cell: u32) -> Option<()> {
        if self.s.traced {
            self.serve(pc, host::note, [cell, 0, 0])?;
        }
        Some(())
    }

    /// The numeric result a service left in the frame.
    pub(super) fn service_result(&mut self, ty: Ty) -> Value {
        let f = self.frame();
        let t = if ty == Ty::F { types::F32 } else { types::I32 };
        self.b.ins().load(t, MemFlags::trusted(), f, frame_off(offset_of!(Frame, ret)))
    }

    pub(super) fn string(&mut self, pc: usize, op: Op) -> Option<()> {
        match op {
            Op::PushS { k } => self.serve(pc, host::push_const, [k, 0, 0]),
            Op::LoadS { sym } | Op::StoreS { sym } | Op::AppendS { sym } => {
                let cell = *self.s.plan.sym_cell.get(usize::from(sym))?;
                let f: Service = match op {
                    Op::LoadS { .. } => return self.serve(pc, host::load_s, [cell, 0, 0]),
                    Op::StoreS { .. } => host::store_s,
                    _ => host::append_s,
                };
                self.serve(pc, f, [cell, 0, 0])?;
                self.note_cell(pc, cell)
            }
            Op::Decode {} => self.serve(pc, host::decode, [0, 0, 0]),
            _ => {
                self.serve(pc, host::compare, [host::compare_code(op)?, 0, 0])?;
                let v = self.service_result(Ty::I);
                self.push(Ty::I, v);
                Some(())
            }
        }
    }

    /// `Call`: the numeric arguments go to the frame's stack buffer in
    /// order, the string arguments are already on the VM's string stack.
    pub(super) fn call(&mut self, pc: usize, op: Op) -> Option<()> {
        let Op::Call { func, argc, ret, types: tys } = op else { return None };
        if let Some((how, ints)) = crate::vm::Vm::in_place_of(func, argc, ret, tys) {
            return self.call_in_place(pc, (func, how), ints);
        }
        let n = usize::from(argc);
        let numeric: Vec<Kind> = (0..n).map(|i| Kind::arg(tys, i)).filter(|k| *k != Kind::Bytes).collect();
        let stack = self.load_ptr(offset_of!(Frame, stack));
        for (j, k) in numeric.iter().enumerate().rev() {
            let v = self.pop(if *k == Kind::Real { Ty::F } else { Ty::I })?;
            self.b.ins().store(MemFlags::trusted(), v, stack, (j * 4) as i32);
        }
        let packed = u32::from(func) | u32::from(argc) << 8 | u32::from(ret) << 16;
        self.serve(pc, host::call, [packed, tys, numeric.len() as u32])?;
        match Kind::from_bits(u32::from(ret)) {
            Kind::Bytes => {}
            Kind::Real => {
                let v = self.service_result(Ty::F);
                self.push(Ty::F, v);
            }
            _ => {
                let v = self.service_result(Ty::I);
                self.push(Ty::I, v);
            }
        }
        Some(())
    }

    /// A string function run in place: its INT arguments go as the
    /// service's words, with no stack buffer and no decoding at run time.
    fn call_in_place(&mut self, pc: usize, (func, how): (u8, InPlace), ints: usize) -> Option<()> {
        let zero = self.b.ins().iconst(types::I32, 0);
        let mut words = [zero; 2];
        for i in (0..ints.min(2)).rev() {
            words[i] = self.pop(Ty::I)?;
        }
        let func = self.b.ins().iconst(types::I32, i64::from(func));
        self.serve_values(pc, host::in_place, [func, words[0], words[1]])?;
        if how == InPlace::Len {
            let v = self.service_result(Ty::I);
            self.push(Ty::I, v);
        }
        Some(())
    }
}

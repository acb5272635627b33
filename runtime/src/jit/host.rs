//! The runtime's services that compiled code calls: strings and library
//! functions, run by the interpreter's own methods on the VM.
//!
//! Each service has one signature, `(frame, a, b, c) -> status`: status 0
//! is success (a numeric result is left in `Frame::ret`), 1 a fault, which
//! the service leaves in `Vm::jit_fault` and the compiled code reports at
//! its instruction. Because the interpreter's methods do the work, values,
//! string budgets and faults are the interpreter's by construction.

use super::Frame;
use crate::errors::Fault;
use crate::isa::Op;
use crate::store::Store;
use crate::vm::Vm;
use crate::wire::Bytes;
use linc_format::Code;
use linc_stdlib::call::InPlace;
use std::panic::{catch_unwind, AssertUnwindSafe};

/// The shape of every service.
pub(crate) type Service = extern "C" fn(*mut Frame, u32, u32, u32) -> u32;

/// What the services reach, read from the frame.
struct Host<'a> {
    vm: &'a mut Vm,
    store: &'a mut Store,
    consts: &'a [Bytes],
    stack: *const u32,
}

/// Runs `f` on the frame's host; a fault or a panic becomes status 1.
fn serve(frame: *mut Frame, f: impl FnOnce(&mut Host<'_>) -> Result<u32, Fault>) -> u32 {
    serve_at(frame, |h| {
        f(h).map_err(|fault| {
            h.vm.jit_fault = Some(fault);
            0
        })
    })
}

/// Runs `f` on the frame's host: status 0 with its result in the frame,
/// or 1 + the offset from the calling instruction of the one that faulted,
/// `f` having left the fault in `Vm::jit_fault`; a panic is R0099 at
/// offset 0.
fn serve_at(frame: *mut Frame, f: impl FnOnce(&mut Host<'_>) -> Result<u32, u32>) -> u32 {
    // SAFETY: compiled code passes the frame `Compiled::run` built, whose
    // pointers are to the running VM, store and constants; nothing else
    // uses them while the compiled code runs.
    let frame = unsafe { &mut *frame };
    let mut host = unsafe {
        Host {
            vm: &mut *frame.vm,
            store: &mut *frame.store,
            consts: std::slice::from_raw_parts(frame.consts, frame.nconsts),
            stack: frame.stack,
        }
    };
    match catch_unwind(AssertUnwindSafe(|| f(&mut host))) {
        Ok(Ok(v)) => {
            frame.ret = v;
            0
        }
        Ok(Err(at)) => at.saturating_add(1),
        Err(_) => {
            host.vm.jit_fault = Some(Fault::new(Code::R0099, "internal error in a runtime service"));
            1
        }
    }
}

/// `PushS k`.
pub(crate) extern "C" fn push_const(frame: *mut Frame, k: u32, _: u32, _: u32) -> u32 {
    serve(frame, |h| h.vm.push_const(h.consts, k).map(|()| 0))
}

/// `LoadS` of cell `c`.
pub(crate) extern "C" fn load_s(frame: *mut Frame, c: u32, _: u32, _: u32) -> u32 {
    serve(frame, |h| h.vm.load_s(h.store, c).map(|()| 0))
}

/// `StoreS` to cell `c`.
pub(crate) extern "C" fn store_s(frame: *mut Frame, c: u32, _: u32, _: u32) -> u32 {
    serve(frame, |h| h.vm.store_s(h.store, c).map(|()| 0))
}

/// `AppendS` to cell `c`.
pub(crate) extern "C" fn append_s(frame: *mut Frame, c: u32, _: u32, _: u32) -> u32 {
    serve(frame, |h| h.vm.append_s(h.store, c).map(|()| 0))
}

/// `Decode`.
pub(crate) extern "C" fn decode(frame: *mut Frame, _: u32, _: u32, _: u32) -> u32 {
    serve(frame, |h| h.vm.decode().map(|()| 0))
}

/// The string comparisons, numbered as [`compare_code`] numbers them.
pub(crate) extern "C" fn compare(frame: *mut Frame, code: u32, _: u32, _: u32) -> u32 {
    let op = compare_op(code);
    serve(frame, |h| Ok(h.vm.compare_s(op) as u32))
}

/// The string comparison [`compare_code`] numbers `code`.
fn compare_op(code: u32) -> Op {
    match code {
        0 => Op::EqS {},
        1 => Op::NeS {},
        2 => Op::LtS {},
        3 => Op::GtS {},
        4 => Op::LeS {},
        _ => Op::GeS {},
    }
}

/// The number [`compare`] takes for a string comparison.
pub(crate) fn compare_code(op: Op) -> Option<u32> {
    Some(match op {
        Op::EqS {} => 0,
        Op::NeS {} => 1,
        Op::LtS {} => 2,
        Op::GtS {} => 3,
        Op::LeS {} => 4,
        Op::GeS {} => 5,
        _ => return None,
    })
}

/// `Call`: `packed` is func | argc << 8 | ret << 16; the compiled code
/// has written the `nnum` numeric arguments, in order, at the start of the
/// frame's stack buffer.
pub(crate) extern "C" fn call(frame: *mut Frame, packed: u32, types: u32, nnum: u32) -> u32 {
    serve(frame, |h| {
        let (func, argc, ret) = (packed as u8, (packed >> 8) as u8, (packed >> 16) as u8);
        let (stack, mut left) = (h.stack, nnum as usize);
        let pop_num = |_: &mut Vm| {
            // SAFETY: the compiled code wrote `nnum` words there, within
            // the buffer sized for its deepest stack.
            left = left.saturating_sub(1);
            unsafe { *stack.add(left) }
        };
        Ok(h.vm.call(func, argc, ret, types, pop_num)?.unwrap_or(0))
    })
}

/// `Call` of a string function run in place ([`Vm::in_place_of`]):
/// `func` is its library function number, `a` and `b` its INT arguments;
/// LEN's result is left in the frame.
pub(crate) extern "C" fn in_place(frame: *mut Frame, func: u32, a: u32, b: u32) -> u32 {
    serve(frame, |h| {
        let how = InPlace::of(func as usize).ok_or_else(|| Fault::new(Code::R0099, "no such string function"))?;
        Ok(h.vm.call_in_place(how, [a as i32, b as i32])?.unwrap_or(0))
    })
}

/// A run of string instructions ([`crate::vm::str_run`]): the `run`th of
/// the running code. Status 0, or 1 + the offset in the run of the
/// instruction that faulted.
pub(crate) extern "C" fn str_run(frame: *mut Frame, run: u32, _: u32, _: u32) -> u32 {
    // SAFETY: as in `serve`; `code` is the running `Compiled`.
    let code = unsafe { &*(*frame).code };
    serve_at(frame, |h| match code.str_runs.get(run as usize) {
        Some(steps) => h.vm.run_strs(h.store, h.consts, steps),
        None => {
            h.vm.jit_fault = Some(Fault::new(Code::R0099, "no such string run"));
            Err(0)
        }
    })
}

/// After a write in traced code: the cells go back to the store and the
/// run's tracer sees `what` (a slot when `is_slot` is 1, else a store cell),
/// as the interpreter reports each write.
pub(crate) extern "C" fn note(frame: *mut Frame, what: u32, is_slot: u32, _: u32) -> u32 {
    // SAFETY: as in `serve`; `code` is the running `Compiled`, `mem` holds
    // `mem_len` slots and `trace` points at the run's `Tracer`.
    let frame = unsafe { &mut *frame };
    let (store, code) = unsafe { (&mut *frame.store, &*frame.code) };
    let mem = unsafe { std::slice::from_raw_parts(frame.mem, frame.mem_len) };
    let trace = unsafe { &mut *frame.trace.cast::<crate::vm::Tracer<'_>>() };
    let noted = catch_unwind(AssertUnwindSafe(|| {
        code.copy_out(store, mem);
        let cell = if is_slot == 1 { code.cell_of_slot(what) } else { Some(what) };
        if let (Some(t), Some(c)) = (trace.as_mut(), cell) {
            t(store, c);
        }
    }));
    if noted.is_err() {
        // SAFETY: as above; the tracer's borrow of the store has ended.
        let vm = unsafe { &mut *frame.vm };
        vm.jit_fault = Some(Fault::new(Code::R0099, "internal error while tracing a write"));
        return 1;
    }
    0
}

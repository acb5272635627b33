//! The load-time verifier and linker.
//!
//! Verification is separate from decoding and from execution: it proves,
//! for every instruction of an action, that jumps land on instructions,
//! constants, symbols, locals and bits are in range and of the right kind,
//! calls name real functions with acceptable arguments, and both stacks are
//! balanced on every path (never popped below empty, equal where paths
//! meet, empty at `Ret` and `Yield`). The VM relies on this and on typed
//! cells, so no object file, however damaged, can make it read or write out
//! of bounds.

use crate::errors::LoadError;
use crate::isa::{Kind, Op, MAX_CALL_ARGS};
use crate::object::{ActionCode, Class, ObjectFile, Sub, Symbol};
use crate::store::{class_of, Cell, Store};
use linc_stdlib::SIGNATURES;

/// Stack sizes an action needs, found by the verifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Limits {
    pub max_num: usize,
    pub max_str: usize,
}

fn invalid(code: &'static str, a: &ActionCode, op: usize, what: impl Into<String>) -> LoadError {
    LoadError::Invalid { code, action: a.name.clone(), op, what: what.into() }
}

/// Checks one instruction's operands against the object's tables.
fn check_operands(obj: &ObjectFile, a: &ActionCode, pc: usize, op: &Op) -> Result<(), LoadError> {
    let n = a.ops.len();
    if let Some(t) = op.target() {
        if t as usize >= n {
            return Err(invalid("E0705", a, pc, format!("jump to instruction {t}, but the action has {n}")));
        }
    }
    match *op {
        Op::PushS { k } if k as usize >= obj.strings.len() => {
            return Err(invalid("E0706", a, pc, format!("string constant {k} does not exist")));
        }
        Op::Return { kind } if kind > 3 => {
            return Err(invalid("E0710", a, pc, format!("result kind {kind} does not exist")));
        }
        Op::LoadLoc { n } | Op::StoreLoc { n } if n >= a.locals => {
            return Err(invalid("E0711", a, pc, format!("local {n} does not exist (the action has {})", a.locals)));
        }
        Op::Call { func, argc, ret, types } => {
            let sig = SIGNATURES
                .get(usize::from(func))
                .ok_or_else(|| invalid("E0710", a, pc, format!("function {func} does not exist")))?;
            let argc = usize::from(argc);
            if argc > MAX_CALL_ARGS || !sig.arity_ok(argc) || ret > 3 {
                return Err(invalid("E0710", a, pc, format!("{} can't be called with {argc} arguments", sig.name)));
            }
            for i in 0..argc {
                let k = Kind::arg(types, i);
                let ok = match sig.param(i) {
                    Some(linc_stdlib::Param::Bytes) => k == Kind::Bytes,
                    Some(_) => k != Kind::Bytes,
                    None => false,
                };
                if !ok {
                    return Err(invalid(
                        "E0710",
                        a,
                        pc,
                        format!("argument {} of {} has the wrong kind", i + 1, sig.name),
                    ));
                }
            }
        }
        _ => {}
    }
    if let Some(s) = op.symbol() {
        let sym = obj
            .symbols
            .get(usize::from(s))
            .ok_or_else(|| invalid("E0707", a, pc, format!("symbol {s} does not exist")))?;
        if !symbol_fits(op, sym) {
            return Err(invalid("E0707", a, pc, format!("{} can't use `{}` ({:?})", op.name(), sym.text(), sym.class)));
        }
    }
    Ok(())
}

/// Whether an instruction may use a symbol of this kind.
fn symbol_fits(op: &Op, sym: &Symbol) -> bool {
    let field = sym.sub == Sub::Field;
    let c = sym.class;
    match *op {
        Op::LoadI { .. } | Op::StoreI { .. } | Op::LoadRefI { .. } | Op::StoreRefI { .. } => field && c.is_int(),
        Op::LoadR { .. } | Op::StoreR { .. } | Op::LoadRefR { .. } | Op::StoreRefR { .. } => field && c == Class::Real,
        Op::LoadS { .. } | Op::StoreS { .. } | Op::LoadRefS { .. } | Op::StoreRefS { .. } => field && c.is_string(),
        Op::LoadBit { bit, .. } | Op::StoreBit { bit, .. } => field && c.bits().is_some_and(|w| bit < w),
        Op::LoadRefBit { .. } | Op::StoreRefBit { .. } => field && c.bits().is_some(),
        Op::LoadAlarm { .. } => matches!(sym.sub, Sub::Alarm(_)) && c == Class::Alarms,
        Op::LoadSuppress { .. } | Op::StoreSuppress { .. } => matches!(sym.sub, Sub::Suppress(_)) && c == Class::Alarms,
        Op::Ref { .. } | Op::RefOff { .. } => field && c != Class::Alarms,
        _ => true,
    }
}

/// Verifies one action; returns the stack sizes it needs.
pub fn verify_action(obj: &ObjectFile, a: &ActionCode) -> Result<Limits, LoadError> {
    let n = a.ops.len();
    if n == 0 {
        return Err(invalid("E0708", a, 0, "empty code (an action ends with Ret)"));
    }
    for (pc, op) in a.ops.iter().enumerate() {
        check_operands(obj, a, pc, op)?;
    }
    // Abstract interpretation of the two stack depths.
    let mut depth: Vec<Option<(u32, u32)>> = vec![None; n];
    let mut work = vec![0usize];
    depth[0] = Some((0, 0));
    let mut limits = Limits::default();
    while let Some(pc) = work.pop() {
        let Some((num, strs)) = depth[pc] else {
            continue;
        };
        let op = &a.ops[pc];
        let e = op.effect();
        if num < e.num_pop || strs < e.str_pop {
            return Err(invalid("E0708", a, pc, format!("{} pops an empty stack", op.name())));
        }
        let after = (num - e.num_pop + e.num_push, strs - e.str_pop + e.str_push);
        limits.max_num = limits.max_num.max(after.0 as usize);
        limits.max_str = limits.max_str.max(after.1 as usize);
        if matches!(op, Op::Ret {} | Op::Yield {} | Op::Return { .. }) && after != (0, 0) {
            return Err(invalid("E0708", a, pc, format!("{} with values left on the stack", op.name())));
        }
        let mut next = Vec::with_capacity(2);
        match op {
            Op::Ret {} | Op::Return { .. } => {}
            Op::Jump { to } => next.push(*to as usize),
            Op::JumpIfFalse { to } | Op::JumpIfTrue { to } => {
                next.push(*to as usize);
                next.push(pc + 1);
            }
            _ => next.push(pc + 1),
        }
        for t in next {
            if t >= n {
                return Err(invalid("E0708", a, pc, "execution runs past the last instruction"));
            }
            match depth[t] {
                None => {
                    depth[t] = Some(after);
                    work.push(t);
                }
                Some(d) if d != after => {
                    return Err(invalid("E0708", a, t, format!("stack depths {d:?} and {after:?} meet here")));
                }
                Some(_) => {}
            }
        }
    }
    Ok(limits)
}

/// A symbol bound to the live database.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Target {
    pub cell: u32,
    /// Last cell of the run `cell` starts (for offsets).
    pub run_end: u32,
    /// Alarm index for alarm symbols; `u16::MAX` for the block-wide suppression.
    pub alarm: u16,
}

/// Binds the symbols an action uses to cells of `store`. `own` is the block
/// that runs the action, for `ACTION name : TYPE` field references.
pub fn link_action(
    obj: &ObjectFile,
    a: &ActionCode,
    store: &Store,
    own: Option<usize>,
) -> Result<Vec<Target>, LoadError> {
    let used: std::collections::BTreeSet<u16> = a.ops.iter().filter_map(Op::symbol).collect();
    let mut targets = vec![Target { cell: u32::MAX, run_end: 0, alarm: 0 }; obj.symbols.len()];
    for s in used {
        let sym = &obj.symbols[usize::from(s)];
        let fail = |why: String| LoadError::Link { symbol: sym.text(), why };
        let block = if sym.block.is_empty() {
            own.ok_or_else(|| {
                fail(format!("action `{}` runs on a {} block; name one with --block", a.name, a.block_type))
            })?
        } else {
            store.db.block(&sym.block).ok_or_else(|| fail("the database has no such block".into()))?
        };
        let t = store.db.block_template(block);
        let fi = t.field(&sym.field).ok_or_else(|| fail(format!("block type {} has no such field", t.name)))?;
        let class = class_of(&t.fields[fi].ty);
        if class != sym.class {
            return Err(fail(format!(
                "the field is {class:?} in this database, but the action was compiled for {:?}",
                sym.class
            )));
        }
        let cell = store.first[block] + fi as u32;
        let alarm = match (&sym.sub, store.cells.get(cell as usize)) {
            (Sub::Field, _) | (Sub::Suppress(None), _) => u16::MAX,
            (Sub::Alarm(name) | Sub::Suppress(Some(name)), Some(Cell::Alarms(al))) => al
                .names
                .iter()
                .position(|n| n.eq_ignore_ascii_case(name))
                .map(|i| i as u16)
                .ok_or_else(|| fail("the block has no such alarm".into()))?,
            _ => return Err(fail("not an alarm field".into())),
        };
        targets[usize::from(s)] = Target { cell, run_end: store.run_end[cell as usize], alarm };
    }
    Ok(targets)
}

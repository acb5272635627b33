//! Reading and writing cells of the store for the VM, and locating a
//! fault in the source: the parts of a run that are not dispatch.

use super::Running;
use crate::errors::{Fault, RuntimeError};
use crate::link::Target;
use crate::store::{bits_value, Cell, Store};
use linc_format::Code;

pub(super) fn corrupt() -> Fault {
    Fault::new(Code::R0099, "the object does not match the database (field of another type)")
}

pub(super) fn target(l: &Running, sym: u16) -> Target {
    l.prog.targets.get(usize::from(sym)).copied().unwrap_or(Target { cell: u32::MAX, run_end: 0, alarm: 0 })
}

pub(super) fn cell(l: &Running, sym: u16) -> u32 {
    target(l, sym).cell
}

pub(super) fn note(trace: &mut super::Tracer, store: &Store, cell: u32) {
    if let Some(t) = trace.as_mut() {
        t(store, cell);
    }
}

/// A cell reached through an offset may be a read-only field of the same
/// run (PID's SP sits between PV and SL); direct writes are refused at link.
pub(super) fn writable(store: &Store, c: u32) -> Result<u32, Fault> {
    if store.is_readonly(c) {
        return Err(Fault::new(
            Code::R0008,
            format!("{} is read-only; an offset led the write to it", store.describe(c)),
        ));
    }
    Ok(c)
}

pub(super) fn load_int(store: &Store, c: u32) -> Result<i32, Fault> {
    match store.cells.get(c as usize) {
        Some(Cell::Int(i)) => Ok(*i),
        Some(Cell::Bool(b)) => Ok(i32::from(*b)),
        Some(Cell::Bits { v, width }) => Ok(bits_value(*v, *width)),
        _ => Err(corrupt()),
    }
}

pub(super) fn load_bit(store: &Store, c: u32, bit: u8) -> Result<i32, Fault> {
    match store.cells.get(c as usize) {
        Some(Cell::Bits { v, width }) if bit < *width => Ok(i32::from((v >> bit) & 1)),
        _ => Err(corrupt()),
    }
}

/// An INT into an INT, BOOL (non-zero is TRUE) or bitfield (its low 8 or 16 bits).
pub(super) fn store_int(store: &mut Store, c: u32, v: i32) -> Result<(), Fault> {
    if store.refuse_forced(c) {
        return Ok(());
    }
    match store.cells.get_mut(c as usize) {
        Some(Cell::Int(i)) => *i = v,
        Some(Cell::Bool(b)) => *b = v != 0,
        Some(Cell::Bits { v: bits, width }) => *bits = if *width == 8 { (v as u16) & 0xFF } else { v as u16 },
        _ => return Err(corrupt()),
    }
    Ok(())
}

pub(super) fn store_bit(store: &mut Store, c: u32, bit: u8, v: i32) -> Result<(), Fault> {
    if store.refuse_forced(c) {
        return Ok(());
    }
    match store.cells.get_mut(c as usize) {
        Some(Cell::Bits { v: bits, width }) if bit < *width => {
            if v != 0 {
                *bits |= 1 << bit;
            } else {
                *bits &= !(1 << bit);
            }
            Ok(())
        }
        _ => Err(corrupt()),
    }
}

/// The value of string cell `c` as `LoadS` reads it: an enumerated field
/// reads as its value's name (`None`: not a string cell, which the
/// verifier rules out).
#[inline(always)]
pub(super) fn cell_text(store: &Store, c: u32) -> Option<&[u8]> {
    match store.cells.get(c as usize)? {
        Cell::Text(t) | Cell::Bseq(t) | Cell::Wstr(t) => Some(&t[..]),
        Cell::Enum { idx } => Some(store.enum_names(c).get(usize::from(*idx)).map_or(&[][..], |n| n.as_bytes())),
        _ => None,
    }
}

/// Stores `s` into string cell `c`, copying it into the cell's own buffer
/// (which keeps its capacity from store to store).
#[inline(always)]
pub(super) fn store_str(store: &mut Store, c: u32, s: &[u8]) -> Result<(), Fault> {
    if store.refuse_forced(c) {
        return Ok(());
    }
    match store.cells.get_mut(c as usize) {
        Some(Cell::Text(t) | Cell::Bseq(t) | Cell::Wstr(t)) => {
            t.clear();
            super::str_stack::append(t, s);
            Ok(())
        }
        _ => store_enum(store, c, s),
    }
}

/// [`store_str`] to an enumerated field: the value whose name `s` is
/// (ignoring case).
fn store_enum(store: &mut Store, c: u32, s: &[u8]) -> Result<(), Fault> {
    if let Some(Cell::Enum { .. }) = store.cells.get(c as usize) {
        let names = store.enum_names(c);
        let Some(idx) = names.iter().position(|n| n.as_bytes().eq_ignore_ascii_case(s)) else {
            let msg = format!(
                "'{}' is not a value of {} ({})",
                String::from_utf8_lossy(s),
                store.describe(c),
                names.join(", ")
            );
            return Err(Fault::new(Code::R0004, msg));
        };
        if let Some(Cell::Enum { idx: i }) = store.cells.get_mut(c as usize) {
            *i = idx as u16;
        }
        return Ok(());
    }
    Err(corrupt())
}

/// Adds the action name and source position to a fault: the statement
/// containing the failing instruction, or for the watchdog the innermost
/// loop around it.
pub(super) fn locate(l: &Running, pc: usize, f: Fault) -> RuntimeError {
    let a = l.code;
    // The line table is sorted by instruction (the verifier proves it).
    let stmt = a.lines[..a.lines.partition_point(|e| e.op as usize <= pc)].last();
    let mut at = stmt.map(|e| (e.line, e.col)).unwrap_or((0, 0));
    let mut message = f.message;
    if f.code == Code::R0006 {
        let inner =
            a.loops.iter().filter(|lp| (lp.start as usize..lp.end as usize).contains(&pc)).max_by_key(|lp| lp.start);
        if let Some(lp) = inner {
            at = (lp.line, lp.col);
            message = format!("{message}; stopped in the loop at line {}", lp.line);
        }
    }
    let mut code = f.code;
    let absent = l.ops.get(pc).and_then(|op| op.symbol()).filter(|&s| target(l, s).is_absent());
    if let Some(s) = absent {
        let sym = l.prog.symbols.get(usize::from(s)).and_then(|&o| l.linked.object().symbols.get(usize::from(o)));
        code = Code::R0010;
        message = format!(
            "invalid point reference: the database has no {}",
            sym.map_or_else(|| "such point".to_string(), |s| format!("`{}`", s.text()))
        );
    }
    let u = l.unit;
    RuntimeError { code, message, action: u.name.clone(), file: u.file.clone(), line: at.0, col: at.1 }
}

//! Runtime errors in a running strategy, as a PLC kernel handles them
//! (`001_…` "Error Handling"): the first error is kept in an error status
//! until it is cleared, later ones are ignored; the failing program stops
//! and its block shows it; the other programs go on; an optional error
//! program runs when an error is entered and may clear it; an error while
//! it runs is a double error, which stops every program.

use super::trace::{seconds, Trace};
use super::Strategy;
use crate::errors::RuntimeError;
use crate::store::Cell;
use linc_format::Code;
use std::fmt;

/// Template name of the block that shows the error status (and names the
/// error program in its `ErrProg` field).
pub const SYSTEM: &str = "SYSTEM";

/// The runtime error codes an error status can hold: what a program's fault
/// enters and what the console's `ERRRAISE` accepts (a saved status with any
/// other code reads as R0099).
pub const RUNTIME_CODES: &[Code] = &[
    Code::R0001,
    Code::R0002,
    Code::R0003,
    Code::R0004,
    Code::R0005,
    Code::R0006,
    Code::R0007,
    Code::R0008,
    Code::R0010,
    Code::R0011,
    Code::R0099,
];

/// Why a strategy could not be built, located at a block of the database.
#[derive(Clone, Debug, PartialEq)]
pub struct StrategyError {
    pub code: Code,
    pub block: String,
    pub message: String,
}

impl StrategyError {
    pub fn new(code: Code, block: String, message: impl Into<String>) -> StrategyError {
        StrategyError { code, block, message: message.into() }
    }
}

impl fmt::Display for StrategyError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "block `{}`: {}", self.block, self.message)
    }
}

/// The error status word: the first runtime error since the last clear.
#[derive(Clone, Debug, PartialEq)]
pub struct ErrorStatus {
    pub error: RuntimeError,
    /// The block whose program failed.
    pub block: String,
    /// Simulated time of the error, µs since the start.
    pub at_us: u64,
    /// The error program failed too; every program was stopped.
    pub double: bool,
}

impl ErrorStatus {
    /// The number shown in `SYSTEM.ErrNum`: the digits of the code (R0001 → 1).
    pub fn number(&self) -> i32 {
        self.error.code.as_str().get(1..).and_then(|d| d.parse().ok()).unwrap_or(99)
    }
}

impl Strategy {
    /// Stops program `m` after a runtime error and enters the error if the
    /// status is free; runs the error program if there is one.
    pub(super) fn enter_error(&mut self, m: usize, task: u8, e: RuntimeError, mut trace: Option<&mut Trace>) {
        let block = self.members[m].block;
        let name = self.store.db.blocks[block].name.clone();
        // An FST table stops itself (RUNFLG 5) and runs again when started.
        self.members[m].stopped = self.members[m].fst.is_none();
        self.failures.push(e.clone());
        self.show_failed(m, task, trace.as_deref_mut());
        if let Some(t) = trace.as_deref_mut() {
            t.line(&serde_json::json!({
                "time": seconds(self.now_us), "task": task, "program": name,
                "error": e.code, "line": e.line, "message": e.message,
            }));
        }
        if Some(m) == self.error_program {
            // A double error: the kernel stops every program.
            self.halted = true;
            let first = self.error.take();
            let double = ErrorStatus { error: e, block: name, at_us: self.now_us, double: true };
            self.error = Some(first.map(|f| ErrorStatus { double: true, ..f }).unwrap_or(double));
            self.mirror(task, trace);
            return;
        }
        if self.error.is_some() {
            return;
        }
        self.enter_status(e, name, task, trace);
    }

    /// Enters an error in the free error status, shows it in the SYSTEM
    /// block and runs the error program.
    pub(super) fn enter_status(&mut self, e: RuntimeError, name: String, task: u8, mut trace: Option<&mut Trace>) {
        self.error = Some(ErrorStatus { error: e, block: name, at_us: self.now_us, double: false });
        self.mirror(task, trace.as_deref_mut());
        if let Some(ep) = self.error_program {
            if let Err(e2) = self.run_member(ep, task, trace.as_deref_mut()) {
                self.enter_error(ep, task, e2, trace);
            }
        }
    }

    /// The failed program's block: `Active` off, `Status` ERROR, its
    /// `Software` alarm on.
    fn show_failed(&mut self, m: usize, task: u8, mut trace: Option<&mut Trace>) {
        let c = self.members[m].cells;
        if let Some(a) = c.active {
            self.host_write(m, task, a, Cell::Bool(false), trace.as_deref_mut());
        }
        if let Some(s) = c.status {
            let idx = self.store.enum_names(s).iter().position(|n| n.eq_ignore_ascii_case("ERROR"));
            if let Some(idx) = idx {
                self.host_write(m, task, s, Cell::Enum { idx: idx as u16 }, trace.as_deref_mut());
            }
        }
        if let Some(Cell::Alarms(al)) = c.alarms.and_then(|a| self.store.cells.get_mut(a as usize)) {
            if let Some(i) = al.names.iter().position(|n| n.eq_ignore_ascii_case("Software")) {
                al.active[i] = true;
            }
            if let (Some(t), Some(a)) = (trace, c.alarms) {
                t.write(&self.store, self.now_us, task, &self.store.db.blocks[self.members[m].block].name, a);
            }
        }
    }

    /// Copies the error status into the SYSTEM block's fields.
    pub(super) fn mirror(&mut self, task: u8, mut trace: Option<&mut Trace>) {
        let Some(sys) = self.system else { return };
        let e = self.error.clone();
        let text = |s: &str| Cell::Text(s.as_bytes().to_vec());
        let values = [
            ("ErrNum", Cell::Int(e.as_ref().map_or(0, ErrorStatus::number))),
            ("ErrCode", text(e.as_ref().map_or("", |e| e.error.code.as_str()))),
            ("ErrBlock", text(e.as_ref().map_or("", |e| e.block.as_str()))),
            ("ErrLine", Cell::Int(e.as_ref().map_or(0, |e| e.error.line as i32))),
            ("Double", Cell::Bool(e.as_ref().is_some_and(|e| e.double))),
        ];
        for (field, v) in values {
            if let Some(cell) = self.store.cell_of(sys, field) {
                self.host_write(usize::MAX, task, cell, v, trace.as_deref_mut());
            }
        }
    }

    /// `SYSTEM.Clear := TRUE` (from any program, `--set` or the console)
    /// clears the error status; the engine sets it back to FALSE. Programs
    /// stopped by an error stay stopped.
    pub(super) fn check_clear(&mut self, task: u8, mut trace: Option<&mut Trace>) {
        let Some(cell) = self.clear else { return };
        if self.store.cells.get(cell as usize) != Some(&Cell::Bool(true)) || self.halted {
            return;
        }
        self.host_write(usize::MAX, task, cell, Cell::Bool(false), trace.as_deref_mut());
        if self.error.take().is_some() {
            if let Some(t) = trace.as_deref_mut() {
                t.line(&serde_json::json!({ "time": seconds(self.now_us), "task": task, "cleared": true }));
            }
            self.mirror(task, trace);
        }
    }
}

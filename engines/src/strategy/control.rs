//! What the console does to a running strategy besides reading and writing
//! fields: programs started, stopped and suspended by block (as a PLC
//! kernel's command interpreter starts and stops its programs), the error
//! status raised and cleared by hand, and each program's state shown.

use super::trace::Trace;
use super::{Strategy, WantKind};
use crate::errors::RuntimeError;
use crate::sequence::Status;
use crate::store::Cell;
use linc_format::Code;

/// A program as the console sees it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProgramState {
    /// Not scanned and at its start: never started, stopped, failed, a
    /// sequence at rest (RESET, STOPPED, ERROR) or a table with RUNFLG ≠ 1.
    Inactive,
    /// Kept as it is (steps, timers, registers) but not scanned.
    Suspended,
    Running,
}

impl ProgramState {
    pub fn name(self) -> &'static str {
        match self {
            ProgramState::Inactive => "inactive",
            ProgramState::Suspended => "suspended",
            ProgramState::Running => "running",
        }
    }
}

/// One program of the strategy, for `P?`.
#[derive(Clone, Debug, PartialEq)]
pub struct ProgramInfo {
    pub block: String,
    pub kind: WantKind,
    pub task: u8,
    pub state: ProgramState,
    /// Where it is: the failing line of an action in the error status
    /// (else `-`), a sequence's status and active steps, an FST table's
    /// step (the one it goes on with, [`Strategy::fst_step`]) and RUNFLG.
    pub position: String,
}

impl Strategy {
    fn member_of(&self, block: usize) -> Option<usize> {
        self.members.iter().position(|m| m.block == block)
    }

    fn runflg(&self, m: usize) -> Option<(u32, i32)> {
        let cell = self.store.cell_of(self.members[m].block, "RUNFLG")?;
        match self.store.cells.get(cell as usize) {
            Some(Cell::Int(i)) => Some((cell, *i)),
            _ => Some((cell, 0)),
        }
    }

    /// Every program, in database order.
    pub fn programs(&self) -> Vec<ProgramInfo> {
        (0..self.members.len()).map(|m| self.program_info(m)).collect()
    }

    fn program_info(&self, m: usize) -> ProgramInfo {
        let member = &self.members[m];
        let block = self.store.db.blocks[member.block].name.clone();
        let task = self.store.db.blocks[member.block].task;
        let (kind, at_rest, position) = if let Some(seq) = member.seq.as_deref() {
            // Each active step with its time (`.T`), as the monitor shows it.
            let steps = seq
                .active_steps()
                .iter()
                .map(|n| match seq.step(n) {
                    Some((_, us)) => format!("{n} {}s", us as f64 / 1e6),
                    None => n.to_string(),
                })
                .collect::<Vec<_>>()
                .join(", ");
            let rest = matches!(seq.status, Status::Reset | Status::Stopped | Status::Error);
            let pos = if steps.is_empty() {
                seq.status.name().to_string()
            } else {
                format!("{}: {steps}", seq.status.name())
            };
            (WantKind::Sequence, rest, pos)
        } else if member.fst.is_some() {
            let flag = self.runflg(m).map_or(0, |(_, v)| v);
            let step = self.fst_step(member.block).unwrap_or(0);
            (WantKind::Fst, flag != 1, format!("step {step} RUNFLG {flag}"))
        } else {
            let line = self.error.as_ref().filter(|e| e.block == block && e.error.line > 0);
            (WantKind::Action, false, line.map_or("-".to_string(), |e| format!("line {}", e.error.line)))
        };
        let state = match () {
            _ if member.stopped || at_rest => ProgramState::Inactive,
            _ if member.suspended => ProgramState::Suspended,
            _ => ProgramState::Running,
        };
        ProgramInfo { block, kind, task, state, position }
    }

    /// The state of the program `block` runs, or `None` if it runs none.
    pub fn program_state(&self, block: usize) -> Option<ProgramState> {
        self.member_of(block).map(|m| self.program_info(m).state)
    }

    /// Starts, suspends or stops the program of `block`. Starting resumes
    /// a suspended program where it was and begins a stopped one afresh (a
    /// sequence's `Run` and a table's RUNFLG are set so it goes); stopping
    /// resets it (a sequence to RESET, a table to step 0 with RUNFLG 0).
    /// `false` if the block runs no program.
    pub fn set_program_state(&mut self, block: usize, state: ProgramState) -> bool {
        let Some(m) = self.member_of(block) else { return false };
        match state {
            ProgramState::Suspended => self.members[m].suspended = true,
            ProgramState::Running => {
                let member = &mut self.members[m];
                if member.stopped {
                    member.act.reset();
                    member.qual = Default::default();
                    if let Some(f) = member.fst.as_deref_mut() {
                        f.restart();
                    }
                }
                // A failed sequence stays in ERROR until reset: a start resets it.
                if let Some(seq) = member.seq.as_deref_mut().filter(|s| s.status == Status::Error) {
                    seq.command(crate::sequence::Command::Reset);
                    member.act.reset();
                }
                self.members[m].stopped = false;
                self.members[m].suspended = false;
                self.command_field(m, "Run", Cell::Bool(true));
                if self.members[m].fst.is_some() {
                    if let Some((cell, _)) = self.runflg(m) {
                        self.set_cell(cell, Cell::Int(1));
                    }
                }
            }
            ProgramState::Inactive => {
                let member = &mut self.members[m];
                member.act.reset();
                member.qual = Default::default();
                member.stopped = true;
                member.suspended = false;
                if let Some(f) = member.fst.as_deref_mut() {
                    f.restart();
                }
                if let Some(seq) = member.seq.as_deref_mut() {
                    seq.command(crate::sequence::Command::Reset);
                }
                self.command_field(m, "Run", Cell::Bool(false));
                if let Some((cell, _)) = self.members[m].fst.as_ref().and(self.runflg(m)) {
                    self.set_cell(cell, Cell::Int(0));
                }
            }
        }
        true
    }

    /// A field of a sequence's SFC_CON block, written as the console would.
    fn command_field(&mut self, m: usize, field: &str, v: Cell) {
        if self.members[m].seq.is_none() {
            return;
        }
        if let Some(cell) = self.store.cell_of(self.members[m].block, field) {
            self.set_cell(cell, v);
        }
    }

    /// A write by the console: a forced cell keeps its forced value.
    fn set_cell(&mut self, cell: u32, v: Cell) {
        if !self.store.is_forced(cell) {
            if let Some(slot) = self.store.cells.get_mut(cell as usize) {
                *slot = v;
            }
        }
    }

    /// Raises an error by hand, as the kernel's MF command does: it enters
    /// the error status like a runtime error of `block`'s program (so the
    /// error program runs), without stopping any program. `false` if the
    /// status already holds an error (it is kept) or every program is halted.
    pub fn raise_error(&mut self, code: Code, block: &str, trace: Option<&mut Trace>) -> bool {
        if self.error.is_some() || self.halted {
            return false;
        }
        let message = "raised by the console".to_string();
        let e = RuntimeError { code, message, action: String::new(), file: String::new(), line: 0, col: 0 };
        let task = self.error_program.map_or(0, |ep| self.store.db.blocks[self.members[ep].block].task);
        self.enter_status(e, block.to_string(), task, trace);
        true
    }

    /// Clears the error status, as writing `SYSTEM.Clear` does. Programs
    /// stopped by an error stay stopped; a double error's halt stays.
    pub fn clear_error(&mut self) -> bool {
        let had = self.error.take().is_some();
        if had {
            self.mirror(0, None);
        }
        had
    }

    /// The period of the fastest task (µs), one `SCAN`.
    pub fn fastest_period_us(&self) -> Option<u64> {
        self.tasks.iter().map(|t| t.period_us).min()
    }

    /// The device clock in whole seconds, local time as the FST commands
    /// and a ROC host's opcode 7 read it (POSIX seconds read with no zone).
    pub fn device_seconds(&self) -> i64 {
        (self.start + self.now_us as f64 / 1e6).floor() as i64 + self.vm.clock.utc_offset
    }

    /// Sets the device clock, as a ROC host's opcode 8 does: the clock
    /// jumps to `local`, and elapsed time, the task schedule and every
    /// timer are untouched (they count simulated time, not the calendar).
    pub fn set_device_seconds(&mut self, local: i64) {
        let shift = (local - self.device_seconds()) as f64;
        self.start += shift;
        self.store.now = self.start + self.now_us as f64 / 1e6;
    }

    /// The simulated clock in ISO 8601 with milliseconds, as the device
    /// shows it (`2026-01-05T06:00:00.300`).
    pub fn now_text(&self) -> String {
        let whole = self.start.floor() as i64 + (self.now_us / 1_000_000) as i64;
        let frac = ((self.start - self.start.floor()) * 1e6).round() as u64 + self.now_us % 1_000_000;
        let (whole, frac) = (whole + (frac / 1_000_000) as i64, frac % 1_000_000);
        format!("{}.{:03}", crate::roc::iso(whole), frac / 1000)
    }

    /// Writes the trace lines of writes dropped because their cell was
    /// forced (`{"time", "task", "program", "field", "forced": true}`).
    pub(super) fn trace_ignored(&mut self, m: usize, task: u8, trace: Option<&mut Trace>) {
        let cells = self.store.take_ignored();
        let Some(t) = trace else { return };
        let program = super::m_name(&self.store, self.members.get(m).map(|x| x.block));
        for cell in cells {
            t.line(&serde_json::json!({
                "time": super::trace::seconds(self.now_us), "task": task, "program": program,
                "field": self.store.describe(cell), "forced": true,
            }));
        }
    }
}

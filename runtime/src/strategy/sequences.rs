//! SFC_CON blocks in a strategy: each runs the sequence its `FileName`
//! holds, one scan per run of its task, commanded by its fields (guide
//! §20.6.3; the state table is in docs/sequences.md).

use super::trace::Trace;
use super::{Strategy, StrategyError, Want};
use crate::errors::RuntimeError;
use crate::object::UnitKind;
use crate::sequence::host::{Traced, VmHost};
use crate::sequence::{Command, Status};
use crate::store::{Cell, Store};
use crate::verify::Verified;

/// Whether a block is a sequence control block (an SFC_CON, or any
/// template with SFC_CON's command fields and no `ActName`).
pub(super) fn is_sfc_con(store: &Store, block: usize) -> bool {
    let t = store.db.block_template(block);
    ["FileName", "Run", "Hold", "Stop", "Reset", "Status"].iter().all(|f| t.field(f).is_some())
        && t.field("ActName").is_none()
}

/// The sequence unit of an SFC_CON block's file: its first sequence.
pub(super) fn unit_of(v: &Verified, w: &Want, block_name: &dyn Fn(usize) -> String) -> Result<usize, StrategyError> {
    v.object()
        .units
        .iter()
        .position(|u| u.kind == UnitKind::Sequence)
        .ok_or_else(|| StrategyError::new("E0833", block_name(w.block), format!("`{}` holds no sequence", w.file)))
}

fn flag(store: &Store, block: usize, field: &str) -> Option<bool> {
    match store.cell_of(block, field).and_then(|c| store.cells.get(c as usize)) {
        Some(Cell::Bool(b)) => Some(*b),
        _ => None,
    }
}

/// The command the block's fields ask for, given the sequence's status:
/// Reset first, then Stop, then Hold (from RUNNING or STOPPED), then Run
/// (and Run written FALSE while running stops it).
fn command(store: &Store, block: usize, status: Status) -> Option<Command> {
    let f = |name| flag(store, block, name).unwrap_or(false);
    let scanning = matches!(status, Status::Running | Status::Held);
    match () {
        _ if f("Reset") => Some(Command::Reset),
        _ if f("Stop") && status != Status::Stopped => Some(Command::Stop),
        _ if f("Hold") && matches!(status, Status::Running | Status::Stopped) => Some(Command::Hold),
        _ if !f("Hold") && status == Status::Held => Some(Command::Run),
        _ if f("Run") && matches!(status, Status::Reset | Status::Stopped) => Some(Command::Run),
        _ if !f("Run") && scanning => Some(Command::Stop),
        _ => None,
    }
}

impl Strategy {
    /// One scan of an SFC_CON block's sequence.
    pub(super) fn scan_sequence(
        &mut self,
        m: usize,
        task: u8,
        mut trace: Option<&mut Trace>,
    ) -> Result<(), RuntimeError> {
        let block = self.members[m].block;
        let name = self.store.db.blocks[block].name.clone();
        let now = self.now_us;
        let member = &mut self.members[m];
        let Some(seq) = member.seq.as_mut() else { return Ok(()) };
        if let Some(c) = command(&self.store, block, seq.status) {
            if c == Command::Reset {
                member.act.reset();
            }
            seq.command(c);
        }
        let mut host = VmHost {
            vm: &mut self.vm,
            linked: &self.objects[member.object],
            act: &mut member.act,
            store: &mut self.store,
            trace: trace.as_deref_mut().map(|trace| Traced { trace, now_us: now, task, program: &name }),
        };
        let result = seq.scan(now, &mut host);
        let (status, steps) = (seq.status, seq.active_steps().len());
        self.show_sequence(m, task, status, steps, trace);
        result
    }

    /// The block's fields after a scan, as §20.6.3 has them per status.
    fn show_sequence(&mut self, m: usize, task: u8, status: Status, steps: usize, mut trace: Option<&mut Trace>) {
        let block = self.members[m].block;
        let (run, hold, init) = match status {
            Status::Reset => (false, false, true),
            Status::Running => (true, false, false),
            Status::Held => (true, true, false),
            Status::Stopped | Status::Error => (false, false, false),
        };
        let status_name = match status {
            Status::Reset => "RESET",
            Status::Running => "RUNNING",
            Status::Held => "HELD",
            Status::Stopped => "STOPPED",
            Status::Error => "ERROR",
        };
        // Hold is only ever set here: a Hold written while the sequence is
        // not yet running stays pending for the next scan.
        let mut writes = vec![("Run", Cell::Bool(run)), ("Init", Cell::Bool(init))];
        if hold {
            writes.push(("Hold", Cell::Bool(true)));
        }
        writes.extend([("Reset", Cell::Bool(false)), ("Stop", Cell::Bool(false))]);
        writes.push(("Steps", Cell::Int(steps as i32)));
        if let Some(cell) = self.store.cell_of(block, "Status") {
            if let Some(idx) = self.store.enum_names(cell).iter().position(|n| n == status_name) {
                writes.push(("Status", Cell::Enum { idx: idx as u16 }));
            }
        }
        for (field, v) in writes {
            if let Some(cell) = self.store.cell_of(block, field) {
                self.host_write(m, task, cell, v, trace.as_deref_mut());
            }
        }
    }
}

//! SFC_CON blocks in a strategy: each runs the sequence its `FileName`
//! holds, one scan per run of its task, commanded by its fields (guide
//! §20.6.3; the state table is in docs/sequences.md). A command field is
//! read at the start of a scan, whoever wrote it, the sequence included.

use super::trace::Trace;
use super::{BlockCells, Strategy, StrategyError, Want};
use crate::errors::RuntimeError;
use crate::object::UnitKind;
use crate::sequence::host::{Traced, VmHost};
use crate::sequence::{Command, Status};
use crate::store::{Cell, Store};
use crate::verify::Verified;
use linc_format::Code;

/// The sequence unit of an SFC_CON block's file: its first sequence.
pub(super) fn unit_of(v: &Verified, w: &Want, block_name: &dyn Fn(usize) -> String) -> Result<usize, StrategyError> {
    v.object()
        .units
        .iter()
        .position(|u| u.kind == UnitKind::Sequence)
        .ok_or_else(|| StrategyError::new(Code::E0833, block_name(w.block), format!("`{}` holds no sequence", w.file)))
}

/// A BOOL field's value (FALSE when the block has no such field).
fn flag(store: &Store, cell: Option<u32>) -> bool {
    matches!(cell.and_then(|c| store.cells.get(c as usize)), Some(Cell::Bool(true)))
}

/// The command the block's fields ask for, given the sequence's status:
/// Reset first, then Stop, then Hold (from RUNNING or STOPPED), then Run
/// (and Run written FALSE while running stops it).
fn command(store: &Store, c: &BlockCells, status: Status) -> Option<Command> {
    let scanning = matches!(status, Status::Running | Status::Held);
    let (run, hold) = (flag(store, c.run), flag(store, c.hold));
    match () {
        _ if flag(store, c.reset) => Some(Command::Reset),
        _ if flag(store, c.stop) && status != Status::Stopped => Some(Command::Stop),
        _ if hold && matches!(status, Status::Running | Status::Stopped) => Some(Command::Hold),
        _ if !hold && status == Status::Held => Some(Command::Run),
        _ if run && matches!(status, Status::Reset | Status::Stopped) => Some(Command::Run),
        _ if !run && scanning => Some(Command::Stop),
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
        // The block's name is copied only for a trace (the store is borrowed by the scan).
        let name = trace.as_ref().map(|_| self.store.db.blocks[self.members[m].block].name.clone());
        let now = self.now_us;
        let member = &mut self.members[m];
        let Some(seq) = member.seq.as_mut() else { return Ok(()) };
        if let Some(c) = command(&self.store, &member.cells, seq.status) {
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
            trace: trace.as_deref_mut().map(|trace| Traced {
                trace,
                now_us: now,
                task,
                program: name.as_deref().unwrap_or(""),
            }),
        };
        let commands = [member.cells.run, member.cells.hold, member.cells.reset, member.cells.stop];
        let before = commands.map(|c| c.and_then(|c| host.store.cells.get(c as usize).cloned()));
        let result = seq.scan(now, &mut host);
        let (status, steps) = (seq.status, seq.active_count());
        // A command field the scan itself wrote (an action's `SEQ1.Run :=
        // FALSE`) stands, to be read at the start of the next scan.
        let written =
            std::array::from_fn(|i| commands[i].and_then(|c| self.store.cells.get(c as usize).cloned()) != before[i]);
        self.show_sequence(m, task, (status, steps), written, trace);
        result
    }

    /// The block's fields after a scan, as §20.6.3 has them per status,
    /// except the command fields (`Run`, `Hold`, `Reset`, `Stop`, in that
    /// order in `written`) that the scan wrote.
    fn show_sequence(
        &mut self,
        m: usize,
        task: u8,
        (status, steps): (Status, usize),
        written: [bool; 4],
        mut trace: Option<&mut Trace>,
    ) {
        let (run, hold, init) = match status {
            Status::Reset => (false, false, true),
            Status::Running => (true, false, false),
            Status::Held => (true, true, false),
            Status::Stopped | Status::Error => (false, false, false),
        };
        let status_name = status.name();
        let c = self.members[m].cells;
        // Hold is only ever set here: a Hold written while the sequence is
        // not yet running stays pending for the next scan.
        let status_idx = c.status.and_then(|cell| self.store.enum_names(cell).iter().position(|n| n == status_name));
        let unless = |i: usize, v: Option<Cell>| v.filter(|_| !written[i]);
        let writes = [
            (c.run, unless(0, Some(Cell::Bool(run)))),
            (c.init, Some(Cell::Bool(init))),
            (c.hold, unless(1, hold.then_some(Cell::Bool(true)))),
            (c.reset, unless(2, Some(Cell::Bool(false)))),
            (c.stop, unless(3, Some(Cell::Bool(false)))),
            (c.steps, Some(Cell::Int(steps as i32))),
            (c.status, status_idx.map(|idx| Cell::Enum { idx: idx as u16 })),
        ];
        for (cell, v) in writes {
            if let (Some(cell), Some(v)) = (cell, v) {
                self.host_write(m, task, cell, v, trace.as_deref_mut());
            }
        }
    }
}

//! Strategies: every program a database names, run in its user task on a
//! simulated clock (ADR 0006, `docs/strategies.md`).
//!
//! The database is the strategy. Action-type blocks (templates with
//! `FileName` and `ActName` fields: ACTION, DIGACT, RAW_COM) each run one
//! LIN action; tasks run every period, in priority order (task 1 first),
//! and the blocks of a task in database order. A runtime error stops only
//! the failing program; the strategy keeps the first error in its error
//! status, as a PLC kernel's error word does, and may run an error program.

mod control;
mod errors;
mod fst;
mod observe;
pub mod qualifier;
mod runs;
mod sequences;
mod state;
mod state_parts;
pub mod trace;

pub use control::{ProgramInfo, ProgramState};
pub use errors::{ErrorStatus, StrategyError, RUNTIME_CODES};
pub use fst::{register, steps_per_cycle};
use linc_format::Code;
pub use runs::LinesRan;
pub use state::StateError;

use crate::link::{Linked, Program};
use crate::store::{Cell, Store};
use crate::verify::Verified;
use crate::vm::{Activation, Vm};
use qualifier::{QualState, Qualifier};
use trace::Trace;

pub use linc_format::db::programs::{Want, WantKind};

/// A block must name both its file and (unless it runs a sequence) its
/// action (E0830).
pub fn complete(w: &Want, store: &Store) -> Result<(), StrategyError> {
    let Some(missing) = w.missing() else { return Ok(()) };
    let block = store.db.blocks[w.block].name.clone();
    Err(StrategyError::new(Code::E0830, block, format!("the block names no action: its {missing} is empty")))
}

/// Text of a string field of a block, if the block's template has it.
fn text_field(store: &Store, block: usize, field: &str) -> Option<String> {
    match store.cell_of(block, field).and_then(|c| store.cells.get(c as usize)) {
        Some(Cell::Text(t)) => Some(String::from_utf8_lossy(t).into_owned()),
        _ => None,
    }
}

/// The blocks of a store that name a program, by its live values, in
/// database order (the rule is the database's:
/// `linc_format::db::programs`).
pub fn wanted(store: &Store) -> Vec<Want> {
    linc_format::db::programs::wanted(&store.db, &|b, field| text_field(store, b, field))
}

/// The cells through which the engine drives and shows a block.
#[derive(Clone, Copy, Debug, Default)]
struct BlockCells {
    trigger: Option<u32>,
    qualifier: Option<u32>,
    qual_time: Option<u32>,
    active: Option<u32>,
    status: Option<u32>,
    alarms: Option<u32>,
    /// SFC_CON's commands and state.
    run: Option<u32>,
    hold: Option<u32>,
    init: Option<u32>,
    reset: Option<u32>,
    stop: Option<u32>,
    steps: Option<u32>,
}

impl BlockCells {
    /// Looked up once, when the strategy is built, not at every scan.
    fn of(store: &Store, block: usize) -> BlockCells {
        let c = |f| store.cell_of(block, f);
        BlockCells {
            trigger: c("Trigger"),
            qualifier: c("Qualifier"),
            qual_time: c("QualTime"),
            active: c("Active"),
            status: c("Status"),
            alarms: c("Alarms"),
            run: c("Run"),
            hold: c("Hold"),
            init: c("Init"),
            reset: c("Reset"),
            stop: c("Stop"),
            steps: c("Steps"),
        }
    }
}

/// One program of the strategy and its state.
#[derive(Clone, Debug)]
struct Member {
    block: usize,
    object: usize,
    program: usize,
    act: Activation,
    qual: QualState,
    stopped: bool,
    /// Kept as it is but not scanned (the console's SUSPEND).
    suspended: bool,
    cells: BlockCells,
    /// The qualifier each value of the block's `Qualifier` enumeration
    /// stands for, read from the names once, not at every scan.
    quals: Box<[Qualifier]>,
    /// The sequence an SFC_CON block runs.
    seq: Option<Box<crate::sequence::Sequence>>,
    /// The state of the table an FST block runs.
    fst: Option<Box<fst::FstRun>>,
    /// What the action's last execution ran, when a picture watches it.
    watch: Option<Box<runs::Watch>>,
}

#[derive(Clone, Debug)]
struct TaskRun {
    number: u8,
    period_us: u64,
    next_us: u64,
    members: Vec<usize>,
}

/// A strategy ready to run.
pub struct Strategy {
    pub store: Store,
    objects: Vec<Linked>,
    /// Each object's CRC for the fingerprint (`state.rs`), summed before
    /// linking: a unit's code is linked in place, so the linked objects no
    /// longer hold the bytes the object file had.
    sums: Vec<u32>,
    members: Vec<Member>,
    tasks: Vec<TaskRun>,
    vm: Vm,
    error: Option<ErrorStatus>,
    error_program: Option<usize>,
    system: Option<usize>,
    /// SYSTEM.Clear, looked up once: it is read after every program's scan.
    clear: Option<u32>,
    halted: bool,
    /// Runtime errors of this `run_for`, in order (entered or not).
    failures: Vec<crate::RuntimeError>,
    now_us: u64,
    /// Instants run since the strategy was built (each runs every task
    /// due then): what `linc serve` counts as scans, whoever ran them.
    instants: u64,
    start: f64,
    /// The ROC device's clockwork (TDO outputs, history logger).
    device: fst::Device,
}

/// The unit of an action block: the action its `ActName` names.
fn action_unit(v: &Verified, w: &Want, block_name: &dyn Fn(usize) -> String) -> Result<usize, StrategyError> {
    let unit = v.unit_named(&w.action).filter(|&u| v.object().units[u].kind == crate::object::UnitKind::Action);
    unit.ok_or_else(|| {
        let have: Vec<&str> = v.object().units.iter().map(|u| u.name.as_str()).collect();
        let msg = format!("`{}` has no action `{}` (it has {})", w.file, w.action, have.join(", "));
        StrategyError::new(Code::E0831, block_name(w.block), msg)
    })
}

/// Seconds to whole microseconds of simulated time.
pub fn micros(seconds: f64) -> u64 {
    (seconds.max(0.0) * 1e6).round().min(u64::MAX as f64) as u64
}

impl Strategy {
    /// Links every wanted action (`wants[i].1` indexes `objects`) to the
    /// store. `start` is the clock's start in POSIX seconds.
    pub fn build(
        store: Store,
        objects: Vec<Verified>,
        wants: &[(Want, usize)],
        vm: Vm,
        start: f64,
    ) -> Result<Strategy, StrategyError> {
        let block_name = |b: usize| store.db.blocks[b].name.clone();
        let mut programs: Vec<Vec<Program>> = vec![Vec::new(); objects.len()];
        let mut members = Vec::with_capacity(wants.len());
        for (w, o) in wants {
            let v = objects.get(*o).ok_or_else(|| StrategyError::new(Code::E0831, block_name(w.block), "no object"))?;
            let unit = match w.kind {
                WantKind::Action => action_unit(v, w, &block_name)?,
                WantKind::Sequence => sequences::unit_of(v, w, &block_name)?,
                WantKind::Fst => fst::unit_of(v, w, &block_name)?,
            };
            let program = programs[*o].len();
            programs[*o].push(Program { unit, own: Some(w.block) });
            let cells = BlockCells::of(&store, w.block);
            let names = cells.qualifier.map(|c| store.enum_names(c)).unwrap_or_default();
            let quals = names.iter().map(|n| Qualifier::parse(n).unwrap_or(Qualifier::N)).collect();
            let act = Activation::default();
            members.push(Member {
                block: w.block,
                object: *o,
                program,
                act,
                qual: QualState::default(),
                stopped: false,
                suspended: false,
                cells,
                quals,
                seq: None,
                fst: None,
                watch: None,
            });
        }
        let sums = objects.iter().map(|v| crate::object::crc32(&v.object().to_bytes_without_files())).collect();
        let mut linked = Vec::with_capacity(objects.len());
        for (o, v) in objects.into_iter().enumerate() {
            let l = v.link_each(&store, &programs[o]).map_err(|(i, e)| {
                let block = programs[o][i].own.map(block_name).unwrap_or_default();
                StrategyError::new(e.code(), block, e.to_string())
            })?;
            linked.push(l);
        }
        for m in &mut members {
            m.act = Activation::new(&linked[m.object], m.program, 0);
            if let Some(unit) = linked[m.object].unit(m.program).filter(|u| !u.charts.is_empty()) {
                m.seq =
                    Some(Box::new(crate::sequence::Sequence::new(crate::sequence::chart::Chart::from_unit(unit, 0))));
            }
        }
        let mut store = store;
        for m in &mut members {
            if let Some(unit) = linked[m.object].unit(m.program).filter(|u| u.kind == crate::object::UnitKind::Fst) {
                m.fst = Some(Box::new(fst::FstRun::new(&mut store, m.block, unit)));
            }
        }
        let tasks = tasks(&store, &members);
        let device = fst::Device::of(&store);
        let mut s = Strategy {
            store,
            objects: linked,
            sums,
            members,
            tasks,
            vm,
            error: None,
            error_program: None,
            system: None,
            clear: None,
            halted: false,
            failures: Vec::new(),
            now_us: 0,
            instants: 0,
            start,
            device,
        };
        s.store.now = start;
        s.find_error_program()?;
        Ok(s)
    }

    /// The SYSTEM block (if any) and the error program it names in `ErrProg`.
    fn find_error_program(&mut self) -> Result<(), StrategyError> {
        let system = (0..self.store.db.blocks.len())
            .find(|&b| self.store.db.block_template(b).name.eq_ignore_ascii_case(errors::SYSTEM));
        self.system = system;
        self.clear = system.and_then(|s| self.store.cell_of(s, "Clear"));
        let Some(sys) = system else { return Ok(()) };
        let name = text_field(&self.store, sys, "ErrProg").unwrap_or_default();
        if name.is_empty() {
            return Ok(());
        }
        let member = self
            .store
            .db
            .block(&name)
            .and_then(|b| self.members.iter().position(|m| m.block == b && m.seq.is_none() && m.fst.is_none()));
        let sys_name = self.store.db.blocks[sys].name.clone();
        let member = member.ok_or_else(|| {
            StrategyError::new(Code::E0832, sys_name, format!("the error program `{name}` is not an action-type block"))
        })?;
        self.error_program = Some(member);
        Ok(())
    }

    /// The error status: the first runtime error since it was last cleared.
    pub fn error(&self) -> Option<&ErrorStatus> {
        self.error.as_ref()
    }

    /// Simulated time since the start, in microseconds.
    pub fn elapsed_us(&self) -> u64 {
        self.now_us
    }

    /// The sequence an SFC_CON block runs, for the monitor's controls.
    pub fn sequence_mut(&mut self, block: usize) -> Option<&mut crate::sequence::Sequence> {
        self.members.iter_mut().find(|m| m.block == block).and_then(|m| m.seq.as_deref_mut())
    }

    /// The sequence an SFC_CON block runs, for a monitor's picture.
    pub fn sequence(&self, block: usize) -> Option<&crate::sequence::Sequence> {
        self.members.iter().find(|m| m.block == block).and_then(|m| m.seq.as_deref())
    }

    /// When the next scan of any task is due (µs of simulated time); `None`
    /// without tasks.
    pub fn next_due_us(&self) -> Option<u64> {
        self.tasks.iter().map(|t| t.next_us).min()
    }

    /// Whether a double error stopped every program.
    pub fn halted(&self) -> bool {
        self.halted
    }

    /// Runs the tasks for `duration` µs of simulated time: every task whose
    /// time has come runs at that instant, in task order, until the end
    /// (a task due exactly at the end does not run; the next call runs it).
    /// Returns the runtime errors that stopped programs, in order.
    pub fn run_for(&mut self, duration_us: u64, mut trace: Option<&mut Trace>) -> Vec<crate::RuntimeError> {
        let end = self.now_us.saturating_add(duration_us);
        while let Some(next) = self.next_due_us().filter(|&n| n < end) {
            self.run_instant(next, trace.as_deref_mut());
        }
        self.set_time(end);
        std::mem::take(&mut self.failures)
    }

    /// Runs the tasks due next, at their instant, and leaves the clock
    /// there: one step of a real-time run (`linc serve`), which decides
    /// itself when that instant has come. Returns the runtime errors.
    pub fn run_due(&mut self, trace: Option<&mut Trace>) -> Vec<crate::RuntimeError> {
        if let Some(next) = self.next_due_us() {
            self.run_instant(next, trace);
        }
        std::mem::take(&mut self.failures)
    }

    /// How many instants have run since the strategy was built (each one
    /// runs every task due then), by `run_for` and `run_due` alike.
    pub fn instants(&self) -> u64 {
        self.instants
    }

    fn run_instant(&mut self, next: u64, mut trace: Option<&mut Trace>) {
        self.instants += 1;
        self.set_time(next);
        self.device_tick(trace.as_deref_mut());
        self.trace_ignored(usize::MAX, 0, trace.as_deref_mut());
        for t in 0..self.tasks.len() {
            if self.tasks[t].next_us == next {
                self.run_task(t, trace.as_deref_mut());
                self.tasks[t].next_us = next.saturating_add(self.tasks[t].period_us);
            }
        }
    }

    fn set_time(&mut self, us: u64) {
        self.now_us = us;
        self.store.now = self.start + us as f64 / 1e6;
    }

    fn run_task(&mut self, t: usize, mut trace: Option<&mut Trace>) {
        let number = self.tasks[t].number;
        for i in 0..self.tasks[t].members.len() {
            let m = self.tasks[t].members[i];
            if self.halted {
                return;
            }
            if Some(m) == self.error_program || self.members[m].stopped || self.members[m].suspended {
                continue;
            }
            self.scan_member(m, number, trace.as_deref_mut());
            self.trace_ignored(m, number, trace.as_deref_mut());
        }
    }

    /// One scan of one program: a sequence, an FST table or an action block.
    fn scan_member(&mut self, m: usize, number: u8, mut trace: Option<&mut Trace>) {
        if self.members[m].seq.is_some() || self.members[m].fst.is_some() {
            let scanned = if self.members[m].fst.is_some() {
                self.scan_fst(m, number, trace.as_deref_mut())
            } else {
                self.scan_sequence(m, number, trace.as_deref_mut())
            };
            if let Err(e) = scanned {
                self.enter_error(m, number, e, trace.as_deref_mut());
            }
            self.check_clear(number, trace.as_deref_mut());
            return;
        }
        let runs = self.scan_qualifier(m, number, trace.as_deref_mut());
        if runs {
            self.watch_before(m);
            let ran = self.run_member(m, number, trace.as_deref_mut());
            self.watch_after(m);
            if let Err(e) = ran {
                self.enter_error(m, number, e, trace.as_deref_mut());
            }
        }
        self.check_clear(number, trace);
    }

    /// Applies the block's qualifier to its trigger; shows the result in `Active`.
    fn scan_qualifier(&mut self, m: usize, task: u8, trace: Option<&mut Trace>) -> bool {
        let c = self.members[m].cells;
        let trigger = match c.trigger.and_then(|c| self.store.cells.get(c as usize)) {
            Some(Cell::Bool(b)) => *b,
            // A block without a Trigger (RAW_COM) runs its action every scan.
            _ => true,
        };
        let q = c
            .qualifier
            .and_then(|cell| self.members[m].quals.get(enum_index(&self.store, cell)))
            .copied()
            .unwrap_or(Qualifier::N);
        let time = match c.qual_time.and_then(|c| self.store.cells.get(c as usize)) {
            Some(Cell::Real(r)) => micros(f64::from(*r)),
            _ => 0,
        };
        let now = self.now_us;
        let runs = self.members[m].qual.scan(q, time, trigger, now);
        if let Some(a) = c.active {
            self.host_write(m, task, a, Cell::Bool(runs), trace);
        }
        runs
    }

    fn run_member(
        &mut self,
        m: usize,
        task: u8,
        trace: Option<&mut Trace>,
    ) -> Result<crate::vm::Outcome, crate::RuntimeError> {
        let now = self.now_us;
        // The block's name is copied only for a trace (the store is borrowed by the run).
        let name = trace.as_ref().map(|_| self.store.db.blocks[self.members[m].block].name.clone());
        let member = &mut self.members[m];
        let linked = &self.objects[member.object];
        let mut note =
            trace.map(|t| move |s: &Store, cell: u32| t.write(s, now, task, name.as_deref().unwrap_or(""), cell));
        let tracer: crate::vm::Tracer = match note.as_mut() {
            Some(f) => Some(f),
            None => None,
        };
        self.vm.run(linked, &mut member.act, &mut self.store, tracer)
    }

    /// A write by the engine itself (Active, Status, alarms), traced like a program's.
    fn host_write(&mut self, m: usize, task: u8, cell: u32, v: Cell, trace: Option<&mut Trace>) {
        if self.store.is_forced(cell) {
            if self.store.cells.get(cell as usize) != Some(&v) {
                self.store.refuse_forced(cell);
            }
            return;
        }
        if let Some(slot) = self.store.cells.get_mut(cell as usize) {
            if *slot == v {
                return;
            }
            *slot = v;
        }
        if let Some(t) = trace {
            let name = m_name(&self.store, self.members.get(m).map(|x| x.block));
            t.write(&self.store, self.now_us, task, &name, cell);
        }
    }
}

/// The program a host write is traced under: the member's block, or the
/// strategy itself for the error status.
fn m_name(store: &Store, block: Option<usize>) -> String {
    block.map(|b| store.db.blocks[b].name.clone()).unwrap_or_else(|| "(strategy)".to_string())
}

fn enum_index(store: &Store, cell: u32) -> usize {
    match store.cells.get(cell as usize) {
        Some(Cell::Enum { idx }) => usize::from(*idx),
        _ => usize::MAX,
    }
}

/// Groups members by the task of their block, tasks in number order.
fn tasks(store: &Store, members: &[Member]) -> Vec<TaskRun> {
    let mut out: Vec<TaskRun> = store
        .db
        .tasks
        .iter()
        .map(|t| TaskRun { number: t.number, period_us: micros(t.period).max(1), next_us: 0, members: Vec::new() })
        .collect();
    out.sort_by_key(|t| t.number);
    for (i, m) in members.iter().enumerate() {
        let n = store.db.blocks[m.block].task;
        if let Some(t) = out.iter_mut().find(|t| t.number == n) {
            t.members.push(i);
        }
    }
    out
}

//! FST blocks in a strategy: each runs the table its `FileName` holds, in
//! its task, as a ROC runs a Function Sequence Table (`docs/fst.md`).
//!
//! In each cycle a running table (RUNFLG 1) executes up to its steps-per-
//! cycle limit, stopping early at END (the next cycle starts at step 0), at
//! WT (it sleeps for the time asked, then goes on at the next step) and
//! while a BRK delay is in force (one command per BRK × 100 ms, END and
//! the step 0 after it included). A runtime fault —
//! a point removed from the database, an invalid history index — stops the
//! table with RUNFLG 5 and IP at the failing step.

use super::trace::{seconds, Trace};
use super::{Strategy, StrategyError, Want};
use crate::errors::RuntimeError;
use crate::object::{Unit, UnitKind};
use crate::store::{Cell, Store};
use crate::verify::Verified;
use crate::vm::Outcome;
use linc_format::Code;

/// Steps one cycle may execute when the block's STEPS is 0.
pub const DEFAULT_STEPS: u32 = 20;

/// The FST timers' interval and the unit of BRK.
pub const TICK_US: u64 = 100_000;

/// WT's range in seconds (Table B-14).
pub const MIN_WAIT: f64 = 0.1;
pub const MAX_WAIT: f64 = 999_999.0;

/// Whether a block is an FST point (a template with the FST registers and
/// a `FileName`).
pub(super) fn is_fst(store: &Store, block: usize) -> bool {
    linc_format::db::programs::is_fst(store.db.block_template(block))
}

/// The FST unit of an FST block's file: its first table.
pub(super) fn unit_of(v: &Verified, w: &Want, block_name: &dyn Fn(usize) -> String) -> Result<usize, StrategyError> {
    v.object()
        .units
        .iter()
        .position(|u| u.kind == UnitKind::Fst)
        .ok_or_else(|| StrategyError::new(Code::E0834, block_name(w.block), format!("`{}` holds no FST table", w.file)))
}

/// The cells of an FST block the engine reads and writes.
#[derive(Clone, Copy, Debug, Default)]
struct FstCells {
    rr: Option<u32>,
    cf: Option<u32>,
    runflg: Option<u32>,
    ip: Option<u32>,
    brk: Option<u32>,
    steps: Option<u32>,
}

/// One FST block's engine state.
#[derive(Clone, Debug)]
pub(super) struct FstRun {
    cells: FstCells,
    /// Instruction offset of each step, for IP.
    offsets: Vec<u32>,
    /// Asleep (WT, BRK) until this time.
    wait_until: u64,
    /// Whether the table ran at the last scan (a stop and start begins again at step 0).
    running: bool,
}

/// An FST block's whole-number register as the engine reads it (0 when
/// the block has no such field).
pub fn register(store: &Store, block: usize, field: &str) -> i32 {
    int(store, store.cell_of(block, field))
}

/// The steps a cycle may begin with these BRK and STEPS: one while BRK
/// delays the table, else STEPS, or [`DEFAULT_STEPS`] when it is 0.
pub fn steps_per_cycle(brk: i32, steps: i32) -> u32 {
    match (brk, steps) {
        (1.., _) => 1,
        (_, s @ 1..) => s as u32,
        _ => DEFAULT_STEPS,
    }
}

fn int(store: &Store, cell: Option<u32>) -> i32 {
    match cell.and_then(|c| store.cells.get(c as usize)) {
        Some(Cell::Int(i)) => *i,
        Some(Cell::Bits { v, .. }) => i32::from(*v),
        Some(Cell::Real(r)) => *r as i32,
        _ => 0,
    }
}

impl FstRun {
    /// The state of `block` running `unit`. A block whose file does not set
    /// RUNFLG starts running, as a table does when started after download.
    pub(super) fn new(store: &mut Store, block: usize, unit: &Unit) -> FstRun {
        let c = |f: &str| store.cell_of(block, f);
        let cells = FstCells {
            rr: c("RR"),
            cf: c("CMPFLG"),
            runflg: c("RUNFLG"),
            ip: c("IP"),
            brk: c("BRK"),
            steps: c("STEPS"),
        };
        let t = store.db.block_template(block);
        let set = t.field("RUNFLG").is_some_and(|f| store.db.blocks[block].values.iter().any(|(i, _)| *i == f));
        if let (false, Some(cell)) = (set, cells.runflg) {
            store.cells[cell as usize] = Cell::Int(1);
        }
        let offsets = unit.main().map(|b| b.labels[..unit.steps.len()].to_vec()).unwrap_or_default();
        FstRun { cells, offsets, wait_until: 0, running: false }
    }
}

impl FstRun {
    /// A running table begins again at step 0 at its next cycle, awake
    /// (any WT or BRK deadline forgotten): after a warm start (B.1.6) and
    /// when the console stops or starts the program. The registers and
    /// timers are fields and stay (the timers count on, with the device).
    pub(super) fn restart(&mut self) {
        self.running = false;
        self.wait_until = 0;
    }
}

/// Microseconds of a WT of `secs` seconds: within 0.1 s to 999,999 s, in
/// whole 100 ms intervals (rounded to the nearest).
fn wait_us(secs: f32) -> u64 {
    let s = f64::from(secs).clamp(MIN_WAIT, MAX_WAIT);
    ((s * 10.0).round() as u64).max(1) * TICK_US
}

impl Strategy {
    /// One cycle of an FST block's table.
    pub(super) fn scan_fst(&mut self, m: usize, task: u8, mut trace: Option<&mut Trace>) -> Result<(), RuntimeError> {
        let now = self.now_us;
        let Some(f) = self.members[m].fst.as_deref() else { return Ok(()) };
        let (c, running) = (f.cells, f.running);
        if int(&self.store, c.runflg) != 1 {
            if let Some(f) = self.members[m].fst.as_mut() {
                f.running = false;
            }
            self.members[m].act.reset();
            return Ok(());
        }
        if let (false, Some(f)) = (running, self.members[m].fst.as_mut()) {
            // Started (again): from step 0, awake.
            f.running = true;
            f.wait_until = 0;
            self.members[m].act.reset();
        }
        if self.members[m].fst.as_ref().is_some_and(|f| now < f.wait_until) {
            return Ok(());
        }
        let brk = int(&self.store, c.brk);
        let budget = steps_per_cycle(brk, int(&self.store, c.steps));
        let result = self.fst_cycle(m, task, budget, brk, trace.as_deref_mut());
        let ip = self.next_ip(m, result.is_err());
        if let Some(cell) = c.ip {
            self.host_write(m, task, cell, Cell::Int(ip as i32), trace.as_deref_mut());
        }
        if result.is_err() {
            if let Some(cell) = c.runflg {
                self.host_write(m, task, cell, Cell::Int(5), trace);
            }
            if let Some(f) = self.members[m].fst.as_mut() {
                f.running = false;
            }
        }
        result
    }

    /// The step (0-based row) FST block `block`'s table goes on with: the
    /// step its `IP` names after a cycle — step 0 after END or when
    /// stopped, the failing step after a fault. The one meaning of "current
    /// step" that the program list, the console's `P?` and the table's
    /// picture share (docs/fst.md). `None` when the block runs no table.
    pub fn fst_step(&self, block: usize) -> Option<usize> {
        let m = self.members.iter().position(|m| m.block == block && m.fst.is_some())?;
        let f = self.members[m].fst.as_deref()?;
        let failed = int(&self.store, f.cells.runflg) == 5;
        let ip = self.next_ip(m, failed);
        Some(f.offsets.iter().position(|&o| o == ip).unwrap_or(0))
    }

    /// IP after a cycle of member `m`: the offset of "the next function to
    /// be executed" (B.2) — where the suspended run resumes, or step 0 after
    /// END — or, after a fault, of the failing step.
    fn next_ip(&self, m: usize, failed: bool) -> u32 {
        let member = &self.members[m];
        let Some(f) = member.fst.as_deref() else { return 0 };
        let step = usize::from(member.act.step);
        match member.act.resume_point().0 {
            _ if failed => f.offsets.get(step).copied().unwrap_or(0),
            // A run resumes at a step's `Step` or, after a WT or BRK that
            // was the last step, at the final `Ret`: step 0 comes next.
            Some(pc) if f.offsets.contains(&pc) => pc,
            _ => f.offsets.first().copied().unwrap_or(0),
        }
    }

    /// Runs up to `budget` steps; with a trace, one step per VM run so each
    /// step is recorded with RR and CF after it.
    fn fst_cycle(
        &mut self,
        m: usize,
        task: u8,
        budget: u32,
        brk: i32,
        mut trace: Option<&mut Trace>,
    ) -> Result<(), RuntimeError> {
        let now = self.now_us;
        let mut left = budget;
        loop {
            let per_run = if trace.is_some() { 1 } else { left };
            let member = &mut self.members[m];
            member.act.steps_left = per_run;
            member.act.pause = None;
            let logged = (self.store.roc.alarms.total(), self.store.roc.events.total());
            let outcome = self.run_member(m, task, trace.as_deref_mut());
            let member = &mut self.members[m];
            let used = per_run - member.act.steps_left;
            left -= used;
            if let (Some(t), 1..) = (trace.as_deref_mut(), used) {
                self.trace_step(m, task, t);
                self.trace_logged(m, task, logged, t);
            }
            let member = &mut self.members[m];
            let Some(f) = member.fst.as_mut() else { return Ok(()) };
            match outcome {
                Err(e) => return Err(e),
                Ok(Outcome::Done) => {
                    // END is a command like any other: under BRK, step 0
                    // waits the break period after it (B-15).
                    if brk > 0 {
                        f.wait_until = now + brk as u64 * TICK_US;
                    }
                    return Ok(());
                }
                Ok(Outcome::Suspended) => match member.act.pause.take() {
                    Some((0, secs)) => {
                        f.wait_until = now + wait_us(secs);
                        return Ok(());
                    }
                    Some((_, n)) if n >= 1.0 => {
                        f.wait_until = now + (n as u64) * TICK_US;
                        return Ok(());
                    }
                    _ if left > 0 => {}
                    _ => {
                        if brk > 0 {
                            f.wait_until = now + brk as u64 * TICK_US;
                        }
                        return Ok(());
                    }
                },
            }
        }
    }

    /// A trace line for an alarm or event the step just logged.
    fn trace_logged(&self, m: usize, task: u8, before: (u64, u64), t: &mut Trace) {
        let roc = &self.store.roc;
        for (key, log, was) in [("alarm", &roc.alarms, before.0), ("event", &roc.events, before.1)] {
            if log.total() == was {
                continue;
            }
            if let Some(e) = log.iter().last() {
                let line = serde_json::json!({
                    "time": seconds(self.now_us), "task": task,
                    "program": self.store.db.blocks[self.members[m].block].name,
                    key: e.text, "value": e.value.to_string().parse::<f64>().unwrap_or(0.0),
                });
                t.line(&line);
            }
        }
    }

    /// A trace line for the step member `m` just executed: its number and
    /// command, and RR and CF after it.
    fn trace_step(&self, m: usize, task: u8, t: &mut Trace) {
        let member = &self.members[m];
        let Some(f) = member.fst.as_deref() else { return };
        let step = member.act.step;
        let cmd = self.objects[member.object].unit(member.program).and_then(|u| u.steps.get(usize::from(step)));
        // RR as its shortest decimal form (0.1, not 0.10000000149011612).
        let rr = match f.cells.rr.and_then(|c| self.store.cells.get(c as usize)) {
            Some(Cell::Real(r)) => r.to_string().parse::<f64>().unwrap_or(0.0),
            _ => 0.0,
        };
        let program = &self.store.db.blocks[member.block].name;
        let cmd = cmd.map(String::as_str).unwrap_or("");
        t.fst_step(self.now_us, task, program, (step, cmd), rr, int(&self.store, f.cells.cf));
    }
}

/// The ROC device's own clockwork, run whenever simulated time moves:
/// the FST timers count down, timed discrete outputs (TDO) turn off when
/// their time is up, and the history logger samples its points. Found once
/// when the strategy is built, so a strategy without ROC points pays
/// nothing.
#[derive(Clone, Debug, Default)]
pub(super) struct Device {
    /// `TMR1`–`TMR4` of every FST point, whether or not it runs a table:
    /// ST sets the timers of "any of the available FSTs" (Table B-14).
    timers: Vec<u32>,
    /// `TDOREM` and `STATUS` of every DOU point.
    tdo: Vec<(u32, u32)>,
    /// Whether any history point is sampled by the logger.
    logs: bool,
    pub(super) last_us: u64,
}

impl Device {
    pub(super) fn of(store: &Store) -> Device {
        let tdo = (0..store.db.blocks.len())
            .filter(|&b| store.db.block_template(b).name.eq_ignore_ascii_case("DOU"))
            .filter_map(|b| Some((store.cell_of(b, "TDOREM")?, store.cell_of(b, "STATUS")?)))
            .collect();
        let logs = (0..store.db.blocks.len()).any(|b| store.db.block_template(b).name.eq_ignore_ascii_case("HIST"));
        let timers = (0..store.db.blocks.len())
            .filter(|&b| is_fst(store, b))
            .flat_map(|b| ["TMR1", "TMR2", "TMR3", "TMR4"].map(|f| store.cell_of(b, f)))
            .flatten()
            .collect();
        Device { timers, tdo, logs, last_us: 0 }
    }
}

impl Strategy {
    /// Counts every FST timer above 0 down by `ticks` (to 0 at the least).
    fn tick_timers(&mut self, ticks: u64, mut trace: Option<&mut Trace>) {
        if ticks == 0 {
            return;
        }
        for i in 0..self.device.timers.len() {
            let cell = self.device.timers[i];
            let v = int(&self.store, Some(cell));
            if v > 0 {
                let left = i64::from(v).saturating_sub(ticks.min(i64::MAX as u64) as i64).max(0) as i32;
                self.host_write(usize::MAX, 0, cell, Cell::Int(left), trace.as_deref_mut());
            }
        }
    }

    /// Advances the device's clockwork to now.
    pub(super) fn device_tick(&mut self, mut trace: Option<&mut Trace>) {
        let now = self.now_us;
        let dt = now.saturating_sub(self.device.last_us);
        // The 100 ms boundaries of the simulated clock passed since the last tick.
        let ticks = (now / TICK_US).saturating_sub(self.device.last_us / TICK_US);
        self.device.last_us = now;
        if dt == 0 {
            return;
        }
        self.tick_timers(ticks, trace.as_deref_mut());
        for i in 0..self.device.tdo.len() {
            let (rem, status) = self.device.tdo[i];
            let Some(Cell::Real(left)) = self.store.cells.get(rem as usize).cloned() else { continue };
            if left <= 0.0 {
                continue;
            }
            let after = (f64::from(left) - dt as f64 / 1e6).max(0.0) as f32;
            self.host_write(usize::MAX, 0, rem, Cell::Real(after), trace.as_deref_mut());
            if after == 0.0 {
                self.host_write(usize::MAX, 0, status, Cell::Int(0), trace.as_deref_mut());
            }
        }
        if self.device.logs {
            let local = self.store.now.floor() as i64 + self.vm.clock.utc_offset;
            let crate::store::Store { db, cells, first, roc, .. } = &mut self.store;
            let mut value_of = |point: &str| {
                let (block, field) = crate::roc::split_archpt(point)?;
                let b = db.point(block)?;
                let f = db.block_template(b).field(field)?;
                match cells.get(first[b] as usize + f)? {
                    Cell::Real(r) => Some(*r),
                    Cell::Int(i) => Some(*i as f32),
                    Cell::Bits { v, .. } => Some(f32::from(*v)),
                    Cell::Bool(b) => Some(f32::from(u8::from(*b))),
                    _ => None,
                }
            };
            roc.history.sample(local, &mut value_of);
        }
    }
}

//! The command console over a running strategy (`docs/console.md`): what a
//! PLC kernel's command interpreter gives — display, modify and force
//! fields, start and stop programs, the error status — plus the LINtools
//! sequence monitor's controls and simulated time. Commands are data in
//! and text out; the CLI only reads lines and prints replies.

pub mod fields;
pub mod parse;

use crate::sequence::Sequence;
use crate::store::Store;
use crate::strategy::trace::Trace;
use crate::strategy::{ProgramState, Strategy};
use fields::{address, parse_value, show_value, Addr};
use linc_format::Code;
use parse::{Command, SeqControl, TransForce};

/// Fields shown by a range display (`D REC1.A0-`).
pub const RANGE: usize = 16;

/// Longest `ADVANCE`: 366 days of simulated time.
pub const MAX_ADVANCE_US: u64 = 366 * 86_400 * 1_000_000;

/// Runtime error codes `ERRRAISE` accepts (a raise enters the status as
/// one of these would).
pub const RAISABLE: &[Code] = crate::strategy::RUNTIME_CODES;

/// Why a command was refused; it changed nothing.
#[derive(Clone, Debug, PartialEq)]
pub struct ConsoleError {
    pub code: Code,
    pub message: String,
}

impl ConsoleError {
    pub fn new(code: Code, message: impl Into<String>) -> ConsoleError {
        ConsoleError { code, message: message.into() }
    }
}

impl std::fmt::Display for ConsoleError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.code, self.message)
    }
}

/// A duration as an ST time constant, with or without `T#` (`10m`, `T#1h30m`).
pub fn duration(text: &str) -> Result<u64, String> {
    let secs = crate::db::duration_seconds(text)
        .map_err(|why| format!("`{text}` is not a duration like 10s, 1h30m or T#2.5s: {why}"))?;
    let us = crate::strategy::micros(secs);
    if !secs.is_finite() || us == 0 || us > MAX_ADVANCE_US {
        return Err(format!("`{text}`: the duration must be more than 0 and at most 366 days"));
    }
    Ok(us)
}

/// A strategy driven by commands.
pub struct Console {
    pub strategy: Strategy,
    failures: Vec<crate::RuntimeError>,
    /// Whether `SAVE` has somewhere to go (the CLI's `--state FILE`).
    pub can_save: bool,
    /// The state `SAVE` asked for, until the caller writes it.
    saved: Option<Vec<u8>>,
    /// The most scans one `ADVANCE` may run, where the caller bounds it
    /// (`linc serve`: a line runs on the plant's thread, and every client
    /// waits for it).
    pub max_scans: Option<u64>,
}

fn not_found(why: String) -> ConsoleError {
    ConsoleError::new(Code::C0003, why)
}

impl Console {
    pub fn new(strategy: Strategy) -> Console {
        Console { strategy, failures: Vec::new(), can_save: false, saved: None, max_scans: None }
    }

    /// The retentive state the last `SAVE` took, for the caller to write
    /// (atomically) to its state file (`docs/state.md`).
    pub fn take_saved(&mut self) -> Option<Vec<u8>> {
        self.saved.take()
    }

    /// One input line: commands separated by `;` (outside quotes), each executed in order;
    /// one reply per command. A failed command changes nothing and does
    /// not stop the later ones on the line.
    pub fn execute(&mut self, line: &str) -> Vec<Result<String, ConsoleError>> {
        self.execute_traced(line, None)
    }

    /// [`Console::execute`] with the strategy trace: the runs of
    /// ADVANCE/SCAN are traced as `linc run --trace` traces them, and the
    /// fields a command changed are lines of program `(console)`.
    pub fn execute_traced(&mut self, line: &str, mut trace: Option<&mut Trace>) -> Vec<Result<String, ConsoleError>> {
        let mut replies = Vec::new();
        for c in commands(line) {
            let reply = self.one(c, trace.as_deref_mut());
            if let (Ok(_), Some(t)) = (&reply, trace.as_deref_mut()) {
                self.note_changes(t);
            }
            replies.push(reply);
        }
        replies
    }

    /// Trace lines for every field whose value differs from what the trace
    /// last saw: what the command itself wrote (M, F, START, RUN …).
    fn note_changes(&self, t: &mut Trace) {
        let store = &self.strategy.store;
        let now = self.strategy.elapsed_us();
        for cell in 0..store.cells.len() as u32 {
            t.write(store, now, 0, "(console)", cell);
        }
    }

    /// Runtime errors of programs that happened during ADVANCE/SCAN since
    /// the last call.
    pub fn take_failures(&mut self) -> Vec<crate::RuntimeError> {
        std::mem::take(&mut self.failures)
    }

    /// How far `text` runs the strategy when it is an `ADVANCE` or a
    /// `SCAN` (a scenario runs those scans itself); `None` for any other
    /// command, or one that does not parse (running it reports why).
    pub fn advance_of(&self, text: &str) -> Option<Result<u64, ConsoleError>> {
        match parse::parse(text, &duration) {
            Ok(Command::Advance(us)) => Some(Ok(us)),
            Ok(Command::Scan) => Some(self.scan_us()),
            _ => None,
        }
    }

    /// Refuses an `ADVANCE` that would run more scans of the fastest task
    /// than [`Console::max_scans`] (counted before anything runs).
    fn within_limit(&self, us: u64) -> Result<(), ConsoleError> {
        let (Some(max), Some(period)) = (self.max_scans, self.strategy.fastest_period_us()) else { return Ok(()) };
        let scans = us / period.max(1);
        if scans <= max {
            return Ok(());
        }
        let most = max.saturating_mul(period) as f64 / 1e6;
        Err(ConsoleError::new(
            Code::C0013,
            format!("this would run {scans} scans; a served plant runs at most {max} a line (ADVANCE {most}s here): advance in steps, or use linc run"),
        ))
    }

    fn scan_us(&self) -> Result<u64, ConsoleError> {
        self.strategy.fastest_period_us().ok_or_else(|| {
            ConsoleError::new(Code::C0006, "the strategy has no task to scan: use ADVANCE to move the clock")
        })
    }

    fn one(&mut self, text: &str, trace: Option<&mut Trace>) -> Result<String, ConsoleError> {
        match parse::parse(text, &duration)? {
            Command::Display(paths) => self.display(&paths),
            Command::Modify { path, value } => self.modify(&path, &value),
            Command::Force { path, value } => self.force(&path, value.as_deref()),
            Command::Forces => Ok(self.forces()),
            Command::Programs => Ok(self.programs()),
            Command::Program { block, state } => self.program(&block, state),
            Command::Sequence { block, control } => self.sequence(&block, control),
            Command::HoldStep { block, step, hold } => self.hold_step(&block, &step, hold),
            Command::ForceTrans { block, transition, force } => self.force_trans(&block, &transition, force),
            Command::Advance(us) => {
                self.within_limit(us)?;
                Ok(self.advance(us, trace))
            }
            Command::Scan => {
                let us = self.scan_us()?;
                Ok(self.advance(us, trace))
            }
            Command::Now => Ok(self.strategy.now_text()),
            Command::Save => {
                if !self.can_save {
                    return Err(ConsoleError::new(
                        Code::C0012,
                        "SAVE needs a state file: start the console with --state FILE",
                    ));
                }
                self.saved = Some(self.strategy.save_state());
                Ok(format!("state saved at {}", self.strategy.now_text()))
            }
            Command::ErrorShow => Ok(self.error_text()),
            Command::ErrorClear => {
                let had = self.strategy.clear_error();
                Ok(if had { "error cleared" } else { "no error" }.to_string())
            }
            Command::ErrorRaise { code, block } => self.raise(&code, block.as_deref()),
        }
    }

    fn store(&self) -> &Store {
        &self.strategy.store
    }

    fn addr(&self, path: &str) -> Result<Addr, ConsoleError> {
        address(self.store(), path).map_err(not_found)
    }

    fn display(&self, paths: &[String]) -> Result<String, ConsoleError> {
        let mut lines = Vec::new();
        for p in paths {
            if let Some(from) = p.strip_suffix('-') {
                let a = self.addr(from.trim())?;
                lines.extend(fields::range(self.store(), a, RANGE).into_iter().map(|(n, v)| format!("{n} = {v}")));
            } else {
                let a = self.addr(p)?;
                lines.push(format!("{p} = {}", show_value(self.store(), a)));
            }
        }
        Ok(lines.join("\n"))
    }

    /// Whether anything may set the field at `a`: a field the block
    /// computes (read-only) and alarm states are refused.
    fn settable(&self, a: Addr) -> Result<(), ConsoleError> {
        if self.store().is_readonly(a.cell) {
            let why = format!("{} is read-only: the block computes it", self.store().describe(a.cell));
            return Err(ConsoleError::new(Code::C0005, why));
        }
        if matches!(self.store().cells.get(a.cell as usize), Some(crate::store::Cell::Alarms(_))) {
            return Err(ConsoleError::new(Code::C0004, "alarm states can't be modified or forced"));
        }
        Ok(())
    }

    /// Whether `M` may write the field at `a` now: settable and not forced
    /// (a forced field keeps its forced value until released).
    pub fn modifiable(&self, a: Addr) -> Result<(), ConsoleError> {
        self.settable(a)?;
        if self.store().is_forced(a.cell) {
            let path = self.store().describe(a.cell);
            let why = format!("{path} is forced: release it first (F {path}=N)");
            return Err(ConsoleError::new(Code::C0009, why));
        }
        Ok(())
    }

    /// A value the console may write to a field: parsed by its type; a
    /// field the block computes (read-only) is refused.
    fn new_value(&self, path: &str, value: &str) -> Result<(Addr, crate::store::Cell), ConsoleError> {
        let a = self.addr(path)?;
        self.settable(a)?;
        let cell = parse_value(self.store(), a, value).map_err(|why| ConsoleError::new(Code::C0004, why))?;
        Ok((a, cell))
    }

    fn modify(&mut self, path: &str, value: &str) -> Result<String, ConsoleError> {
        let (a, cell) = self.new_value(path, value)?;
        self.modify_all(&[(a, cell)]).map_err(|(_, e)| e)?;
        Ok(format!("{path} = {}", show_value(self.store(), a)))
    }

    /// `M` of several fields at once, all or none, for a client on the wire
    /// (a ROC host's opcode 181, a Modbus write of several registers): each
    /// must be [`Console::modifiable`]; the first that is not is returned
    /// with its index and nothing is written. The cells are already of
    /// their fields' types.
    pub fn modify_all(&mut self, writes: &[(Addr, crate::store::Cell)]) -> Result<(), (usize, ConsoleError)> {
        for (i, (a, _)) in writes.iter().enumerate() {
            self.modifiable(*a).map_err(|e| (i, e))?;
        }
        for (a, cell) in writes {
            if let Some(slot) = self.strategy.store.cells.get_mut(a.cell as usize) {
                *slot = cell.clone();
            }
        }
        Ok(())
    }

    fn force(&mut self, path: &str, value: Option<&str>) -> Result<String, ConsoleError> {
        let Some(value) = value else {
            let a = self.addr(path)?;
            if !self.store().is_forced(a.cell) {
                return Err(ConsoleError::new(Code::C0009, format!("{path} is not forced")));
            }
            self.strategy.store.set_forced(a.cell, false);
            return Ok(format!("{path} released = {}", show_value(self.store(), a)));
        };
        let (a, cell) = self.new_value(path, value)?;
        let store = &mut self.strategy.store;
        if let Some(slot) = store.cells.get_mut(a.cell as usize) {
            *slot = cell;
        }
        store.set_forced(a.cell, true);
        Ok(format!("{path} = {} (forced)", show_value(self.store(), a)))
    }

    fn forces(&self) -> String {
        let s = self.store();
        let mut lines: Vec<String> =
            s.forced_cells().into_iter().map(|c| format!("forced {} = {}", s.describe(c), s.show(c))).collect();
        if lines.is_empty() {
            lines.push("no forces".to_string());
        }
        lines.push(format!("writes ignored: {}", s.ignored_writes));
        lines.join("\n")
    }

    fn programs(&self) -> String {
        let ps = self.strategy.programs();
        if ps.is_empty() {
            return "no programs".to_string();
        }
        ps.iter()
            .map(|p| format!("{} {} task {} {} {}", p.block, p.kind.name(), p.task, p.state.name(), p.position))
            .collect::<Vec<_>>()
            .join("\n")
    }

    fn block(&self, name: &str) -> Result<usize, ConsoleError> {
        self.store().db.block(name).ok_or_else(|| not_found(format!("the database has no block `{name}`")))
    }

    fn program(&mut self, name: &str, state: ProgramState) -> Result<String, ConsoleError> {
        let b = self.block(name)?;
        if !self.strategy.set_program_state(b, state) {
            return Err(ConsoleError::new(Code::C0006, format!("block `{name}` runs no program")));
        }
        let done = match state {
            ProgramState::Running => "started",
            ProgramState::Suspended => "suspended",
            ProgramState::Inactive => "stopped",
        };
        Ok(format!("{name} {done}"))
    }

    fn sequence_of(&mut self, name: &str) -> Result<(usize, &mut Sequence), ConsoleError> {
        let b = self.block(name)?;
        match self.strategy.sequence_mut(b) {
            Some(s) => Ok((b, s)),
            None => Err(ConsoleError::new(Code::C0006, format!("block `{name}` runs no sequence"))),
        }
    }

    /// RESET/STOP/HOLD/RUN, written to the SFC_CON's fields as an operator
    /// would: the sequence obeys at its next scan. STOP on a block that
    /// runs no sequence stops its program (as PSTOP).
    fn sequence(&mut self, name: &str, control: SeqControl) -> Result<String, ConsoleError> {
        let b = self.block(name)?;
        if self.strategy.sequence_mut(b).is_none() {
            if control == SeqControl::Stop {
                return self.program(name, ProgramState::Inactive);
            }
            return Err(ConsoleError::new(Code::C0006, format!("block `{name}` runs no sequence")));
        }
        let writes: &[(&str, bool)] = match control {
            SeqControl::Reset => &[("Reset", true)],
            SeqControl::Stop => &[("Stop", true)],
            SeqControl::Hold => &[("Hold", true)],
            SeqControl::Run => &[("Run", true), ("Hold", false)],
        };
        let store = &mut self.strategy.store;
        for (field, v) in writes {
            if let Some(c) = store.cell_of(b, field) {
                if !store.is_forced(c) {
                    store.cells[c as usize] = crate::store::Cell::Bool(*v);
                }
            }
        }
        let c = format!("{control:?}").to_uppercase();
        Ok(format!("{name} {c} requested (at its next scan)"))
    }

    fn hold_step(&mut self, name: &str, step: &str, hold: bool) -> Result<String, ConsoleError> {
        let (_, seq) = self.sequence_of(name)?;
        if seq.step(step).is_none() {
            return Err(ConsoleError::new(Code::C0007, format!("the sequence of `{name}` has no step `{step}`")));
        }
        let held = &mut seq.monitor.held;
        held.retain(|h| !h.eq_ignore_ascii_case(step));
        if hold {
            held.insert(step.to_string());
        }
        Ok(format!("{name}.{step} {}", if hold { "held" } else { "released" }))
    }

    fn force_trans(&mut self, name: &str, t: &str, force: TransForce) -> Result<String, ConsoleError> {
        let (_, seq) = self.sequence_of(name)?;
        if !has_transition(&seq.chart, t) {
            return Err(ConsoleError::new(Code::C0007, format!("the sequence of `{name}` has no transition `{t}`")));
        }
        let forced = &mut seq.monitor.forced;
        forced.retain(|n, _| !n.eq_ignore_ascii_case(t));
        match force {
            TransForce::Hold => forced.insert(t.to_string(), false),
            TransForce::Continue => forced.insert(t.to_string(), true),
            TransForce::Normal => None,
        };
        Ok(format!("{name}.{t} {}", format!("{force:?}").to_uppercase()))
    }

    /// Runs the tasks; the reply is the clock after. Runtime errors are
    /// kept as data for [`Console::take_failures`], which the caller reports
    /// through its renderer right after the reply.
    fn advance(&mut self, us: u64, trace: Option<&mut Trace>) -> String {
        let failed = self.strategy.run_for(us, trace);
        self.failures.extend(failed);
        self.strategy.now_text()
    }

    fn error_text(&self) -> String {
        match self.strategy.error() {
            None => "no error".to_string(),
            Some(e) => {
                let line = if e.error.line > 0 { format!(" line {}", e.error.line) } else { String::new() };
                let double = if e.double { " (double error: every program stopped)" } else { "" };
                let at = crate::strategy::trace::seconds(e.at_us);
                format!(
                    "error {} [{}] in {}{line} at {at}s: {}{double}",
                    e.number(),
                    e.error.code,
                    e.block,
                    e.error.message
                )
            }
        }
    }

    fn raise(&mut self, code: &str, block: Option<&str>) -> Result<String, ConsoleError> {
        let code = code.to_ascii_uppercase();
        let Some(&code) = RAISABLE.iter().find(|c| c.as_str() == code.as_str()) else {
            let why = format!(
                "`{code}` is not a runtime error code ({})",
                RAISABLE.iter().map(|c| c.as_str()).collect::<Vec<_>>().join(", ")
            );
            return Err(ConsoleError::new(Code::C0010, why));
        };
        let name = match block {
            Some(b) => self.store().db.blocks[self.block(b)?].name.clone(),
            None => "(console)".to_string(),
        };
        if !self.strategy.raise_error(code, &name, None) {
            let why = "the error status already holds an error (clear it first with ERRCLR)";
            return Err(ConsoleError::new(Code::C0011, why));
        }
        Ok(self.error_text())
    }
}

/// Whether every command of `line` only reads (or does not parse, and so
/// will be refused with its C-code without changing anything).
pub fn reads_only(line: &str) -> bool {
    commands(line).into_iter().all(|c| parse::parse(c, &duration).map_or(true, |c| c.reads_only()))
}

/// The commands of a line: split at `;` outside quotes (`M X.S='a;b'`),
/// blank ones dropped.
pub(crate) fn commands(line: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut start, mut quote) = (0, None);
    for (i, ch) in line.char_indices() {
        match (ch, quote) {
            ('\'' | '"', None) => quote = Some(ch),
            (c, Some(q)) if c == q => quote = None,
            (';', None) => {
                out.push(&line[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(&line[start..]);
    out.retain(|c| !c.trim().is_empty());
    out
}

fn has_transition(chart: &crate::sequence::chart::Chart, name: &str) -> bool {
    chart.transitions.iter().any(|t| t.name.eq_ignore_ascii_case(name))
        || chart.actions.iter().any(|a| match &a.body {
            crate::sequence::chart::Body::Chart(sub) => has_transition(sub, name),
            crate::sequence::chart::Body::Code(_) => false,
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_splits_at_semicolons_outside_quotes() {
        assert_eq!(commands("M X.S='a;b'; D X.S"), ["M X.S='a;b'", " D X.S"]);
        assert_eq!(commands(r#"M X.S="x;'y"; NOW"#), [r#"M X.S="x;'y""#, " NOW"]);
        assert_eq!(commands("NOW"), ["NOW"]);
    }

    #[test]
    fn reading_lines_are_told_from_writing_ones() {
        assert!(reads_only("D X.Y; P?; F?; NOW; ERR?"));
        assert!(reads_only("NOSUCH X"), "refused anyway, with C0001");
        assert!(!reads_only("D X.Y; M X.Y=1"));
        for w in ["F X.Y=1", "START B", "RESET B", "HOLDSTEP B S", "FORCETRANS B T HOLD", "ADVANCE 1s", "SCAN", "SAVE"]
        {
            assert!(!reads_only(w), "{w}");
        }
        assert!(!reads_only("ERRCLR") && !reads_only("ERRRAISE R0001"));
    }

    #[test]
    fn durations_are_st_time_constants() {
        assert_eq!(duration("10s"), Ok(10_000_000));
        assert_eq!(duration("T#1h30m"), Ok(5_400_000_000));
        assert_eq!(duration("250ms"), Ok(250_000));
        assert!(duration("0s").is_err());
        assert!(duration("367d").is_err());
        assert!(duration("soon").is_err());
        assert!(duration("é").is_err());
    }
}

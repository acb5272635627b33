//! Retentive state: what a strategy keeps through a warm start, saved as a
//! versioned, checksummed document (`docs/state.md` says what is kept and
//! why).
//!
//! The file is one header line, `{"linc-state":1,"crc32":N,"length":N}`,
//! then a JSON body of exactly `length` bytes whose CRC-32 is `crc32`. The
//! header is read within its first [`HEADER_MAX`] bytes and the body is
//! parsed only once its length and checksum hold, so a file cut short or
//! damaged is refused before anything is decoded, and nothing is allocated
//! beyond the bytes given. Restoring decodes everything first and changes
//! the strategy only when all of it fits.

use super::state_parts::{self as parts, misfit, uint};
use super::{ErrorStatus, Strategy};
use crate::object::crc32;
use crate::sequence::engine::ChartState;
use crate::sequence::Status;
use crate::store::Cell;
use crate::strategy::qualifier::QualState;
use linc_format::Code;
use serde_json::{json, Value};
use std::fmt;

/// The version of the state document this runtime writes and reads.
pub const VERSION: u64 = 1;

/// A header longer than this is not a state file's.
const HEADER_MAX: usize = 128;

/// Why a saved state was refused: E0840 damaged or cut short, E0841 another
/// version, E0842 made for another strategy.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct StateError {
    pub code: Code,
    pub message: String,
}

impl StateError {
    pub fn new(code: Code, message: impl Into<String>) -> StateError {
        StateError { code, message: message.into() }
    }
}

impl fmt::Display for StateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for StateError {}

fn damaged(what: impl fmt::Display) -> StateError {
    StateError::new(Code::E0840, format!("the state file is damaged or cut short: {what}"))
}

/// The body of a state file, once its header, length and checksum hold.
fn body(bytes: &[u8]) -> Result<&[u8], StateError> {
    let window = bytes.get(..HEADER_MAX.min(bytes.len())).unwrap_or(bytes);
    let Some(nl) = window.iter().position(|&b| b == b'\n') else {
        return Err(damaged(format!("no header line ({} bytes)", bytes.len())));
    };
    let header: Value = serde_json::from_slice(&bytes[..nl]).map_err(|_| damaged("the header is not readable"))?;
    let fields = header.as_object().filter(|o| o.len() == 3).ok_or_else(|| damaged("the header is not a state's"))?;
    let number = |k: &str| fields.get(k).and_then(Value::as_u64).ok_or_else(|| damaged("the header is not a state's"));
    let version = number("linc-state")?;
    let (crc, length) = (number("crc32")?, number("length")?);
    if version != VERSION {
        return Err(StateError::new(
            Code::E0841,
            format!("the state file is of version {version}; this linc reads version {VERSION}"),
        ));
    }
    let rest = &bytes[nl + 1..];
    if rest.len() as u64 != length {
        return Err(damaged(format!("the header says {length} bytes follow, {} do", rest.len())));
    }
    if u64::from(crc32(rest)) != crc {
        return Err(damaged("the checksum does not match"));
    }
    Ok(rest)
}

/// Everything a restore will set, decoded before anything is changed.
struct Restored {
    now_us: u64,
    start: f64,
    rng: u64,
    device_us: u64,
    tasks: Vec<u64>,
    cells: Vec<Cell>,
    error: Option<ErrorStatus>,
    halted: bool,
    members: Vec<MemberState>,
    roc: crate::roc::RocState,
}

struct MemberState {
    stopped: bool,
    resume: Option<u32>,
    locals: Vec<u32>,
    retained: Vec<u32>,
    qual: QualState,
    seq: Option<(Status, Option<u64>, ChartState)>,
}

impl Strategy {
    /// The retentive state as bytes (a versioned, checksummed document).
    pub fn save_state(&self) -> Vec<u8> {
        let mut body = serde_json::to_vec(&self.state_json()).unwrap_or_default();
        body.push(b'\n');
        let header = json!({"linc-state": VERSION, "crc32": crc32(&body), "length": body.len()});
        let mut out = header.to_string().into_bytes();
        out.push(b'\n');
        out.extend_from_slice(&body);
        out
    }

    /// Restores a warm start from `bytes`; refuses (changing nothing) a
    /// file cut short, damaged, of another version, or made for another
    /// strategy (different blocks, fields or programs).
    pub fn restore_state(&mut self, bytes: &[u8]) -> Result<(), StateError> {
        let body = body(bytes)?;
        let doc: Value = serde_json::from_slice(body).map_err(|_| damaged("the body is not readable"))?;
        let print = doc["fingerprint"].as_str().unwrap_or("");
        if print != self.fingerprint() {
            return Err(misfit(format!(
                "it was saved from a strategy of {} blocks and {} programs with other blocks, fields or programs",
                doc["blocks"], doc["programs"]
            )));
        }
        let r = self.decode(&doc)?;
        self.apply(r);
        Ok(())
    }

    /// A CRC-32 of the strategy's shape: every block with its template and
    /// fields' names and types, and every program's object file without its
    /// source file names. The file names say where the sources were read
    /// from, not what the programs are: the same plant named by another
    /// path (`./plant.json`, an absolute path) is the same strategy.
    fn fingerprint(&self) -> String {
        let db = &self.store.db;
        let mut shape = String::new();
        for (b, block) in db.blocks.iter().enumerate() {
            let t = db.block_template(b);
            shape.push_str(&format!("{}:{}(", block.name, t.name));
            for f in &t.fields {
                shape.push_str(&format!("{}:{:?},", f.name, f.ty));
            }
            shape.push_str(")\n");
        }
        for m in &self.members {
            let sum = self.sums.get(m.object).copied().unwrap_or(0);
            shape.push_str(&format!("{} {} {} {:08x}\n", db.blocks[m.block].name, m.object, m.program, sum));
        }
        format!("{:08x}", crc32(shape.as_bytes()))
    }

    fn state_json(&self) -> Value {
        let members: Vec<Value> = self.members.iter().map(member_json).collect();
        json!({
            "fingerprint": self.fingerprint(),
            "blocks": self.store.db.blocks.len(),
            "programs": self.members.len(),
            "clock": {
                "elapsed_us": self.now_us,
                "start": self.start.to_bits(),
                "rng": self.vm.clock.state,
                "device_us": self.device.last_us,
                "tasks": self.tasks.iter().map(|t| t.next_us).collect::<Vec<u64>>(),
            },
            "cells": self.store.cells.iter().map(parts::cell_json).collect::<Vec<Value>>(),
            "error": self.error.as_ref().map_or(Value::Null, parts::error_json),
            "halted": self.halted,
            "members": members,
            "roc": self.store.roc.state_json(),
        })
    }

    fn decode(&self, doc: &Value) -> Result<Restored, StateError> {
        let clock = &doc["clock"];
        let tasks = parts::array(&clock["tasks"], self.tasks.len(), "the task times")?;
        let tasks = tasks.iter().map(|t| uint(t, "a task time")).collect::<Result<Vec<u64>, _>>()?;
        let cells = parts::array(&doc["cells"], self.store.cells.len(), "the database values")?;
        let cells = cells
            .iter()
            .zip(&self.store.cells)
            .enumerate()
            .map(|(i, (v, live))| {
                let at = self.store.describe(i as u32);
                let cell = parts::cell_from(v, live, &at)?;
                let fits = match &cell {
                    Cell::Enum { idx } => usize::from(*idx) < self.store.enum_names(i as u32).len(),
                    Cell::Bits { v, width } => *width >= 16 || u32::from(*v) >> width == 0,
                    // What the loader and the VM never let into a field.
                    Cell::Real(x) => x.is_finite(),
                    Cell::Text(b) | Cell::Bseq(b) | Cell::Wstr(b) => b.len() <= crate::vm::MAX_STRING,
                    _ => true,
                };
                fits.then_some(cell).ok_or_else(|| misfit(format!("{at} holds a value out of its field's range")))
            })
            .collect::<Result<Vec<Cell>, _>>()?;
        let members = parts::array(&doc["members"], self.members.len(), "the programs")?;
        let members = members
            .iter()
            .zip(&self.members)
            .map(|(v, m)| member_from(v, m, &self.objects[m.object]))
            .collect::<Result<Vec<MemberState>, _>>()?;
        let now_us = uint(&clock["elapsed_us"], "the clock")?;
        // A task is next due after now and within one period: a schedule
        // far behind the clock would run every missed scan at once.
        let due = |(t, next): (&super::TaskRun, &u64)| *next >= now_us && *next - now_us <= t.period_us;
        if !self.tasks.iter().zip(&tasks).all(due) {
            return Err(misfit("a task is due outside the period after the clock"));
        }
        let start = f64::from_bits(uint(&clock["start"], "the clock's start")?);
        if !start.is_finite() {
            return Err(misfit("the clock's start is not a time"));
        }
        Ok(Restored {
            now_us,
            start,
            rng: uint(&clock["rng"], "the random generator")?,
            device_us: uint(&clock["device_us"], "the device clock")?,
            tasks,
            cells,
            error: parts::error_from(&doc["error"])?,
            halted: parts::boolean(&doc["halted"], "the halt flag")?,
            members,
            roc: self.store.roc.from_state_json(&doc["roc"]).map_err(misfit)?,
        })
    }

    /// Sets everything decoded; FST tables restart at step 0 (B.1.6).
    fn apply(&mut self, r: Restored) {
        self.store.cells = r.cells;
        self.store.roc = r.roc;
        self.start = r.start;
        self.set_time(r.now_us);
        self.vm.clock.state = r.rng;
        self.device.last_us = r.device_us;
        for (t, next) in self.tasks.iter_mut().zip(r.tasks) {
            t.next_us = next;
        }
        self.error = r.error;
        self.halted = r.halted;
        self.failures.clear();
        for (m, s) in self.members.iter_mut().zip(r.members) {
            m.stopped = s.stopped;
            m.qual = s.qual;
            m.act.retained = s.retained;
            m.act.set_resume_point(s.resume, s.locals);
            if let (Some(seq), Some((status, last_us, state))) = (m.seq.as_deref_mut(), s.seq) {
                seq.status = status;
                seq.last_us = last_us;
                seq.state = state;
                // The monitor's holds and forces are the console's, never retentive.
                seq.monitor = Default::default();
            }
            if let Some(f) = m.fst.as_deref_mut() {
                f.restart();
                m.act.reset();
            }
        }
    }
}

fn member_json(m: &super::Member) -> Value {
    let (resume, locals) = m.act.resume_point();
    let q = &m.qual;
    let seq = m.seq.as_deref().map_or(Value::Null, |s| {
        json!({
            "status": s.status.name(),
            "last_us": s.last_us,
            "chart": parts::chart_json(&s.chart, &s.state),
        })
    });
    json!({
        "stopped": m.stopped,
        "resume": resume,
        "locals": locals,
        "retained": m.act.retained,
        "qual": {"was": q.was, "since": q.since, "fired": q.fired, "stored": q.stored},
        "seq": seq,
    })
}

fn member_from(v: &Value, m: &super::Member, linked: &crate::Linked) -> Result<MemberState, StateError> {
    let retained = parts::u32s(&v["retained"], "a program's retained slots")?;
    if retained.len() != m.act.retained.len() {
        return Err(misfit("a program's retained slots"));
    }
    let resume = match &v["resume"] {
        Value::Null => None,
        r => Some(u32::try_from(uint(r, "a resume point")?).map_err(|_| misfit("a resume point"))?),
    };
    let locals = parts::u32s(&v["locals"], "a program's locals")?;
    if let Some(at) = resume {
        // Only where the verified code suspends, with its locals: resuming
        // anywhere else would start inside an expression, with stacks the
        // verifier never saw, or past the end of the code.
        let (program, block) = (m.act.program, m.act.block);
        let ops = linked.ops(program, block).unwrap_or_default();
        let locals_of = linked.unit(program).and_then(|u| u.blocks.get(block)).map(|b| usize::from(b.locals));
        if !crate::vm::can_resume_at(ops, at as usize) || locals_of != Some(locals.len()) {
            return Err(misfit("a program's resume point is not where its code can stop"));
        }
    }
    let q = &v["qual"];
    let qual = QualState {
        was: parts::boolean(&q["was"], "a qualifier")?,
        since: uint(&q["since"], "a qualifier")?,
        fired: parts::boolean(&q["fired"], "a qualifier")?,
        stored: parts::boolean(&q["stored"], "a qualifier")?,
    };
    let seq = match (m.seq.as_deref(), &v["seq"]) {
        (None, Value::Null) => None,
        (Some(s), j) if !j.is_null() => {
            let last_us = match &j["last_us"] {
                Value::Null => None,
                t => Some(uint(t, "a sequence's last scan")?),
            };
            Some((parts::status_from(&j["status"])?, last_us, parts::chart_from(&s.chart, &j["chart"])?))
        }
        _ => return Err(misfit("a program is a sequence in one and not the other")),
    };
    Ok(MemberState { stopped: parts::boolean(&v["stopped"], "a program's stop")?, resume, locals, retained, qual, seq })
}

#[cfg(test)]
#[path = "state_tests.rs"]
mod tests;

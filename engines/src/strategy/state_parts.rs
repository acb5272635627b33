//! The parts of a saved state (`docs/state.md`): cells, sequence charts,
//! activations and the error status, each to JSON and back. Decoding reads
//! against the live strategy's shape (a cell's kind, a chart's steps), never
//! against sizes the file claims, so a file can make nothing larger than
//! the strategy it is restored into.

use super::state::StateError;
use super::ErrorStatus;
use crate::errors::RuntimeError;
use crate::sequence::chart::{Body, Chart};
use crate::sequence::engine::ChartState;
use crate::sequence::Status;
use crate::store::{Alarms, Cell};
use linc_format::Code;
use serde_json::{json, Value};

/// A file whose checksum holds but whose content does not fit: made by
/// something else than `save_state`, or for another strategy.
pub(super) fn misfit(what: impl std::fmt::Display) -> StateError {
    StateError::new(Code::E0842, format!("the state does not fit this strategy: {what}"))
}

pub(super) fn uint(v: &Value, what: &str) -> Result<u64, StateError> {
    v.as_u64().ok_or_else(|| misfit(format!("{what} is not a whole number")))
}

pub(super) fn boolean(v: &Value, what: &str) -> Result<bool, StateError> {
    v.as_bool().ok_or_else(|| misfit(format!("{what} is not true or false")))
}

/// An array of exactly `n` elements.
pub(super) fn array<'a>(v: &'a Value, n: usize, what: &str) -> Result<&'a [Value], StateError> {
    match v.as_array() {
        Some(a) if a.len() == n => Ok(a),
        Some(a) => Err(misfit(format!("{what} has {} entries, the strategy {n}", a.len()))),
        None => Err(misfit(format!("{what} is not a list"))),
    }
}

fn bools(v: &Value, n: usize, what: &str) -> Result<Vec<bool>, StateError> {
    array(v, n, what)?.iter().map(|b| boolean(b, what)).collect()
}

fn u64s(v: &Value, n: usize, what: &str) -> Result<Vec<u64>, StateError> {
    array(v, n, what)?.iter().map(|b| uint(b, what)).collect()
}

pub(super) fn u32s(v: &Value, what: &str) -> Result<Vec<u32>, StateError> {
    let a = v.as_array().ok_or_else(|| misfit(format!("{what} is not a list")))?;
    a.iter().map(|x| uint(x, what).and_then(|n| u32::try_from(n).map_err(|_| misfit(what)))).collect()
}

fn hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

fn unhex(v: &Value, what: &str) -> Result<Vec<u8>, StateError> {
    let s = v.as_str().ok_or_else(|| misfit(format!("{what} is not text")))?;
    if s.len() % 2 != 0 {
        return Err(misfit(format!("{what} is not hexadecimal")));
    }
    (0..s.len())
        .step_by(2)
        .map(|i| s.get(i..i + 2).and_then(|d| u8::from_str_radix(d, 16).ok()))
        .collect::<Option<Vec<u8>>>()
        .ok_or_else(|| misfit(format!("{what} is not hexadecimal")))
}

/// A cell as `[kind, value…]`; REALs and deadlines by their bits, so NaN,
/// infinities and every last bit come back exactly.
pub(super) fn cell_json(c: &Cell) -> Value {
    match c {
        Cell::Real(r) => json!(["R", r.to_bits()]),
        Cell::Int(i) => json!(["I", i]),
        Cell::Bool(b) => json!(["B", b]),
        Cell::Bits { v, width } => json!(["W", v, width]),
        Cell::Enum { idx } => json!(["E", idx]),
        Cell::Text(t) => json!(["T", hex(t)]),
        Cell::Bseq(t) => json!(["Q", hex(t)]),
        Cell::Wstr(t) => json!(["U", hex(t)]),
        Cell::Alarms(a) => {
            let until: Vec<u64> = a.until.iter().map(|u| u.to_bits()).collect();
            json!(["A", a.active, until, a.all_until.to_bits()])
        }
    }
}

/// The saved value of a cell of the same kind as `live`.
pub(super) fn cell_from(v: &Value, live: &Cell, at: &str) -> Result<Cell, StateError> {
    let a = v.as_array().ok_or_else(|| misfit(format!("{at} is not a value")))?;
    let kind = a.first().and_then(Value::as_str).unwrap_or("");
    let arg = |i: usize| a.get(i).unwrap_or(&Value::Null);
    let small = |i: usize, max: u64| uint(arg(i), at).ok().filter(|&n| n <= max);
    let cell = match (kind, live) {
        ("R", Cell::Real(_)) => small(1, u64::from(u32::MAX)).map(|b| Cell::Real(f32::from_bits(b as u32))),
        ("I", Cell::Int(_)) => arg(1).as_i64().and_then(|i| i32::try_from(i).ok()).map(Cell::Int),
        ("B", Cell::Bool(_)) => arg(1).as_bool().map(Cell::Bool),
        ("W", Cell::Bits { width, .. }) if small(2, 255) == Some(u64::from(*width)) => {
            small(1, u64::from(u16::MAX)).map(|v| Cell::Bits { v: v as u16, width: *width })
        }
        ("E", Cell::Enum { .. }) => small(1, u64::from(u16::MAX)).map(|idx| Cell::Enum { idx: idx as u16 }),
        ("T", Cell::Text(_)) => Some(Cell::Text(unhex(arg(1), at)?)),
        ("Q", Cell::Bseq(_)) => Some(Cell::Bseq(unhex(arg(1), at)?)),
        ("U", Cell::Wstr(_)) => Some(Cell::Wstr(unhex(arg(1), at)?)),
        ("A", Cell::Alarms(live)) => Some(alarms_from(a, live, at)?),
        _ => None,
    };
    cell.ok_or_else(|| misfit(format!("{at} is not a value of its field's type")))
}

fn alarms_from(a: &[Value], live: &Alarms, at: &str) -> Result<Cell, StateError> {
    let n = live.names.len();
    let none = Value::Null;
    let active = bools(a.get(1).unwrap_or(&none), n, at)?;
    let until = u64s(a.get(2).unwrap_or(&none), n, at)?.into_iter().map(f64::from_bits).collect();
    let all_until = f64::from_bits(uint(a.get(3).unwrap_or(&none), at)?);
    Ok(Cell::Alarms(Box::new(Alarms { names: live.names.clone(), active, until, all_until })))
}

/// A chart's live state; chart actions' charts nested as the chart nests them.
pub(super) fn chart_json(chart: &Chart, st: &ChartState) -> Value {
    let children: Vec<Value> = chart
        .actions
        .iter()
        .enumerate()
        .map(|(a, action)| match (&action.body, st.child(a)) {
            (Body::Chart(sub), Some(c)) => chart_json(sub, c),
            _ => Value::Null,
        })
        .collect();
    json!({
        "active": st.active, "elapsed": st.elapsed, "e_fired": st.e_fired,
        "stored": st.stored, "pending": st.pending_start, "children": children,
    })
}

/// The recursion follows the live chart's nesting, not the file's.
pub(super) fn chart_from(chart: &Chart, v: &Value) -> Result<ChartState, StateError> {
    let mut st = ChartState::start(chart);
    let (steps, actions) = (chart.steps.len(), chart.actions.len());
    st.active = bools(&v["active"], steps, "a chart's active steps")?;
    st.elapsed = u64s(&v["elapsed"], steps, "a chart's step times")?;
    let fired = array(&v["e_fired"], steps, "a chart's E actions")?;
    for (i, (f, s)) in fired.iter().zip(&chart.steps).enumerate() {
        st.e_fired[i] = bools(f, s.assocs.len(), "a step's E actions")?;
    }
    st.stored = bools(&v["stored"], actions, "a chart's stored actions")?;
    st.pending_start = boolean(&v["pending"], "a chart's start")?;
    let children = array(&v["children"], actions, "a chart's chart actions")?;
    for (a, (c, action)) in children.iter().zip(&chart.actions).enumerate() {
        st.children[a] = match (&action.body, c) {
            (_, Value::Null) => None,
            (Body::Chart(sub), c) => Some(chart_from(sub, c)?),
            (Body::Code(_), _) => return Err(misfit("a code action has a chart")),
        };
    }
    Ok(st)
}

pub(super) fn status_from(v: &Value) -> Result<Status, StateError> {
    let all = [Status::Reset, Status::Running, Status::Held, Status::Stopped, Status::Error];
    all.into_iter().find(|s| v.as_str() == Some(s.name())).ok_or_else(|| misfit("a sequence's status"))
}

pub(super) fn error_json(e: &ErrorStatus) -> Value {
    let r = &e.error;
    json!({
        "code": r.code, "message": r.message, "action": r.action, "file": r.file, "line": r.line, "col": r.col,
        "block": e.block, "at_us": e.at_us, "double": e.double,
    })
}

pub(super) fn error_from(v: &Value) -> Result<Option<ErrorStatus>, StateError> {
    if v.is_null() {
        return Ok(None);
    }
    let text = |k: &str| v[k].as_str().map(str::to_string).ok_or_else(|| misfit("the error status"));
    let small = |k: &str| uint(&v[k], "the error status").map(|n| n.min(u64::from(u32::MAX)) as u32);
    let code = v["code"].as_str().unwrap_or("");
    let code = super::RUNTIME_CODES.iter().find(|c| **c == code).copied().unwrap_or(Code::R0099);
    let error = RuntimeError {
        code,
        message: text("message")?,
        action: text("action")?,
        file: text("file")?,
        line: small("line")?,
        col: small("col")?,
    };
    let (block, at_us, double) =
        (text("block")?, uint(&v["at_us"], "the error time")?, boolean(&v["double"], "the error status")?);
    Ok(Some(ErrorStatus { error, block, at_us, double }))
}

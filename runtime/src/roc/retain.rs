//! The device's logs and history archives in a saved state
//! (`docs/state.md`): a ROC keeps them through a warm start. The points'
//! configuration comes from the database, so only what the logger and the
//! FSTs wrote is saved; archives are read back at the live sizes only.

use super::history::Entry;
use super::{Log, LogEntry, RocState};
use serde_json::{json, Value};
use std::collections::VecDeque;

/// Why a saved device state does not fit (the strategy turns it into E0842).
pub type Misfit = String;

fn entries_json(e: &[Entry]) -> Value {
    Value::Array(e.iter().map(|e| json!([e.stamp, e.value.to_bits()])).collect())
}

fn entries_from(v: &Value, live: &[Entry], what: &str) -> Result<Vec<Entry>, Misfit> {
    let a = v.as_array().filter(|a| a.len() == live.len()).ok_or_else(|| format!("{what} has another size"))?;
    a.iter()
        .map(|e| {
            let stamp = e.get(0).and_then(Value::as_i64);
            let bits = e.get(1).and_then(Value::as_u64).and_then(|b| u32::try_from(b).ok());
            match (stamp, bits) {
                (Some(stamp), Some(b)) => Ok(Entry { stamp, value: f32::from_bits(b) }),
                _ => Err(format!("{what} holds an entry that is not one")),
            }
        })
        .collect()
}

fn log_json(l: &Log) -> Value {
    let entries: Vec<Value> = l.entries.iter().map(|e| json!([e.time, e.text, e.value.to_bits(), e.source])).collect();
    json!({"total": l.total, "entries": entries})
}

fn log_from(v: &Value, live: &Log, what: &str) -> Result<Log, Misfit> {
    let bad = || format!("the {what} log is not one");
    let a = v["entries"].as_array().filter(|a| a.len() <= live.capacity).ok_or_else(bad)?;
    let mut entries = VecDeque::with_capacity(a.len());
    for e in a {
        let time = e.get(0).and_then(Value::as_i64).ok_or_else(bad)?;
        let text = e.get(1).and_then(Value::as_str).ok_or_else(bad)?;
        let value = e.get(2).and_then(Value::as_u64).and_then(|b| u32::try_from(b).ok()).ok_or_else(bad)?;
        let source = e.get(3).and_then(Value::as_str).ok_or_else(bad)?;
        entries.push_back(LogEntry::new(time, text, f32::from_bits(value), source));
    }
    let total = v["total"].as_u64().filter(|&t| t >= entries.len() as u64).ok_or_else(bad)?;
    Ok(Log { capacity: live.capacity, entries, total })
}

impl RocState {
    /// The logs and every point's archives and write positions.
    pub fn state_json(&self) -> Value {
        let points: Vec<Value> = self
            .history
            .points
            .iter()
            .map(|p| {
                json!({
                    "periodic": entries_json(&p.periodic), "daily": entries_json(&p.daily),
                    "minute": entries_json(&p.minute),
                    "next_periodic": p.next_periodic, "next_daily": p.next_daily,
                })
            })
            .collect();
        json!({
            "alarms": log_json(&self.alarms), "events": log_json(&self.events),
            "points": points, "last": self.history.last,
        })
    }

    /// The state `v` saved, read against this one's configuration.
    pub fn from_state_json(&self, v: &Value) -> Result<RocState, Misfit> {
        let mut out = self.clone();
        out.alarms = log_from(&v["alarms"], &self.alarms, "alarm")?;
        out.events = log_from(&v["events"], &self.events, "event")?;
        let points =
            v["points"].as_array().filter(|a| a.len() == self.history.points.len()).ok_or("the history points")?;
        for (p, s) in out.history.points.iter_mut().zip(points) {
            p.periodic = entries_from(&s["periodic"], &p.periodic, "a periodic archive")?;
            p.daily = entries_from(&s["daily"], &p.daily, "a daily archive")?;
            p.minute = entries_from(&s["minute"], &p.minute, "a minute archive")?;
            let index = |k: &str, n: usize| {
                s[k].as_u64().map(|i| i as usize).filter(|&i| i < n.max(1)).ok_or(format!("a point's {k}"))
            };
            p.next_periodic = index("next_periodic", p.periodic.len())?;
            p.next_daily = index("next_daily", p.daily.len())?;
        }
        out.history.last = match &v["last"] {
            Value::Null => None,
            t => Some(t.as_i64().ok_or("the logger's clock")?),
        };
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::db::Database;

    fn state() -> RocState {
        let db = Database::from_json(
            r#"{"blocks": {"HIST 9": {"type": "HIST", "values": {"ARCHTYP": "FSTDATA", "PERIODIC": 35}}}}"#,
        )
        .expect("database");
        RocState::new(&db)
    }

    #[test]
    fn logs_and_archives_come_back_as_they_were() {
        let mut s = state();
        for i in 0..3 {
            s.alarms.push(LogEntry::new(1_699_920_000 + i, "HIGH LEVEL!", f32::NAN, "FST 1"));
        }
        s.events.push(LogEntry::new(1_699_920_060, "PUMP ON", 52.5, "FST 2"));
        assert_eq!(s.history.write(9.0, 3.0, Some(12.5), 1_699_920_000), Ok(4.0));
        let fresh = state();
        let back = fresh.from_state_json(&s.state_json()).expect("fits");
        // NaN is not equal to itself: compare the saved forms, then a value.
        assert_eq!(back.state_json(), s.state_json());
        assert_eq!(back.alarms.total(), 3);
        assert_eq!(back.history.point(9).map(|p| p.archive(super::super::Archive::Periodic)[3].value), Some(12.5));
        assert_eq!(back.events.iter().next().map(|e| e.text.as_str()), Some("PUMP ON"));
    }

    #[test]
    fn archives_of_another_size_do_not_fit() {
        let mut saved = state().state_json();
        saved["points"][0]["periodic"] = json!([[0, 0]]);
        assert!(state().from_state_json(&saved).is_err());
        let mut saved = state().state_json();
        saved["alarms"]["entries"] = Value::Array(vec![json!([0, "X", 0, "F"]); 241]);
        assert!(state().from_state_json(&saved).is_err(), "more entries than the log holds");
    }
}

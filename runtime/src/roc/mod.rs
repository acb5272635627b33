//! The ROC device's own state that FST tables read and write
//! (`docs/fst-history.md`): the alarm and event logs (ALM, EVT), the
//! history archives (RDB, WDB, WTM, DHV … PIN) with the logger that
//! fills CURRENT points, and the clock functions (GTE, DWK, MND).
//!
//! Pure data and functions: nothing here runs a table or touches the
//! store. The VM calls in with the device clock (POSIX seconds, no time
//! zone) and the values it resolved; errors are [`HistError`] values with
//! code `R0011`, on which the FST halts.

mod clock;
mod history;
mod log;
mod logger;
mod retain;
#[cfg(test)]
mod tests;

pub use clock::{civil, day_of_week, gte, iso, minutes_since_midnight, Civil, DAY};
pub use history::{
    split_archpt, Archive, ArchiveType, Entry, HistError, HistFn, History, Point, DEFAULT_DAILY, DEFAULT_PERIOD,
    DEFAULT_PERIODIC, HALT, MAX_DAILY, MAX_PERIODIC, MAX_POINTS, MINUTE_ENTRIES,
};
pub use log::{Log, LogEntry, ALARM_LOG, EVENT_LOG, MESSAGE_CHARS};

use crate::db::Database;
use serde_json::{json, Value};

/// Everything a ROC device keeps for its FSTs besides the database values.
#[derive(Clone, Debug, PartialEq)]
pub struct RocState {
    pub alarms: Log,
    pub events: Log,
    pub history: History,
}

impl RocState {
    /// Empty logs and the history points the database configures.
    pub fn new(db: &Database) -> Self {
        RocState { alarms: Log::new(ALARM_LOG), events: Log::new(EVENT_LOG), history: History::from_db(db) }
    }

    /// For `--out`: `{"alarms": log, "events": log, "history": {"points": [...]}}`.
    pub fn to_json(&self) -> Value {
        json!({"alarms": self.alarms.to_json(), "events": self.events.to_json(), "history": self.history.to_json()})
    }
}

/// A REAL for JSON: the shortest decimal that reads back to the same f32
/// (as `--out` prints block values), `null` when not finite.
fn real(r: f32) -> Value {
    match crate::text::format_real(r).parse::<f64>() {
        Ok(x) if x.is_finite() => json!(x),
        _ => Value::Null,
    }
}

//! TEMPORARY stub of the ROC device state (being written on branch roc-state).
#![allow(dead_code, unused_variables)]
use crate::db::Database;

pub const ALARM_LOG: usize = 240;
pub const EVENT_LOG: usize = 240;

#[derive(Clone, Debug, PartialEq)]
pub struct LogEntry {
    pub time: i64,
    pub text: String,
    pub value: f32,
    pub source: String,
}

#[derive(Clone, Debug, Default)]
pub struct Log {
    entries: std::collections::VecDeque<LogEntry>,
}
impl Log {
    pub fn new(cap: usize) -> Log {
        Log::default()
    }
    pub fn push(&mut self, e: LogEntry) {
        self.entries.push_back(e);
    }
    pub fn iter(&self) -> impl Iterator<Item = &LogEntry> {
        self.entries.iter()
    }
    pub fn len(&self) -> usize {
        self.entries.len()
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HistFn {
    Rdb,
    Dhv,
    Dht,
    Phv,
    Pht,
    Mhv,
    Dis,
    Din,
    Pis,
    Pin,
    Gte,
}
impl HistFn {
    pub fn from_u8(b: u8) -> Option<HistFn> {
        use HistFn::*;
        [Rdb, Dhv, Dht, Phv, Pht, Mhv, Dis, Din, Pis, Pin, Gte].get(usize::from(b)).copied()
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct HistError {
    pub code: &'static str,
    pub message: String,
}

#[derive(Clone, Debug, Default)]
pub struct History {}
impl History {
    pub fn from_db(db: &Database) -> History {
        History {}
    }
    pub fn write(&mut self, hp: f32, idx: f32, value: Option<f32>, now: i64) -> Result<f32, HistError> {
        Err(HistError { code: "R0011", message: "stub".into() })
    }
    pub fn read(&self, f: HistFn, arg1: f32, arg2: f32) -> Result<(f32, f32), HistError> {
        Err(HistError { code: "R0011", message: "stub".into() })
    }
    pub fn sample(&mut self, now: i64, value_of: &mut dyn FnMut(&str) -> Option<f32>) {}
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::Value::Null
    }
}

pub fn day_of_week(now: i64) -> f32 {
    0.0
}
pub fn minutes_since_midnight(now: i64) -> f32 {
    0.0
}

#[derive(Clone, Debug, Default)]
pub struct RocState {
    pub alarms: Log,
    pub events: Log,
    pub history: History,
}
impl RocState {
    pub fn new(db: &Database) -> RocState {
        RocState::default()
    }
    pub fn to_json(&self) -> serde_json::Value {
        serde_json::Value::Null
    }
}

//! The alarm and event logs that ALM and EVT write (Table B-15).
//!
//! The device gives each log a fixed amount of memory and the manual warns
//! that ALM and EVT "can quickly overfill" it; linc models that as a
//! bounded circular log that forgets its oldest entry when full, and
//! counts every entry ever logged so a report can say how many were lost.

use super::real;
use serde_json::{json, Value};
use std::collections::VecDeque;

/// Entries the alarm log holds (the ROC800's alarm log size).
pub const ALARM_LOG: usize = 240;
/// Entries the event log holds.
pub const EVENT_LOG: usize = 240;
/// Characters of an ALM or EVT message that are kept.
pub const MESSAGE_CHARS: usize = 10;

/// One logged alarm or event.
#[derive(Clone, Debug, PartialEq)]
pub struct LogEntry {
    /// The device clock when it was logged, POSIX seconds.
    pub time: i64,
    /// The message: at most [`MESSAGE_CHARS`] characters once logged.
    pub text: String,
    /// ARGUMENT2's value.
    pub value: f32,
    /// The FST block that logged it.
    pub source: String,
}

impl LogEntry {
    /// An entry whose message is cut to its first [`MESSAGE_CHARS`]
    /// characters (characters, not bytes: a message is never cut inside a
    /// UTF-8 sequence).
    pub fn new(time: i64, text: &str, value: f32, source: &str) -> Self {
        LogEntry { time, text: text.chars().take(MESSAGE_CHARS).collect(), value, source: source.to_string() }
    }

    fn to_json(&self) -> Value {
        json!({
            "time": super::clock::iso(self.time),
            "stamp": self.time,
            "text": self.text,
            "value": real(self.value),
            "source": self.source,
        })
    }
}

/// A bounded circular log.
#[derive(Clone, Debug, PartialEq)]
pub struct Log {
    pub(super) capacity: usize,
    pub(super) entries: VecDeque<LogEntry>,
    pub(super) total: u64,
}

impl Log {
    /// A log that keeps the last `capacity` entries (0 keeps none but
    /// still counts them).
    pub fn new(capacity: usize) -> Self {
        Log { capacity, entries: VecDeque::new(), total: 0 }
    }

    /// Logs an entry, dropping the oldest one when the log is full. The
    /// message is cut to [`MESSAGE_CHARS`] characters here too, so the
    /// log holds to that whichever way the entry was built.
    pub fn push(&mut self, mut entry: LogEntry) {
        self.total = self.total.saturating_add(1);
        if self.capacity == 0 {
            return;
        }
        if let Some((cut, _)) = entry.text.char_indices().nth(MESSAGE_CHARS) {
            entry.text.truncate(cut);
        }
        if self.entries.len() >= self.capacity {
            self.entries.pop_front();
        }
        self.entries.push_back(entry);
    }

    /// The entries held, oldest first.
    pub fn iter(&self) -> impl Iterator<Item = &LogEntry> {
        self.entries.iter()
    }

    /// The `i`-th entry held, oldest first.
    pub fn get(&self, i: usize) -> Option<&LogEntry> {
        self.entries.get(i)
    }

    pub fn len(&self) -> usize {
        self.entries.len()
    }

    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    pub fn capacity(&self) -> usize {
        self.capacity
    }

    /// Entries ever logged, including those since dropped.
    pub fn total(&self) -> u64 {
        self.total
    }

    /// Entries logged and since dropped for want of room.
    pub fn dropped(&self) -> u64 {
        self.total - self.entries.len() as u64
    }

    /// `{"capacity", "total", "dropped", "entries": [oldest first]}`.
    pub fn to_json(&self) -> Value {
        json!({
            "capacity": self.capacity,
            "total": self.total,
            "dropped": self.dropped(),
            "entries": self.entries.iter().map(LogEntry::to_json).collect::<Vec<_>>(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_full_log_drops_its_oldest_entry() {
        let mut log = Log::new(ALARM_LOG);
        for i in 0..240 {
            log.push(LogEntry::new(i, "HIGH LEVEL", i as f32, "FST 1"));
        }
        assert_eq!((log.len(), log.total(), log.dropped()), (240, 240, 0));
        assert_eq!(log.iter().next().map(|e| e.time), Some(0));
        log.push(LogEntry::new(240, "HIGH LEVEL", 240.0, "FST 1"));
        assert_eq!((log.len(), log.total(), log.dropped()), (240, 241, 1));
        let times: Vec<i64> = log.iter().map(|e| e.time).collect();
        assert_eq!(times.first(), Some(&1), "entry 0 is gone");
        assert_eq!(times.last(), Some(&240), "oldest first, newest last");
    }

    #[test]
    fn messages_keep_their_first_ten_characters() {
        let e = LogEntry::new(0, "PUMP 1 FAILED TO START", 1.0, "FST 2");
        assert_eq!(e.text, "PUMP 1 FAI");
        assert_eq!(LogEntry::new(0, "ÄÖÜäöüßéèêë", 0.0, "").text, "ÄÖÜäöüßéèê", "characters, not bytes");
        let mut log = Log::new(2);
        log.push(LogEntry { time: 0, text: "0123456789ABC".into(), value: 0.0, source: "FST 1".into() });
        assert_eq!(log.iter().next().map(|e| e.text.as_str()), Some("0123456789"));
    }

    #[test]
    fn a_log_of_no_capacity_only_counts() {
        let mut log = Log::new(0);
        log.push(LogEntry::new(5, "X", 0.0, "FST 1"));
        assert_eq!((log.len(), log.total(), log.dropped()), (0, 1, 1));
    }

    #[test]
    fn the_json_has_iso_times_and_shortest_reals() {
        let mut log = Log::new(EVENT_LOG);
        log.push(LogEntry::new(1_700_000_000, "OPENED", 0.1, "FST 1"));
        let j = log.to_json();
        assert_eq!(j["total"], 1);
        assert_eq!(j["entries"][0]["time"], "2023-11-14T22:13:20");
        assert_eq!(j["entries"][0]["value"], 0.1, "0.1f32 prints as 0.1, not 0.10000000149011612");
        assert_eq!(j["entries"][0]["source"], "FST 1");
    }
}

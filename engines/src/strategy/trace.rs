//! The strategy trace: one JSON object per line for every change of a
//! field's value, with the simulated time, task and program that made it.
//! Writes that leave a value as it was are not recorded, so a trace shows
//! what happened, and the same run always gives the same bytes.

use crate::store::Store;
use std::io::Write;

/// Writes trace lines, remembering each field's last value to give the old one.
pub struct Trace<'w> {
    out: &'w mut dyn Write,
    shown: Vec<Option<String>>,
    failed: Option<std::io::Error>,
}

/// Seconds of simulated time as a JSON number (0.3, not 0.30000000000000004).
pub fn seconds(us: u64) -> serde_json::Value {
    serde_json::json!(us as f64 / 1e6)
}

impl<'w> Trace<'w> {
    pub fn new(out: &'w mut dyn Write, store: &Store) -> Trace<'w> {
        let shown = (0..store.cells.len() as u32).map(|c| Some(store.show(c))).collect();
        Trace { out, shown, failed: None }
    }

    /// The old and new text of `cell` if its value changed since it was
    /// last seen (the new one is remembered).
    fn changed(&mut self, store: &Store, cell: u32) -> Option<(String, String)> {
        let new = store.show(cell);
        let slot = self.shown.get_mut(cell as usize)?;
        if slot.as_deref() == Some(new.as_str()) {
            return None;
        }
        Some((slot.replace(new.clone()).unwrap_or_default(), new))
    }

    /// Records `cell` if its value changed since it was last seen.
    pub fn write(&mut self, store: &Store, now_us: u64, task: u8, program: &str, cell: u32) {
        let Some((old, new)) = self.changed(store, cell) else { return };
        let line = serde_json::json!({
            "time": seconds(now_us), "task": task, "program": program,
            "field": store.describe(cell), "old": old, "new": new,
        });
        self.line(&line);
    }

    /// Records a write by a client on the wire (`roc 127.0.0.1:51000`) if
    /// it changed the value: the client's address where a program's
    /// write has its task and program.
    pub fn client_write(&mut self, store: &Store, now_us: u64, client: &str, cell: u32) {
        let Some((old, new)) = self.changed(store, cell) else { return };
        let line = serde_json::json!({
            "time": seconds(now_us), "client": client, "field": store.describe(cell), "old": old, "new": new,
        });
        self.line(&line);
    }

    /// Records a client's write that was refused, and why (`forced`,
    /// `read-only`): nothing changed, but the attempt is part of the story.
    pub fn client_refused(&mut self, store: &Store, now_us: u64, client: &str, cell: u32, why: &str) {
        let line = serde_json::json!({
            "time": seconds(now_us), "client": client, "field": store.describe(cell), "refused": why,
        });
        self.line(&line);
    }

    /// Records a step activated or deactivated, a transition fired or an
    /// action run by a sequence.
    pub fn sequence_event(&mut self, e: crate::sequence::engine::Event, now_us: u64, task: u8, program: &str) {
        use crate::sequence::engine::Event;
        let (key, name, active) = match e {
            Event::Activated(s) => ("step", s, Some(true)),
            Event::Deactivated(s) => ("step", s, Some(false)),
            Event::Fired(t) => ("fired", t, None),
            Event::Ran(a) => ("ran", a, None),
        };
        let mut line = serde_json::json!({ "time": seconds(now_us), "task": task, "program": program, key: name });
        if let (Some(v), Some(obj)) = (active, line.as_object_mut()) {
            obj.insert("active".into(), serde_json::Value::Bool(v));
        }
        self.line(&line);
    }

    /// Records any other event (an error entered or cleared).
    pub fn line(&mut self, v: &serde_json::Value) {
        if self.failed.is_none() {
            if let Err(e) = writeln!(self.out, "{v}") {
                self.failed = Some(e);
            }
        }
    }

    /// The first write error, if any (reported once, at the end).
    pub fn finish(mut self) -> std::io::Result<()> {
        match self.failed.take() {
            Some(e) => Err(e),
            None => self.out.flush(),
        }
    }
}

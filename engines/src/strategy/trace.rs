//! The strategy trace: one JSON object per line for every change of a
//! field's value, with the simulated time, task and program that made it.
//! Writes that leave a value as it was are not recorded, so a trace shows
//! what happened, and the same run always gives the same bytes.

use crate::store::{Cell, Store};
use std::io::Write;

/// Writes trace lines, remembering each field's last value to give the old one.
pub struct Trace<'w> {
    /// Where lines go: a borrowed writer, or one the trace owns (a file
    /// committed when the trace is finished).
    out: Box<dyn Write + 'w>,
    /// Each cell as it was last seen: a write that leaves the bits as they
    /// were is dismissed without formatting the value, which is most
    /// writes of a running strategy; the old text of a change is shown
    /// from it.
    seen: Vec<Cell>,
    /// The line being written, kept to spare an allocation per line.
    buf: Vec<u8>,
    failed: Option<std::io::Error>,
}

/// Whether two cells hold the same bits, so that they show the same text
/// (`==` on a REAL calls 0.0 and -0.0 equal, which show differently).
fn identical(a: &Cell, b: &Cell) -> bool {
    match (a, b) {
        (Cell::Real(x), Cell::Real(y)) => x.to_bits() == y.to_bits(),
        (Cell::Real(_), _) | (_, Cell::Real(_)) => false,
        _ => a == b,
    }
}

/// Seconds of simulated time as a JSON number (0.3, not 0.30000000000000004).
pub fn seconds(us: u64) -> serde_json::Value {
    serde_json::json!(us as f64 / 1e6)
}

impl<'w> Trace<'w> {
    pub fn new(out: impl Write + 'w, store: &Store) -> Trace<'w> {
        Trace { out: Box::new(out), seen: store.cells.clone(), buf: Vec::new(), failed: None }
    }

    /// The old and new text of `cell` if its value changed since it was
    /// last seen (the new one is remembered). Bits that differ but show
    /// the same (two NaNs) are no change.
    fn changed(&mut self, store: &Store, cell: u32) -> Option<(String, String)> {
        let now = store.cells.get(cell as usize)?;
        let seen = self.seen.get_mut(cell as usize)?;
        if identical(seen, now) {
            return None;
        }
        let (old, new) = (store.show_as(cell, seen), store.show_as(cell, now));
        seen.clone_from(now);
        (old != new).then_some((old, new))
    }

    /// Records `cell` if its value changed since it was last seen. The
    /// line is written field by field, in the order and bytes a
    /// `serde_json::Value` of it would print, but without building one: a
    /// long run writes one per change.
    pub fn write(&mut self, store: &Store, now_us: u64, task: u8, program: &str, cell: u32) {
        let Some((old, new)) = self.changed(store, cell) else { return };
        let mut b = self.head(now_us, task, program);
        b.extend_from_slice(b",\"field\":");
        let _ = serde_json::to_writer(&mut b, &store.describe(cell));
        b.extend_from_slice(b",\"old\":");
        let _ = serde_json::to_writer(&mut b, &old);
        b.extend_from_slice(b",\"new\":");
        let _ = serde_json::to_writer(&mut b, &new);
        b.extend_from_slice(b"}\n");
        self.end(b);
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
        let mut b = self.head(now_us, task, program);
        let _ = write!(b, ",\"{key}\":");
        let _ = serde_json::to_writer(&mut b, name);
        if let Some(v) = active {
            let _ = write!(b, ",\"active\":{v}");
        }
        b.extend_from_slice(b"}\n");
        self.end(b);
    }

    /// Records a step an FST table executed: its number and command
    /// (`step`), and RR and CF after it.
    pub fn fst_step(&mut self, now_us: u64, task: u8, program: &str, step: (u16, &str), rr: f64, cf: i32) {
        let mut b = self.head(now_us, task, program);
        let _ = write!(b, ",\"step\":{},\"cmd\":", step.0);
        let _ = serde_json::to_writer(&mut b, step.1);
        b.extend_from_slice(b",\"RR\":");
        let _ = serde_json::to_writer(&mut b, &rr);
        let _ = writeln!(b, ",\"CF\":{cf}}}");
        self.end(b);
    }

    /// The buffer, holding the start of a line every program's event has:
    /// `{"time":…,"task":…,"program":…`.
    fn head(&mut self, now_us: u64, task: u8, program: &str) -> Vec<u8> {
        let mut b = self.start();
        b.extend_from_slice(b"{\"time\":");
        let _ = serde_json::to_writer(&mut b, &(now_us as f64 / 1e6));
        let _ = write!(b, ",\"task\":{task},\"program\":");
        let _ = serde_json::to_writer(&mut b, program);
        b
    }

    /// Records any other event (an error entered or cleared).
    pub fn line(&mut self, v: &serde_json::Value) {
        let mut b = self.start();
        let _ = serde_json::to_writer(&mut b, v);
        b.push(b'\n');
        self.end(b);
    }

    /// The line buffer, empty, to write a line into.
    fn start(&mut self) -> Vec<u8> {
        let mut b = std::mem::take(&mut self.buf);
        b.clear();
        b
    }

    /// Writes the line in `b` whole, so that a sink sees one write per
    /// line, and keeps the buffer for the next.
    fn end(&mut self, b: Vec<u8>) {
        if self.failed.is_none() {
            if let Err(e) = self.out.write_all(&b) {
                self.failed = Some(e);
            }
        }
        self.buf = b;
    }

    /// The first write error, if any (reported once, at the end).
    pub fn finish(mut self) -> std::io::Result<()> {
        match self.failed.take() {
            Some(e) => Err(e),
            None => self.out.flush(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::db::Database;

    /// A store of one FST block, and the cell of its R1.
    fn store() -> (Store, u32) {
        let db = r#"{ "device": "ROC800", "blocks": { "FST 1": { "type": "FST" } } }"#;
        let s = Store::new(Database::from_json(db).expect("database"));
        let cell = s.db.block("FST 1").and_then(|b| s.cell_of(b, "R1")).expect("R1");
        (s, cell)
    }

    /// The lines written field by field are the bytes the `Value` of each
    /// prints, escapes and awkward times included.
    #[test]
    fn lines_are_the_json_values_they_stand_for() {
        let (mut s, cell) = store();
        let mut out = Vec::new();
        let mut t = Trace::new(&mut out, &s);
        s.cells[cell as usize] = Cell::Real(2.5);
        t.write(&s, 300_000, 2, "a \"quoted\"\\ name\n", cell);
        t.sequence_event(crate::sequence::engine::Event::Activated("S\t1"), 1_000_000, 0, "seq");
        t.sequence_event(crate::sequence::engine::Event::Fired("T1"), 7, 0, "seq");
        t.fst_step(100_000, 1, "FST 1", (3, "SAV"), 0.1, -2);
        t.fst_step(200_000, 1, "FST 1", (4, "\"x\""), f64::NAN, 0);
        t.finish().expect("written");
        let want = [
            serde_json::json!({ "time": 0.3, "task": 2, "program": "a \"quoted\"\\ name\n",
                "field": "FST 1.R1", "old": "0.0", "new": "2.5" }),
            serde_json::json!({ "time": 1.0, "task": 0, "program": "seq", "step": "S\t1", "active": true }),
            serde_json::json!({ "time": 0.000007, "task": 0, "program": "seq", "fired": "T1" }),
            serde_json::json!({ "time": 0.1, "task": 1, "program": "FST 1", "step": 3, "cmd": "SAV", "RR": 0.1, "CF": -2 }),
            serde_json::json!({ "time": 0.2, "task": 1, "program": "FST 1", "step": 4, "cmd": "\"x\"", "RR": f64::NAN, "CF": 0 }),
        ];
        let want: String = want.iter().map(|v| format!("{v}\n")).collect();
        assert_eq!(String::from_utf8(out).expect("UTF-8"), want);
    }

    /// A write that leaves the bits as they were is no change; 0.0 to -0.0
    /// is one, though `==` calls them equal.
    #[test]
    fn a_change_is_a_change_of_bits() {
        let (mut s, cell) = store();
        let mut out = Vec::new();
        let mut t = Trace::new(&mut out, &s);
        t.write(&s, 0, 0, "p", cell);
        s.cells[cell as usize] = Cell::Real(-0.0);
        t.write(&s, 1, 0, "p", cell);
        t.write(&s, 2, 0, "p", cell);
        s.cells[cell as usize] = Cell::Real(0.0);
        t.write(&s, 3, 0, "p", cell);
        t.finish().expect("written");
        let text = String::from_utf8(out).expect("UTF-8");
        let times: Vec<_> = text.lines().map(|l| serde_json::from_str::<serde_json::Value>(l).expect("JSON")).collect();
        let changes: Vec<_> = times.iter().map(|v| (v["time"].clone(), v["new"].clone())).collect();
        assert_eq!(changes, [(serde_json::json!(1e-6), "-0.0".into()), (serde_json::json!(3e-6), "0.0".into())]);
    }
}

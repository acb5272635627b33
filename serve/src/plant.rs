//! The plant thread: the strategy run in real time (the simulated clock
//! follows the wall clock times the speed), every scan at its instant and
//! none skipped, a late one counted; the console's commands executed
//! between scans; and at most ten times a second what changed published to
//! the event streams.

use crate::pictures::Picture;
use crate::{Ask, Event, Reply, Speed};
use linc_engines::console::Console;
use linc_engines::strategy::trace::Trace;
use linc_runtime::store::Cell;
use serde_json::{json, Map, Value};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, RecvTimeoutError};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};
use tokio::sync::broadcast;

/// How often changes are published at most.
pub const PUBLISH_EVERY: Duration = Duration::from_millis(100);

/// Where simulated time should be at a wall-clock instant: it follows the
/// wall clock from a base pair, rebased whenever a command moved it.
struct RealTime {
    speed: Speed,
    wall: Instant,
    sim: u64,
}

impl RealTime {
    /// The simulated µs the clock should have reached at `now`.
    fn target(&self, now: Instant) -> u64 {
        match self.speed {
            Speed::Max => u64::MAX,
            Speed::Times(k) => self.sim.saturating_add((now.duration_since(self.wall).as_secs_f64() * k * 1e6) as u64),
        }
    }

    /// The wall-clock instant simulated time `sim` is due.
    fn wall_of(&self, sim: u64) -> Instant {
        match self.speed {
            Speed::Max => self.wall,
            Speed::Times(k) => self.wall + Duration::from_secs_f64(sim.saturating_sub(self.sim) as f64 / 1e6 / k),
        }
    }
}

/// How the plant runs.
pub struct Setup {
    pub speed: Speed,
    pub until: Option<u64>,
    pub allow_writes: bool,
    /// Where `SAVE` writes the state.
    pub state: Option<std::path::PathBuf>,
    /// The ROC device (either dialect), when serving one.
    pub roc: Option<crate::wire::roc::RocDevice>,
    /// The Modbus device, when serving one.
    pub modbus: Option<crate::wire::modbus::ModbusDevice>,
}

/// What the plant thread owns.
pub struct Plant {
    pub console: Console,
    pub pictures: Vec<Picture>,
    clock: RealTime,
    /// A scan is late when it starts this much after its instant.
    tolerance: Duration,
    pub late: u64,
    /// The strategy's instant count when serving began: scans are counted
    /// from it, whoever ran them (the clock, or an `ADVANCE`).
    first_instant: u64,
    /// The most requests that were waiting when a scan ended (answered
    /// before the plant goes on): the work clients can queue ahead of the
    /// next scan, which the isolation rules bound to one request per
    /// connection.
    busiest: usize,
    /// The requests of one drain, kept to reuse its capacity.
    batch: Vec<Ask>,
    until: Option<u64>,
    last: Vec<Cell>,
    history: crate::history::History,
    last_status: String,
    published: Instant,
    events: broadcast::Sender<Arc<Event>>,
    status: Arc<Mutex<Value>>,
    allow_writes: bool,
    state: Option<std::path::PathBuf>,
    roc: Option<crate::wire::roc::RocDevice>,
    modbus: Option<crate::wire::modbus::ModbusDevice>,
}

impl Plant {
    pub fn new(
        console: Console,
        pictures: Vec<Picture>,
        setup: Setup,
        events: broadcast::Sender<Arc<Event>>,
        status: Arc<Mutex<Value>>,
    ) -> Plant {
        let Setup { speed, until, allow_writes, state, roc, modbus } = setup;
        let sim = console.strategy.elapsed_us();
        let period = console.strategy.fastest_period_us().unwrap_or(1_000_000);
        let tolerance = match speed {
            Speed::Times(k) => Duration::from_secs_f64(period as f64 / 2e6 / k).max(Duration::from_millis(1)),
            Speed::Max => Duration::MAX,
        };
        let last = console.strategy.store.cells.clone();
        let first_instant = console.strategy.instants();
        let mut p = Plant {
            console,
            pictures,
            clock: RealTime { speed, wall: Instant::now(), sim },
            tolerance,
            late: 0,
            first_instant,
            busiest: 0,
            batch: Vec::new(),
            until,
            last,
            history: Default::default(),
            last_status: String::new(),
            published: Instant::now(),
            events,
            status,
            allow_writes,
            state,
            roc,
            modbus,
        };
        p.publish();
        p
    }

    /// Runs until `stop` is set, the `--for` time is reached or every
    /// asker is gone.
    pub fn run(&mut self, asks: &Receiver<Ask>, stop: &AtomicBool, mut trace: Option<&mut Trace>) {
        let until = self.until.unwrap_or(u64::MAX);
        while !stop.load(Ordering::Relaxed) {
            let now = Instant::now();
            let target = self.clock.target(now);
            let s = &mut self.console.strategy;
            match s.next_due_us().filter(|&n| n < until && n <= target) {
                Some(n) => {
                    if self.clock.wall_of(n).checked_add(self.tolerance).is_some_and(|due| now > due) {
                        self.late += 1;
                    }
                    let failures = s.run_due(trace.as_deref_mut());
                    drop(failures); // they are in the error status the page shows
                    if !self.answer_waiting(asks, trace.as_deref_mut()) {
                        return;
                    }
                }
                None => {
                    let el = s.elapsed_us();
                    let to = target.min(until);
                    if to != u64::MAX && to > el {
                        s.run_for(to - el, trace.as_deref_mut());
                    }
                    if s.elapsed_us() >= until {
                        break;
                    }
                    let wait = match s.next_due_us() {
                        Some(n) => self.clock.wall_of(n).saturating_duration_since(now),
                        None => PUBLISH_EVERY,
                    };
                    match asks.recv_timeout(wait.min(PUBLISH_EVERY)) {
                        Ok(a) => self.answer(a, trace.as_deref_mut()),
                        Err(RecvTimeoutError::Timeout) => {}
                        Err(RecvTimeoutError::Disconnected) => return,
                    }
                }
            }
            if self.published.elapsed() >= PUBLISH_EVERY {
                self.publish();
            }
        }
        self.publish();
    }

    /// Answers what is waiting without blocking; `false` when every asker
    /// is gone. The queue is taken in batches — everything that arrived
    /// while the plant was busy, then answered — so `busiest` counts the
    /// requests that waited together, not the ones a fast client sends
    /// while the earlier ones are being answered.
    fn answer_waiting(&mut self, asks: &Receiver<Ask>, mut trace: Option<&mut Trace>) -> bool {
        let mut batch = std::mem::take(&mut self.batch);
        let open = loop {
            let open = loop {
                match asks.try_recv() {
                    Ok(a) => batch.push(a),
                    Err(std::sync::mpsc::TryRecvError::Empty) => break true,
                    Err(std::sync::mpsc::TryRecvError::Disconnected) => break false,
                }
            };
            if batch.is_empty() {
                break open;
            }
            self.busiest = self.busiest.max(batch.len());
            for a in batch.drain(..) {
                self.answer(a, trace.as_deref_mut());
            }
            if !open {
                break false;
            }
        };
        self.batch = batch;
        open
    }

    fn answer(&mut self, a: Ask, trace: Option<&mut Trace>) {
        match a {
            Ask::Command { line, reply } => {
                let r = self.command(&line, trace);
                let _ = reply.send(r);
                self.publish();
            }
            Ask::Block { name, reply } => {
                let _ = reply.send(crate::json::block(&self.console.strategy.store, &name));
            }
            Ask::Trend { path, reply } => {
                let _ = reply.send(self.trend(&path));
            }
            Ask::Blocks { reply } => {
                let _ = reply.send(crate::json::blocks(&self.console.strategy.store));
            }
            Ask::Roc { frame, peer, session, reply } => {
                if let Some(device) = self.roc {
                    let console = &mut self.console;
                    let answer = guarded(|| device.answer(console, &frame, &peer, session, trace))
                        .unwrap_or_else(|| device.internal_error(&frame, &peer));
                    let _ = reply.send(answer);
                }
            }
            Ask::Modbus { request, peer, reply } => {
                if let Some(device) = self.modbus {
                    let console = &mut self.console;
                    let answer = guarded(|| device.answer(console, &request, &peer, trace))
                        .unwrap_or_else(|| device.internal_error(&request, &peer));
                    let _ = reply.send(answer);
                }
            }
            Ask::Picture { name, reply } if name.starts_with(crate::pictures::TREND) => {
                let spec = &name[crate::pictures::TREND.len()..];
                let _ = reply.send(crate::pictures::trend(spec, &self.history, &self.console.strategy));
            }
            Ask::Picture { name, reply } => {
                let s = &mut self.console.strategy;
                let pic = self.pictures.iter_mut().find(|p| p.name.eq_ignore_ascii_case(&name));
                let _ = reply.send(pic.map(|p| {
                    p.refresh(s);
                    p.svg.clone()
                }));
            }
        }
    }

    /// One console line, through the console engine like every control.
    /// A command that moved the clock (ADVANCE, SCAN) rebases real time.
    fn command(&mut self, line: &str, trace: Option<&mut Trace>) -> Reply {
        if !self.allow_writes && !linc_engines::console::reads_only(line) {
            return Reply::Refused;
        }
        let before = self.console.strategy.elapsed_us();
        let replies = self.console.execute_traced(line, trace);
        let failures: Vec<String> = self.console.take_failures().iter().map(|e| e.to_string()).collect();
        let after = self.console.strategy.elapsed_us();
        if after != before {
            self.clock = RealTime { speed: self.clock.speed, wall: Instant::now(), sim: after };
        }
        let mut failures = failures;
        // SAVE took the state; it is written here, atomically.
        if let (Some(bytes), Some(path)) = (self.console.take_saved(), &self.state) {
            if let Err(e) = linc_driver::files::write_atomic(path, &bytes) {
                failures.push(e.diagnostic().message.clone());
            }
        }
        Reply::Done { replies, failures }
    }

    /// Scans run while serving: by the clock and by `ADVANCE`/`SCAN` lines.
    fn scans(&self) -> u64 {
        self.console.strategy.instants() - self.first_instant
    }

    /// What the run leaves, once it has stopped.
    pub fn finish(self) -> crate::Finished {
        let (scans, late, busiest) = (self.scans(), self.late, self.busiest);
        crate::Finished { console: self.console, scans, late, busiest, trace_error: None }
    }

    /// Publishes the status, the values and the pictures that changed.
    pub fn publish(&mut self) {
        self.published = Instant::now();
        let status = self.status_json();
        let text = status.to_string();
        if text != self.last_status {
            self.send("status", text.clone());
            self.last_status = text;
            if let Ok(mut s) = self.status.lock() {
                *s = status;
            }
        }
        let values = self.changed_values();
        if !values.is_empty() {
            self.send("values", Value::Object(values).to_string());
        }
        let s = &mut self.console.strategy;
        let mut drawn = Vec::new();
        for p in &mut self.pictures {
            if p.refresh(s) {
                drawn.push(json!({"block": p.name, "svg": p.svg}).to_string());
            }
        }
        for d in drawn {
            self.send("picture", d);
        }
    }

    fn send(&self, name: &'static str, data: String) {
        // No stream listening is not an error: the next one starts afresh.
        let _ = self.events.send(Arc::new(Event { name, data }));
    }

    /// Every field whose value changed since the last publication, by path.
    /// (Each is also kept in the history for trends.)
    fn changed_values(&mut self) -> Map<String, Value> {
        let store = &self.console.strategy.store;
        let now_us = self.console.strategy.elapsed_us();
        let mut out = Map::new();
        for (i, (now, was)) in store.cells.iter().zip(self.last.iter_mut()).enumerate() {
            if now != was {
                let text = store.show(i as u32);
                self.history.record(now_us, i as u32, &text);
                out.insert(store.describe(i as u32), Value::String(text));
                was.clone_from(now);
            }
        }
        self.history.trim(now_us);
        out
    }

    /// A field's recent changes and its value now, for a trend.
    fn trend(&self, path: &str) -> Option<Value> {
        let store = &self.console.strategy.store;
        let cell = linc_engines::console::fields::address(store, path).ok()?.cell;
        let secs = |us: u64| us as f64 / 1e6;
        let points: Vec<Value> = self.history.of(cell).into_iter().map(|(t, v)| json!([secs(t), v])).collect();
        Some(json!({"field": store.describe(cell), "now": secs(self.console.strategy.elapsed_us()),
                    "value": store.show(cell), "points": points}))
    }

    fn status_json(&self) -> Value {
        let s = &self.console.strategy;
        let programs: Vec<Value> = s
            .programs()
            .into_iter()
            .map(|p| {
                let picture = self.pictures.iter().find(|q| q.name == p.block).map(|q| q.kind);
                // The program the error status names is shown as failed.
                let failed = s.error().is_some_and(|e| e.block == p.block);
                let mut v = json!({"block": p.block, "kind": p.kind.name(), "task": p.task, "state": p.state.name(),
                       "failed": failed, "position": p.position, "picture": picture});
                if let Some(seq) = s.store.db.block(&p.block).and_then(|b| s.sequence(b)) {
                    let active: Vec<Value> = seq
                        .active_steps()
                        .into_iter()
                        .map(|n| json!({"step": n, "t": seq.step(n).map_or(0.0, |(_, us)| us as f64 / 1e6)}))
                        .collect();
                    let mut held: Vec<&String> = seq.monitor.held.iter().collect();
                    held.sort();
                    v["status"] = json!(seq.status.name());
                    v["active"] = json!(active);
                    v["held"] = json!(held);
                    let forced: std::collections::BTreeMap<&String, &str> =
                        seq.monitor.forced.iter().map(|(t, on)| (t, if *on { "continue" } else { "hold" })).collect();
                    v["forced"] = json!(forced);
                }
                v
            })
            .collect();
        let error = s.error().map(|e| {
            json!({"number": e.number(), "code": e.error.code.as_str(), "block": e.block,
                   "message": e.error.message, "line": e.error.line, "double": e.double})
        });
        let speed = match self.clock.speed {
            Speed::Max => json!("max"),
            Speed::Times(k) => json!(k),
        };
        json!({"now": s.now_text(), "elapsed": s.elapsed_us() as f64 / 1e6, "speed": speed,
               "scans": self.scans(), "late_scans": self.late, "halted": s.halted(),
               "writes": self.allow_writes, "error": error, "programs": programs})
    }
}

/// Runs a wire device's answer so that a bug in it (a panic) costs the
/// client its request, answered as a general error, not the plant its
/// thread: every client and the scans go on. The fuzz of the devices
/// (serve/tests/wire_fuzz.rs) calls them directly, so a panic still fails
/// the tests.
fn guarded<T>(f: impl FnOnce() -> T) -> Option<T> {
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(f)).ok()
}

#[cfg(test)]
mod tests {
    use super::guarded;
    use crate::wire::modbus::ModbusDevice;
    use crate::wire::roc::RocDevice;
    use linc_comms::roc::{Address, Frame};

    #[test]
    fn a_panicking_answer_becomes_a_general_error_not_a_dead_plant() {
        assert_eq!(guarded(|| 7), Some(7));
        let hook = std::panic::take_hook();
        std::panic::set_hook(Box::new(|_| {}));
        let caught = guarded(|| -> u8 { panic!("a bug") });
        std::panic::set_hook(hook);
        assert_eq!(caught, None);
        let me = Address { unit: 1, group: 2 };
        let req = Frame { dst: me, src: Address { unit: 3, group: 1 }, opcode: 180, data: vec![] };
        let a = RocDevice { address: me, allow_writes: false, dialect: crate::wire::roc::Dialect::RocPlus }
            .internal_error(&req, "p");
        assert_eq!((a.reply.opcode, a.reply.data.as_slice(), a.reply.dst), (255, &[50u8, 4][..], req.src));
        let m = ModbusDevice { allow_writes: false }.internal_error(&linc_comms::modbus::Request::ReadCoils(0, 1), "p");
        assert_eq!((m.function, m.reply), (1, Err(linc_comms::modbus::Exception::ServerDeviceFailure)));
    }
}

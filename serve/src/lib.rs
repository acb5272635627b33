//! `linc serve`: a strategy run in real time behind a live monitor page
//! and a JSON API (docs/serve.md, ADR 0015).
//!
//! Two threads share nothing but messages: the plant thread owns the
//! console (and so the strategy) and runs it; the HTTP side (tokio and
//! axum) asks it for what it needs and relays what it publishes. Every
//! control is a console command line, so the page, the API and `--console`
//! go through one implementation of the rules and C-codes.

mod history;
mod http;
mod http_conn;
mod http_guard;
mod json;
mod pictures;
mod plant;
pub mod wire;

pub use wire::{Limits, Log};

use linc_compiler::diag::Problems;
use linc_engines::console::{Console, ConsoleError};
use linc_engines::strategy::trace::Trace;
use linc_engines::strategy::Want;
use linc_format::Code;
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::Sender;
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use tokio::sync::{broadcast, oneshot};

pub use plant::PUBLISH_EVERY;

/// The most scans one console line may run on a served plant (C0013):
/// the line runs on the plant's thread, and every client waits for it.
pub const MAX_SCANS_PER_LINE: u64 = 100_000;

/// How fast simulated time goes: a multiple of the wall clock, or as fast
/// as the machine runs it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Speed {
    Times(f64),
    Max,
}

/// How to serve.
pub struct Config {
    pub addr: SocketAddr,
    pub speed: Speed,
    /// Every request must carry it (required off loopback; an empty or
    /// blank one is refused at the start).
    pub token: Option<String>,
    /// Names besides the loopback ones and the bound address that a
    /// request's `Host` may give (`--allow-host`).
    pub allow_hosts: Vec<String>,
    pub allow_writes: bool,
    /// Stop when simulated time reaches this (`--for`).
    pub until_us: Option<u64>,
    /// Where `SAVE` writes the retentive state (`--state`).
    pub state: Option<PathBuf>,
    /// A ROC device (in its database family's dialect) on this address, answering as this unit and group
    /// (`--roc`, `--roc-address`).
    pub roc: Option<(SocketAddr, linc_comms::roc::Address)>,
    /// The ROC device on this serial port too, its line, and the unit
    /// and group it answers as (`--roc-serial`, `--baud`, …): one device,
    /// so with `roc` as well both must give the same address.
    pub roc_serial: Option<(PathBuf, linc_comms::serial::Line, linc_comms::roc::Address)>,
    /// A Modbus TCP server on this address, over the database's map
    /// (`--modbus`).
    pub modbus: Option<SocketAddr>,
    /// What the wire servers put up with.
    pub limits: wire::Limits,
    /// Where the wire servers' log lines go (nowhere unless the caller
    /// says: the command line renders them as notes, I0004).
    pub log: wire::Log,
    /// Where the trace goes (`--trace`): every change a scan, a console
    /// line or a client on the wire made, committed when the server stops.
    pub trace: Option<linc_driver::files::AtomicFile>,
}

impl Config {
    /// Serving on `addr` at speed 1, read-only, with no token, no end, no
    /// state file and no wire servers; the wire servers' log lines are
    /// dropped.
    pub fn new(addr: SocketAddr) -> Config {
        Config {
            addr,
            speed: Speed::Times(1.0),
            token: None,
            allow_hosts: Vec::new(),
            allow_writes: false,
            until_us: None,
            state: None,
            roc: None,
            roc_serial: None,
            modbus: None,
            limits: wire::Limits::default(),
            log: Arc::new(|_| {}),
            trace: None,
        }
    }
}

/// One published change: an SSE event's name and JSON data.
#[derive(Debug)]
pub struct Event {
    pub name: &'static str,
    pub data: String,
}

/// The answer to a console line.
#[derive(Debug)]
pub enum Reply {
    /// A line that writes, without `--allow-writes`: nothing was run.
    Refused,
    /// One reply per command, then the runtime errors of the scans the
    /// line ran (ADVANCE, SCAN).
    Done { replies: Vec<Result<String, ConsoleError>>, failures: Vec<String> },
}

/// What the HTTP side asks the plant thread.
pub(crate) enum Ask {
    Command {
        line: String,
        reply: oneshot::Sender<Reply>,
    },
    Block {
        name: String,
        reply: oneshot::Sender<Option<serde_json::Value>>,
    },
    Blocks {
        reply: oneshot::Sender<serde_json::Value>,
    },
    Picture {
        name: String,
        reply: oneshot::Sender<Option<String>>,
    },
    Trend {
        path: String,
        reply: oneshot::Sender<Option<serde_json::Value>>,
    },
    /// A ROC Plus request frame for this device, from `peer`.
    Roc {
        frame: linc_comms::roc::Frame,
        peer: String,
        /// The connection's login (the access level), if any.
        session: Option<u8>,
        reply: oneshot::Sender<wire::roc::Answer>,
    },
    /// A Modbus request, from `peer`.
    Modbus {
        request: linc_comms::modbus::Request,
        peer: String,
        reply: oneshot::Sender<wire::modbus::MbAnswer>,
    },
}

/// What a served run leaves: the console (for `--state`) and its counts.
pub struct Finished {
    pub console: Console,
    pub scans: u64,
    pub late: u64,
    /// The most requests (HTTP, ROC, Modbus) that were waiting when a scan
    /// ended: at most one per connection.
    pub busiest: usize,
    /// Why the trace could not be written, if it could not.
    pub trace_error: Option<String>,
}

/// A running server.
pub struct Server {
    addr: SocketAddr,
    roc: Option<SocketAddr>,
    roc_dialect: wire::roc::Dialect,
    modbus: Option<SocketAddr>,
    asks: Sender<Ask>,
    stop: Arc<AtomicBool>,
    plant: JoinHandle<Finished>,
    http: JoinHandle<()>,
    closing: Option<oneshot::Sender<()>>,
}

/// Runs console lines on a served plant.
#[derive(Clone)]
pub struct Handle {
    asks: Sender<Ask>,
}

impl Handle {
    /// Runs a console line on the plant, as `POST /api/command` does
    /// (refused alike without `--allow-writes`); `None` once the plant
    /// has stopped.
    pub fn command(&self, line: &str) -> Option<Reply> {
        let (reply, answer) = oneshot::channel();
        self.asks.send(Ask::Command { line: line.to_string(), reply }).ok()?;
        answer.blocking_recv().ok()
    }
}

/// Why the server could not start.
#[derive(Debug)]
pub enum StartError {
    /// Off loopback without a token.
    NeedsToken(SocketAddr),
    /// `--token ''` (or blanks): what an unset variable gives, and a
    /// token anyone can send.
    BlankToken,
    Bind(SocketAddr, std::io::Error),
    /// `--modbus` over a database with no `"modbus"` map.
    NoModbusMap,
    /// The serial port could not be opened (E0905).
    Serial(PathBuf, String),
    /// `roc` and `roc_serial` with different addresses for their one device.
    RocAddresses(linc_comms::roc::Address, linc_comms::roc::Address),
    /// The threads or the runtime could not be made.
    Runtime(std::io::Error),
}

impl StartError {
    /// As a refused request: E0905, against the port's path, for a serial
    /// port that can't be opened; E0903 for the rest.
    pub fn problems(&self) -> Problems {
        match self {
            StartError::Serial(path, why) => linc_driver::roc::serial_unopenable(path, why),
            _ => Problems::usage(Code::E0903, self.to_string()),
        }
    }
}

/// A listener bound now (so a busy port fails at the start), handed to
/// the network thread.
fn bind(addr: SocketAddr) -> Result<(std::net::TcpListener, SocketAddr), StartError> {
    let listener = std::net::TcpListener::bind(addr).map_err(|e| StartError::Bind(addr, e))?;
    let bound = listener.local_addr().map_err(|e| StartError::Bind(addr, e))?;
    listener.set_nonblocking(true).map_err(|e| StartError::Bind(bound, e))?;
    Ok((listener, bound))
}

impl std::fmt::Display for StartError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            StartError::NeedsToken(a) => {
                write!(
                    f,
                    "{a} is not a loopback address: serving it needs --token TOKEN, which every request must carry"
                )
            }
            StartError::BlankToken => write!(
                f,
                "--token is empty or blank, which any client can send: give a secret (is the variable it came from unset?)"
            ),
            StartError::Bind(a, e) => write!(f, "can't listen on {a}: {e}"),
            StartError::NoModbusMap => {
                write!(f, "--modbus needs a \"modbus\" register map in the database (docs/modbus.md)")
            }
            StartError::Serial(path, why) => write!(f, "can't open the serial port `{}`: {why}", path.display()),
            StartError::RocAddresses(tcp, serial) => {
                write!(f, "one ROC device answers as one address: {tcp} over TCP but {serial} on the serial port")
            }
            StartError::Runtime(e) => write!(f, "can't start the server: {e}"),
        }
    }
}

/// Starts the plant thread and the HTTP server over a plant built by the
/// driver (its strategy, and the programs its blocks name for the live
/// pictures); one that can't start is a refused request.
pub fn start(plant: linc_driver::plant::Plant, cfg: Config) -> Result<Server, Problems> {
    let (wants, dir) = (plant.wants.clone(), plant.dir.clone());
    let Some(strategy) = plant.into_strategy() else {
        return Err(Problems::usage(Code::E0903, "linc serve runs a strategy"));
    };
    start_console(Console::new(strategy), &wants, &dir, cfg).map_err(|e| e.problems())
}

/// The wire servers' ports, bound (and the serial port opened) before
/// anything runs, so a busy port or a wrong path fails the start.
struct Bound {
    roc: Option<(std::net::TcpListener, SocketAddr)>,
    serial: Option<wire::serial::Port>,
    /// The ROC device's address, with either.
    me: Option<linc_comms::roc::Address>,
    /// The Modbus listener, where it listens and the unit of the map.
    modbus: Option<(std::net::TcpListener, SocketAddr, u8)>,
}

/// Binds the wire servers' ports; the serial port is opened on `rt`, the
/// runtime that will serve it.
fn bind_wires(cfg: &Config, console: &Console, rt: &tokio::runtime::Runtime) -> Result<Bound, StartError> {
    let roc = cfg.roc.map(|(a, _)| bind(a)).transpose()?;
    let me = match (cfg.roc.map(|r| r.1), cfg.roc_serial.as_ref().map(|r| r.2)) {
        (Some(tcp), Some(serial)) if tcp != serial => return Err(StartError::RocAddresses(tcp, serial)),
        (tcp, serial) => tcp.or(serial),
    };
    let unit = match (cfg.modbus, console.strategy.store.db.modbus.as_ref()) {
        (None, _) => None,
        (Some(_), None) => return Err(StartError::NoModbusMap),
        (Some(_), Some(map)) => Some(map.unit),
    };
    let modbus = cfg.modbus.map(bind).transpose()?.zip(unit).map(|((l, a), u)| (l, a, u));
    let serial = match &cfg.roc_serial {
        None => None,
        Some((path, line, _)) => {
            let _runtime = rt.enter();
            let stream = wire::serial::open(path, line).map_err(|e| StartError::Serial(path.clone(), e.to_string()))?;
            Some(wire::serial::Port { path: path.clone(), line: *line, stream })
        }
    };
    Ok(Bound { roc, serial, me, modbus })
}

/// Starts the plant thread and the HTTP server over `console`'s strategy;
/// `wants` are the programs its blocks name, with sources relative to `dir`.
fn start_console(mut console: Console, wants: &[Want], dir: &Path, cfg: Config) -> Result<Server, StartError> {
    if cfg.token.as_deref().is_some_and(|t| t.trim().is_empty()) {
        return Err(StartError::BlankToken);
    }
    if !cfg.addr.ip().is_loopback() && cfg.token.is_none() {
        return Err(StartError::NeedsToken(cfg.addr));
    }
    let (listener, addr) = bind(cfg.addr)?;
    // Built here rather than on the network thread: the serial port is
    // opened on it now, so a port that can't be opened fails the start.
    let rt = tokio::runtime::Builder::new_multi_thread().worker_threads(2).enable_all().build();
    let rt = rt.map_err(StartError::Runtime)?;
    let bound = bind_wires(&cfg, &console, &rt)?;
    let (roc_addr, modbus_addr) = (bound.roc.as_ref().map(|r| r.1), bound.modbus.as_ref().map(|m| m.1));
    let dialect = wire::roc::Dialect::of(console.strategy.store.db.device);
    let links = Arc::new(console.strategy.store.db.roc_forward.clone());
    console.can_save = cfg.state.is_some();
    console.max_scans = Some(MAX_SCANS_PER_LINE);
    let pictures = pictures::load(dir, wants, &console.strategy);
    let (events, _) = broadcast::channel(256);
    let status = Arc::new(Mutex::new(serde_json::Value::Null));
    let (asks, asked) = std::sync::mpsc::channel();
    let stop = Arc::new(AtomicBool::new(false));
    let plant = plant::Plant::new(
        console,
        pictures,
        plant::Setup {
            speed: cfg.speed,
            until: cfg.until_us,
            allow_writes: cfg.allow_writes,
            state: cfg.state,
            roc: bound.me.map(|address| wire::roc::RocDevice { address, allow_writes: cfg.allow_writes, dialect }),
            modbus: bound.modbus.as_ref().map(|_| wire::modbus::ModbusDevice { allow_writes: cfg.allow_writes }),
        },
        events.clone(),
        status.clone(),
    );
    let plant = run_plant(plant, cfg.trace, asked, stop.clone()).map_err(StartError::Runtime)?;
    let (closing, closed) = oneshot::channel();
    let hosts = http_guard::Hosts::new(addr, &cfg.allow_hosts);
    let state = http::AppState::new(asks.clone(), events, status, (cfg.token, hosts, cfg.limits));
    let station = bound.me.map(|me| wire::roc_server::Station { me, dialect, links });
    let wires = http::Wires {
        roc: bound.roc.zip(station.clone()).map(|((l, _), st)| (l, st)),
        roc_serial: bound.serial.zip(station),
        modbus: bound.modbus.map(|(l, _, u)| (l, u)),
        asks: asks.clone(),
        limits: cfg.limits,
        log: cfg.log,
    };
    let http = std::thread::Builder::new()
        .name("linc-net".into())
        .spawn(move || http::serve(rt, listener, state, wires, closed))
        .map_err(StartError::Runtime)?;
    Ok(Server {
        addr,
        roc: roc_addr,
        roc_dialect: dialect,
        modbus: modbus_addr,
        asks,
        stop,
        plant,
        http,
        closing: Some(closing),
    })
}

/// The plant thread: runs the plant until it is told to stop (or reaches
/// `--for`), then commits the trace.
fn run_plant(
    mut plant: plant::Plant,
    mut trace_file: Option<linc_driver::files::AtomicFile>,
    asked: std::sync::mpsc::Receiver<Ask>,
    flag: Arc<AtomicBool>,
) -> std::io::Result<JoinHandle<Finished>> {
    std::thread::Builder::new().name("linc-plant".into()).spawn(move || {
        let trace_error = match trace_file.as_mut() {
            None => {
                plant.run(&asked, &flag, None);
                None
            }
            Some(file) => {
                let mut t = Trace::new(file, &plant.console.strategy.store);
                plant.run(&asked, &flag, Some(&mut t));
                t.finish().err().map(|e| format!("can't write the trace: {e}"))
            }
        };
        // A trace that could not be written whole is not put in place:
        // dropping the file removes its temporary.
        let committed = match (trace_error.is_none(), trace_file) {
            (true, Some(f)) => f.commit().err().map(|e| e.diagnostic().message.clone()),
            _ => None,
        };
        let mut finished = plant.finish();
        finished.trace_error = trace_error.or(committed);
        finished
    })
}

impl Server {
    /// The address it listens on (the port chosen when asked for port 0).
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Where the ROC device listens, if it does.
    pub fn roc_addr(&self) -> Option<SocketAddr> {
        self.roc
    }

    /// The ROC dialect the device speaks, by its database's family.
    pub fn roc_dialect(&self) -> wire::roc::Dialect {
        self.roc_dialect
    }

    /// Where the Modbus TCP server listens, if it does.
    pub fn modbus_addr(&self) -> Option<SocketAddr> {
        self.modbus
    }

    /// A handle that runs console lines on the plant from another thread
    /// (`--console` reads standard input on one).
    pub fn handle(&self) -> Handle {
        Handle { asks: self.asks.clone() }
    }

    /// Whether the plant has stopped by itself (`--for` reached).
    pub fn finished(&self) -> bool {
        self.plant.is_finished()
    }

    /// Blocks until the plant stops by itself (`--for`).
    pub fn wait_finished(&self) {
        while !self.finished() {
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
    }

    /// Stops the plant and the server (open event streams end) and returns
    /// what the run left.
    pub fn stop(mut self) -> Finished {
        self.stop.store(true, Ordering::Relaxed);
        if let Some(c) = self.closing.take() {
            let _ = c.send(());
        }
        let finished = self.plant.join().unwrap_or_else(|p| std::panic::resume_unwind(p));
        let _ = self.http.join();
        finished
    }
}

/// Ctrl-C and SIGTERM (what a service manager sends), watched from when
/// this is made: a signal that arrives before [`Signals::wait`] is kept, so
/// a command makes one before it says it is serving.
pub struct Signals {
    rt: tokio::runtime::Runtime,
    #[cfg(unix)]
    watched: Option<(tokio::signal::unix::Signal, tokio::signal::unix::Signal)>,
}

impl Signals {
    /// Starts watching; `None` where no signal can be watched (then only
    /// `--for` ends a run).
    pub fn watch() -> Option<Signals> {
        let rt = tokio::runtime::Builder::new_current_thread().enable_all().build().ok()?;
        #[cfg(unix)]
        {
            use tokio::signal::unix::{signal, SignalKind};
            let watched = rt.block_on(async {
                Some((signal(SignalKind::interrupt()).ok()?, signal(SignalKind::terminate()).ok()?))
            });
            Some(Signals { rt, watched })
        }
        #[cfg(not(unix))]
        Some(Signals { rt })
    }

    /// Blocks until `server`'s plant stops by itself (`--for`) or a signal
    /// asks the process to stop.
    pub fn wait(mut self, server: &Server) {
        let finished = async {
            while !server.finished() {
                tokio::time::sleep(std::time::Duration::from_millis(20)).await;
            }
        };
        #[cfg(unix)]
        if let Some((int, term)) = self.watched.as_mut() {
            return self.rt.block_on(async {
                tokio::select! {
                    () = finished => {}
                    _ = int.recv() => {}
                    _ = term.recv() => {}
                }
            });
        }
        self.rt.block_on(async {
            tokio::select! {
                () = finished => {}
                _ = tokio::signal::ctrl_c() => {}
            }
        });
    }
}

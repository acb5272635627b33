//! `linc serve PLANT.json`: the strategy run in real time behind a live
//! monitor page and a JSON API (docs/serve.md). The CLI builds the plant
//! as `linc console` does, hands it to `linc-serve`, optionally reads
//! console lines from standard input, and on Ctrl-C (or at `--for`) stops
//! and saves `--state`.

use crate::console_cmd::{bounded_lines, MAX_LINE};
use crate::run_cmd::Common;
use crate::strategy_cmd::{self, Options as StrategyOptions, Retain};
use linc_driver::Reporter;
use linc_engines::console::Console;
use linc_serve::{Config, Reply, Speed};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

/// `linc serve`'s options.
#[derive(clap::Args)]
pub struct ServeArgs {
    /// The strategy's database (.json).
    pub file: PathBuf,
    /// Where to listen (loopback by default; any other address needs --token).
    #[arg(long, value_name = "ADDR:PORT", default_value = "127.0.0.1:8080")]
    pub http: SocketAddr,
    /// Simulated seconds per wall-clock second, or `max` (as fast as it runs).
    #[arg(long, value_name = "N|max", default_value = "1", value_parser = speed)]
    pub speed: SpeedArg,
    /// Stop after this much simulated time (default: run until Ctrl-C).
    #[arg(long = "for", value_name = "DURATION")]
    pub duration: Option<String>,
    /// Let the page and the API change the plant (modify, force, start, stop, hold, …).
    #[arg(long)]
    pub allow_writes: bool,
    /// Every request must carry this token (`Authorization: Bearer TOKEN` or `?token=TOKEN`).
    #[arg(long, value_name = "TOKEN")]
    pub token: Option<String>,
    /// Also read console commands from standard input while serving.
    #[arg(long)]
    pub console: bool,
    /// Set a field before the start: BLOCK.FIELD=VALUE (repeatable).
    #[arg(long)]
    pub set: Vec<String>,
    /// Fix the clock: YYYY-MM-DDTHH:MM:SS (UTC).
    #[arg(long, value_name = "YYYY-MM-DDTHH:MM:SS", value_parser = crate::now)]
    pub now: Option<String>,
    /// Seed of RANDOM, for repeatable runs.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Restore the retentive state from FILE at the start and save it there on SAVE and at the end.
    #[arg(long, value_name = "FILE")]
    pub state: Option<PathBuf>,
    /// With --state: ignore the state file and start cold (it is still saved).
    #[arg(long, requires = "state")]
    pub cold: bool,
    /// Write the strategy trace here (JSON lines): every change a scan, a console line or a
    /// client on the wire made, written when the server stops.
    #[arg(long, value_name = "FILE")]
    pub trace: Option<PathBuf>,
    /// Also be a ROC Plus device on this TCP port (loopback) or ADDR:PORT (any other address must be named).
    #[arg(long, value_name = "[ADDR:]PORT", value_parser = wire_addr)]
    pub roc: Option<SocketAddr>,
    /// Also be a Modbus TCP server over the database's "modbus" map on this port (loopback) or ADDR:PORT.
    #[arg(long, value_name = "[ADDR:]PORT", value_parser = wire_addr)]
    pub modbus: Option<SocketAddr>,
    /// The ROC unit and group the device answers to.
    #[arg(long, value_name = "UNIT,GROUP", default_value = "1,2", value_parser = roc_address, requires = "roc")]
    pub roc_address: linc_comms::roc::Address,
    /// Most clients connected to each wire server at once; more are refused and logged.
    #[arg(long, value_name = "N", default_value_t = 64, value_parser = clap::value_parser!(u16).range(1..=4096))]
    pub max_clients: u16,
    /// Drop a wire client that sends nothing for this long.
    #[arg(long, value_name = "DURATION", default_value = "60s")]
    pub client_timeout: String,
    /// Which tier runs the code; `compiled` translates every block at the start rather than
    /// while the plant runs (translation happens on the plant's thread, between scans).
    #[arg(long, value_enum, default_value = "auto")]
    pub tier: crate::TierArg,
}

#[derive(Clone, Copy, Debug)]
pub struct SpeedArg(Speed);

fn speed(s: &str) -> Result<SpeedArg, String> {
    if s.eq_ignore_ascii_case("max") {
        return Ok(SpeedArg(Speed::Max));
    }
    match s.parse::<f64>() {
        Ok(k) if k.is_finite() && (0.001..=1_000_000.0).contains(&k) => Ok(SpeedArg(Speed::Times(k))),
        _ => Err("a speed is a number from 0.001 to 1000000 (times the wall clock), or max".into()),
    }
}

/// `PORT` (on loopback) or `ADDR:PORT`: a wire server listens on loopback
/// unless another address is named.
fn wire_addr(s: &str) -> Result<SocketAddr, String> {
    if let Ok(port) = s.parse::<u16>() {
        return Ok(SocketAddr::from(([127, 0, 0, 1], port)));
    }
    s.parse().map_err(|_| format!("`{s}` is not a port or ADDR:PORT (127.0.0.1:4000)"))
}

/// `UNIT,GROUP`, each 0 to 255.
pub fn roc_address(s: &str) -> Result<linc_comms::roc::Address, String> {
    let bad = || format!("`{s}` is not UNIT,GROUP (two numbers from 0 to 255, like 1,2)");
    let (u, g) = s.split_once(',').ok_or_else(bad)?;
    let unit = u.trim().parse().map_err(|_| bad())?;
    let group = g.trim().parse().map_err(|_| bad())?;
    Ok(linc_comms::roc::Address { unit, group })
}

/// Set by SIGINT (Ctrl-C): the main loop stops the server cleanly.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

#[cfg(unix)]
fn on_interrupt() {
    extern "C" fn handler(_: libc::c_int) {
        INTERRUPTED.store(true, Ordering::SeqCst);
    }
    // SAFETY: the handler only stores to an atomic, which is async-signal-safe.
    unsafe {
        libc::signal(libc::SIGINT, handler as *const () as libc::sighandler_t);
        libc::signal(libc::SIGTERM, handler as *const () as libc::sighandler_t);
    }
}

#[cfg(not(unix))]
fn on_interrupt() {}

pub fn run(a: ServeArgs, r: &mut Reporter) -> u8 {
    let until_us = match a.duration.as_deref().map(linc_driver::database::duration).transpose() {
        Ok(d) => d,
        Err(msg) => return crate::report::usage(r, msg),
    };
    let idle = match linc_driver::database::duration(&a.client_timeout) {
        Ok(us) => Duration::from_micros(us),
        Err(msg) => return crate::report::usage(r, format!("--client-timeout: {msg}")),
    };
    let common = Common {
        set: a.set,
        show: Vec::new(),
        trace: None,
        out: None,
        now: a.now,
        seed: a.seed,
        watchdog: linc_runtime::vm::DEFAULT_WATCHDOG,
        tier: a.tier.into(),
    };
    let retain = Retain { state: a.state.clone(), cold: a.cold };
    let so =
        StrategyOptions { db: a.file.clone(), duration: String::new(), common, single: None, retain, script: None };
    let mut strategy = match strategy_cmd::load(&so, r) {
        Ok(s) => s,
        Err(status) => return status,
    };
    if let Some(path) = &a.state {
        if let Err(status) = linc_driver::state::warm_start(path, a.cold, &mut strategy, r) {
            return status;
        }
    }
    let wants = linc_engines::strategy::wanted(&strategy.store);
    let dir = a.file.parent().map(PathBuf::from).unwrap_or_default();
    let until_us = until_us.map(|d| strategy.elapsed_us().saturating_add(d));
    let trace = match &a.trace {
        None => None,
        Some(path) => {
            let inputs: Vec<&std::path::Path> =
                [Some(a.file.as_path()), a.state.as_deref()].into_iter().flatten().collect();
            match linc_driver::files::check_output(path, &inputs)
                .and_then(|_| linc_driver::files::AtomicFile::create(path))
            {
                Ok(f) => Some(f),
                Err(e) => return crate::report::refused(r, e.diagnostic()),
            }
        }
    };
    let limits = linc_serve::Limits { max_clients: usize::from(a.max_clients), idle, ..Default::default() };
    let cfg = Config {
        speed: a.speed.0,
        token: a.token,
        allow_writes: a.allow_writes,
        until_us,
        state: a.state.clone(),
        roc: a.roc.map(|addr| (addr, a.roc_address)),
        modbus: a.modbus,
        limits,
        trace,
        ..Config::new(a.http)
    };
    let server = match linc_serve::start(Console::new(strategy), &wants, &dir, cfg) {
        Ok(s) => s,
        Err(e) => return crate::report::usage(r, e),
    };
    let mode = if a.allow_writes { "controls on" } else { "read-only" };
    crate::out::line(&format!("serving http://{}/ ({mode}); Ctrl-C stops", server.addr()));
    if let Some(roc) = server.roc_addr() {
        crate::out::line(&format!("ROC Plus device {} on {roc}", a.roc_address));
    }
    if let Some(m) = server.modbus_addr() {
        crate::out::line(&format!("Modbus TCP server on {m}"));
    }
    on_interrupt();
    if a.console {
        let handle = server.handle();
        let mut rr = Reporter::new(r.format());
        std::thread::spawn(move || console_lines(&handle, &mut rr));
    }
    while !INTERRUPTED.load(Ordering::SeqCst) && !server.finished() {
        std::thread::sleep(Duration::from_millis(50));
    }
    let done = server.stop();
    crate::out::line(&format!(
        "stopped at {}: {} scans, {} late",
        done.console.strategy.now_text(),
        done.scans,
        done.late
    ));
    if let Some(why) = &done.trace_error {
        r.command(linc_format::Code::E0900, why.clone());
    }
    if let Some(path) = &a.state {
        if let Err(status) = linc_driver::state::save(path, &done.console.strategy, r) {
            return status;
        }
    }
    if done.trace_error.is_some() {
        return 2;
    }
    0
}

/// `--console`: each line of standard input run on the plant, replies
/// printed as `linc console` prints them.
fn console_lines(handle: &linc_serve::Handle, r: &mut Reporter) {
    for line in bounded_lines(std::io::stdin().lock()) {
        let Ok(line) = line else {
            let why = format!("a console line is at most {MAX_LINE} bytes");
            let e = linc_engines::console::ConsoleError::new(linc_format::Code::C0002, why);
            crate::out::line(&crate::console_cmd::error_text(&e, r));
            continue;
        };
        if line.trim().is_empty() {
            continue;
        }
        match handle.command(&line) {
            None => return,
            Some(Reply::Refused) => {
                crate::out::line("refused: this server is read-only (start it with --allow-writes)");
            }
            Some(Reply::Done { replies, failures }) => {
                for reply in replies {
                    crate::console_cmd::print_reply(reply, r);
                }
                for f in failures {
                    crate::out::line(&f);
                }
            }
        }
    }
}

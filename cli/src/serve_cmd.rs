//! `linc serve PLANT.json`: the strategy run in real time behind a live
//! monitor page and a JSON API (docs/serve.md). The driver builds the plant
//! as it builds every other; `linc-serve` serves it until Ctrl-C (or
//! `--for`); this optionally reads console lines from standard input, then
//! saves `--state`.

use crate::report::Reporter;
use linc_compiler::diag::{Diagnostic, Problems};
use linc_driver::console::{bounded_lines, MAX_LINE};
use linc_driver::plant::{PlantSpec, StateFile};
use linc_format::Code;
use linc_serve::{Config, Reply, Server, Speed};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

/// `linc serve`'s options.
#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("roc_device").multiple(true).args(["roc", "serial"])))]
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
    /// Also answer requests that reach the server by this DNS name (repeatable). Loopback names
    /// and the listening address always do; any other name in a request's Host is refused
    /// (what stops DNS rebinding).
    #[arg(long, value_name = "NAME", value_parser = host_name)]
    pub allow_host: Vec<String>,
    /// Also read console commands from standard input while serving.
    #[arg(long)]
    pub console: bool,
    /// Set a field before the start: BLOCK.FIELD=VALUE (repeatable).
    #[arg(long)]
    pub set: Vec<String>,
    /// Fix the clock: YYYY-MM-DDTHH:MM:SS (UTC).
    #[arg(long, value_name = "YYYY-MM-DDTHH:MM:SS", value_parser = crate::now)]
    pub now: Option<i64>,
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
    /// Also be a ROC device (ROC Plus, or the ROC protocol for an FB107 database) on this TCP port (loopback) or ADDR:PORT (any other address must be named).
    #[arg(long, value_name = "[ADDR:]PORT", value_parser = wire_addr)]
    pub roc: Option<SocketAddr>,
    /// Also be the ROC device on this serial port (with --baud); with --roc too, one device
    /// answers on both.
    #[arg(long, id = "serial", value_name = "PATH", requires = "baud")]
    pub roc_serial: Option<PathBuf>,
    #[command(flatten)]
    pub line: crate::line_args::LineArgs,
    /// Also be a Modbus TCP server over the database's "modbus" map on this port (loopback) or ADDR:PORT.
    #[arg(long, value_name = "[ADDR:]PORT", value_parser = wire_addr)]
    pub modbus: Option<SocketAddr>,
    /// The ROC unit and group the device answers to.
    #[arg(long, value_name = "UNIT,GROUP", default_value = "1,2", value_parser = roc_address, requires = "roc_device")]
    pub roc_address: linc_driver::roc::Address,
    /// Most clients connected to each server (HTTP, ROC, Modbus) at once; more are refused and logged.
    #[arg(long, value_name = "N", default_value_t = 64, value_parser = clap::value_parser!(u16).range(1..=4096))]
    pub max_clients: u16,
    /// Drop a client that sends nothing (a wire client) or reads nothing (HTTP) for this long.
    #[arg(long, value_name = "DURATION", default_value = "60s")]
    pub client_timeout: String,
    /// Which tier runs the code; `auto` translates in the background while the plant runs on the
    /// interpreter, so no scan waits; `compiled` translates every block at its first run, on the
    /// plant's thread.
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

/// A DNS name: letters, digits, `-` and `.`, without a port (the server's
/// own port is the only one it answers on).
fn host_name(s: &str) -> Result<String, String> {
    let ok = !s.is_empty() && s.len() <= 253 && s.chars().all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '.');
    if ok {
        Ok(s.to_ascii_lowercase())
    } else {
        Err(format!("`{s}` is not a DNS name (like plant.example.com, without a port)"))
    }
}

/// `UNIT,GROUP`, each 0 to 255.
pub fn roc_address(s: &str) -> Result<linc_driver::roc::Address, String> {
    let bad = || format!("`{s}` is not UNIT,GROUP (two numbers from 0 to 255, like 1,2)");
    let (u, g) = s.split_once(',').ok_or_else(bad)?;
    let unit = u.trim().parse().map_err(|_| bad())?;
    let group = g.trim().parse().map_err(|_| bad())?;
    Ok(linc_driver::roc::Address { unit, group })
}

pub fn run(a: ServeArgs, r: &Reporter) -> u8 {
    let server = match start(&a, r) {
        Ok(s) => s,
        Err(status) => return status,
    };
    // Watched before the first line says it serves: a Ctrl-C from then on
    // stops it cleanly.
    let signals = linc_serve::Signals::watch();
    let mode = if a.allow_writes { "controls on" } else { "read-only" };
    crate::out::line(&format!("serving http://{}/ ({mode}); Ctrl-C stops", server.addr()));
    if let Some(roc) = server.roc_addr() {
        crate::out::line(&format!("{} device {} on {roc}", server.roc_dialect().name(), a.roc_address));
    }
    if let (Some(path), Some(line)) = (&a.roc_serial, a.line.line()) {
        crate::out::line(&format!(
            "{} device {} on serial {} at {line}",
            server.roc_dialect().name(),
            a.roc_address,
            path.display()
        ));
    }
    if let Some(m) = server.modbus_addr() {
        crate::out::line(&format!("Modbus TCP server on {m}"));
    }
    if a.console {
        let handle = server.handle();
        let rr = *r;
        std::thread::spawn(move || console_lines(&handle, &rr));
    }
    match signals {
        Some(s) => s.wait(&server),
        None => server.wait_finished(),
    }
    stop(server, a.state.as_deref(), r)
}

/// The plant built by the driver and served; the exit status of what
/// stopped it before it served.
fn start(a: &ServeArgs, r: &Reporter) -> Result<Server, u8> {
    let duration = |flag: &str, text: &str| linc_driver::database::duration(flag, text);
    let times = a
        .duration
        .as_deref()
        .map(|d| duration("--for", d))
        .transpose()
        .and_then(|until| Ok((until, duration("--client-timeout", &a.client_timeout)?)));
    let (until_us, idle) = times.map_err(|p| r.report(&p))?;
    let state = a.state.clone().map(|path| StateFile { path, cold: a.cold });
    let outputs = [("--trace", &a.trace), ("--state", &a.state)];
    let spec = PlantSpec {
        set: a.set.clone(),
        now: a.now,
        seed: a.seed,
        tier: a.tier.into(),
        state,
        outputs: outputs.iter().filter_map(|(f, p)| Some((f.to_string(), (*p).clone()?))).collect(),
        ..PlantSpec::strategy(a.file.clone())
    };
    let mut plant = linc_driver::plant::build(&spec).map_err(|p| r.report(&p))?;
    r.report(&std::mem::take(&mut plant.warnings));
    let until_us = until_us.map(|d| plant.strategy().map_or(0, |s| s.elapsed_us()).saturating_add(d));
    let trace = a.trace.as_deref().map(linc_driver::files::AtomicFile::create).transpose();
    let trace = trace.map_err(|e| r.report(&e.into()))?;
    let max_clients = usize::from(a.max_clients);
    let limits = linc_serve::Limits { max_clients, idle: Duration::from_micros(idle), ..Default::default() };
    let log_to = *r;
    let cfg = Config {
        speed: a.speed.0,
        token: a.token.clone(),
        allow_hosts: a.allow_host.clone(),
        allow_writes: a.allow_writes,
        until_us,
        state: a.state.clone(),
        roc: a.roc.map(|addr| (addr, a.roc_address)),
        roc_serial: a.roc_serial.clone().zip(a.line.line()).map(|(path, line)| (path, line, a.roc_address)),
        modbus: a.modbus,
        limits,
        trace,
        log: std::sync::Arc::new(move |line| log_to.note(Code::I0004, line)),
        ..Config::new(a.http)
    };
    linc_serve::start(plant, cfg).map_err(|p| r.report(&p))
}

/// Stops the server, says where it stopped, and saves the state.
fn stop(server: Server, state: Option<&std::path::Path>, r: &Reporter) -> u8 {
    let done = server.stop();
    let (compiled, blocks) = done.console.strategy.compiled_blocks();
    crate::out::line(&format!(
        "stopped at {}: {} scans, {} late, {compiled} of {blocks} code blocks compiled",
        done.console.strategy.now_text(),
        done.scans,
        done.late
    ));
    let mut problems = Problems::new();
    if let Some(why) = &done.trace_error {
        problems.append(Problems::usage(Code::E0900, why.clone()));
    }
    if let Some(path) = state {
        if let Err(p) = linc_driver::plant::save_state(path, &done.console.strategy) {
            problems.append(p);
        }
    }
    r.report(&problems)
}

/// `--console`: each line of standard input run on the plant, replies
/// printed as `linc console` prints them.
fn console_lines(handle: &linc_serve::Handle, r: &Reporter) {
    for line in bounded_lines(std::io::stdin().lock()) {
        let Ok(line) = line else {
            let why = format!("a console line is at most {MAX_LINE} bytes");
            let refused = Problems::finding(Diagnostic::command(Code::C0002, why));
            crate::out::line(r.text(&refused).trim_end());
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
                    match reply {
                        Ok(text) if text.is_empty() => {}
                        Ok(text) => crate::out::line(&text),
                        Err(e) => crate::out::line(r.text(&linc_driver::console::refused(&e)).trim_end()),
                    }
                }
                for f in failures {
                    crate::out::line(&f);
                }
            }
        }
    }
}

//! `linc roc poll`: the ROC communication module's master side against a
//! device (docs/roc-host.md). Reading and writing the files is the
//! driver's, polling is linc-comms'; this prints.

use crate::out;
use crate::report::Reporter;
use linc_driver::roc::Address;
use linc_driver::roc::{LinkTo, PollRequest};
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

#[derive(clap::Subcommand)]
pub enum RocCommand {
    /// Run a command list (CSV in the module manual's columns) against a ROC or ROC Plus device over TCP
    /// or a serial line.
    Poll(PollArgs),
}

#[derive(clap::Args)]
#[command(group(clap::ArgGroup::new("device").required(true).args(["host", "serial"])))]
pub struct PollArgs {
    /// The device: ADDR:PORT.
    #[arg(long, value_name = "ADDR:PORT", conflicts_with = "line")]
    pub host: Option<SocketAddr>,
    /// The device on this serial port instead (with --baud).
    #[arg(long, id = "serial", value_name = "PATH", requires = "baud")]
    pub serial: Option<PathBuf>,
    #[command(flatten)]
    pub line: crate::line_args::LineArgs,
    /// The command list: PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD.
    #[arg(long, value_name = "CMDS.csv")]
    pub commands: PathBuf,
    /// The initial word table, runs by start address ({"0": [3, 0, 2], …}); all zeros without it.
    #[arg(long, value_name = "WORDS.json")]
    pub words: Option<PathBuf>,
    /// Keep polling for this long, each command by its POLL TIME (without it every command runs once).
    #[arg(long = "for", value_name = "DURATION")]
    pub duration: Option<String>,
    /// Write the word table and each command's status here.
    #[arg(long, value_name = "WORDS.json")]
    pub out: Option<PathBuf>,
    /// How long to wait for each reply (the module's default is one second).
    #[arg(long, value_name = "DURATION", default_value = "1s")]
    pub timeout: String,
    /// This host's own ROC unit and group, the source of its requests.
    #[arg(long, value_name = "UNIT,GROUP", default_value = "3,1", value_parser = crate::serve_cmd::roc_address)]
    pub unit: Address,
    /// The protocol the device speaks: roc (FloBoss 107; the module's whole list) or rocplus (8, 180, 181).
    #[arg(long, value_enum, default_value = "roc")]
    pub protocol: ProtocolArg,
}

#[derive(Clone, Copy, clap::ValueEnum)]
pub enum ProtocolArg {
    Roc,
    #[value(name = "rocplus")]
    RocPlus,
}

impl From<ProtocolArg> for linc_driver::roc::Protocol {
    fn from(p: ProtocolArg) -> Self {
        match p {
            ProtocolArg::Roc => Self::Roc,
            ProtocolArg::RocPlus => Self::RocPlus,
        }
    }
}

pub fn run(c: RocCommand, r: &Reporter) -> u8 {
    match c {
        RocCommand::Poll(a) => poll_cmd(a, r),
    }
}

/// Exit status: 0 when every command's last status is 0, 1 when one
/// ended with an error, 2 for a file or argument problem.
fn poll_cmd(a: PollArgs, r: &Reporter) -> u8 {
    let duration = |flag: &str, text: &str| linc_driver::database::duration(flag, text).map(Duration::from_micros);
    let times = duration("--timeout", &a.timeout)
        .and_then(|t| Ok((t, a.duration.as_deref().map(|d| duration("--for", d)).transpose()?)));
    let (timeout, run_for) = match times {
        Ok(t) => t,
        Err(p) => return r.report(&p),
    };
    let link = match (a.host, a.serial, a.line.line()) {
        (_, Some(path), Some(line)) => LinkTo::Serial { path, line },
        (Some(addr), ..) => LinkTo::Tcp(addr),
        // clap requires one of the two, and --baud with --serial.
        _ => return crate::report::usage(r, "--host ADDR:PORT or --serial PATH --baud N"),
    };
    let req = PollRequest {
        link,
        commands: a.commands,
        words: a.words,
        run_for,
        out: a.out,
        timeout,
        unit: a.unit,
        protocol: a.protocol.into(),
    };
    match linc_driver::roc::poll(&req, &mut |line| out::line(line)) {
        Ok(status) => u8::from(status.iter().any(|&s| s != 0)),
        Err(p) => r.report(&p),
    }
}

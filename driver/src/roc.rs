//! `linc roc poll` as a library: the command list and the word table read
//! with their errors located in the file, the list run against a device by
//! linc-comms' host, and the word table written back atomically, never over
//! an input.

use crate::files::{read_input_text, write_atomic};
use linc_comms::error::FileError;
pub use linc_comms::roc::host::Protocol;
use linc_comms::roc::host::{poll::poll as run_list, status_text, Command, Host, TcpLink, Words};
use linc_comms::roc::host::{Link, SerialLink};
pub use linc_comms::roc::Address;
pub use linc_comms::serial::{DataBits, Line, Parity, StopBits};
use linc_compiler::diag::{Diagnostic, Problems, Span};
use linc_format::Code;
use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// What to poll, and how.
pub struct PollRequest {
    /// The device's end: `--host` or `--serial`.
    pub link: LinkTo,
    /// The command list (`--commands`).
    pub commands: PathBuf,
    /// The initial word table (`--words`); all zeros without it.
    pub words: Option<PathBuf>,
    /// Keep polling this long, each command by its POLL TIME; once without.
    pub run_for: Option<Duration>,
    /// Where the word table and each command's status go (`--out`).
    pub out: Option<PathBuf>,
    pub timeout: Duration,
    /// This host's own unit and group.
    pub unit: Address,
    /// The protocol the device speaks (`--protocol`): which commands the
    /// list may hold.
    pub protocol: Protocol,
}

/// Where the device is.
#[derive(Clone, Debug)]
pub enum LinkTo {
    /// Over TCP (`--host ADDR:PORT`).
    Tcp(SocketAddr),
    /// On a serial port (`--serial PATH --baud N`).
    Serial { path: PathBuf, line: Line },
}

impl LinkTo {
    /// The link, opened now for a serial port: a port that can't be
    /// opened is a refused request (E0905) shown against its path, where
    /// a TCP device that does not answer is each command's timeout.
    fn open(&self, timeout: Duration) -> Result<Box<dyn Link>, Problems> {
        match self {
            LinkTo::Tcp(addr) => Ok(Box::new(TcpLink::new(*addr, timeout))),
            LinkTo::Serial { path, line } => SerialLink::open(&path.to_string_lossy(), *line, timeout)
                .map(|l| Box::new(l) as Box<dyn Link>)
                .map_err(|e| serial_unopenable(path, &e)),
        }
    }
}

/// A serial port that could not be opened (E0905), shown against its path.
pub fn serial_unopenable(path: &Path, e: &dyn std::fmt::Display) -> Problems {
    let name = path.display().to_string();
    Problems::whole_file(&name, Code::E0905, format!("can't open the serial port `{name}`: {e}"))
}

/// A comms file error at its place in the file (a refused request).
fn located(path: &Path, text: String, e: FileError) -> Problems {
    let mut p = Problems::new();
    let id = p.add_file(path.display().to_string(), text);
    let span = e.span.map(|(s, t)| Span::new(s, t)).unwrap_or_default();
    p.push(Diagnostic::error(e.code, e.message, span).label("here").in_file(id));
    p.refused()
}

/// Reads a file with `parse`.
fn read<T>(path: &Path, parse: impl Fn(&str) -> Result<T, FileError>) -> Result<T, Problems> {
    let text = read_input_text(path).map_err(|e| Problems::unreadable(path, &e))?;
    parse(&text).map_err(|e| located(path, text, e))
}

/// Runs the command list: each status line goes to `say` as it happens
/// (every command's once without `run_for`, errors only with it, then each
/// command's last status). The statuses, each command's last; a list or
/// word table that can't be read, an output that names an input, or a
/// serial port that can't be opened, is a refused request, before any
/// request is sent.
pub fn poll(req: &PollRequest, say: &mut dyn FnMut(&str)) -> Result<Vec<u16>, Problems> {
    let list = read(&req.commands, |text| linc_comms::roc::host::commands::parse(text, req.protocol))?;
    let words = match &req.words {
        Some(p) => read(p, Words::parse)?,
        None => Words::default(),
    };
    if let Some(out) = &req.out {
        let inputs: Vec<&Path> = [Some(req.commands.as_path()), req.words.as_deref()].into_iter().flatten().collect();
        crate::files::check_output(out, &inputs)?;
    }
    let mut host = Host { me: req.unit, words };
    let mut link = req.link.open(req.timeout)?;
    let once = req.run_for.is_none();
    let status = run_list(&mut host, &list, link.as_mut(), req.run_for, |i, code| {
        if once || code != 0 {
            say(&status_line(i, &list[i], code));
        }
    });
    if !once {
        for (i, code) in status.iter().enumerate().filter(|(i, _)| list[*i].enabled()) {
            say(&format!("command {}: last status {code} ({})", i + 1, status_text(*code)));
        }
    }
    if let Some(path) = &req.out {
        write_atomic(path, host.words.to_json(Some(&status)).as_bytes())?;
    }
    Ok(status)
}

fn status_line(i: usize, c: &Command, code: u16) -> String {
    let how = if code == 0 { "done".to_string() } else { format!("error {code}: {}", status_text(code)) };
    format!("command {} (line {}): {} to {},{}: {how}", i + 1, c.line, c.opcode, c.unit, c.group)
}

//! `linc roc poll`: the ROC communication module's master side against a
//! device (docs/roc-host.md). Reading and writing the files is the
//! driver's, polling is linc-comms'; this prints.

use crate::out;
use crate::report::usage;
use linc_comms::roc::host::{poll::poll, status_text, Host, TcpLink};
use linc_comms::roc::Address;
use linc_driver::Reporter;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

#[derive(clap::Subcommand)]
pub enum RocCommand {
    /// Run a command list (CSV in the module manual's columns) against a ROC Plus device over TCP.
    Poll(PollArgs),
}

#[derive(clap::Args)]
pub struct PollArgs {
    /// The device: ADDR:PORT.
    #[arg(long, value_name = "ADDR:PORT")]
    pub host: SocketAddr,
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
}

pub fn run(c: RocCommand, r: &mut Reporter) -> u8 {
    match c {
        RocCommand::Poll(a) => poll_cmd(a, r),
    }
}

fn duration(text: &str, what: &str) -> Result<Duration, String> {
    linc_driver::database::duration(text).map(Duration::from_micros).map_err(|e| format!("{what}: {e}"))
}

/// Exit status: 0 when every command's last status is 0, 1 when one
/// ended with an error, 2 for a file or argument problem.
fn poll_cmd(a: PollArgs, r: &mut Reporter) -> u8 {
    let (timeout, run_for) =
        match (duration(&a.timeout, "--timeout"), a.duration.as_deref().map(|d| duration(d, "--for"))) {
            (Ok(t), None) => (t, None),
            (Ok(t), Some(Ok(d))) => (t, Some(d)),
            (Err(e), _) | (_, Some(Err(e))) => return usage(r, e),
        };
    let list = match linc_driver::roc::commands(&a.commands, r) {
        Ok(l) => l,
        Err(s) => return s,
    };
    let words = match linc_driver::roc::words(a.words.as_deref(), r) {
        Ok(w) => w,
        Err(s) => return s,
    };
    // `--out` may not name an input: refused before any request is sent.
    if let Some(out) = &a.out {
        let inputs: Vec<&std::path::Path> =
            [Some(a.commands.as_path()), a.words.as_deref()].into_iter().flatten().collect();
        if let Err(e) = linc_driver::files::check_output(out, &inputs) {
            return crate::report::refused(r, e.diagnostic());
        }
    }
    let mut host = Host { me: a.unit, words };
    let mut link = TcpLink::new(a.host, timeout);
    let once = run_for.is_none();
    let status = poll(&mut host, &list, &mut link, run_for, |i, code| {
        if once || code != 0 {
            let c = &list[i];
            let line = format!(
                "command {} (line {}): {} to {},{}: {}",
                i + 1,
                c.line,
                c.opcode,
                c.unit,
                c.group,
                if code == 0 { "done".to_string() } else { format!("error {code}: {}", status_text(code)) }
            );
            out::line(&line);
        }
    });
    if !once {
        for (i, code) in status.iter().enumerate().filter(|(i, _)| list[*i].enabled()) {
            out::line(&format!("command {}: last status {code} ({})", i + 1, status_text(*code)));
        }
    }
    if let Some(path) = &a.out {
        if let Err(s) = linc_driver::roc::write_words(path, &host.words, &status, r) {
            return s;
        }
    }
    u8::from(status.iter().any(|&s| s != 0))
}

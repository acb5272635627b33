//! A wire server on a serial port (`--roc-serial`): real ROC links are
//! RS-232/485 lines and radios. The port is one long-lived connection,
//! served by the same connection loop as a TCP client, so frames are found
//! in the byte stream alike (noise dropped, split frames joined, a request
//! that stops half-way dropped after [`Limits::request`]). What differs is
//! what ends it: a quiet line is normal, so silence does not; a port that
//! fails (an adapter unplugged, a hang-up) is logged and opened again after
//! a short pause, and the server goes on.

use super::net::{client, until_closed, Limits, Log, Peer, Stop, Wire};
use crate::Ask;
use linc_comms::serial::Line;
use std::path::{Path, PathBuf};
use std::time::Duration;
use tokio::sync::watch;
use tokio_serial::SerialStream;

/// How long a failed port rests before it is opened again: long enough
/// not to spin on a port that is gone, short enough that the host's next
/// poll finds it back.
pub(crate) const REOPEN_AFTER: Duration = Duration::from_secs(1);

/// The serial port a server was started on: where, how its line runs, and
/// the port itself, opened at the start (so a wrong path fails there).
pub(crate) struct Port {
    pub path: PathBuf,
    pub line: Line,
    pub stream: SerialStream,
}

/// Opens the port at `path`, on the runtime whose context is entered.
pub(crate) fn open(path: &Path, line: &Line) -> Result<SerialStream, tokio_serial::Error> {
    // The builder's timeout is for blocking reads; this port never blocks.
    SerialStream::open(&line.builder(&path.to_string_lossy(), Duration::from_secs(1)))
}

/// Serves protocol `W` on the port until `closing` turns true: the
/// connection loop on the port, again on the same port after a request
/// that took too long (its bytes are dropped), again on the port opened
/// anew after it failed.
pub(crate) async fn serve<W: Wire>(
    port: Port,
    plant: (std::sync::mpsc::Sender<Ask>, Limits, Log),
    mut closing: watch::Receiver<bool>,
    wire: impl Fn() -> W,
) {
    let Port { path, line, stream } = port;
    let name = path.display().to_string();
    let log = plant.2.clone();
    let mut open = Some(stream);
    loop {
        let mut stream = match open.take() {
            Some(s) => s,
            None => match reopen(&path, &line, &log, &mut closing, W::NAME).await {
                Some(s) => s,
                None => return,
            },
        };
        let peer = Peer { name: name.clone(), idle_ends: false };
        let stop = tokio::select! {
            stop = client(&mut stream, peer, wire(), plant.clone()) => stop,
            () = until_closed(&mut closing) => return,
        };
        match stop {
            Stop::Over => return,
            Stop::Idle | Stop::Slow => open = Some(stream),
            Stop::Closed(e) => {
                let what = match e {
                    Some(e) => format!("the serial port failed: {e}"),
                    None => "the serial line hung up".to_string(),
                };
                log(format!("{} {name}: {what}; opening it again in {} s", W::NAME, REOPEN_AFTER.as_secs()));
            }
        }
    }
}

/// The port opened again, after [`REOPEN_AFTER`] and then every
/// [`REOPEN_AFTER`] while it can't be; `None` when the server closes
/// meanwhile. The first failure is logged and the success, not each try,
/// so a port that stays gone does not flood the log.
async fn reopen(
    path: &Path,
    line: &Line,
    log: &Log,
    closing: &mut watch::Receiver<bool>,
    what: &str,
) -> Option<SerialStream> {
    let name = path.display();
    let mut failed = false;
    loop {
        tokio::select! {
            () = tokio::time::sleep(REOPEN_AFTER) => {}
            () = until_closed(closing) => return None,
        }
        match open(path, line) {
            Ok(s) => {
                log(format!("{what} {name}: the serial port is open again"));
                return Some(s);
            }
            Err(e) if !failed => {
                let every = REOPEN_AFTER.as_secs();
                log(format!("{what} {name}: can't open the serial port again: {e}; trying every {every} s"));
                failed = true;
            }
            Err(_) => {}
        }
    }
}

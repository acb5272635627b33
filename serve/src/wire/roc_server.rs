//! The ROC server: frames off TCP, or off a serial line, for this device
//! go to the plant thread; the connection loop is the one every wire
//! server shares. The
//! dialect decides which frames are this device's (the ROC protocol also
//! answers the universal address and obeys broadcasts silently), and a
//! store-and-forward frame bound further is passed on here, off the plant
//! thread, so a slow radio link never holds a scan.

use super::net::{Next, Wire};
use super::roc::{Answer, Dialect};
use crate::Ask;
use linc_comms::roc::rocp::{self, forward, Addressed};
use linc_comms::roc::{Address, Deframer, Frame};
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::oneshot;

/// How long a relay waits for the next device's reply.
pub(crate) const RELAY_TIMEOUT: Duration = Duration::from_secs(3);

/// What every connection to the device knows of it.
#[derive(Clone, Debug)]
pub(crate) struct Station {
    pub me: Address,
    pub dialect: Dialect,
    /// Where store and forward reaches each device (`"roc": {"forward"}`).
    pub links: Arc<Vec<((u8, u8), SocketAddr)>>,
}

/// One client's ROC state: its frames, the operator logged in on the
/// connection (the access level), and whether the request at the plant
/// was a broadcast (answered by no reply).
pub(crate) struct Roc {
    station: Station,
    frames: Deframer,
    session: Option<u8>,
    silent: bool,
}

impl Roc {
    pub(crate) fn new(station: Station) -> Roc {
        Roc { station, frames: Deframer::default(), session: None, silent: false }
    }

    /// A store-and-forward frame bound past this device: passed on, or an
    /// error reply for a path it cannot follow. `None` when it ends here.
    fn relay(&self, frame: &Frame, peer: &str) -> Option<Next<Answer>> {
        let me = self.station.me;
        let w = forward::parse(&frame.data).ok()?;
        let next = match w.path.route(me) {
            Ok(forward::Route::Here) => return None,
            Ok(forward::Route::Next(a)) => a,
            Err(e) => return Some(Next::Reply(error_reply(frame, me, e).unwrap_or_default())),
        };
        let link = self.station.links.iter().find(|(d, _)| *d == (next.unit, next.group)).map(|&(_, a)| a);
        Some(Next::Later(Box::pin(pass_on(frame.clone(), me, (w.path, next), link, peer.to_string()))))
    }
}

/// Error 22 (invalid store and forward path) for a frame, from `me`.
fn error_reply(req: &Frame, me: Address, e: linc_comms::roc::ops::RocError) -> Option<Vec<u8>> {
    Frame { dst: req.src, src: me, opcode: rocp::ERROR, data: rocp::error_data(e, req.opcode) }.encode()
}

/// Passes a store-and-forward frame along `path` to `next` over `link` and brings its
/// reply back to the host with this device as the source; no link, no
/// answer within [`RELAY_TIMEOUT`], or a reply that is not for this path,
/// is error 22. Each outcome is logged.
async fn pass_on(
    req: Frame,
    me: Address,
    (path, next): (forward::Path, Address),
    link: Option<SocketAddr>,
    peer: String,
) -> (Option<Vec<u8>>, Vec<String>) {
    let fail = |why: String| {
        let e = linc_comms::roc::ops::RocError::at_data(rocp::code::FORWARD_PATH, 2);
        (error_reply(&req, me, e), vec![format!("roc {peer}: store and forward to {next} refused: {why}")])
    };
    let Some(addr) = link else { return fail(format!("no link to {next} in the database's `roc.forward`")) };
    let out = Frame { dst: next, src: me, opcode: rocp::FORWARD, data: req.data.clone() };
    let reply = match tokio::time::timeout(RELAY_TIMEOUT, exchange(addr, &out)).await {
        Ok(Ok(r)) => r,
        Ok(Err(e)) => return fail(format!("{addr}: {e}")),
        Err(_) => return fail(format!("{addr} did not answer within {} s", RELAY_TIMEOUT.as_secs())),
    };
    let ours = |f: &Frame| forward::parse(&f.data).is_ok_and(|w| w.path == path);
    if reply.opcode != rocp::ERROR && !(reply.opcode == rocp::FORWARD && ours(&reply)) {
        return fail(format!("{addr} answered with opcode {} for another path", reply.opcode));
    }
    let back = Frame { dst: req.src, src: me, opcode: reply.opcode, data: reply.data };
    (back.encode(), vec![format!("roc {peer}: passed a store-and-forward frame to {next} at {addr}")])
}

/// Sends a frame over a new connection and waits for the reply from its
/// destination to this device (other frames are dropped).
async fn exchange(addr: SocketAddr, out: &Frame) -> std::io::Result<Frame> {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let bytes = out.encode().ok_or_else(|| std::io::Error::other("frame too long"))?;
    let mut s = tokio::net::TcpStream::connect(addr).await?;
    s.write_all(&bytes).await?;
    let mut frames = Deframer::default();
    let mut buf = [0u8; 512];
    loop {
        let n = s.read(&mut buf).await?;
        if n == 0 {
            return Err(std::io::Error::other("closed the connection without a reply"));
        }
        frames.push(&buf[..n]);
        while let Some(f) = frames.next_frame() {
            if f.src == out.dst && f.dst == out.src {
                return Ok(f);
            }
        }
    }
}

impl Wire for Roc {
    type Answer = Answer;
    const NAME: &'static str = "roc";

    fn push(&mut self, bytes: &[u8]) {
        self.frames.push(bytes);
    }

    fn pending(&self) -> usize {
        self.frames.pending()
    }

    /// A whole frame for this device goes to the plant (a store-and-forward
    /// frame bound further is passed on); frames for other addresses and
    /// bytes that make no frame (a bad CRC) get no reply.
    fn next(&mut self, peer: &str) -> Option<Next<Answer>> {
        let frame = self.frames.next_frame()?;
        let me = self.station.me;
        self.silent = false;
        match self.station.dialect {
            Dialect::RocPlus if frame.dst != me => return Some(Next::Skip),
            Dialect::RocPlus => {}
            Dialect::Roc => match rocp::addressed(me, frame.dst) {
                Addressed::Other => return Some(Next::Skip),
                Addressed::Broadcast => self.silent = true,
                Addressed::Answer if frame.opcode == rocp::FORWARD => {
                    if let Some(next) = self.relay(&frame, peer) {
                        return Some(next);
                    }
                }
                Addressed::Answer => {}
            },
        }
        let (reply, answer) = oneshot::channel();
        Some(Next::Ask(Ask::Roc { frame, peer: peer.to_string(), session: self.session, reply }, answer))
    }

    fn answered(&mut self, answer: Answer) -> (Option<Vec<u8>>, Vec<String>) {
        self.session = answer.session;
        if std::mem::take(&mut self.silent) {
            return (None, answer.log);
        }
        (answer.reply.encode(), answer.log)
    }

    fn farewell(&self, peer: &str) -> Option<String> {
        let dropped = self.frames.dropped;
        (dropped > 0).then(|| format!("roc {peer}: {dropped} bytes made no frame (bad CRC or noise) and were dropped"))
    }
}

//! The one connection loop of both wire servers: the connection cap, the
//! timeouts that drop idle and slow clients, the log lines that say why,
//! and each client's requests in turn to the plant. A protocol plugs in
//! what differs ([`Wire`]: how requests come off the stream, what the
//! plant is asked, how its answer goes back), in `roc_server.rs` and
//! `modbus_server.rs`.
//!
//! Each connection is a task on the server's runtime with at most one
//! request at the plant at a time, so however hostile the traffic, the
//! plant thread sees at most one question per client between two scans.
//! The loop is generic over the stream: a serial port (`serial.rs`) is
//! served by it as one long-lived connection.

use crate::Ask;
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;
use tokio::io::{AsyncRead, AsyncReadExt, AsyncWrite, AsyncWriteExt};
use tokio::net::TcpListener;
use tokio::sync::{oneshot, watch, Semaphore};
// The runtime's clock, not the system's: the timeouts and the once-a-second
// log follow tokio's time, which a test can pause and move on.
use tokio::time::Instant;

/// How much a server puts up with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Clients connected at once; more are refused (and logged).
    pub max_clients: usize,
    /// A client that sends nothing for this long is dropped.
    pub idle: Duration,
    /// A request must arrive whole within this long of its first byte (a
    /// client sending a byte a second is dropped).
    pub request: Duration,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits { max_clients: 64, idle: Duration::from_secs(60), request: Duration::from_secs(5) }
    }
}

/// Where a server's log lines go (the CLI prints them to standard error).
pub type Log = Arc<dyn Fn(String) + Send + Sync>;

/// Refusals over the cap are logged at most once a second, with a count,
/// so a flood of connections can't flood the log; the ones not yet logged
/// when a burst ends are logged a second after the last line, so no count
/// is lost. Owned by one accept loop.
#[derive(Default)]
struct Refusals {
    /// Refused and not yet logged, and the latest of them.
    pending: u64,
    peer: Option<SocketAddr>,
    /// When the last line was logged.
    logged: Option<Instant>,
}

impl Refusals {
    fn note(&mut self, peer: SocketAddr, how: &Listen) {
        self.pending += 1;
        self.peer = Some(peer);
        if self.logged.is_none_or(|t| t.elapsed() >= Duration::from_secs(1)) {
            self.flush(how);
        }
    }

    /// When the refusals not yet logged are due to be.
    fn due(&self) -> Option<Instant> {
        let logged = self.logged?;
        (self.pending > 0).then(|| logged + Duration::from_secs(1))
    }

    fn flush(&mut self, how: &Listen) {
        let Some(peer) = self.peer.filter(|_| self.pending > 0) else { return };
        let (what, cap) = (how.what, how.limits.max_clients);
        (how.log)(format!("{what}: refused {peer} and {} more: {cap} clients is the limit", self.pending - 1));
        self.pending = 0;
        self.logged = Some(Instant::now());
    }
}

/// How one server listens: its name in the log, what a client over the
/// cap is sent before it is closed, its limits and its log.
#[derive(Clone)]
pub(crate) struct Listen {
    pub what: &'static str,
    pub busy: &'static [u8],
    /// Whether closing waits (up to [`Limits::request`]) for the clients
    /// to finish what they are in: HTTP connections finish their request
    /// and end; a wire client is simply dropped.
    pub drain: bool,
    pub limits: Limits,
    pub log: Log,
}

/// The accept loop every server shares (ROC, Modbus, HTTP): clients are
/// served by `serve`, each in a task of its own, while fewer than the cap
/// are connected; one over the cap is sent `busy` (if the socket takes it
/// at once), closed and counted. Returns when `closing` turns true (and,
/// with [`Listen::drain`], the clients have finished).
pub(crate) async fn accept<F, Fut>(listener: TcpListener, how: Listen, mut closing: watch::Receiver<bool>, serve: F)
where
    F: Fn(tokio::net::TcpStream, SocketAddr) -> Fut,
    Fut: std::future::Future<Output = ()> + Send + 'static,
{
    let permits = Arc::new(Semaphore::new(how.limits.max_clients));
    let mut refusals = Refusals::default();
    loop {
        let due = refusals.due();
        let accepted = tokio::select! {
            a = listener.accept() => a,
            () = sleep_until(due), if due.is_some() => {
                refusals.flush(&how);
                continue;
            }
            () = until_closed(&mut closing) => {
                refusals.flush(&how);
                if how.drain {
                    let all = permits.acquire_many(how.limits.max_clients as u32);
                    let _ = tokio::time::timeout(how.limits.request, all).await;
                }
                return;
            }
        };
        let Ok((stream, peer)) = accepted else { continue };
        match permits.clone().try_acquire_owned() {
            Ok(permit) => {
                let task = serve(stream, peer);
                tokio::spawn(async move {
                    task.await;
                    drop(permit);
                });
            }
            Err(_) => {
                if !how.busy.is_empty() {
                    let _ = stream.try_write(how.busy);
                }
                refusals.note(peer, &how);
            }
        }
    }
}

/// Returns when `closing` is true (or its sender is gone).
pub(crate) async fn until_closed(closing: &mut watch::Receiver<bool>) {
    while !*closing.borrow_and_update() {
        if closing.changed().await.is_err() {
            return;
        }
    }
}

async fn sleep_until(due: Option<Instant>) {
    if let Some(t) = due {
        tokio::time::sleep_until(t).await;
    }
}

/// Accepts clients of protocol `W`, each served by the connection loop;
/// `wire` makes each connection's protocol state.
pub(crate) async fn accept_wire<W: Wire>(
    listener: TcpListener,
    plant: (std::sync::mpsc::Sender<Ask>, Limits, Log),
    closing: watch::Receiver<bool>,
    wire: impl Fn() -> W,
) {
    let (asks, limits, log) = plant;
    let how = Listen { what: W::NAME, busy: b"", drain: false, limits, log: log.clone() };
    accept(listener, how, closing, move |stream, peer| {
        let _ = stream.set_nodelay(true);
        let peer = Peer { name: peer.to_string(), idle_ends: true };
        let served = client(stream, peer, wire(), (asks.clone(), limits, log.clone()));
        async move {
            served.await;
        }
    })
    .await
}

/// Who a connection is with.
pub(crate) struct Peer {
    /// How log lines name it: `127.0.0.1:51000`, `/dev/ttyS0`.
    pub name: String,
    /// Whether sending nothing for [`Limits::idle`] ends the connection: a
    /// TCP client that does is gone or stuck, and holds a place under the
    /// cap; a serial line is quiet between polls as a matter of course.
    pub idle_ends: bool,
}

/// What a protocol plugs into the connection loop.
pub(crate) trait Wire: Send + 'static {
    /// The plant's answer to one request.
    type Answer: Send + 'static;
    /// How log lines name the protocol (`roc`, `modbus`).
    const NAME: &'static str;
    /// Takes the bytes read.
    fn push(&mut self, bytes: &[u8]);
    /// Bytes waiting for the rest of their request.
    fn pending(&self) -> usize;
    /// The next whole request, if any, and what to do with it.
    fn next(&mut self, peer: &str) -> Option<Next<Self::Answer>>;
    /// The bytes to send back for the plant's answer (none: no reply), and
    /// the log lines it brought.
    fn answered(&mut self, answer: Self::Answer) -> (Option<Vec<u8>>, Vec<String>);
    /// A last log line when the connection ends (bytes thrown away).
    fn farewell(&self, _peer: &str) -> Option<String> {
        None
    }
}

/// An answer that waits on something other than the plant: the bytes to
/// send back, if any, and the log lines.
pub(crate) type Later = std::pin::Pin<Box<dyn std::future::Future<Output = (Option<Vec<u8>>, Vec<String>)> + Send>>;

/// What a protocol makes of a request off the stream.
pub(crate) enum Next<A> {
    /// A question for the plant, and where its answer comes.
    Ask(Ask, oneshot::Receiver<A>),
    /// Answered without the plant (a request that does not decode).
    Reply(Vec<u8>),
    /// Answered without the plant, once something else has answered (a
    /// store-and-forward frame passed on to the next device): the bytes to
    /// send back, if any, and the log lines.
    Later(Later),
    /// Not for this device: no reply.
    Skip,
    /// A stream that can't go on: closed, and logged with why.
    Close(String),
}

/// Serves one client: each request the protocol takes off the stream is
/// answered in turn (through the plant, or by the protocol itself) until
/// the client leaves, is idle or slow too long, or sends what can't go on.
/// Returns why it ended (what a serial port's loop needs to go on).
pub(crate) async fn client<W: Wire, S: AsyncRead + AsyncWrite + Unpin>(
    mut stream: S,
    peer: Peer,
    mut wire: W,
    (asks, limits, log): (std::sync::mpsc::Sender<Ask>, Limits, Log),
) -> Stop {
    let mut buf = [0u8; 4096];
    let mut begun: Option<Instant> = None;
    let idle = peer.idle_ends.then_some(limits.idle);
    let peer = peer.name.as_str();
    let stop = 'conn: loop {
        let n = match read_some(&mut stream, &mut buf, (idle, limits.request), begun).await {
            Ok(n) => n,
            Err(stop) => break stop,
        };
        wire.push(&buf[..n]);
        while let Some(next) = wire.next(peer) {
            let bytes = match next {
                Next::Skip => continue,
                Next::Close(why) => {
                    log(format!("{} {peer}: dropped: {why}", W::NAME));
                    return Stop::Over;
                }
                Next::Reply(bytes) => Some(bytes),
                Next::Later(answer) => {
                    let (bytes, lines) = answer.await;
                    lines.into_iter().for_each(|line| log(line));
                    bytes
                }
                Next::Ask(ask, answer) => {
                    if asks.send(ask).is_err() {
                        return Stop::Over;
                    }
                    let Ok(answer) = answer.await else { return Stop::Over };
                    let (bytes, lines) = wire.answered(answer);
                    lines.into_iter().for_each(|line| log(line));
                    bytes
                }
            };
            if let Some(bytes) = bytes {
                if let Err(stop) = reply(&mut stream, &bytes, &limits).await {
                    break 'conn stop;
                }
            }
        }
        begun = waiting_since(wire.pending(), begun);
    };
    if let Some(line) = wire.farewell(peer) {
        log(line);
    }
    if let Some(why) = stop.why(&limits) {
        log(format!("{} {peer}: dropped: {why}", W::NAME));
    }
    stop
}

/// Why a connection ended.
#[derive(Debug)]
pub(crate) enum Stop {
    /// The client closed the connection (end of file: `None`), or reading
    /// or writing failed.
    Closed(Option<std::io::Error>),
    /// Nothing for [`Limits::idle`].
    Idle,
    /// A request begun and not finished within [`Limits::request`].
    Slow,
    /// The plant has stopped, or the protocol closed the stream (logged).
    Over,
}

impl Stop {
    /// The log line for a dropped client, `None` for one that left.
    fn why(&self, limits: &Limits) -> Option<String> {
        match self {
            Stop::Closed(_) | Stop::Over => None,
            Stop::Idle => Some(format!("idle for {} s", limits.idle.as_secs())),
            Stop::Slow => Some(format!("a request took more than {} s to arrive", limits.request.as_secs())),
        }
    }
}

/// Reads what arrives, with the deadline that applies: the request's if
/// `begun` (bytes of an unfinished request wait), else the idle one, if
/// silence ends the connection (`idle`); without either, it waits.
async fn read_some<R: AsyncRead + Unpin>(
    stream: &mut R,
    buf: &mut [u8],
    (idle, request): (Option<Duration>, Duration),
    begun: Option<Instant>,
) -> Result<usize, Stop> {
    let (deadline, why) = match (begun, idle) {
        (Some(t), _) => (t + request, Stop::Slow),
        (None, Some(idle)) => (Instant::now() + idle, Stop::Idle),
        (None, None) => return read_result(stream.read(buf).await),
    };
    match tokio::time::timeout_at(deadline, stream.read(buf)).await {
        Err(_) => Err(why),
        Ok(read) => read_result(read),
    }
}

fn read_result(read: std::io::Result<usize>) -> Result<usize, Stop> {
    match read {
        Ok(0) => Err(Stop::Closed(None)),
        Ok(n) => Ok(n),
        Err(e) => Err(Stop::Closed(Some(e))),
    }
}

/// Writes a reply, giving a client that does not read it [`Limits::idle`]
/// before the connection is dropped; `Err` ends the connection.
async fn reply<S: AsyncWrite + Unpin>(stream: &mut S, bytes: &[u8], limits: &Limits) -> Result<(), Stop> {
    match tokio::time::timeout(limits.idle, stream.write_all(bytes)).await {
        Ok(Ok(())) => Ok(()),
        Ok(Err(e)) => Err(Stop::Closed(Some(e))),
        Err(_) => {
            let why = format!("a reply could not be written in {} s", limits.idle.as_secs());
            Err(Stop::Closed(Some(std::io::Error::new(std::io::ErrorKind::TimedOut, why))))
        }
    }
}

/// When the bytes waiting for the rest of their request began to wait:
/// `None` when nothing waits, else `begun` or now.
fn waiting_since(pending: usize, begun: Option<Instant>) -> Option<Instant> {
    if pending == 0 {
        None
    } else {
        begun.or(Some(Instant::now()))
    }
}

/// The connection loop in tokio's paused time: timeouts fire at exactly
/// the simulated instant they are due, however busy the machine is.
#[cfg(test)]
mod tests {
    use super::*;
    use crate::wire::roc::Answer;
    use crate::wire::roc_server::{Roc, Station};
    use linc_comms::roc::{Address, Frame};
    use std::sync::Mutex;
    use tokio::io::{duplex, DuplexStream};

    const ME: Address = Address { unit: 1, group: 2 };

    fn limits() -> Limits {
        Limits { max_clients: 4, idle: Duration::from_secs(2), request: Duration::from_secs(1) }
    }

    /// A ROC connection served by the loop, the client's end of it, what
    /// the loop logs, and where its questions to the plant go.
    fn connection() -> (DuplexStream, Arc<Mutex<Vec<String>>>, std::sync::mpsc::Receiver<Ask>) {
        let (server, client_end) = duplex(4096);
        let lines = Arc::new(Mutex::new(Vec::new()));
        let kept = lines.clone();
        let log: Log = Arc::new(move |l| kept.lock().unwrap().push(l));
        let (asks, asked) = std::sync::mpsc::channel();
        let peer = Peer { name: "127.0.0.1:5000".into(), idle_ends: true };
        let station = Station { me: ME, dialect: crate::wire::roc::Dialect::RocPlus, links: Default::default() };
        tokio::spawn(client(server, peer, Roc::new(station), (asks, limits(), log)));
        (client_end, lines, asked)
    }

    /// Reads until the loop closes the connection; the simulated time it took.
    async fn closed(mut c: DuplexStream) -> Duration {
        let start = Instant::now();
        let mut buf = [0u8; 64];
        while c.read(&mut buf).await.is_ok_and(|n| n > 0) {}
        start.elapsed()
    }

    fn read_frame(opcode: u8) -> Vec<u8> {
        Frame { dst: ME, src: Address { unit: 3, group: 1 }, opcode, data: vec![1, 17, 0, 2] }.encode().unwrap()
    }

    #[tokio::test(start_paused = true)]
    async fn an_idle_client_is_dropped_at_the_idle_limit() {
        let (c, log, _) = connection();
        assert_eq!(closed(c).await, Duration::from_secs(2));
        assert_eq!(*log.lock().unwrap(), ["roc 127.0.0.1:5000: dropped: idle for 2 s"]);
    }

    #[tokio::test(start_paused = true)]
    async fn a_quiet_serial_line_is_not_dropped_but_a_stalled_request_still_is() {
        let (mut c, server) = duplex(4096);
        let lines = Arc::new(Mutex::new(Vec::new()));
        let kept = lines.clone();
        let log: Log = Arc::new(move |l| kept.lock().unwrap().push(l));
        let (asks, _asked) = std::sync::mpsc::channel();
        let peer = Peer { name: "/dev/ttyS0".into(), idle_ends: false };
        let station = Station { me: ME, dialect: crate::wire::roc::Dialect::RocPlus, links: Default::default() };
        let served = tokio::spawn(client(server, peer, Roc::new(station), (asks, limits(), log)));
        // An hour of silence: ten times nothing, and the line is still served.
        tokio::time::sleep(Duration::from_secs(3600)).await;
        assert!(!served.is_finished() && lines.lock().unwrap().is_empty());
        // Half a frame is still a request that must arrive within 1 s.
        c.write_all(&read_frame(180)[..4]).await.unwrap();
        let stop = served.await.unwrap();
        assert!(matches!(stop, Stop::Slow), "{stop:?}");
        assert_eq!(*lines.lock().unwrap(), ["roc /dev/ttyS0: dropped: a request took more than 1 s to arrive"]);
    }

    #[tokio::test(start_paused = true)]
    async fn a_request_that_trickles_in_is_dropped_at_the_request_limit() {
        let (mut c, log, _) = connection();
        let start = Instant::now();
        let frame = read_frame(180);
        // A byte every 600 ms: the second second of the request is never reached.
        for b in &frame[..3] {
            if c.write_all(std::slice::from_ref(b)).await.is_err() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(600)).await;
        }
        let took = start.elapsed() + closed(c).await;
        assert_eq!(took, Duration::from_millis(1200), "dropped when the third byte was due, after 1 s of waiting");
        assert_eq!(*log.lock().unwrap(), ["roc 127.0.0.1:5000: dropped: a request took more than 1 s to arrive"]);
    }

    #[tokio::test(start_paused = true)]
    async fn a_whole_request_is_asked_and_answered_and_noise_is_logged() {
        let (mut c, log, asked) = connection();
        // The plant: answers each question with an echo of its opcode.
        std::thread::spawn(move || {
            while let Ok(Ask::Roc { frame, reply, .. }) = asked.recv() {
                let echo = Frame { dst: frame.src, src: frame.dst, opcode: frame.opcode, data: vec![] };
                let _ = reply.send(Answer { reply: echo, log: vec!["answered".into()], session: None });
            }
        });
        let mut noisy = vec![0x55, 0xAA];
        noisy.extend(read_frame(180));
        c.write_all(&noisy).await.unwrap();
        let mut reply = [0u8; 8];
        c.read_exact(&mut reply).await.unwrap();
        assert_eq!((reply[4], reply[5]), (180, 0), "{reply:?}");
        drop(c);
        tokio::time::sleep(Duration::from_millis(10)).await;
        let log = log.lock().unwrap().join("\n");
        assert_eq!(log, "answered\nroc 127.0.0.1:5000: 2 bytes made no frame (bad CRC or noise) and were dropped");
    }

    #[tokio::test(start_paused = true)]
    async fn refusals_over_the_cap_are_logged_at_most_once_a_second_and_none_is_lost() {
        let lines = Arc::new(Mutex::new(Vec::new()));
        let kept = lines.clone();
        let how = Listen {
            what: "roc",
            busy: b"",
            drain: false,
            limits: limits(),
            log: Arc::new(move |l| kept.lock().unwrap().push(l)),
        };
        let mut r = Refusals::default();
        let peer: SocketAddr = "127.0.0.1:6000".parse().unwrap();
        for _ in 0..100 {
            r.note(peer, &how);
            tokio::time::sleep(Duration::from_millis(15)).await;
        }
        // 1.5 s of refusals: the first logged at once, 67 more a second
        // later, and the 32 of the burst's last half second when their
        // second has passed.
        let due = r.due().expect("refusals wait to be logged");
        assert_eq!(due, Instant::now() + Duration::from_millis(505), "a second after the line at 1,005 ms");
        tokio::time::sleep_until(due).await;
        r.flush(&how);
        assert_eq!(r.due(), None);
        assert_eq!(
            *lines.lock().unwrap(),
            [
                "roc: refused 127.0.0.1:6000 and 0 more: 4 clients is the limit",
                "roc: refused 127.0.0.1:6000 and 66 more: 4 clients is the limit",
                "roc: refused 127.0.0.1:6000 and 31 more: 4 clients is the limit"
            ]
        );
    }
}

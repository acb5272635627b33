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

use crate::Ask;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
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
/// so a flood of connections can't flood the log.
#[derive(Default)]
struct Refusals {
    count: AtomicU64,
    last: std::sync::Mutex<Option<Instant>>,
}

impl Refusals {
    fn note(&self, what: &str, peer: SocketAddr, cap: usize, log: &Log) {
        let n = self.count.fetch_add(1, Ordering::Relaxed) + 1;
        let Ok(mut last) = self.last.lock() else { return };
        if last.is_none_or(|t| t.elapsed() >= Duration::from_secs(1)) {
            *last = Some(Instant::now());
            self.count.store(0, Ordering::Relaxed);
            log(format!("{what}: refused {peer} and {} more: {cap} clients is the limit", n - 1));
        }
    }
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
    fn next(&mut self, peer: SocketAddr) -> Option<Next<Self::Answer>>;
    /// The bytes to send back for the plant's answer (none: no reply), and
    /// the log lines it brought.
    fn answered(&mut self, answer: Self::Answer) -> (Option<Vec<u8>>, Vec<String>);
    /// A last log line when the connection ends (bytes thrown away).
    fn farewell(&self, _peer: SocketAddr) -> Option<String> {
        None
    }
}

/// What a protocol makes of a request off the stream.
pub(crate) enum Next<A> {
    /// A question for the plant, and where its answer comes.
    Ask(Ask, oneshot::Receiver<A>),
    /// Answered without the plant (a request that does not decode).
    Reply(Vec<u8>),
    /// Not for this device: no reply.
    Skip,
    /// A stream that can't go on: closed, and logged with why.
    Close(String),
}

/// Accepts clients of protocol `W` until `closing` turns true, each served
/// by the connection loop in a task of its own while fewer than the cap
/// are connected; `wire` makes each connection's protocol state.
pub(crate) async fn accept<W: Wire>(
    listener: TcpListener,
    plant: (std::sync::mpsc::Sender<Ask>, Limits, Log),
    mut closing: watch::Receiver<bool>,
    wire: impl Fn() -> W,
) {
    let (asks, limits, log) = plant;
    let what = W::NAME;
    let permits = Arc::new(Semaphore::new(limits.max_clients));
    let refusals = Refusals::default();
    loop {
        let accepted = tokio::select! {
            a = listener.accept() => a,
            _ = closing.changed() => return,
        };
        let Ok((stream, peer)) = accepted else { continue };
        match permits.clone().try_acquire_owned() {
            Ok(permit) => {
                let _ = stream.set_nodelay(true);
                let task = client(stream, peer, wire(), (asks.clone(), limits, log.clone()));
                tokio::spawn(async move {
                    task.await;
                    drop(permit);
                });
            }
            Err(_) => refusals.note(what, peer, limits.max_clients, &log),
        }
    }
}

/// Serves one client: each request the protocol takes off the stream is
/// answered in turn (through the plant, or by the protocol itself) until
/// the client leaves, is idle or slow too long, or sends what can't go on.
pub(crate) async fn client<W: Wire, S: AsyncRead + AsyncWrite + Unpin>(
    mut stream: S,
    peer: SocketAddr,
    mut wire: W,
    (asks, limits, log): (std::sync::mpsc::Sender<Ask>, Limits, Log),
) {
    let mut buf = [0u8; 4096];
    let mut begun: Option<Instant> = None;
    let stop = 'conn: loop {
        let n = match read_some(&mut stream, &mut buf, &limits, begun).await {
            Ok(n) => n,
            Err(stop) => break stop,
        };
        wire.push(&buf[..n]);
        while let Some(next) = wire.next(peer) {
            let bytes = match next {
                Next::Skip => continue,
                Next::Close(why) => {
                    log(format!("{} {peer}: dropped: {why}", W::NAME));
                    return;
                }
                Next::Reply(bytes) => Some(bytes),
                Next::Ask(ask, answer) => {
                    if asks.send(ask).is_err() {
                        return;
                    }
                    let Ok(answer) = answer.await else { return };
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
}

/// Why a read gave nothing.
enum Stop {
    /// The client closed the connection or it failed.
    Closed,
    /// Nothing for [`Limits::idle`].
    Idle,
    /// A request begun and not finished within [`Limits::request`].
    Slow,
}

impl Stop {
    /// The log line for a dropped client, `None` for one that left.
    fn why(&self, limits: &Limits) -> Option<String> {
        match self {
            Stop::Closed => None,
            Stop::Idle => Some(format!("idle for {} s", limits.idle.as_secs())),
            Stop::Slow => Some(format!("a request took more than {} s to arrive", limits.request.as_secs())),
        }
    }
}

/// Reads what arrives, with the deadline that applies: the request's if
/// `begun` (bytes of an unfinished request wait), else the idle one.
async fn read_some<R: AsyncRead + Unpin>(
    stream: &mut R,
    buf: &mut [u8],
    limits: &Limits,
    begun: Option<Instant>,
) -> Result<usize, Stop> {
    let (deadline, why) = match begun {
        Some(t) => (t + limits.request, Stop::Slow),
        None => (Instant::now() + limits.idle, Stop::Idle),
    };
    match tokio::time::timeout_at(deadline, stream.read(buf)).await {
        Err(_) => Err(why),
        Ok(Ok(0)) | Ok(Err(_)) => Err(Stop::Closed),
        Ok(Ok(n)) => Ok(n),
    }
}

/// Writes a reply, giving a client that does not read it [`Limits::idle`]
/// before the connection is dropped; `Err` ends the connection.
async fn reply<S: AsyncWrite + Unpin>(stream: &mut S, bytes: &[u8], limits: &Limits) -> Result<(), Stop> {
    match tokio::time::timeout(limits.idle, stream.write_all(bytes)).await {
        Ok(Ok(())) => Ok(()),
        _ => Err(Stop::Closed),
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
    use crate::wire::roc_server::Roc;
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
        let peer: SocketAddr = "127.0.0.1:5000".parse().unwrap();
        tokio::spawn(client(server, peer, Roc::new(ME), (asks, limits(), log)));
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
    async fn refusals_over_the_cap_are_logged_at_most_once_a_second() {
        let lines = Arc::new(Mutex::new(Vec::new()));
        let kept = lines.clone();
        let log: Log = Arc::new(move |l| kept.lock().unwrap().push(l));
        let r = Refusals::default();
        let peer: SocketAddr = "127.0.0.1:6000".parse().unwrap();
        for _ in 0..100 {
            r.note("roc", peer, 4, &log);
            tokio::time::sleep(Duration::from_millis(15)).await;
        }
        // 1.5 s of refusals: the first logged at once, the rest a second later.
        assert_eq!(
            *lines.lock().unwrap(),
            [
                "roc: refused 127.0.0.1:6000 and 0 more: 4 clients is the limit",
                "roc: refused 127.0.0.1:6000 and 66 more: 4 clients is the limit"
            ]
        );
    }
}

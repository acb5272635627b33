//! What both wire servers share: the connection cap, the timeouts that
//! drop idle and slow clients, and the log lines that say why.
//!
//! Each connection is a task on the server's runtime with at most one
//! request at the plant at a time, so however hostile the traffic, the
//! plant thread sees at most one question per client between two scans.

use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::{Duration, Instant};
use tokio::io::{AsyncRead, AsyncReadExt};
use tokio::net::{TcpListener, TcpStream};
use tokio::sync::{watch, Semaphore};

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

/// Accepts clients until `closing` turns true, each served by `serve` in a
/// task of its own while fewer than the cap are connected.
pub async fn accept<F, Fut>(
    what: &'static str,
    listener: TcpListener,
    limits: Limits,
    log: Log,
    mut closing: watch::Receiver<bool>,
    serve: F,
) where
    F: Fn(TcpStream, SocketAddr) -> Fut,
    Fut: std::future::Future<Output = ()> + Send + 'static,
{
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
                let task = serve(stream, peer);
                tokio::spawn(async move {
                    task.await;
                    drop(permit);
                });
            }
            Err(_) => refusals.note(what, peer, limits.max_clients, &log),
        }
    }
}

/// Why a read gave nothing.
pub enum Stop {
    /// The client closed the connection or it failed.
    Closed,
    /// Nothing for [`Limits::idle`].
    Idle,
    /// A request begun and not finished within [`Limits::request`].
    Slow,
}

impl Stop {
    /// The log line for a dropped client, `None` for one that left.
    pub fn why(&self, limits: &Limits) -> Option<String> {
        match self {
            Stop::Closed => None,
            Stop::Idle => Some(format!("idle for {} s", limits.idle.as_secs())),
            Stop::Slow => Some(format!("a request took more than {} s to arrive", limits.request.as_secs())),
        }
    }
}

/// Reads what arrives, with the deadline that applies: the request's if
/// `begun` (bytes of an unfinished request wait), else the idle one.
pub async fn read_some<R: AsyncRead + Unpin>(
    stream: &mut R,
    buf: &mut [u8],
    limits: &Limits,
    begun: Option<Instant>,
) -> Result<usize, Stop> {
    let (deadline, why) = match begun {
        Some(t) => (t + limits.request, Stop::Slow),
        None => (Instant::now() + limits.idle, Stop::Idle),
    };
    match tokio::time::timeout_at(deadline.into(), stream.read(buf)).await {
        Err(_) => Err(why),
        Ok(Ok(0)) | Ok(Err(_)) => Err(Stop::Closed),
        Ok(Ok(n)) => Ok(n),
    }
}

/// Writes a reply, giving a client that does not read it [`Limits::idle`]
/// before the connection is dropped; `Err` ends the connection.
pub async fn reply(stream: &mut tokio::net::TcpStream, bytes: &[u8], limits: &Limits) -> Result<(), Stop> {
    use tokio::io::AsyncWriteExt;
    match tokio::time::timeout(limits.idle, stream.write_all(bytes)).await {
        Ok(Ok(())) => Ok(()),
        _ => Err(Stop::Closed),
    }
}

/// When the bytes waiting for the rest of their request began to wait:
/// `None` when nothing waits, else `begun` or now.
pub fn waiting_since(pending: usize, begun: Option<Instant>) -> Option<Instant> {
    if pending == 0 {
        None
    } else {
        begun.or(Some(Instant::now()))
    }
}

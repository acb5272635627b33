//! One HTTP connection, served by hyper with the limits every server of
//! `linc serve` has (the wire servers' [`Limits`]): a request's head must
//! arrive whole within [`Limits::request`] of when the server began to
//! wait for it (so a connection that sends nothing, or trickles a header,
//! or sits idle between requests, is closed then — Apache's keep-alive
//! default is the same 5 s), a body within the same time (the handler
//! reads it, `http.rs`), and a client that stops reading what it is sent
//! (a stalled event stream) is dropped after [`Limits::idle`]. The cap on
//! connections is the accept loop's (`wire/net.rs`).

use crate::wire::Limits;
use axum::Router;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use std::future::Future;
use std::io;
use std::pin::Pin;
use std::task::{Context, Poll};
use std::time::Duration;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::sync::watch;
use tokio::time::Sleep;

/// The largest request head (request line and headers) a client may send;
/// the monitor's are a few hundred bytes.
pub const MAX_HEAD: usize = 16 * 1024;

/// The most headers one request may have.
const MAX_HEADERS: usize = 64;

/// Serves one connection until the client leaves, breaks a limit, or the
/// server closes (then the request in progress is finished first, within
/// [`Limits::request`]).
pub(crate) async fn connection<S>(stream: S, app: Router, limits: Limits, mut closing: watch::Receiver<bool>)
where
    S: AsyncRead + AsyncWrite + Unpin + Send + 'static,
{
    let io = TokioIo::new(Stalled { inner: stream, idle: limits.idle, stalled: None });
    let mut builder = hyper::server::conn::http1::Builder::new();
    builder
        .timer(TokioTimer::new())
        .header_read_timeout(limits.request)
        .max_buf_size(MAX_HEAD)
        .max_headers(MAX_HEADERS);
    let conn = builder.serve_connection(io, TowerToHyperService::new(app));
    tokio::pin!(conn);
    tokio::select! {
        _ = conn.as_mut() => {}
        () = crate::wire::net::until_closed(&mut closing) => {
            conn.as_mut().graceful_shutdown();
            let _ = tokio::time::timeout(limits.request, conn).await;
        }
    }
}

/// A stream whose writes may not wait longer than `idle` for the client
/// to read: what keeps a client that opens the event stream and never
/// reads it from holding its connection (and the plant's events) forever.
struct Stalled<S> {
    inner: S,
    idle: Duration,
    /// Armed when a write could not go on, disarmed when one does.
    stalled: Option<Pin<Box<Sleep>>>,
}

impl<S> Stalled<S> {
    /// What a write that is pending becomes: still pending, or an error
    /// once it has waited `idle`.
    fn waiting<T>(&mut self, cx: &mut Context<'_>) -> Poll<io::Result<T>> {
        let idle = self.idle;
        let timer = self.stalled.get_or_insert_with(|| Box::pin(tokio::time::sleep(idle)));
        match timer.as_mut().poll(cx) {
            Poll::Ready(()) => Poll::Ready(Err(io::Error::new(io::ErrorKind::TimedOut, "the client stopped reading"))),
            Poll::Pending => Poll::Pending,
        }
    }

    fn went_on<T>(&mut self, r: Poll<io::Result<T>>, cx: &mut Context<'_>) -> Poll<io::Result<T>> {
        match r {
            Poll::Pending => self.waiting(cx),
            done => {
                self.stalled = None;
                done
            }
        }
    }
}

impl<S: AsyncRead + Unpin> AsyncRead for Stalled<S> {
    fn poll_read(self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().inner).poll_read(cx, buf)
    }
}

impl<S: AsyncWrite + Unpin> AsyncWrite for Stalled<S> {
    fn poll_write(self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &[u8]) -> Poll<io::Result<usize>> {
        let me = self.get_mut();
        let r = Pin::new(&mut me.inner).poll_write(cx, buf);
        me.went_on(r, cx)
    }

    fn poll_flush(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        let me = self.get_mut();
        let r = Pin::new(&mut me.inner).poll_flush(cx);
        me.went_on(r, cx)
    }

    fn poll_shutdown(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<io::Result<()>> {
        Pin::new(&mut self.get_mut().inner).poll_shutdown(cx)
    }
}

/// The limits in tokio's paused time: each fires at exactly the simulated
/// instant it is due, however busy the machine is.
#[cfg(test)]
mod tests {
    use super::*;
    use axum::routing::get;
    use tokio::io::{duplex, AsyncReadExt, AsyncWriteExt, DuplexStream};
    use tokio::time::Instant;

    fn limits() -> Limits {
        Limits { max_clients: 4, idle: Duration::from_secs(60), request: Duration::from_secs(5) }
    }

    /// A connection served with a page at `/` and an endless body at
    /// `/stream`; the client's end, and a sender that closes the server.
    fn served(buffer: usize) -> (DuplexStream, watch::Sender<bool>, tokio::task::JoinHandle<()>) {
        let endless = futures_util::stream::repeat_with(|| Ok::<_, std::convert::Infallible>(vec![b'x'; 1024]));
        let app = Router::new()
            .route("/", get(|| async { "ok" }))
            .route("/stream", get(move || async move { axum::body::Body::from_stream(endless) }));
        let (server, client) = duplex(buffer);
        let (close, closing) = watch::channel(false);
        let task = tokio::spawn(super::connection(server, app, limits(), closing));
        (client, close, task)
    }

    /// Reads until the server closes; the simulated time it took.
    async fn closed(c: &mut DuplexStream) -> Duration {
        let start = Instant::now();
        let mut buf = [0u8; 4096];
        while c.read(&mut buf).await.is_ok_and(|n| n > 0) {}
        start.elapsed()
    }

    #[tokio::test(start_paused = true)]
    async fn a_connection_that_sends_nothing_is_closed_at_the_request_limit() {
        let (mut c, _close, task) = served(4096);
        assert_eq!(closed(&mut c).await, Duration::from_secs(5));
        task.await.unwrap();
    }

    #[tokio::test(start_paused = true)]
    async fn a_header_that_trickles_in_is_cut_at_the_request_limit() {
        let (mut c, _close, task) = served(4096);
        let start = Instant::now();
        for b in b"GET / HTTP/1.1\r\nHost: x\r\n" {
            if c.write_all(std::slice::from_ref(b)).await.is_err() {
                break;
            }
            tokio::time::sleep(Duration::from_millis(500)).await;
        }
        let took = start.elapsed() + closed(&mut c).await;
        let due = Duration::from_secs(5)..=Duration::from_millis(5500);
        assert!(due.contains(&took), "cut after {took:?}, not when the 5 s were up");
        task.await.unwrap();
    }

    #[tokio::test(start_paused = true)]
    async fn an_idle_keep_alive_connection_is_closed_at_the_request_limit() {
        let (mut c, _close, task) = served(4096);
        c.write_all(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n").await.unwrap();
        let mut reply = vec![0u8; 256];
        let n = c.read(&mut reply).await.unwrap();
        assert!(reply[..n].starts_with(b"HTTP/1.1 200"), "{}", String::from_utf8_lossy(&reply[..n]));
        assert!(reply[..n].ends_with(b"ok"));
        assert_eq!(closed(&mut c).await, Duration::from_secs(5), "5 s after the answer");
        task.await.unwrap();
    }

    #[tokio::test(start_paused = true)]
    async fn a_client_that_stops_reading_is_dropped_at_the_idle_limit() {
        let (mut c, _close, task) = served(8192);
        c.write_all(b"GET /stream HTTP/1.1\r\nHost: x\r\n\r\n").await.unwrap();
        let start = Instant::now();
        // The client never reads: the buffer fills, writes wait, and the
        // connection ends a minute after they began to wait.
        task.await.unwrap();
        assert_eq!(start.elapsed(), Duration::from_secs(60));
        drop(c);
    }

    #[tokio::test(start_paused = true)]
    async fn closing_finishes_the_request_in_progress_then_ends() {
        let (mut c, close, task) = served(4096);
        c.write_all(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n").await.unwrap();
        let mut reply = vec![0u8; 256];
        let n = c.read(&mut reply).await.unwrap();
        assert!(reply[..n].starts_with(b"HTTP/1.1 200"));
        close.send(true).unwrap();
        assert_eq!(closed(&mut c).await, Duration::ZERO, "an idle connection ends at once");
        task.await.unwrap();
    }
}

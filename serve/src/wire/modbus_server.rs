//! The Modbus TCP server: tokio-modbus's framing over a transport of
//! linc's that enforces the cap and the timeouts, each request answered by
//! the plant thread.

use super::modbus::MbAnswer;
use super::net::{Limits, Log, Stop};
use crate::Ask;
use std::future::Future;
use std::net::SocketAddr;
use std::pin::Pin;
use std::sync::mpsc::Sender;
use std::sync::Arc;
use std::task::{Context, Poll};
use std::time::Instant;
use tokio::io::{AsyncRead, AsyncWrite, ReadBuf};
use tokio::net::TcpStream;
use tokio::sync::{oneshot, watch, OwnedSemaphorePermit, Semaphore};
use tokio::time::Sleep;
use tokio_modbus::server::tcp::Server;
use tokio_modbus::{ExceptionCode, Response, SlaveRequest};

/// A client's connection with linc's rules: dropped when idle for
/// [`Limits::idle`], or when a request has been arriving (bytes since the
/// last reply) for longer than [`Limits::request`]; it holds its place
/// under the cap until dropped, and logs why it was dropped.
struct Guarded {
    inner: TcpStream,
    limits: Limits,
    deadline: Pin<Box<Sleep>>,
    /// When the first byte after the last reply came.
    begun: Option<Instant>,
    stop: Option<Stop>,
    peer: SocketAddr,
    log: Log,
    _permit: OwnedSemaphorePermit,
}

impl Guarded {
    fn rearm(&mut self) {
        let at = match self.begun {
            Some(t) => t + self.limits.request,
            None => Instant::now() + self.limits.idle,
        };
        self.deadline.as_mut().reset(at.into());
    }
}

impl AsyncRead for Guarded {
    fn poll_read(mut self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &mut ReadBuf<'_>) -> Poll<std::io::Result<()>> {
        let before = buf.filled().len();
        match Pin::new(&mut self.inner).poll_read(cx, buf) {
            Poll::Ready(Ok(())) => {
                if buf.filled().len() > before && self.begun.is_none() {
                    self.begun = Some(Instant::now());
                }
                self.rearm();
                Poll::Ready(Ok(()))
            }
            Poll::Ready(Err(e)) => Poll::Ready(Err(e)),
            Poll::Pending => match self.deadline.as_mut().poll(cx) {
                Poll::Ready(()) => {
                    self.stop = Some(if self.begun.is_some() { Stop::Slow } else { Stop::Idle });
                    Poll::Ready(Err(std::io::ErrorKind::TimedOut.into()))
                }
                Poll::Pending => Poll::Pending,
            },
        }
    }
}

impl AsyncWrite for Guarded {
    fn poll_write(mut self: Pin<&mut Self>, cx: &mut Context<'_>, buf: &[u8]) -> Poll<std::io::Result<usize>> {
        // A reply is going out: the request it answers has arrived.
        self.begun = None;
        self.rearm();
        Pin::new(&mut self.inner).poll_write(cx, buf)
    }

    fn poll_flush(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.inner).poll_flush(cx)
    }

    fn poll_shutdown(mut self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<std::io::Result<()>> {
        Pin::new(&mut self.inner).poll_shutdown(cx)
    }
}

impl Drop for Guarded {
    fn drop(&mut self) {
        if let Some(why) = self.stop.as_ref().and_then(|s| s.why(&self.limits)) {
            (self.log)(format!("modbus {}: dropped: {why}", self.peer));
        }
    }
}

/// One client's service: requests for the map's unit (or 0 and 255, which
/// Modbus TCP devices take as "this device") go to the plant.
struct PlantService {
    asks: Sender<Ask>,
    peer: String,
    unit: u8,
    log: Log,
}

type Answer = Pin<Box<dyn Future<Output = Result<Option<Response>, ExceptionCode>> + Send>>;

impl tokio_modbus::server::Service for PlantService {
    type Request = SlaveRequest<'static>;
    type Response = Option<Response>;
    type Exception = ExceptionCode;
    type Future = Answer;

    fn call(&self, req: SlaveRequest<'static>) -> Answer {
        if req.slave != self.unit && req.slave != 0 && req.slave != 255 {
            return Box::pin(async { Ok(None) });
        }
        let (reply, answer) = oneshot::channel();
        let sent = self.asks.send(Ask::Modbus { request: req.request, peer: self.peer.clone(), reply });
        let log = self.log.clone();
        Box::pin(async move {
            sent.map_err(|_| ExceptionCode::ServerDeviceBusy)?;
            let MbAnswer { reply, log: lines } = answer.await.map_err(|_| ExceptionCode::ServerDeviceBusy)?;
            for line in lines {
                log(line);
            }
            reply.map(Some)
        })
    }
}

/// Serves Modbus TCP on `listener` until `closing` turns true. An error
/// accepting a client (out of file descriptors) restarts the loop on the
/// same socket after a pause, rather than ending the server.
pub(crate) async fn serve(
    listener: std::net::TcpListener,
    unit: u8,
    asks: Sender<Ask>,
    limits: Limits,
    log: Log,
    mut closing: watch::Receiver<bool>,
) {
    let permits = Arc::new(Semaphore::new(limits.max_clients));
    let refusals = Arc::new(super::net::Refusals::default());
    loop {
        let Ok(l) = listener.try_clone().and_then(tokio::net::TcpListener::from_std) else { return };
        let (asks, log2, permits, refusals) = (asks.clone(), log.clone(), permits.clone(), refusals.clone());
        let on_connected = move |stream: TcpStream, peer: SocketAddr| {
            let (asks, log, permits, refusals) = (asks.clone(), log2.clone(), permits.clone(), refusals.clone());
            async move {
                let Ok(permit) = permits.try_acquire_owned() else {
                    refusals.note("modbus", peer, limits.max_clients, &log);
                    return Ok(None);
                };
                let _ = stream.set_nodelay(true);
                let deadline = Box::pin(tokio::time::sleep(limits.idle));
                let service = PlantService { asks, peer: peer.to_string(), unit, log: log.clone() };
                let transport =
                    Guarded { inner: stream, limits, deadline, begun: None, stop: None, peer, log, _permit: permit };
                Ok(Some((service, transport)))
            }
        };
        let stop = {
            let mut c = closing.clone();
            async move {
                let _ = c.changed().await;
            }
        };
        match Server::new(l).serve_until(&on_connected, |_err| {}, stop).await {
            Ok(_) => return,
            Err(e) => {
                log(format!("modbus: accepting a client failed ({e}); listening again"));
                tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                if *closing.borrow_and_update() {
                    return;
                }
            }
        }
    }
}

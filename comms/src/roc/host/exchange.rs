//! One request and its reply over any byte stream, the part every link
//! shares: the frame written, then bytes read until the reply to it
//! arrives (other frames dropped, noise skipped by the [`Deframer`]) or
//! the deadline passes.

use super::poll::LinkError;
use crate::roc::{Deframer, Frame};
use std::io::{ErrorKind, Read, Write};
use std::time::{Duration, Instant};

/// A stream a link reads with a time limit.
pub(super) trait Timed: Read + Write {
    fn limit_reads(&mut self, left: Duration);
}

impl Timed for std::net::TcpStream {
    fn limit_reads(&mut self, left: Duration) {
        let _ = self.set_read_timeout(Some(left));
    }
}

impl Timed for Box<dyn serialport::SerialPort> {
    fn limit_reads(&mut self, left: Duration) {
        let _ = self.set_timeout(left);
    }
}

/// How an exchange failed: the stream may be kept, or must be dropped
/// (closed, hung up or broken) and opened again for the next attempt.
enum Failed {
    Timeout,
    Broken,
}

/// A link's stream and the frames read from it: opened when an exchange
/// needs it, dropped (with the bytes held from it) when it breaks, so the
/// next attempt opens it again. TCP and serial links differ only in how
/// they open it.
pub(super) struct Held<S> {
    stream: Option<S>,
    frames: Deframer,
}

impl<S: Timed> Held<S> {
    pub(super) fn new(stream: Option<S>) -> Held<S> {
        Held { stream, frames: Deframer::default() }
    }

    /// One request and its reply, opening the stream with `open` first if
    /// there is none; any failure is a timeout to the host (the module's
    /// status 8 after its attempts).
    pub(super) fn exchange(
        &mut self,
        request: &Frame,
        timeout: Duration,
        open: impl FnOnce() -> Option<S>,
    ) -> Result<Frame, LinkError> {
        if self.stream.is_none() {
            self.stream = Some(open().ok_or(LinkError::Timeout)?);
            self.frames = Deframer::default();
        }
        let Some(stream) = self.stream.as_mut() else { return Err(LinkError::Timeout) };
        match exchange(stream, &mut self.frames, request, timeout) {
            Ok(reply) => Ok(reply),
            Err(Failed::Broken) => {
                self.stream = None;
                Err(LinkError::Timeout)
            }
            Err(Failed::Timeout) => Err(LinkError::Timeout),
        }
    }
}

/// Sends `request` and waits until `timeout` for the frame from its
/// device to this host.
fn exchange<S: Timed + ?Sized>(
    stream: &mut S,
    frames: &mut Deframer,
    request: &Frame,
    timeout: Duration,
) -> Result<Frame, Failed> {
    let bytes = request.encode().ok_or(Failed::Timeout)?;
    let deadline = Instant::now() + timeout;
    stream.write_all(&bytes).and_then(|()| stream.flush()).map_err(|_| Failed::Broken)?;
    let mut buf = [0u8; 1024];
    loop {
        while let Some(f) = frames.next_frame() {
            if f.dst == request.src && f.src == request.dst {
                return Ok(f);
            }
        }
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            return Err(Failed::Timeout);
        }
        stream.limit_reads(left);
        match stream.read(&mut buf) {
            // The end of the stream: closed, or on a terminal hung up.
            Ok(0) => return Err(Failed::Broken),
            Ok(n) => frames.push(&buf[..n]),
            Err(e) if matches!(e.kind(), ErrorKind::WouldBlock | ErrorKind::TimedOut) => return Err(Failed::Timeout),
            Err(e) if e.kind() == ErrorKind::Interrupted => {}
            Err(_) => return Err(Failed::Broken),
        }
    }
}

//! The host's link to a device over TCP: blocking, one request at a time
//! (a poll list runs its commands in order), reconnecting after the
//! device closed the connection.

use super::poll::{Link, LinkError};
use crate::roc::{Deframer, Frame};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::{Duration, Instant};

pub struct TcpLink {
    addr: SocketAddr,
    stream: Option<TcpStream>,
    frames: Deframer,
    /// How long to wait for a reply (the module's default is one second).
    pub timeout: Duration,
}

impl TcpLink {
    pub fn new(addr: SocketAddr, timeout: Duration) -> TcpLink {
        TcpLink { addr, stream: None, frames: Deframer::default(), timeout }
    }

    fn connected(&mut self) -> Result<&mut TcpStream, LinkError> {
        if self.stream.is_none() {
            let s = TcpStream::connect_timeout(&self.addr, self.timeout).map_err(|_| LinkError::Timeout)?;
            let _ = s.set_nodelay(true);
            self.frames = Deframer::default();
            self.stream = Some(s);
        }
        self.stream.as_mut().ok_or(LinkError::Timeout)
    }
}

impl Link for TcpLink {
    /// Sends the request and waits for a frame from its device to this
    /// host; other frames are dropped. A closed or failed connection is
    /// dropped too, and made again on the next attempt.
    fn exchange(&mut self, request: &Frame) -> Result<Frame, LinkError> {
        let bytes = request.encode().ok_or(LinkError::Timeout)?;
        let deadline = Instant::now() + self.timeout;
        let stream = self.connected()?;
        if stream.write_all(&bytes).is_err() {
            self.stream = None;
            return Err(LinkError::Timeout);
        }
        let mut buf = [0u8; 1024];
        loop {
            while let Some(f) = self.frames.next_frame() {
                if f.dst == request.src && f.src == request.dst {
                    return Ok(f);
                }
            }
            let left = deadline.saturating_duration_since(Instant::now());
            let Some(stream) = self.stream.as_mut().filter(|_| !left.is_zero()) else {
                return Err(LinkError::Timeout);
            };
            let _ = stream.set_read_timeout(Some(left));
            match stream.read(&mut buf) {
                Ok(0) => {
                    self.stream = None;
                    return Err(LinkError::Timeout);
                }
                Ok(n) => self.frames.push(&buf[..n]),
                Err(e) if matches!(e.kind(), std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut) => {
                    return Err(LinkError::Timeout)
                }
                Err(_) => {
                    self.stream = None;
                    return Err(LinkError::Timeout);
                }
            }
        }
    }
}

//! The host's link to a device over TCP: blocking, one request at a time
//! (a poll list runs its commands in order), reconnecting after the
//! device closed the connection.

use super::exchange::{exchange, Failed};
use super::poll::{Link, LinkError};
use crate::roc::{Deframer, Frame};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

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
        let timeout = self.timeout;
        self.connected()?;
        let (Some(stream), frames) = (self.stream.as_mut(), &mut self.frames) else { return Err(LinkError::Timeout) };
        match exchange(stream, frames, request, timeout) {
            Err(Failed::Broken) => {
                self.stream = None;
                Err(LinkError::Timeout)
            }
            other => Ok(other?),
        }
    }
}

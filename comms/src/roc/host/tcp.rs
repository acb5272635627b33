//! The host's link to a device over TCP: blocking, one request at a time
//! (a poll list runs its commands in order), reconnecting after the
//! device closed the connection.

use super::exchange::Held;
use super::poll::{Link, LinkError};
use crate::roc::Frame;
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

pub struct TcpLink {
    addr: SocketAddr,
    held: Held<TcpStream>,
    /// How long to wait for a reply (the module's default is one second).
    pub timeout: Duration,
}

impl TcpLink {
    pub fn new(addr: SocketAddr, timeout: Duration) -> TcpLink {
        TcpLink { addr, held: Held::new(None), timeout }
    }
}

impl Link for TcpLink {
    /// Sends the request and waits for a frame from its device to this
    /// host; other frames are dropped. A closed or failed connection is
    /// dropped too, and made again on the next attempt.
    fn exchange(&mut self, request: &Frame) -> Result<Frame, LinkError> {
        let (addr, timeout) = (self.addr, self.timeout);
        self.held.exchange(request, timeout, || {
            let s = TcpStream::connect_timeout(&addr, timeout).ok()?;
            let _ = s.set_nodelay(true);
            Some(s)
        })
    }
}

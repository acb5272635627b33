//! The host's link to a device over a serial line (RS-232/485, a radio):
//! blocking, one request at a time, as [`super::TcpLink`] is. The bytes
//! are the same frames as over TCP and go through the same [`Deframer`],
//! so noise on the line is dropped and a reply that arrives in pieces is
//! joined; the reply timeout is the same too.

use super::exchange::Held;
use super::poll::{Link, LinkError};
use crate::roc::Frame;
use crate::serial::Line;
use std::time::Duration;

pub struct SerialLink {
    path: String,
    line: Line,
    held: Held<Box<dyn serialport::SerialPort>>,
    /// How long to wait for a reply (the module's default is one second).
    pub timeout: Duration,
}

impl SerialLink {
    /// Opens the port at `path` now, so a wrong path or a port another
    /// program holds is an error before the command list runs, rather
    /// than every command timing out.
    pub fn open(path: &str, line: Line, timeout: Duration) -> Result<SerialLink, serialport::Error> {
        let port = line.builder(path, timeout).open()?;
        Ok(SerialLink { path: path.to_string(), line, held: Held::new(Some(port)), timeout })
    }
}

impl Link for SerialLink {
    /// Sends the request and waits for a frame from its device to this
    /// host; other frames (another host's traffic on a shared line) are
    /// dropped. A port that fails (a USB adapter unplugged and back) is
    /// closed, and opened again on the next attempt.
    fn exchange(&mut self, request: &Frame) -> Result<Frame, LinkError> {
        let (line, path, timeout) = (&self.line, &self.path, self.timeout);
        self.held.exchange(request, timeout, || line.builder(path, timeout).open().ok())
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use crate::roc::Address;
    use serialport::SerialPort;
    use std::io::{Read, Write};

    /// Over a pseudo-terminal: a reply that comes after noise, in two
    /// pieces with a pause between them, is found; silence is a timeout.
    #[test]
    fn a_reply_in_pieces_after_noise_is_found_and_silence_times_out() {
        let (mut master, slave) = serialport::TTYPort::pair().expect("a pseudo-terminal");
        let path = slave.name().expect("the slave's path");
        let mut link = SerialLink::open(&path, Line::new(19200), Duration::from_millis(300)).expect("open");
        let (host, dev) = (Address { unit: 3, group: 1 }, Address { unit: 1, group: 2 });
        let req = Frame { dst: dev, src: host, opcode: 180, data: vec![1, 3, 0, 2] };
        let reply = Frame { dst: host, src: dev, opcode: 180, data: vec![1, 3, 0, 2, 1, 0] };
        let bytes = reply.encode().unwrap();
        let device = std::thread::spawn(move || {
            master.set_timeout(Duration::from_secs(5)).unwrap();
            let mut got = vec![0u8; req.encode().unwrap().len()];
            master.read_exact(&mut got).expect("the request");
            master.write_all(&[0xFF, 0x00, 0x13]).unwrap();
            master.write_all(&bytes[..5]).unwrap();
            std::thread::sleep(Duration::from_millis(50));
            master.write_all(&bytes[5..]).unwrap();
            (got, master)
        });
        assert_eq!(link.exchange(&Frame { dst: dev, src: host, opcode: 180, data: vec![1, 3, 0, 2] }).unwrap(), reply);
        let (got, _master) = device.join().unwrap();
        assert_eq!(Frame::decode(&got).unwrap().0.dst, dev);
        let again = link.exchange(&Frame { dst: dev, src: host, opcode: 180, data: vec![1, 3, 0, 2] });
        assert!(matches!(again, Err(LinkError::Timeout)));
        drop(slave);
    }

    #[test]
    fn a_port_that_does_not_exist_is_an_error_at_once() {
        let e = SerialLink::open("/dev/linc-no-such-port", Line::new(9600), Duration::from_secs(1)).err();
        assert!(e.is_some());
    }
}

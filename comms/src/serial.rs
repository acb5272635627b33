//! A serial line's settings, shared by the two ends that use one: the ROC
//! device a served plant runs on a port (`linc serve --roc-serial`) and
//! the host that polls over one (`linc roc poll --serial`). Real ROC links
//! are RS-232/485 lines and radios; the bytes on them are framed exactly
//! as over TCP, so only opening the port differs.

pub use serialport::{DataBits, Parity, StopBits};
use std::time::Duration;

/// How the line runs: its speed and character framing.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Line {
    pub baud: u32,
    pub data_bits: DataBits,
    pub parity: Parity,
    pub stop_bits: StopBits,
}

impl Line {
    /// `baud` with 8 data bits, no parity and 1 stop bit: what ROC devices
    /// ship with, and so what the command line assumes unless told.
    pub fn new(baud: u32) -> Line {
        Line { baud, data_bits: DataBits::Eight, parity: Parity::None, stop_bits: StopBits::One }
    }

    /// Whether this is the 8N1 framing [`Line::new`] gives.
    pub fn is_8n1(&self) -> bool {
        *self == Line::new(self.baud)
    }

    /// The port at `path` with these settings, opened in exclusive mode
    /// (no other program may open it too: two readers would split the
    /// bytes of one frame between them), without flow control (ROC lines
    /// have none), reads waiting at most `timeout`.
    pub fn builder(&self, path: &str, timeout: Duration) -> serialport::SerialPortBuilder {
        serialport::new(path, self.baud)
            .data_bits(self.data_bits)
            .parity(self.parity)
            .stop_bits(self.stop_bits)
            .flow_control(serialport::FlowControl::None)
            .timeout(timeout)
    }
}

/// `19200 baud`, followed by the framing when it is not 8N1 (`19200 baud,
/// 7 data bits, even parity, 2 stop bits`), as the startup line says it.
impl std::fmt::Display for Line {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} baud", self.baud)?;
        if self.is_8n1() {
            return Ok(());
        }
        let parity = match self.parity {
            Parity::None => "no",
            Parity::Odd => "odd",
            Parity::Even => "even",
        };
        let stops = u8::from(self.stop_bits);
        let s = if stops == 1 { "" } else { "s" };
        write!(f, ", {} data bits, {parity} parity, {stops} stop bit{s}", u8::from(self.data_bits))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_says_its_framing_only_when_it_is_not_8n1() {
        assert_eq!(Line::new(19200).to_string(), "19200 baud");
        let l = Line { data_bits: DataBits::Seven, parity: Parity::Even, ..Line::new(9600) };
        assert_eq!(l.to_string(), "9600 baud, 7 data bits, even parity, 1 stop bit");
        let l = Line { stop_bits: StopBits::Two, ..Line::new(1200) };
        assert_eq!(l.to_string(), "1200 baud, 8 data bits, no parity, 2 stop bits");
    }
}

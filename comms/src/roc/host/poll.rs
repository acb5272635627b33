//! Running the command list: each command's request built from the word
//! table, sent, retried, and its reply stored back, with the module's
//! status codes (`003_…` §5.1.6).

use super::commands::Command;
use super::words::{Words, SIZE};
use crate::roc::frame::MAX_DATA;
use crate::roc::ops;
use crate::roc::{Address, Frame};

/// Command status codes, as the module's Master Error Table holds them.
pub mod status {
    pub const OK: u16 = 0;
    pub const BAD_ADDRESS: u16 = 2;
    pub const BAD_VALUE: u16 = 3;
    pub const INCOMPLETE: u16 = 4;
    pub const TIMEOUT: u16 = 8;
    pub const OVERFLOW: u16 = 10;
    /// A device's opcode 255 error `n` is stored as `ROC_ERROR + n`.
    pub const ROC_ERROR: u16 = 20;
}

/// The module's attempts at a command before it reports a timeout.
pub const ATTEMPTS: usize = 3;

/// What went wrong getting a reply.
#[derive(Debug)]
pub enum LinkError {
    /// No reply in time (or the connection could not be made).
    Timeout,
}

/// A way to a device: sends a request and waits for the reply to it.
pub trait Link {
    fn exchange(&mut self, request: &Frame) -> Result<Frame, LinkError>;
}

/// What a status code means, for the command's report line.
pub fn status_text(code: u16) -> String {
    match code {
        status::OK => "done".into(),
        1 => "illegal function".into(),
        status::BAD_ADDRESS => "bad data address: the values would pass word 3999".into(),
        status::BAD_VALUE => "bad data value: a TLP word is over 255".into(),
        status::INCOMPLETE => "incomplete response: the reply does not match the request".into(),
        status::TIMEOUT => format!("timeout: no reply after {ATTEMPTS} attempts"),
        status::OVERFLOW => "buffer overflow: the request is longer than a frame (fewer parameters)".into(),
        n if n > status::ROC_ERROR => {
            format!("ROC error {}: {}", n - status::ROC_ERROR, roc_error(n - status::ROC_ERROR))
        }
        n => format!("status {n}"),
    }
}

/// The meaning of a device's opcode 255 error code.
fn roc_error(code: u16) -> &'static str {
    match code {
        1 => "invalid opcode",
        2 => "invalid parameter number",
        3 => "invalid logical number",
        4 => "invalid point type",
        5 => "received too many data bytes",
        6 => "received too few data bytes",
        19 => "write to a read-only parameter",
        20 => "security error",
        25 => "invalid parameter range",
        33 => "invalid time",
        50 => "general error",
        51 => "invalid state for write (the parameter is forced)",
        _ => "see the device's error table",
    }
}

/// A host polling one device through `link`.
pub struct Host {
    /// The host's own unit and group, the source of its requests.
    pub me: Address,
    pub words: Words,
}

impl Host {
    /// Runs one command: `OK` or the status code the module would store.
    pub fn run(&mut self, c: &Command, link: &mut dyn Link) -> u16 {
        let data = match self.request(c) {
            Ok(d) => d,
            Err(code) => return code,
        };
        let req = Frame { dst: Address { unit: c.unit, group: c.group }, src: self.me, opcode: c.opcode, data };
        let mut reply = None;
        for _ in 0..ATTEMPTS {
            if let Ok(r) = link.exchange(&req) {
                reply = Some(r);
                break;
            }
        }
        let Some(reply) = reply else { return status::TIMEOUT };
        if reply.opcode == ops::ERROR {
            return reply.data.first().map_or(status::INCOMPLETE, |&c| status::ROC_ERROR + u16::from(c));
        }
        if reply.opcode != c.opcode {
            return status::INCOMPLETE;
        }
        match c.opcode {
            ops::READ => self.store(c, &reply.data),
            _ if reply.data.is_empty() => status::OK,
            _ => status::INCOMPLETE,
        }
    }

    /// The TLPs of a command, from its SRC ADDR words.
    fn tlps(&self, c: &Command) -> Result<Vec<[u8; 3]>, u16> {
        let from = usize::from(c.src);
        let words = &self.words.0[from..from + 3 * usize::from(c.count)];
        words
            .chunks_exact(3)
            .map(|w| {
                let b = |x: u16| u8::try_from(x).map_err(|_| status::BAD_VALUE);
                Ok([b(w[0])?, b(w[1])?, b(w[2])?])
            })
            .collect()
    }

    /// The data of a command's request.
    fn request(&self, c: &Command) -> Result<Vec<u8>, u16> {
        let tlps = self.tlps(c)?;
        let mut data = vec![c.count as u8];
        for (i, t) in tlps.iter().enumerate() {
            data.extend_from_slice(t);
            if c.opcode == ops::WRITE {
                data.extend_from_slice(&self.value(c, i));
            }
        }
        if data.len() > MAX_DATA {
            return Err(status::OVERFLOW);
        }
        Ok(data)
    }

    /// The bytes of value `i` of a 181 from its DEST ADDR words, by TYPE:
    /// a float is two words, low word first; an integer one word; a byte
    /// the low byte of one word.
    fn value(&self, c: &Command, i: usize) -> Vec<u8> {
        let words_each = usize::from(c.ty.div_ceil(2));
        let at = usize::from(c.dest) + i * words_each;
        let w = &self.words.0[at..at + words_each];
        match c.ty {
            4 => [w[0].to_le_bytes(), w[1].to_le_bytes()].concat(),
            2 => w[0].to_le_bytes().to_vec(),
            _ => vec![w[0] as u8],
        }
    }

    /// Stores a 180 reply's values from DEST ADDR: each value's words (a
    /// byte in the low byte of a word, two bytes one word, four bytes two
    /// words low word first, longer text a byte a word), after its TLP's
    /// three words when TYPE is 1. Every value of one command has the same
    /// size (the module's rule), so the reply splits without a parameter
    /// table.
    fn store(&mut self, c: &Command, data: &[u8]) -> u16 {
        let Ok(tlps) = self.tlps(c) else { return status::BAD_VALUE };
        let n = usize::from(c.count);
        let body = data.len().saturating_sub(1 + 3 * n);
        if data.first() != Some(&(c.count as u8)) || body == 0 || !body.is_multiple_of(n) {
            return status::INCOMPLETE;
        }
        let size = body / n;
        let mut out: Vec<u16> = Vec::new();
        for (i, chunk) in data[1..].chunks_exact(3 + size).enumerate() {
            if chunk[..3] != tlps[i] {
                return status::INCOMPLETE;
            }
            if c.ty == 1 {
                out.extend(chunk[..3].iter().map(|&b| u16::from(b)));
            }
            let v = &chunk[3..];
            match size {
                2 => out.push(u16::from_le_bytes([v[0], v[1]])),
                4 => out.extend([u16::from_le_bytes([v[0], v[1]]), u16::from_le_bytes([v[2], v[3]])]),
                _ => out.extend(v.iter().map(|&b| u16::from(b))),
            }
        }
        let at = usize::from(c.dest);
        if at + out.len() > SIZE {
            return status::BAD_ADDRESS;
        }
        self.words.0[at..at + out.len()].copy_from_slice(&out);
        status::OK
    }
}

/// The shortest time between two passes of the list, so that a list of
/// commands with POLL TIME 0 polls briskly without spinning.
pub const MIN_PASS: std::time::Duration = std::time::Duration::from_millis(100);

/// Runs the list: without `duration` every enabled command once, in order;
/// with it, passes of the list until it has passed, each command when its
/// POLL TIME (seconds; 0 every pass) is up. Control commands (PORT 9, 10)
/// run once, as if their enable bit went on once at the start. `report`
/// hears each command's status as it runs; the last status of each
/// command is returned (0 for a disabled one).
pub fn poll(
    host: &mut Host,
    list: &[Command],
    link: &mut dyn Link,
    duration: Option<std::time::Duration>,
    mut report: impl FnMut(usize, u16),
) -> Vec<u16> {
    use std::time::Instant;
    let start = Instant::now();
    let mut last: Vec<u16> = vec![status::OK; list.len()];
    let mut ran: Vec<Option<Instant>> = vec![None; list.len()];
    loop {
        let pass = Instant::now();
        for (i, c) in list.iter().enumerate() {
            let due = match (c.port, ran[i]) {
                (0, _) => false,
                (_, None) => true,
                (9 | 10, Some(_)) => false,
                (_, Some(t)) => c.poll == 0 || t.elapsed().as_secs() >= u64::from(c.poll),
            };
            if due {
                ran[i] = Some(Instant::now());
                last[i] = host.run(c, link);
                report(i, last[i]);
            }
        }
        let Some(d) = duration else { return last };
        if start.elapsed() >= d {
            return last;
        }
        let rest = MIN_PASS.saturating_sub(pass.elapsed()).min(d.saturating_sub(start.elapsed()));
        std::thread::sleep(rest);
        if start.elapsed() >= d {
            return last;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::roc::host::commands::parse;

    /// A device that answers every write with an acknowledgement and
    /// counts the requests per destination unit.
    struct Counter(std::collections::HashMap<u8, usize>);

    impl Link for Counter {
        fn exchange(&mut self, r: &Frame) -> Result<Frame, LinkError> {
            *self.0.entry(r.dst.unit).or_default() += 1;
            Ok(Frame { dst: r.src, src: r.dst, opcode: r.opcode, data: vec![] })
        }
    }

    #[test]
    fn poll_times_decide_how_often_each_command_runs() {
        let list = parse(
            "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n\
             1,1,2,181,1,0,100,2,0,0\n\
             1,2,2,181,1,0,100,2,1,0\n\
             9,3,2,181,1,0,100,2,0,0\n\
             0,4,2,181,1,0,100,2,0,0\n",
        )
        .unwrap();
        let mut host = Host { me: Address { unit: 3, group: 1 }, words: Words::default() };
        // Once: every enabled command once, the disabled one never.
        let mut d = Counter(Default::default());
        assert_eq!(poll(&mut host, &list, &mut d, None, |_, _| {}), vec![0, 0, 0, 0]);
        assert_eq!((d.0.get(&1), d.0.get(&2), d.0.get(&3), d.0.get(&4)), (Some(&1), Some(&1), Some(&1), None));
        // 1.5 s: POLL TIME 0 every pass (at most every 100 ms), 1 s twice,
        // the control command once.
        let mut d = Counter(Default::default());
        poll(&mut host, &list, &mut d, Some(std::time::Duration::from_millis(1500)), |_, _| {});
        let every = d.0[&1];
        assert!((10..=16).contains(&every), "{every} passes");
        assert_eq!((d.0[&2], d.0[&3]), (2, 1));
    }
}

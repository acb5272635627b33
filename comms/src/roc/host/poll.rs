//! Running the command list: each command's request built from the word
//! table, sent (wrapped in opcode 24 when it goes by store and forward),
//! retried, and its reply stored back, with the module's status codes
//! (`003_…` §5.1.6). What each opcode's bytes are in words is
//! [`layouts`](super::layouts)'.

use super::commands::{Command, PATH_WORDS};
use super::layouts::{self, op, Kind};
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
        status::BAD_VALUE => "bad data value: a word sent as a byte (TLP, clock, table or path) is over 255".into(),
        status::INCOMPLETE => "incomplete response: the reply does not match the request".into(),
        status::TIMEOUT => format!("timeout: no reply after {ATTEMPTS} attempts"),
        status::OVERFLOW => "buffer overflow: the request is longer than a frame (fewer parameters)".into(),
        n if n > status::ROC_ERROR => {
            format!("ROC error {}: {}", n - status::ROC_ERROR, roc_error(n - status::ROC_ERROR))
        }
        n => format!("status {n}"),
    }
}

/// The meaning of a device's opcode 255 error code: the codes of both
/// protocols' tables that linc's device sends (docs/roc-protocol.md); the
/// two agree where they overlap.
fn roc_error(code: u16) -> &'static str {
    match code {
        1 => "invalid opcode",
        2 => "invalid parameter number",
        3 => "invalid logical number",
        4 => "invalid point type",
        5 => "received too many data bytes",
        6 => "received too few data bytes",
        13 => "outside the valid address range",
        14 => "invalid history request",
        17 => "too many alarms asked for",
        18 => "too many events asked for",
        19 => "write to a read-only parameter",
        20 => "security error",
        21 => "invalid security logon",
        22 => "invalid store and forward path",
        25 => "invalid parameter range",
        30 => "invalid history point",
        33 => "invalid time",
        50 => "general error",
        51 => "invalid state for write (the parameter is forced)",
        63 => "requested security level too high",
        77 => "invalid logoff string",
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
    /// Nothing is stored for a command that failed.
    pub fn run(&mut self, c: &Command, link: &mut dyn Link) -> u16 {
        match self.try_run(c, link) {
            Ok(()) => status::OK,
            Err(code) => code,
        }
    }

    fn try_run(&mut self, c: &Command, link: &mut dyn Link) -> Result<(), u16> {
        let sent = layouts::request(c, &self.words.0)?;
        if sent.len() > MAX_DATA {
            return Err(status::OVERFLOW);
        }
        let path = self.path(c)?;
        let (opcode, data) = match &path {
            Some(p) => (op::STORE_FORWARD, wrap(p, c.opcode, &sent)?),
            None => (c.opcode, sent.clone()),
        };
        let req = Frame { dst: Address { unit: c.unit, group: c.group }, src: self.me, opcode, data };
        let reply = exchange(link, &req)?;
        let (opcode, data) = match &path {
            Some(p) => unwrap(p, &reply)?,
            None => (reply.opcode, reply.data.as_slice()),
        };
        refused(opcode, data)?;
        if opcode != c.opcode {
            return Err(status::INCOMPLETE);
        }
        let layout = layouts::reply_layout(c, &sent, data)?;
        let words = layouts::place(&layout, data).ok_or(status::INCOMPLETE)?;
        self.store(c.dest, &words)
    }

    /// The store-and-forward path's ten bytes, from the words at STORE
    /// FWD (a word over 255 is status 3); `None` for a direct command.
    fn path(&self, c: &Command) -> Result<Option<Vec<u8>>, u16> {
        if c.store_fwd == 0 {
            return Ok(None);
        }
        let at = usize::from(c.store_fwd);
        layouts::gather(&[(Kind::Bin, PATH_WORDS)], &self.words.0[at..at + PATH_WORDS]).map(Some)
    }

    /// Stores a reply's words from `at`: all of them, or none and status 2
    /// when they would pass word 3999.
    fn store(&mut self, at: u16, words: &[u16]) -> Result<(), u16> {
        let at = usize::from(at);
        if at + words.len() > SIZE {
            return Err(status::BAD_ADDRESS);
        }
        self.words.0[at..at + words.len()].copy_from_slice(words);
        Ok(())
    }
}

/// Sends a request until a reply comes, [`ATTEMPTS`] times at most.
fn exchange(link: &mut dyn Link, req: &Frame) -> Result<Frame, u16> {
    (0..ATTEMPTS).find_map(|_| link.exchange(req).ok()).ok_or(status::TIMEOUT)
}

/// An opcode 255 reply as its status, 20 + its code. The ROC protocol's
/// error data is three bytes (code, opcode, offset), ROC Plus's pairs of
/// (code, offset): the first byte is the code either way.
fn refused(opcode: u8, data: &[u8]) -> Result<(), u16> {
    if opcode != ops::ERROR {
        return Ok(());
    }
    Err(data.first().map_or(status::INCOMPLETE, |&c| status::ROC_ERROR + u16::from(c)))
}

/// An opcode 24 request's data (§6.3, docs/roc-protocol.md): the path,
/// then the wrapped opcode, its length and its data. Status 10 when it
/// no longer fits a frame.
fn wrap(path: &[u8], opcode: u8, data: &[u8]) -> Result<Vec<u8>, u16> {
    let len = u8::try_from(data.len()).map_err(|_| status::OVERFLOW)?;
    let out = [path, &[opcode, len], data].concat();
    if out.len() > MAX_DATA {
        return Err(status::OVERFLOW);
    }
    Ok(out)
}

/// The final device's reply inside a 24 reply: its opcode and data. The
/// relay's own 255 (22, a path it cannot follow, is status 42) is its
/// status; a reply that is not a 24, does not echo the path sent, or
/// whose inner length is not what it carries, is status 4.
fn unwrap<'a>(path: &[u8], reply: &'a Frame) -> Result<(u8, &'a [u8]), u16> {
    refused(reply.opcode, &reply.data)?;
    let d = &reply.data;
    if reply.opcode != op::STORE_FORWARD || d.len() < PATH_WORDS + 2 || d[..PATH_WORDS] != *path {
        return Err(status::INCOMPLETE);
    }
    let (opcode, len, inner) = (d[PATH_WORDS], d[PATH_WORDS + 1], &d[PATH_WORDS + 2..]);
    if inner.len() != usize::from(len) {
        return Err(status::INCOMPLETE);
    }
    Ok((opcode, inner))
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
    use crate::roc::host::commands::{parse, Protocol};

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
            Protocol::Roc,
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

//! Opcodes 118 and 119: the alarm and event logs (docs/roc-protocol.md).
//! A request asks for up to ten records from a log index; the reply
//! repeats the index, gives the log's current index (where the next record
//! will be written) and the records: 23 bytes an alarm, 22 an event.

use super::ops::{code, RocError};
use super::value::pad_ascii;

/// Records one request may ask for.
pub const MAX_RECORDS: u8 = 10;
pub const ALARM_RECORD: usize = 23;
pub const EVENT_RECORD: usize = 22;

/// A request: how many records from which index.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LogRequest {
    pub count: u8,
    pub start: u16,
}

/// Opcode 118 or 119's request: count, then the starting index (2 bytes).
/// More than ten records is error 17 (alarms) or 18 (events) at the count.
pub fn parse(data: &[u8], alarms: bool) -> Result<LogRequest, RocError> {
    match data.len() {
        0..=2 => return Err(RocError::length(code::TOO_FEW_BYTES)),
        3 => {}
        _ => return Err(RocError::length(code::TOO_MANY_BYTES)),
    }
    if data[0] > MAX_RECORDS {
        let c = if alarms { code::TOO_MANY_ALARMS } else { code::TOO_MANY_EVENTS };
        return Err(RocError::at_data(c, 0));
    }
    Ok(LogRequest { count: data[0], start: u16::from_le_bytes([data[1], data[2]]) })
}

/// One logged FST alarm or event: when, which FST (its number), the text
/// and the value.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    pub time: u32,
    pub fst: u8,
    pub text: Vec<u8>,
    pub value: f32,
}

/// An FST alarm record (type 2, condition set): the type byte, the time,
/// the FST number, 13 characters of description, the value.
pub fn alarm(r: &Record) -> [u8; ALARM_RECORD] {
    let mut out = Vec::with_capacity(ALARM_RECORD);
    out.push(2 | 0x40);
    out.extend_from_slice(&r.time.to_le_bytes());
    out.push(r.fst);
    pad_ascii(&r.text, 13, &mut out);
    out.extend_from_slice(&r.value.to_le_bytes());
    out.try_into().unwrap_or([0; ALARM_RECORD])
}

/// An FST event record (type 3): the type byte, the time, the FST number,
/// the value, 10 characters of description, two unused bytes.
pub fn event(r: &Record) -> [u8; EVENT_RECORD] {
    let mut out = Vec::with_capacity(EVENT_RECORD);
    out.push(3);
    out.extend_from_slice(&r.time.to_le_bytes());
    out.push(r.fst);
    out.extend_from_slice(&r.value.to_le_bytes());
    pad_ascii(&r.text, 10, &mut out);
    out.extend_from_slice(&[0, 0]);
    out.try_into().unwrap_or([0; EVENT_RECORD])
}

/// The reply: the count sent, the starting index, the current index, then
/// each record (an empty slot is a record of zeros, type 0, "no alarm").
pub fn reply(req: LogRequest, current: u16, records: &[Vec<u8>]) -> Vec<u8> {
    let mut out = vec![records.len() as u8];
    out.extend_from_slice(&req.start.to_le_bytes());
    out.extend_from_slice(&current.to_le_bytes());
    for r in records {
        out.extend_from_slice(r);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_and_records_have_their_layouts() {
        assert_eq!(parse(&[2, 0x05, 0x00], true), Ok(LogRequest { count: 2, start: 5 }));
        assert_eq!(parse(&[11, 0, 0], true), Err(RocError { code: 17, offset: 6 }));
        assert_eq!(parse(&[11, 0, 0], false), Err(RocError { code: 18, offset: 6 }));
        assert_eq!(parse(&[1, 0], true), Err(RocError { code: 6, offset: 5 }));
        let r = Record { time: 0x0102_0304, fst: 1, text: b"HIGH LEVEL".to_vec(), value: 1.0 };
        let a = alarm(&r);
        assert_eq!(a[0], 0x42, "an FST alarm, set");
        assert_eq!(&a[1..5], &[4, 3, 2, 1]);
        assert_eq!((a[5], &a[6..19]), (1, &b"HIGH LEVEL   "[..]));
        assert_eq!(&a[19..23], &1.0f32.to_le_bytes());
        let e = event(&r);
        assert_eq!((e[0], e[5]), (3, 1));
        assert_eq!(&e[6..10], &1.0f32.to_le_bytes());
        assert_eq!(&e[10..20], b"HIGH LEVEL");
        // Twenty bytes of fields, then two zeros: every event record is 22
        // (docs/roc-protocol.md lists them so).
        assert_eq!((e.len(), &e[20..]), (22, &[0u8, 0][..]));
        let out = reply(LogRequest { count: 1, start: 7 }, 9, &[a.to_vec()]);
        assert_eq!(&out[..5], &[1, 7, 0, 9, 0]);
        assert_eq!(out.len(), 5 + ALARM_RECORD);
    }
}

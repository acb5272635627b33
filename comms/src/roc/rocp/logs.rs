//! Opcode 120 (where each log and archive writes next) and the records of
//! opcodes 121 and 122. Their requests and replies around the records are
//! ROC Plus's 118 and 119 layouts (`crate::roc::logs`); the records are
//! 22 bytes, alarms and events alike, with a six-byte time stamp.

use crate::roc::logs::Record;
use crate::roc::value::pad_ascii;

pub const RECORD: usize = 22;
/// Bytes of opcode 120's reply.
pub const POINTERS: usize = 26;

/// What opcode 120 reports (one RAM area: areas 1 and 2 are 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Pointers {
    pub alarm: u16,
    pub event: u16,
    pub hourly: u16,
    pub daily: u8,
    pub max_alarms: u16,
    pub max_events: u16,
    pub days: u8,
}

/// Opcode 120's reply: the alarm and event log pointers, the hourly
/// pointer of RAM areas 0–2, two reserved bytes, the daily pointer of
/// areas 0–2, a reserved byte, the most alarms and events, the days of
/// daily history of areas 0–2, a reserved byte, the audit log pointer.
pub fn pointers_reply(p: &Pointers) -> Vec<u8> {
    let mut out = Vec::with_capacity(POINTERS);
    for w in [p.alarm, p.event, p.hourly, 0, 0, 0] {
        out.extend_from_slice(&w.to_le_bytes());
    }
    out.extend_from_slice(&[p.daily, 0, 0, 0]);
    out.extend_from_slice(&p.max_alarms.to_le_bytes());
    out.extend_from_slice(&p.max_events.to_le_bytes());
    out.extend_from_slice(&[p.days, 0, 0, 0, 0, 0]);
    out
}

/// A time as the ROC protocol stamps it: second, minute, hour, day, month,
/// year − 2000.
pub fn stamp(seconds: i64) -> [u8; 6] {
    if seconds <= 0 {
        return [0; 6];
    }
    let days = seconds.div_euclid(86_400);
    let (y, m, d) = linc_stdlib::functions::datetime::civil_from_days(days);
    let s = seconds.rem_euclid(86_400);
    let yy = (y - 2000).clamp(0, 255) as u8;
    [(s % 60) as u8, (s / 60 % 60) as u8, (s / 3600) as u8, d as u8, m as u8, yy]
}

/// A record: type (an FST alarm 0x42, an FST event 3), the FST number,
/// the time stamp, ten characters of the message, the value.
pub fn record(alarm: bool, r: &Record, time: i64) -> [u8; RECORD] {
    let mut out = Vec::with_capacity(RECORD);
    out.push(if alarm { 2 | 0x40 } else { 3 });
    out.push(r.fst);
    out.extend_from_slice(&stamp(time));
    pad_ascii(&r.text, 10, &mut out);
    out.extend_from_slice(&r.value.to_le_bytes());
    out.try_into().unwrap_or([0; RECORD])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// abferm/roc's response/120.go gives the same 26 bytes field by field;
    /// the module manual's §6.1.2 example types them INT ×6, BIN ×4,
    /// INT ×2, BIN ×6.
    #[test]
    fn the_pointers_in_26_bytes() {
        let p = Pointers { alarm: 3, event: 258, hourly: 839, daily: 34, max_alarms: 240, max_events: 240, days: 35 };
        let r = pointers_reply(&p);
        assert_eq!(r.len(), POINTERS);
        assert_eq!(&r[..6], &[3, 0, 2, 1, 0x47, 3]);
        assert_eq!(&r[12..16], &[34, 0, 0, 0]);
        assert_eq!(&r[16..20], &[240, 0, 240, 0]);
        assert_eq!(&r[20..], &[35, 0, 0, 0, 0, 0]);
    }

    #[test]
    fn a_record_with_its_stamp() {
        // 2023-11-14 22:13:20
        assert_eq!(stamp(1_700_000_000), [20, 13, 22, 14, 11, 23]);
        let r = Record { time: 0, fst: 1, text: b"TANK HIGH".to_vec(), value: 1.0 };
        let b = record(true, &r, 1_700_000_000);
        assert_eq!(b[..8], [0x42, 1, 20, 13, 22, 14, 11, 23]);
        assert_eq!(&b[8..18], b"TANK HIGH ");
        assert_eq!(b[18..], 1.0f32.to_le_bytes());
        assert_eq!(record(false, &r, 0)[..8], [3, 1, 0, 0, 0, 0, 0, 0]);
    }
}

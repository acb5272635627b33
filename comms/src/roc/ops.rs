//! ROC Plus opcodes as data: each request's layout read from a frame's
//! data, each reply's layout written (docs/roc-protocol.md cites where each
//! layout comes from). Nothing here knows a database: a write's value sizes
//! come from the caller, which knows the parameters.

use linc_format::db::Tlp;

pub const CONFIG: u8 = 6;
pub const CLOCK_READ: u8 = 7;
pub const CLOCK_SET: u8 = 8;
pub const LOGIN: u8 = 17;
pub const ALARMS: u8 = 118;
pub const EVENTS: u8 = 119;
pub const HISTORY_POINT: u8 = 135;
pub const HISTORY_POINTS: u8 = 136;
pub const READ: u8 = 180;
pub const WRITE: u8 = 181;
pub const ERROR: u8 = 255;

/// Opcode 255 error codes (the specification's table 2-32).
pub mod code {
    pub const INVALID_OPCODE: u8 = 1;
    pub const INVALID_PARAMETER: u8 = 2;
    pub const INVALID_LOGICAL: u8 = 3;
    pub const INVALID_POINT_TYPE: u8 = 4;
    pub const TOO_MANY_BYTES: u8 = 5;
    pub const TOO_FEW_BYTES: u8 = 6;
    pub const TOO_MANY_ALARMS: u8 = 17;
    pub const TOO_MANY_EVENTS: u8 = 18;
    pub const READ_ONLY: u8 = 19;
    pub const SECURITY: u8 = 20;
    pub const INVALID_LOGON: u8 = 21;
    pub const PARAMETER_RANGE: u8 = 25;
    pub const INVALID_TIME: u8 = 33;
    pub const GENERAL: u8 = 50;
    pub const INVALID_STATE_FOR_WRITE: u8 = 51;
    pub const ACCESS_LEVEL: u8 = 63;
    pub const INVALID_LOGOFF: u8 = 77;
}

/// Offset of a frame's first data byte from its first byte: error offsets
/// count from the destination unit.
pub const DATA_AT: usize = 6;
/// Offset of the length byte, which errors about the data's size name.
pub const LENGTH_AT: u8 = 5;

/// One opcode 255 error: the code and the offset, in the request, of the
/// byte that caused it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RocError {
    pub code: u8,
    pub offset: u8,
}

impl RocError {
    /// An error about the data byte at `i` of the request's data.
    pub fn at_data(code: u8, i: usize) -> RocError {
        RocError { code, offset: u8::try_from(i + DATA_AT).unwrap_or(u8::MAX) }
    }

    /// An error about the request's length.
    pub fn length(code: u8) -> RocError {
        RocError { code, offset: LENGTH_AT }
    }
}

/// The data of an opcode 255 reply: code and offset pairs.
pub fn error_data(errors: &[RocError]) -> Vec<u8> {
    errors.iter().flat_map(|e| [e.code, e.offset]).collect()
}

pub use linc_format::db::TlpFault;

/// The opcode 255 error for the TLP at data byte `at`, by the part of it
/// that names nothing (the error's offset is that part's byte).
pub fn tlp_error(fault: TlpFault, at: usize) -> RocError {
    match fault {
        TlpFault::PointType => RocError::at_data(code::INVALID_POINT_TYPE, at),
        TlpFault::Logical => RocError::at_data(code::INVALID_LOGICAL, at + 1),
        TlpFault::Parameter => RocError::at_data(code::INVALID_PARAMETER, at + 2),
    }
}

fn tlp(b: &[u8]) -> Tlp {
    Tlp { t: u16::from(b[0]), l: u16::from(b[1]), p: u16::from(b[2]) }
}

/// Opcode 180's request: a count, then that many TLPs of three bytes.
pub fn parse_read(data: &[u8]) -> Result<Vec<Tlp>, RocError> {
    let Some(&n) = data.first() else { return Err(RocError::length(code::TOO_FEW_BYTES)) };
    let want = 1 + 3 * usize::from(n);
    match data.len().cmp(&want) {
        std::cmp::Ordering::Less => return Err(RocError::length(code::TOO_FEW_BYTES)),
        std::cmp::Ordering::Greater => return Err(RocError::length(code::TOO_MANY_BYTES)),
        std::cmp::Ordering::Equal => {}
    }
    if n == 0 {
        return Err(RocError::at_data(code::TOO_FEW_BYTES, 0));
    }
    Ok(data[1..].chunks_exact(3).map(tlp).collect())
}

/// Opcode 180's reply: the count, then each TLP followed by its value. A
/// reply longer than a frame can carry is refused: error 5 (too many data
/// bytes) at the length byte.
pub fn read_reply<'a>(values: impl IntoIterator<Item = (Tlp, &'a [u8])>) -> Result<Vec<u8>, RocError> {
    let mut out = vec![0u8];
    for (t, v) in values {
        out.extend_from_slice(&[t.t as u8, t.l as u8, t.p as u8]);
        out.extend_from_slice(v);
        out[0] = out[0].wrapping_add(1);
    }
    if out.len() > super::frame::MAX_DATA {
        return Err(RocError::length(code::TOO_MANY_BYTES));
    }
    Ok(out)
}

/// One parameter of an opcode 181 request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Write<'a> {
    /// Where its TLP starts in the request's data (errors point into it).
    pub at: usize,
    pub tlp: Tlp,
    pub value: &'a [u8],
}

/// Opcode 181's request: a count, then each TLP with its value, whose size
/// `size_of` gives (the device knows its parameters). The first TLP that
/// names nothing, or data of the wrong length, is the error.
pub fn parse_write(data: &[u8], size_of: impl Fn(Tlp) -> Result<usize, TlpFault>) -> Result<Vec<Write<'_>>, RocError> {
    let Some(&n) = data.first() else { return Err(RocError::length(code::TOO_FEW_BYTES)) };
    if n == 0 {
        return Err(RocError::at_data(code::TOO_FEW_BYTES, 0));
    }
    let mut at = 1;
    let mut out = Vec::with_capacity(usize::from(n));
    for _ in 0..n {
        let Some(head) = data.get(at..at + 3) else { return Err(RocError::length(code::TOO_FEW_BYTES)) };
        let t = tlp(head);
        let size = size_of(t).map_err(|f| tlp_error(f, at))?;
        let Some(value) = data.get(at + 3..at + 3 + size) else {
            return Err(RocError::length(code::TOO_FEW_BYTES));
        };
        out.push(Write { at, tlp: t, value });
        at += 3 + size;
    }
    if at != data.len() {
        return Err(RocError::length(code::TOO_MANY_BYTES));
    }
    Ok(out)
}

/// A calendar time as opcodes 7 and 8 carry it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Clock {
    pub second: u8,
    pub minute: u8,
    pub hour: u8,
    pub day: u8,
    pub month: u8,
    pub year: u16,
    /// 1 Sunday … 7 Saturday (opcode 7 only).
    pub weekday: u8,
}

impl Clock {
    /// Opcode 7's reply: second, minute, hour, day, month, year (two
    /// bytes), day of the week.
    pub fn reply(&self) -> Vec<u8> {
        let [y0, y1] = self.year.to_le_bytes();
        vec![self.second, self.minute, self.hour, self.day, self.month, y0, y1, self.weekday]
    }

    /// Opcode 8's request: second, minute, hour, day, month, year (two
    /// bytes); no day of the week. A field out of its range is error 33 at
    /// that field.
    pub fn parse_set(data: &[u8]) -> Result<Clock, RocError> {
        match data.len() {
            0..=6 => return Err(RocError::length(code::TOO_FEW_BYTES)),
            7 => {}
            _ => return Err(RocError::length(code::TOO_MANY_BYTES)),
        }
        let year = u16::from_le_bytes([data[5], data[6]]);
        let bad = |i: usize| RocError::at_data(code::INVALID_TIME, i);
        let (second, minute, hour, day, month) = (data[0], data[1], data[2], data[3], data[4]);
        if second > 59 {
            return Err(bad(0));
        }
        if minute > 59 {
            return Err(bad(1));
        }
        if hour > 23 {
            return Err(bad(2));
        }
        if !(1..=12).contains(&month) {
            return Err(bad(4));
        }
        if !(1970..=2099).contains(&year) {
            return Err(bad(5));
        }
        if day == 0 || day > days_in_month(year, month) {
            return Err(bad(3));
        }
        Ok(Clock { second, minute, hour, day, month, year, weekday: 0 })
    }
}

/// Days in a month of the Gregorian calendar.
pub fn days_in_month(year: u16, month: u8) -> u8 {
    linc_stdlib::functions::datetime::days_in_month(i64::from(year), u32::from(month)) as u8
}

/// Opcode 17's request, told apart by its length: a standard login (6
/// bytes: operator ID, password, access level) or logout (11 bytes:
/// operator ID, password, the logout text).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Login {
    In { id: [u8; 3], password: u16, level: u8 },
    Out { id: [u8; 3], password: u16, text: [u8; 6] },
}

/// The logout text a standard logout carries.
pub const LOGOUT: &[u8; 6] = b"LOGOUT";

impl Login {
    /// Parses opcode 17. The enhanced login and logout (71 and 76 bytes)
    /// and the session key request (13) are not supported: error 21.
    pub fn parse(data: &[u8]) -> Result<Login, RocError> {
        let id = |d: &[u8]| [d[0], d[1], d[2]];
        let password = |d: &[u8]| u16::from_le_bytes([d[3], d[4]]);
        match data.len() {
            6 => Ok(Login::In { id: id(data), password: password(data), level: data[5] }),
            11 => {
                let mut text = [0u8; 6];
                text.copy_from_slice(&data[5..11]);
                Ok(Login::Out { id: id(data), password: password(data), text })
            }
            _ => Err(RocError::at_data(code::INVALID_LOGON, 0)),
        }
    }
}

/// Opcode 6's reply (revision 1, 215 bytes): run mode, the port, security
/// mode 0, compatibility 0, revision 1, subtype 0, eleven reserved bytes,
/// the type of ROC (6, a ROC800), then the number of points of each point
/// type from 60 to 255.
pub fn config_reply(port: u16, count_of: impl Fn(u8) -> u8) -> Vec<u8> {
    let mut out = Vec::with_capacity(215);
    out.push(1);
    out.extend_from_slice(&port.to_le_bytes());
    out.extend_from_slice(&[0, 0, 1, 0]);
    out.extend_from_slice(&[0; 11]);
    out.push(6);
    out.extend((60..=255u8).map(count_of));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_read_request_lists_its_tlps_and_its_errors_name_the_length() {
        assert_eq!(parse_read(&[2, 3, 0, 2, 3, 1, 2]), Ok(vec![Tlp { t: 3, l: 0, p: 2 }, Tlp { t: 3, l: 1, p: 2 }]));
        assert_eq!(parse_read(&[2, 3, 0, 2]), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(parse_read(&[1, 3, 0, 2, 9]), Err(RocError { code: 5, offset: 5 }));
        assert_eq!(parse_read(&[]), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(parse_read(&[0]), Err(RocError { code: 6, offset: 6 }));
    }

    #[test]
    fn a_read_reply_puts_each_value_after_its_tlp() {
        let a = Tlp { t: 3, l: 0, p: 2 };
        let reply = read_reply([(a, &[0xF4u8, 0x01][..]), (Tlp { l: 1, ..a }, &[0xE8, 0x03][..])]).unwrap();
        assert_eq!(reply, [2, 3, 0, 2, 0xF4, 0x01, 3, 1, 2, 0xE8, 0x03]);
        let big = [0u8; 40];
        let many = (0..7).map(|l| (Tlp { l, ..a }, &big[..]));
        assert_eq!(read_reply(many), Err(RocError { code: 5, offset: 5 }));
    }

    #[test]
    fn a_write_request_is_split_by_the_devices_sizes() {
        let size = |t: Tlp| match (t.t, t.l, t.p) {
            (3, 0 | 1, 2) => Ok(2),
            (3, 0 | 1, _) => Err(TlpFault::Parameter),
            (3, _, _) => Err(TlpFault::Logical),
            _ => Err(TlpFault::PointType),
        };
        let data = [2, 3, 0, 2, 0xF4, 0x01, 3, 1, 2, 0xE8, 0x03];
        let w = parse_write(&data, size).unwrap();
        assert_eq!(
            w,
            vec![
                Write { at: 1, tlp: Tlp { t: 3, l: 0, p: 2 }, value: &[0xF4, 0x01] },
                Write { at: 6, tlp: Tlp { t: 3, l: 1, p: 2 }, value: &[0xE8, 0x03] }
            ]
        );
        // The second TLP's parameter names nothing: error 2 at its byte (6 + 8).
        assert_eq!(parse_write(&[2, 3, 0, 2, 0, 0, 3, 1, 9, 0, 0], size), Err(RocError { code: 2, offset: 14 }));
        assert_eq!(parse_write(&[1, 7, 0, 2, 0, 0], size), Err(RocError { code: 4, offset: 7 }));
        assert_eq!(parse_write(&[1, 3, 5, 2, 0, 0], size), Err(RocError { code: 3, offset: 8 }));
        assert_eq!(parse_write(&[1, 3, 0, 2, 0], size), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(parse_write(&[1, 3, 0, 2, 0, 0, 0], size), Err(RocError { code: 5, offset: 5 }));
        assert_eq!(error_data(&[RocError { code: 2, offset: 14 }]), [2, 14]);
    }

    #[test]
    fn the_clock_both_ways() {
        let c = Clock { second: 5, minute: 4, hour: 3, day: 29, month: 2, year: 2024, weekday: 5 };
        assert_eq!(c.reply(), [5, 4, 3, 29, 2, 0xE8, 0x07, 5]);
        assert_eq!(Clock::parse_set(&c.reply()[..7]), Ok(Clock { weekday: 0, ..c }));
        assert_eq!(Clock::parse_set(&[5, 4, 3, 29, 2, 0xE7, 0x07]), Err(RocError { code: 33, offset: 9 }));
        assert_eq!(Clock::parse_set(&[60, 4, 3, 1, 2, 0xE8, 0x07]), Err(RocError { code: 33, offset: 6 }));
        assert_eq!(Clock::parse_set(&[0, 0, 0, 1, 13, 0xE8, 0x07]), Err(RocError { code: 33, offset: 10 }));
        assert_eq!(Clock::parse_set(&[0, 0, 0, 1, 1]), Err(RocError { code: 6, offset: 5 }));
    }

    #[test]
    fn logins_and_logouts_by_length() {
        assert_eq!(
            Login::parse(&[b'L', b'O', b'I', 0xE8, 0x03, 5]),
            Ok(Login::In { id: *b"LOI", password: 1000, level: 5 })
        );
        let out = [b'L', b'O', b'I', 0xE8, 0x03, b'L', b'O', b'G', b'O', b'U', b'T'];
        assert_eq!(Login::parse(&out), Ok(Login::Out { id: *b"LOI", password: 1000, text: *LOGOUT }));
        assert_eq!(Login::parse(&[0; 71]), Err(RocError { code: 21, offset: 6 }));
    }

    #[test]
    fn the_system_configuration_counts_point_types_from_60() {
        let r = config_reply(0, |t| if t == 98 { 3 } else { 0 });
        assert_eq!(r.len(), 215);
        assert_eq!(r[18], 6, "type of ROC: ROC800");
        assert_eq!(r[19 + 98 - 60], 3);
        assert_eq!(r.iter().skip(19).map(|&b| u32::from(b)).sum::<u32>(), 3);
    }
}

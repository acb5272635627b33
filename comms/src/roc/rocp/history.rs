//! History in the ROC protocol: the last hour of minute values (126), a
//! day's hourly values (128) and values from an archive pointer (130). The
//! requests name a history point by its number; the replies carry floats.

use super::code::INVALID_HISTORY;
use super::exactly;
use crate::roc::ops::RocError;

/// Opcode 126's request: the history point.
pub fn parse_last_hour(data: &[u8]) -> Result<u8, RocError> {
    exactly(data, 1)?;
    Ok(data[0])
}

/// Opcode 126's reply: the point, the minute of the hour now, then the 60
/// values of the minute archive (index 0 is minute 0).
pub fn last_hour_reply(point: u8, minute: u8, values: &[f32; 60]) -> Vec<u8> {
    let mut out = Vec::with_capacity(2 + 240);
    out.extend_from_slice(&[point, minute]);
    values.iter().for_each(|v| out.extend_from_slice(&v.to_le_bytes()));
    out
}

/// Opcode 128's request: a point and a day of the year.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct DayRequest {
    pub point: u8,
    pub day: u8,
    pub month: u8,
}

/// Opcode 128's request: point, day, month; a day that no month has (31
/// April is not refused here: 29 February exists in some year) is error
/// 14 at its byte.
pub fn parse_day(data: &[u8]) -> Result<DayRequest, RocError> {
    exactly(data, 3)?;
    let r = DayRequest { point: data[0], day: data[1], month: data[2] };
    if !(1..=12).contains(&r.month) {
        return Err(RocError::at_data(INVALID_HISTORY, 2));
    }
    if r.day == 0 || r.day > crate::roc::ops::days_in_month(2000, r.month) {
        return Err(RocError::at_data(INVALID_HISTORY, 1));
    }
    Ok(r)
}

/// A time in a 128 reply: second, minute, hour, day, month.
pub type When = [u8; 5];

/// What opcode 128 answers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Day {
    pub request: DayRequest,
    /// The device clock's hour and minute now.
    pub hour: u8,
    pub minute: u8,
    /// The periodic index of the day's first entry; 65535 when none.
    pub first_index: u16,
    pub hours: [f32; 24],
    pub daily: f32,
    pub least: (f32, When),
    pub greatest: (f32, When),
    /// The archived parameter's point type (0 if none).
    pub point_type: u8,
}

/// Bytes of opcode 128's reply.
pub const DAY_REPLY: usize = 134;

/// Opcode 128's reply: point, month, day, hour, minute, the first index,
/// 24 hourly values, the daily value, the least and greatest value, their
/// times, the point type, eight reserved bytes.
pub fn day_reply(d: &Day) -> Vec<u8> {
    let r = &d.request;
    let mut out = Vec::with_capacity(DAY_REPLY);
    out.extend_from_slice(&[r.point, r.month, r.day, d.hour, d.minute]);
    out.extend_from_slice(&d.first_index.to_le_bytes());
    for v in d.hours.iter().chain([&d.daily, &d.least.0, &d.greatest.0]) {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&d.least.1);
    out.extend_from_slice(&d.greatest.1);
    out.push(d.point_type);
    out.extend_from_slice(&[0; 8]);
    out
}

/// Opcode 130's history types.
pub const PERIODIC: u8 = 0;
pub const DAILY: u8 = 1;
/// The point number that asks for an archive's time stamps.
pub const STAMPS: u8 = 254;
/// Most values one 130 asks for.
pub const MAX_VALUES: u8 = 60;

/// Opcode 130's request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct FromPointer {
    pub kind: u8,
    pub point: u8,
    pub count: u8,
    pub start: u16,
}

/// Opcode 130's request: history type, point, values, starting pointer (2
/// bytes); a type other than 0 or 1 or a count outside 1–60 is error 14.
pub fn parse_from_pointer(data: &[u8]) -> Result<FromPointer, RocError> {
    exactly(data, 5)?;
    let r =
        FromPointer { kind: data[0], point: data[1], count: data[2], start: u16::from_le_bytes([data[3], data[4]]) };
    if r.kind > DAILY {
        return Err(RocError::at_data(INVALID_HISTORY, 0));
    }
    if r.count == 0 || r.count > MAX_VALUES {
        return Err(RocError::at_data(INVALID_HISTORY, 2));
    }
    Ok(r)
}

/// Opcode 130's reply: type, point, values sent, then four bytes each.
pub fn from_pointer_reply(r: &FromPointer, values: &[[u8; 4]]) -> Vec<u8> {
    let mut out = Vec::with_capacity(3 + 4 * values.len());
    out.extend_from_slice(&[r.kind, r.point, values.len() as u8]);
    values.iter().for_each(|v| out.extend_from_slice(v));
    out
}

/// A time stamp as 130 gives it for point 254: minute, hour, day, month.
pub fn short_stamp(seconds: i64) -> [u8; 4] {
    let s = super::logs::stamp(seconds);
    [s[1], s[2], s[3], s[4]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_last_hour() {
        assert_eq!(parse_last_hour(&[3]), Ok(3));
        assert_eq!(parse_last_hour(&[]), Err(RocError { code: 6, offset: 5 }));
        let mut v = [0.0f32; 60];
        v[59] = 2.0;
        let r = last_hour_reply(3, 17, &v);
        assert_eq!((r.len(), &r[..2], &r[238..]), (242, &[3u8, 17][..], &2.0f32.to_le_bytes()[..]));
    }

    /// The field order of abferm/roc's response/128.go: 134 bytes.
    #[test]
    fn a_day() {
        let request = parse_day(&[3, 14, 11]).unwrap();
        assert_eq!(request, DayRequest { point: 3, day: 14, month: 11 });
        assert_eq!(parse_day(&[3, 30, 2]), Err(RocError { code: 14, offset: 7 }));
        assert_eq!(parse_day(&[3, 1, 13]), Err(RocError { code: 14, offset: 8 }));
        assert!(parse_day(&[3, 29, 2]).is_ok());
        let mut hours = [0.0; 24];
        hours[5] = 7.5;
        let d = Day {
            request,
            hour: 9,
            minute: 30,
            first_index: 24,
            hours,
            daily: 1.0,
            least: (0.0, [0, 0, 0, 14, 11]),
            greatest: (7.5, [0, 0, 5, 14, 11]),
            point_type: 16,
        };
        let r = day_reply(&d);
        assert_eq!(r.len(), DAY_REPLY);
        assert_eq!(&r[..7], &[3, 11, 14, 9, 30, 24, 0]);
        assert_eq!(&r[7 + 20..7 + 24], &7.5f32.to_le_bytes());
        assert_eq!(&r[103..107], &1.0f32.to_le_bytes());
        assert_eq!(&r[115..125], &[0, 0, 0, 14, 11, 0, 0, 5, 14, 11]);
        assert_eq!(r[125], 16);
    }

    /// A FloBoss 407 host's opcode 130 request quoted with its CRC on
    /// Emerson Exchange 365 ("Roclink protocol"): RAM area (history type)
    /// 0, point 254 (time stamps), 59 values from pointer 781.
    #[test]
    fn a_published_130_request() {
        let wire = [0x01, 0x02, 0x03, 0x01, 0x82, 0x05, 0x00, 0xFE, 0x3B, 0x0D, 0x03, 0xD6, 0xE3];
        let (f, n) = crate::roc::Frame::decode(&wire).unwrap();
        assert_eq!((n, f.opcode), (wire.len(), 130));
        assert_eq!(parse_from_pointer(&f.data), Ok(FromPointer { kind: 0, point: STAMPS, count: 59, start: 781 }));
    }

    /// abferm/roc's 130: type, point, count, pointer (2 bytes); the reply
    /// type, point, count and four bytes a value (response/130.go).
    #[test]
    fn from_a_pointer() {
        let r = parse_from_pointer(&[0, 3, 24, 0x0D, 0x03]).unwrap();
        assert_eq!(r, FromPointer { kind: 0, point: 3, count: 24, start: 781 });
        assert_eq!(parse_from_pointer(&[2, 3, 24, 0, 0]), Err(RocError { code: 14, offset: 6 }));
        assert_eq!(parse_from_pointer(&[0, 3, 61, 0, 0]), Err(RocError { code: 14, offset: 8 }));
        assert_eq!(from_pointer_reply(&r, &[[1, 2, 3, 4]]), [0, 3, 1, 1, 2, 3, 4]);
        assert_eq!(short_stamp(1_700_000_000), [13, 22, 14, 11]);
    }
}

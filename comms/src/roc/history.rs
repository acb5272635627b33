//! The history opcodes a host collects archives with (docs/roc-protocol.md):
//! 135, one point's values or time stamps from an index, and 136, several
//! points' values with a time stamp per period. linc has one history
//! segment, 0, and names points by their history point number.

use super::ops::{code, RocError};

/// Values one 135 reply carries, and elements one 136 reply.
pub const MAX_VALUES: u8 = 60;

/// Which archive, and whether values or their time stamps.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Minute,
    Periodic,
    Daily,
    PeriodicStamps,
    DailyStamps,
}

impl Kind {
    fn from_byte(b: u8) -> Option<Kind> {
        Some(match b {
            0 => Kind::Minute,
            1 => Kind::Periodic,
            2 => Kind::Daily,
            3 => Kind::PeriodicStamps,
            4 => Kind::DailyStamps,
            _ => return None,
        })
    }
}

/// Opcode 135's request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PointRequest {
    pub segment: u8,
    pub point: u8,
    pub kind: Kind,
    pub start: u16,
    pub count: u8,
}

fn check(data: &[u8], len: usize) -> Result<(), RocError> {
    match data.len().cmp(&len) {
        std::cmp::Ordering::Less => Err(RocError::length(code::TOO_FEW_BYTES)),
        std::cmp::Ordering::Greater => Err(RocError::length(code::TOO_MANY_BYTES)),
        std::cmp::Ordering::Equal => Ok(()),
    }
}

/// Error 14 (invalid history request) at a data byte.
fn invalid(at: usize) -> RocError {
    RocError::at_data(14, at)
}

/// 135: segment, point, type, starting index (2 bytes), number of values.
pub fn parse_point(data: &[u8]) -> Result<PointRequest, RocError> {
    check(data, 6)?;
    let kind = Kind::from_byte(data[2]).ok_or(invalid(2))?;
    if data[0] != 0 {
        return Err(invalid(0));
    }
    if data[5] == 0 || data[5] > MAX_VALUES {
        return Err(invalid(5));
    }
    Ok(PointRequest {
        segment: data[0],
        point: data[1],
        kind,
        start: u16::from_le_bytes([data[3], data[4]]),
        count: data[5],
    })
}

/// 135's reply: segment, point, the current index, the count, then each
/// value (FL) or time stamp (seconds since 1970, 4 bytes).
pub fn point_reply(req: &PointRequest, current: u16, values: &[[u8; 4]]) -> Vec<u8> {
    let mut out = vec![req.segment, req.point];
    out.extend_from_slice(&current.to_le_bytes());
    out.push(values.len() as u8);
    for v in values {
        out.extend_from_slice(v);
    }
    out
}

/// Opcode 136's request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PointsRequest {
    pub segment: u8,
    pub start: u16,
    pub kind: Kind,
    pub first_point: u8,
    pub points: u8,
    pub periods: u8,
}

/// 136: segment, index (2 bytes), type (1 periodic or 2 daily), first
/// point, number of points, number of periods; (points + 1) × periods is
/// at most 60.
pub fn parse_points(data: &[u8]) -> Result<PointsRequest, RocError> {
    check(data, 7)?;
    if data[0] != 0 {
        return Err(invalid(0));
    }
    let kind = match data[3] {
        1 => Kind::Periodic,
        2 => Kind::Daily,
        _ => return Err(invalid(3)),
    };
    let (points, periods) = (data[5], data[6]);
    if points == 0 || periods == 0 || (usize::from(points) + 1) * usize::from(periods) > usize::from(MAX_VALUES) {
        return Err(invalid(5));
    }
    Ok(PointsRequest {
        segment: 0,
        start: u16::from_le_bytes([data[1], data[2]]),
        kind,
        first_point: data[4],
        points,
        periods,
    })
}

/// 136's reply: segment, the index asked for, the current index, the
/// number of elements, then each period's time stamp and its points'
/// values.
pub fn points_reply(req: &PointsRequest, current: u16, periods: &[(u32, Vec<f32>)]) -> Vec<u8> {
    let mut out = vec![req.segment];
    out.extend_from_slice(&req.start.to_le_bytes());
    out.extend_from_slice(&current.to_le_bytes());
    out.push(periods.iter().map(|(_, v)| 1 + v.len()).sum::<usize>() as u8);
    for (stamp, values) in periods {
        out.extend_from_slice(&stamp.to_le_bytes());
        for v in values {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_parse_and_replies_lay_out() {
        let r = parse_point(&[0, 3, 1, 10, 0, 2]).unwrap();
        assert_eq!((r.point, r.kind, r.start, r.count), (3, Kind::Periodic, 10, 2));
        assert_eq!(parse_point(&[0, 3, 9, 0, 0, 2]), Err(RocError { code: 14, offset: 8 }));
        assert_eq!(parse_point(&[1, 3, 1, 0, 0, 2]), Err(RocError { code: 14, offset: 6 }), "one segment");
        assert_eq!(parse_point(&[0, 3, 1, 0, 0, 61]), Err(RocError { code: 14, offset: 11 }));
        assert_eq!(parse_point(&[0, 3, 1, 0, 0]), Err(RocError { code: 6, offset: 5 }));
        let out = point_reply(&r, 12, &[1.5f32.to_le_bytes(), 2.5f32.to_le_bytes()]);
        assert_eq!(&out[..5], &[0, 3, 12, 0, 2]);
        assert_eq!(&out[5..9], &1.5f32.to_le_bytes());
        let m = parse_points(&[0, 4, 0, 1, 1, 2, 20]).unwrap();
        assert_eq!((m.start, m.first_point, m.points, m.periods), (4, 1, 2, 20));
        assert_eq!(parse_points(&[0, 4, 0, 1, 1, 2, 21]), Err(RocError { code: 14, offset: 11 }), "3 x 21 > 60");
        let out = points_reply(&m, 6, &[(100, vec![1.0, 2.0])]);
        assert_eq!(&out[..6], &[0, 4, 0, 6, 0, 3]);
        assert_eq!(out.len(), 6 + 4 + 8);
    }
}

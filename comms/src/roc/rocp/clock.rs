//! Opcodes 7 and 8 in the ROC protocol: a one-byte year (years since
//! 2000, as the FloBoss 100-series keeps it), and opcode 7 adds the years
//! since the last leap year before the day of the week.

use crate::roc::ops::{code, days_in_month, Clock, RocError};

/// Opcode 7's reply: second, minute, hour, day, month, year − 2000, the
/// year mod 4 (0 in a leap year of this century), day of the week.
pub fn reply(c: &Clock) -> Vec<u8> {
    let yy = c.year.saturating_sub(2000).min(255) as u8;
    vec![c.second, c.minute, c.hour, c.day, c.month, yy, (c.year % 4) as u8, c.weekday]
}

/// Opcode 8's request: second, minute, hour, day, month, year − 2000. The
/// module sends six to nine bytes (`003_…` §6.1: the leap year and day of
/// the week after); what follows the year is accepted and ignored, the
/// device working both out itself. A field out of range is error 33 there.
pub fn parse_set(data: &[u8]) -> Result<Clock, RocError> {
    match data.len() {
        0..=5 => return Err(RocError::length(code::TOO_FEW_BYTES)),
        6..=9 => {}
        _ => return Err(RocError::length(code::TOO_MANY_BYTES)),
    }
    let bad = |i: usize| RocError::at_data(code::INVALID_TIME, i);
    let (second, minute, hour, day, month) = (data[0], data[1], data[2], data[3], data[4]);
    if data[5] > 99 {
        return Err(bad(5));
    }
    let year = 2000 + u16::from(data[5]);
    for (i, ok) in [(0, second <= 59), (1, minute <= 59), (2, hour <= 23), (4, (1..=12).contains(&month))] {
        if !ok {
            return Err(bad(i));
        }
    }
    if day == 0 || day > days_in_month(year, month) {
        return Err(bad(3));
    }
    Ok(Clock { second, minute, hour, day, month, year, weekday: 0 })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Go driver abferm/roc reads opcode 7 as eight bytes with the
    /// year from 2000 and sets the clock with six (client.go).
    #[test]
    fn both_ways() {
        let c = Clock { second: 5, minute: 4, hour: 3, day: 29, month: 2, year: 2024, weekday: 5 };
        assert_eq!(reply(&c), [5, 4, 3, 29, 2, 24, 0, 5]);
        assert_eq!(reply(&Clock { year: 2026, ..c })[6], 2);
        assert_eq!(parse_set(&[5, 4, 3, 29, 2, 24]), Ok(Clock { weekday: 0, ..c }));
        assert_eq!(parse_set(&[5, 4, 3, 29, 2, 24, 0, 5, 0]), Ok(Clock { weekday: 0, ..c }));
        assert_eq!(parse_set(&[5, 4, 3, 29, 2, 23]), Err(RocError { code: 33, offset: 9 }));
        assert_eq!(parse_set(&[60, 4, 3, 1, 2, 24]), Err(RocError { code: 33, offset: 6 }));
        assert_eq!(parse_set(&[0, 0, 0, 1, 13, 24]), Err(RocError { code: 33, offset: 10 }));
        assert_eq!(parse_set(&[0, 0, 0, 1, 1, 100]), Err(RocError { code: 33, offset: 11 }));
        assert_eq!(parse_set(&[0, 0, 0, 1, 1]), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(parse_set(&[0; 10]), Err(RocError { code: 5, offset: 5 }));
    }
}

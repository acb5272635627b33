//! The device clock as the FST commands see it: POSIX seconds read as a
//! civil date with no time zone (the device keeps local time and knows no
//! zone), so `0` is 1970-01-01 00:00:00 and every day has 86 400 seconds.
//!
//! The calendar arithmetic is the library's one calendar
//! (`linc_stdlib::functions::datetime`, Hinnant's `civil_from_days`,
//! proleptic Gregorian), shared with the date functions and `--now`.

use linc_stdlib::functions::datetime::civil_from_days;

/// Seconds in a day of the device clock (no leap seconds).
pub const DAY: i64 = 86_400;

/// The earliest time GTE accepts: 0001-01-01 00:00:00.
pub const MIN_TIME: f64 = -62_135_596_800.0;
/// The latest time GTE accepts: 9999-12-31 23:59:59 (a four-digit year
/// keeps the ISO text of `--out` well formed).
pub const MAX_TIME: f64 = 253_402_300_799.0;

/// A time of the device clock split into its calendar parts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Civil {
    pub year: i64,
    /// 1–12.
    pub month: u32,
    /// 1–31.
    pub day: u32,
    pub hour: u32,
    pub minute: u32,
    pub second: u32,
}

impl Civil {
    /// `month × 100 + day`, the form DIS, DIN, PIS and PIN take a date in.
    pub fn month_day(&self) -> u32 {
        self.month * 100 + self.day
    }
}

/// The calendar parts of a device time.
pub fn civil(now: i64) -> Civil {
    let (year, month, day) = civil_from_days(now.div_euclid(DAY));
    let secs = now.rem_euclid(DAY) as u32; // 0..86400
    Civil { year, month, day, hour: secs / 3600, minute: secs / 60 % 60, second: secs % 60 }
}

/// GTE: element `element` of the time `seconds` (seconds since 1970 on the
/// device clock): 0 month, 1 day, 2 year, 3 hour, 4 minute, 5 second.
/// A fractional time counts from its whole second (floor). `None` for
/// another element, or a time that is not finite or outside years
/// 1–9999.
pub fn gte(seconds: f64, element: i32) -> Option<f32> {
    if !(MIN_TIME..=MAX_TIME).contains(&seconds) {
        return None; // also NaN
    }
    let c = civil(seconds.floor() as i64);
    let v = match element {
        0 => c.month,
        1 => c.day,
        2 => return Some(c.year as f32), // 1..=9999: exact in f32
        3 => c.hour,
        4 => c.minute,
        5 => c.second,
        _ => return None,
    };
    Some(v as f32)
}

/// DWK: the day of the week, 1 = Sunday … 7 = Saturday (1970-01-01 was a
/// Thursday, 5).
pub fn day_of_week(now: i64) -> f32 {
    ((now.div_euclid(DAY) + 4).rem_euclid(7) + 1) as f32
}

/// MND: whole minutes since midnight, 0–1439 (the seconds of the current
/// minute are dropped, as the device's minute counter does).
pub fn minutes_since_midnight(now: i64) -> f32 {
    (now.rem_euclid(DAY) / 60) as f32
}

/// ISO 8601 local time without a zone (`2023-11-14T22:13:20`): the device
/// clock has none to name.
pub fn iso(now: i64) -> String {
    let c = civil(now);
    format!("{:04}-{:02}-{:02}T{:02}:{:02}:{:02}", c.year, c.month, c.day, c.hour, c.minute, c.second)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_times_split_into_their_calendar_parts() {
        assert_eq!(iso(1_700_000_000), "2023-11-14T22:13:20");
        assert_eq!(iso(0), "1970-01-01T00:00:00");
        assert_eq!(iso(-1), "1969-12-31T23:59:59", "before 1970 counts back");
        assert_eq!(iso(951_782_400), "2000-02-29T00:00:00", "2000 is a leap year (divisible by 400)");
        assert_eq!(iso(1_709_164_800), "2024-02-29T00:00:00");
        assert_eq!(iso(4_102_444_800), "2100-01-01T00:00:00", "2100 is not a leap year");
        assert_eq!(iso(MAX_TIME as i64), "9999-12-31T23:59:59");
        assert_eq!(iso(MIN_TIME as i64), "0001-01-01T00:00:00");
        assert_eq!(civil(1_700_000_000).month_day(), 1114);
    }

    #[test]
    fn gte_extracts_each_element() {
        let t = 1_700_000_000.0;
        let got: Vec<Option<f32>> = (0..6).map(|e| gte(t, e)).collect();
        let want = [11.0, 14.0, 2023.0, 22.0, 13.0, 20.0].map(Some);
        assert_eq!(got, want);
        assert_eq!(gte(t + 0.9, 5), Some(20.0), "fractions of a second are dropped");
        assert_eq!(gte(-0.5, 2), Some(1969.0), "the floor, not the truncation");
        assert_eq!(gte(t, 6), None);
        assert_eq!(gte(t, -1), None);
        assert_eq!(gte(f64::NAN, 0), None);
        assert_eq!(gte(f64::INFINITY, 0), None);
        assert_eq!(gte(MAX_TIME + 1.0, 2), None);
        assert_eq!(gte(MAX_TIME, 2), Some(9999.0));
    }

    #[test]
    fn day_of_week_counts_from_a_thursday() {
        assert_eq!(day_of_week(0), 5.0, "1970-01-01 was a Thursday");
        assert_eq!(day_of_week(1_700_000_000), 3.0, "2023-11-14 was a Tuesday");
        assert_eq!(day_of_week(3 * DAY), 1.0, "1970-01-04 was a Sunday");
        assert_eq!(day_of_week(2 * DAY + DAY - 1), 7.0, "Saturday's last second");
        assert_eq!(day_of_week(-1), 4.0, "1969-12-31 was a Wednesday");
    }

    #[test]
    fn minutes_since_midnight_drops_the_seconds() {
        assert_eq!(minutes_since_midnight(1_700_000_000), 1333.0, "22:13:20");
        assert_eq!(minutes_since_midnight(DAY - 1), 1439.0);
        assert_eq!(minutes_since_midnight(DAY), 0.0);
        assert_eq!(minutes_since_midnight(-60), 1439.0);
    }
}

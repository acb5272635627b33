//! Calendar arithmetic (proleptic Gregorian, no time zones) and
//! DATEANDTIMENOW.

use crate::Env;

/// Seconds in a day.
pub const DAY: i64 = 86_400;

/// Days between 0000-03-01 and 1970-01-01.
const EPOCH_SHIFT: i64 = 719_468;

/// Whether `y` is a Gregorian leap year.
pub fn is_leap(y: i64) -> bool {
    (y % 4 == 0 && y % 100 != 0) || y % 400 == 0
}

/// Days in month `m` (1–12) of year `y`; 0 for a month outside 1–12.
pub fn days_in_month(y: i64, m: u32) -> u32 {
    match m {
        1 | 3 | 5 | 7 | 8 | 10 | 12 => 31,
        4 | 6 | 9 | 11 => 30,
        2 if is_leap(y) => 29,
        2 => 28,
        _ => 0,
    }
}

/// Whether `d/m/y` is a real date with year 0000–9999.
pub fn valid_date(y: i64, m: u32, d: u32) -> bool {
    (0..=9999).contains(&y) && d >= 1 && d <= days_in_month(y, m)
}

/// Days since 1970-01-01 of the date `y-m-d` (the date must be valid).
pub fn days_from_civil(y: i64, m: u32, d: u32) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let m = i64::from(m);
    let mp = if m > 2 { m - 3 } else { m + 9 };
    let doy = (153 * mp + 2) / 5 + i64::from(d) - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - EPOCH_SHIFT
}

/// The date `(year, month, day)` that is `z` days after 1970-01-01.
///
/// `z` is clamped to ±10^12 days so the arithmetic cannot overflow.
pub fn civil_from_days(z: i64) -> (i64, u32, u32) {
    let z = z.clamp(-1_000_000_000_000, 1_000_000_000_000) + EPOCH_SHIFT;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    // 1 <= d <= 31 and 1 <= m <= 12 by construction.
    (y, m as u32, d as u32)
}

/// `dd/mm/yyyy hh:mm:ss` for `secs` seconds since 1970-01-01 00:00:00, or
/// the null sequence when the year is outside 0000–9999.
pub fn date_time_text(secs: i64) -> Vec<u8> {
    // 0000-01-01 00:00:00 and 9999-12-31 23:59:59.
    const FIRST: i64 = -62_167_219_200;
    const LAST: i64 = 253_402_300_799;
    if !(FIRST..=LAST).contains(&secs) {
        return Vec::new();
    }
    let (y, m, d) = civil_from_days(secs.div_euclid(DAY));
    let t = secs.rem_euclid(DAY);
    format!("{d:02}/{m:02}/{y:04} {:02}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60).into_bytes()
}

/// DATEANDTIMENOW([mode]): the current date and time as
/// `dd/mm/yyyy hh:mm:ss` (19 bytes).
///
/// Mode 0 (or no argument) is local time, mode 1 system time. The guide
/// defines no other mode: any other value gives the null sequence, and so
/// does a clock outside the years 0000–9999.
pub fn dateandtimenow(mode: Option<i32>, env: &mut dyn Env) -> Vec<u8> {
    match mode.unwrap_or(0) {
        0 => date_time_text(env.local_time()),
        1 => date_time_text(env.system_time()),
        _ => Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Clock;
    impl Env for Clock {
        fn random(&mut self) -> f64 {
            0.5
        }
        fn local_time(&self) -> i64 {
            1_158_968_586 + 3600
        }
        fn system_time(&self) -> i64 {
            1_158_968_586
        }
    }

    #[test]
    fn civil_round_trip() {
        assert_eq!(civil_from_days(0), (1970, 1, 1));
        assert_eq!(days_from_civil(1970, 1, 1), 0);
        assert_eq!(days_from_civil(2000, 3, 1), 11_017);
        assert_eq!(civil_from_days(-1), (1969, 12, 31));
        assert_eq!(civil_from_days(days_from_civil(2024, 2, 29)), (2024, 2, 29));
        for z in (-800_000..800_000).step_by(997) {
            let (y, m, d) = civil_from_days(z);
            assert!(valid_date(y, m, d) || !(0..=9999).contains(&y));
            assert_eq!(days_from_civil(y, m, d), z);
        }
        let _ = civil_from_days(i64::MAX);
        let _ = civil_from_days(i64::MIN);
    }

    #[test]
    fn leap_years_and_months() {
        assert!(is_leap(2000) && is_leap(2024) && !is_leap(1900) && !is_leap(2023));
        assert_eq!(days_in_month(2023, 2), 28);
        assert_eq!(days_in_month(2024, 2), 29);
        assert_eq!(days_in_month(2024, 13), 0);
        assert!(!valid_date(2023, 2, 29) && valid_date(2024, 2, 29));
        assert!(!valid_date(2024, 0, 1) && !valid_date(2024, 1, 0));
    }

    #[test]
    fn date_and_time_now() {
        // 2006-09-22 23:43:06 UTC.
        assert_eq!(dateandtimenow(Some(1), &mut Clock), b"22/09/2006 23:43:06");
        assert_eq!(dateandtimenow(Some(0), &mut Clock), b"23/09/2006 00:43:06");
        assert_eq!(dateandtimenow(None, &mut Clock), b"23/09/2006 00:43:06");
        assert_eq!(dateandtimenow(Some(2), &mut Clock), b"");
        assert_eq!(dateandtimenow(Some(-1), &mut Clock), b"");
        assert_eq!(date_time_text(0), b"01/01/1970 00:00:00");
        assert_eq!(date_time_text(-1), b"31/12/1969 23:59:59");
        assert_eq!(date_time_text(253_402_300_799), b"31/12/9999 23:59:59");
        assert_eq!(date_time_text(253_402_300_800), b"");
        assert_eq!(date_time_text(-62_167_219_200), b"01/01/0000 00:00:00");
        assert_eq!(date_time_text(i64::MIN), b"");
        assert_eq!(date_time_text(i64::MAX), b"");
    }
}

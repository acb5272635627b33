//! Values as text: how `linc eval`, `--show` and `--trace` print them, and
//! how byte sequences are written into JSON.

use linc_stdlib::Value;
use std::fmt::Write;

/// Prints a REAL in the shortest form that reads back to the same 32-bit
/// float, always with a decimal point (`3.5`, `1024.0`).
pub fn format_real(r: f32) -> String {
    let mut s = format!("{r}");
    if !s.contains(['.', 'e', 'E', 'n', 'N', 'i']) {
        s.push_str(".0");
    }
    s
}

/// Prints a value the way `linc eval` does: integers in decimal, REALs by
/// [`format_real`], `TRUE`/`FALSE`, strings in single quotes with
/// `$`-escapes for `'`, `$` and non-printable bytes.
pub fn format_value(v: &Value) -> String {
    match v {
        Value::Int(i) => i.to_string(),
        Value::Real(r) => format_real(*r),
        Value::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
        Value::Bytes(b) => format!("'{}'", escape(b, true)),
    }
}

/// `$`-escapes bytes so that the text decodes back to them (JSON values of
/// BSEQ and WSTR fields use this).
pub fn encode_dollar(b: &[u8]) -> String {
    escape(b, false)
}

fn escape(b: &[u8], quote: bool) -> String {
    let mut s = String::with_capacity(b.len() + 2);
    for &c in b {
        match c {
            b'$' => s.push_str("$$"),
            b'\'' if quote => s.push_str("$'"),
            0x20..=0x7E => s.push(c as char),
            _ => {
                let _ = write!(s, "${c:02X}");
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use linc_stdlib::value::decode_dollar;

    #[test]
    fn reals_print_shortest_with_a_point() {
        assert_eq!(format_real(3.5), "3.5");
        assert_eq!(format_real(1024.0), "1024.0");
        assert_eq!(format_real(0.1), "0.1");
        assert_eq!(format_real(-0.0033), "-0.0033");
        for x in [0.1f32, 1.0 / 3.0, 123456.79, 1e-7, 3.4e38] {
            assert_eq!(format_real(x).parse::<f32>().ok(), Some(x));
        }
    }

    #[test]
    fn strings_escape_and_round_trip() {
        assert_eq!(format_value(&Value::Bytes(b"it's $5\r\n".to_vec())), "'it$'s $$5$0D$0A'");
        let all: Vec<u8> = (0..=255).collect();
        assert_eq!(decode_dollar(encode_dollar(&all).as_bytes()), all);
    }
}

/// Parses `YYYY-MM-DDTHH:MM:SS` (a space may replace the `T`) into POSIX
/// seconds. Only a real date and time is accepted: exactly four digits of
/// year and two of everything else, a day that exists in that month (29
/// February only in leap years), hours 00 to 23, no leap second. Anything
/// else is `None`, so a mistyped `--now` is refused rather than rolled over
/// into another day.
pub fn parse_timestamp(s: &str) -> Option<i64> {
    let b = s.as_bytes();
    if b.len() != 19 || b[4] != b'-' || b[7] != b'-' || !matches!(b[10], b'T' | b' ') || b[13] != b':' || b[16] != b':'
    {
        return None;
    }
    let num = |from: usize, to: usize| -> Option<i64> {
        let digits = b.get(from..to)?;
        digits.iter().all(u8::is_ascii_digit).then(|| digits.iter().fold(0, |n, d| n * 10 + i64::from(d - b'0')))
    };
    let (y, mo, da) = (num(0, 4)?, num(5, 7)?, num(8, 10)?);
    let (h, mi, se) = (num(11, 13)?, num(14, 16)?, num(17, 19)?);
    // The one calendar of the library (leap years, month lengths, days).
    use linc_stdlib::functions::datetime::{days_from_civil, valid_date};
    let (mo, da) = (u32::try_from(mo).ok()?, u32::try_from(da).ok()?);
    let valid = valid_date(y, mo, da) && h < 24 && mi < 60 && se < 60;
    valid.then(|| days_from_civil(y, mo, da) * 86_400 + h * 3600 + mi * 60 + se)
}

#[cfg(test)]
mod time_tests {
    use super::*;

    #[test]
    fn timestamps() {
        assert_eq!(parse_timestamp("1970-01-01T00:00:00"), Some(0));
        assert_eq!(parse_timestamp("1970-01-05T00:00:00"), Some(345_600));
        assert_eq!(parse_timestamp("2026-11-23T08:30:15"), Some(1_795_422_615));
        assert_eq!(parse_timestamp("2026-11-23 08:30:15"), Some(1_795_422_615));
        assert_eq!(parse_timestamp("2026-13-01T00:00:00"), None);
        assert_eq!(parse_timestamp("yesterday"), None);
    }

    #[test]
    fn only_real_dates_and_times() {
        assert_eq!(parse_timestamp("2024-02-29T00:00:00"), Some(1_709_164_800));
        assert_eq!(parse_timestamp("2000-02-29T00:00:00"), Some(951_782_400));
        assert_eq!(parse_timestamp("2023-12-31T23:59:59"), Some(1_704_067_199));
        for bad in [
            "2023-02-29T00:00:00", // not a leap year
            "1900-02-29T00:00:00", // a century that is not a leap year
            "2024-02-30T00:00:00",
            "2024-04-31T00:00:00",
            "2024-00-10T00:00:00",
            "2024-01-00T00:00:00",
            "2024-01-01T24:00:00",
            "2024-01-01T00:60:00",
            "2024-01-01T00:00:60",
            "2024-1-01T00:00:00",
            "2024-01-01T0:00:00",
            "+024-01-01T00:00:00",
            "2024-01-01T00:00:0 ",
            "2024-01-01T00:00:00Z",
            "2024-01-01X00:00:00",
            "2024-01-01T00:00:+0",
            "2024-01-01T-1:00:00",
            "",
        ] {
            assert_eq!(parse_timestamp(bad), None, "{bad}");
        }
    }
}

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

/// Days since 1970-01-01 of a proleptic Gregorian date.
pub fn days_from_civil(y: i64, m: i64, d: i64) -> i64 {
    let y = if m <= 2 { y - 1 } else { y };
    let era = y.div_euclid(400);
    let yoe = y - era * 400;
    let mp = (m + 9) % 12;
    let doy = (153 * mp + 2) / 5 + d - 1;
    let doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
    era * 146_097 + doe - 719_468
}

/// Parses `YYYY-MM-DDTHH:MM:SS` into POSIX seconds.
pub fn parse_timestamp(s: &str) -> Option<i64> {
    let (date, time) = s.split_once(['T', ' '])?;
    let mut d = date.split('-').map(|p| p.parse::<i64>().ok());
    let (y, mo, da) = (d.next()??, d.next()??, d.next()??);
    let mut t = time.split(':').map(|p| p.parse::<i64>().ok());
    let (h, mi, se) = (t.next()??, t.next()??, t.next()??);
    if d.next().is_some() || t.next().is_some() {
        return None;
    }
    let valid = (1..=12).contains(&mo)
        && (1..=31).contains(&da)
        && (0..24).contains(&h)
        && (0..60).contains(&mi)
        && (0..60).contains(&se);
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
        assert_eq!(parse_timestamp("2026-13-01T00:00:00"), None);
        assert_eq!(parse_timestamp("yesterday"), None);
    }
}

//! SCAN(format, bytes) and IS_VALID(format, bytes) (§12.6.3).
//!
//! A width truncates the input first (a shorter input is scanned whole, so
//! SCAN("6I", b) = SCAN("I", LEFT(b, 6)) whenever `b` has 6 bytes or more).
//! Leading spaces (byte 16#20 only) are skipped except for `C`. Invalid
//! characters at the start give 0 (IS_VALID FALSE); later ones end the
//! conversion and are ignored, so IS_VALID("I", '12AB') is TRUE, as SCAN
//! gives 12.
//!
//! Decisions where the guide is silent:
//!
//! * `I` takes an optional `+` or `-`; `U`, `x`, `X`, `B`, `O` take no sign.
//!   Hexadecimal digits are accepted in either case by both `x` and `X`.
//! * Too many digits saturate: `I` at the 32-bit signed limits, `U`, `x`,
//!   `X`, `B` and `O` at 16#FFFFFFFF. Unsigned results above 2,147,483,647
//!   come back as the same 32-bit pattern (negative INT), so FORMAT then
//!   SCAN gives back every INT.
//! * `F` and `G` need a digit before or after the point (`.5` and `5.` are
//!   valid, `-.` is not). A number beyond the REAL range is not valid (0.0,
//!   FALSE).
//! * `e` and `E` are for FORMAT only: SCAN gives 0, IS_VALID FALSE. A
//!   precision on `F` or `G` is ignored.
//! * `T`/`TP` read `h[h]<sep>m[m]<sep>s[s]` with hours 0–23 and minutes and
//!   seconds 0–59; `D` reads `d[d]/m[m]/yyyy` and `DP` reads `d[d]/m[m]/yy`,
//!   both a real date. Anything incomplete or out of range is invalid. `DP`
//!   maps a two-digit year as POSIX `strptime` does: 69–99 are 1969–1999,
//!   00–68 are 2000–2068; a date whose seconds do not fit a 32-bit INT (after
//!   2038-01-19) is invalid.
//! * SCAN's result kind is the one the checker gives it: REAL when the format
//!   contains `F`, `f`, `G` or `g` anywhere, else INT (an invalid format
//!   or input gives 0 or 0.0 of that kind).

use super::datetime::{days_from_civil, valid_date, DAY};
use super::spec::{parse, Conv};
use crate::Value;

/// A scanned number.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Scanned {
    Int(i32),
    Real(f32),
}

/// Scans `input` as `fmt` says; `None` if the format or the input is not
/// valid.
pub fn scan(fmt: &[u8], input: &[u8]) -> Option<Scanned> {
    let spec = parse(fmt)?;
    let input = match spec.width {
        Some(w) => input.get(..w).unwrap_or(input),
        None => input,
    };
    if spec.conv == Conv::Char {
        return input.first().map(|b| Scanned::Int(i32::from(*b)));
    }
    let skip = input.iter().take_while(|&&c| c == b' ').count();
    let s = input.get(skip..).unwrap_or(&[]);
    let int = |v: u32| Scanned::Int(v as i32);
    Some(match spec.conv {
        Conv::Int => Scanned::Int(signed(s)?),
        Conv::Unsigned => int(unsigned(s, 10)?),
        Conv::HexLower | Conv::HexUpper => int(unsigned(s, 16)?),
        Conv::Binary => int(unsigned(s, 2)?),
        Conv::Octal => int(unsigned(s, 8)?),
        Conv::Fixed => Scanned::Real(real(s, false)?),
        Conv::General => Scanned::Real(real(s, true)?),
        Conv::ExpLower | Conv::ExpUpper | Conv::Char => return None,
        Conv::IsoTime => {
            let (h, m, sec) = time(s, spec.sep)?;
            Scanned::Int((h * 10_000 + m * 100 + sec) as i32)
        }
        Conv::PosixTime => {
            let (h, m, sec) = time(s, spec.sep)?;
            Scanned::Int((h * 3600 + m * 60 + sec) as i32)
        }
        Conv::IsoDate => {
            let (d, m, y) = date(s, 4)?;
            valid_date(y, m, d).then_some(())?;
            let y = i32::try_from(y).ok()?;
            Scanned::Int(y * 10_000 + m as i32 * 100 + d as i32)
        }
        Conv::PosixDate => {
            let (d, m, yy) = date(s, 2)?;
            let y = if yy >= 69 { 1900 + yy } else { 2000 + yy };
            valid_date(y, m, d).then_some(())?;
            let secs = days_from_civil(y, m, d) * DAY;
            Scanned::Int(i32::try_from(secs).ok()?)
        }
    })
}

/// SCAN: the scanned value, of the kind the checker gave the call.
pub fn scan_value(fmt: &[u8], input: &[u8]) -> Value {
    let real_kind = fmt.iter().any(|c| matches!(c, b'F' | b'f' | b'G' | b'g'));
    match (scan(fmt, input), real_kind) {
        (Some(Scanned::Real(r)), true) => Value::Real(r),
        (Some(Scanned::Int(i)), true) => Value::Real(i as f32),
        (Some(Scanned::Int(i)), false) => Value::Int(i),
        // A real conversion always contains F or G; kept total anyway.
        (Some(Scanned::Real(r)), false) => Value::Int(crate::value::round_to_i32(r)),
        (None, true) => Value::Real(0.0),
        (None, false) => Value::Int(0),
    }
}

/// IS_VALID: whether SCAN finds a number.
pub fn is_valid(fmt: &[u8], input: &[u8]) -> bool {
    scan(fmt, input).is_some()
}

/// Reads digits of `radix` from the start of `s`: the saturated value and
/// how many digits there were.
fn digits(s: &[u8], radix: u32) -> (u64, usize) {
    let mut v: u64 = 0;
    let mut n = 0;
    for d in s.iter().map_while(|&c| char::from(c).to_digit(radix)) {
        v = v.saturating_mul(u64::from(radix)).saturating_add(u64::from(d));
        n += 1;
    }
    (v, n)
}

fn signed(s: &[u8]) -> Option<i32> {
    let (neg, body) = match s.first() {
        Some(b'-') => (true, s.get(1..).unwrap_or(&[])),
        Some(b'+') => (false, s.get(1..).unwrap_or(&[])),
        _ => (false, s),
    };
    let (v, n) = digits(body, 10);
    if n == 0 {
        return None;
    }
    let v = i64::try_from(v).unwrap_or(i64::MAX);
    let v = if neg { -v.min(1 << 31) } else { v };
    Some(v.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32)
}

fn unsigned(s: &[u8], radix: u32) -> Option<u32> {
    let (v, n) = digits(s, radix);
    (n > 0).then(|| u32::try_from(v).unwrap_or(u32::MAX))
}

/// The longest prefix of `s` that is a real number (with an exponent only
/// when `exponent`), parsed as REAL.
fn real(s: &[u8], exponent: bool) -> Option<f32> {
    let mut i = usize::from(matches!(s.first(), Some(b'-' | b'+')));
    let int_digits = s.get(i..).map_or(0, |t| digits(t, 10).1);
    i += int_digits;
    let mut frac_digits = 0;
    if s.get(i) == Some(&b'.') {
        frac_digits = s.get(i + 1..).map_or(0, |t| digits(t, 10).1);
        i += 1 + frac_digits;
    }
    if int_digits + frac_digits == 0 {
        return None;
    }
    if exponent && matches!(s.get(i), Some(b'e' | b'E')) {
        let sign = usize::from(matches!(s.get(i + 1), Some(b'-' | b'+')));
        let exp_digits = s.get(i + 1 + sign..).map_or(0, |t| digits(t, 10).1);
        if exp_digits > 0 {
            i += 1 + sign + exp_digits;
        }
    }
    let text = std::str::from_utf8(s.get(..i)?).ok()?;
    let mut normal = text.to_string();
    if frac_digits == 0 && normal.contains('.') {
        // "5." and "5.e3": Rust wants a digit after the point.
        normal = normal.replacen('.', ".0", 1);
    }
    if int_digits == 0 {
        // ".5" and "-.5".
        normal = normal.replacen('.', "0.", 1);
    }
    let x: f32 = normal.parse().ok()?;
    x.is_finite().then_some(x)
}

/// Reads one 1- to `max`-digit field of at least `min` digits at `*i`.
fn field(s: &[u8], i: &mut usize, min: usize, max: usize) -> Option<i64> {
    let t = s.get(*i..).unwrap_or(&[]);
    let t = t.get(..max).unwrap_or(t);
    let (v, n) = digits(t, 10);
    *i += n;
    (n >= min).then(|| i64::try_from(v).unwrap_or(i64::MAX))
}

fn expect(s: &[u8], i: &mut usize, c: u8) -> Option<()> {
    (s.get(*i) == Some(&c)).then(|| *i += 1)
}

/// `h[h]<sep>m[m]<sep>s[s]` as (hours, minutes, seconds).
fn time(s: &[u8], sep: u8) -> Option<(i64, i64, i64)> {
    let mut i = 0;
    let h = field(s, &mut i, 1, 2)?;
    expect(s, &mut i, sep)?;
    let m = field(s, &mut i, 1, 2)?;
    expect(s, &mut i, sep)?;
    let sec = field(s, &mut i, 1, 2)?;
    (h <= 23 && m <= 59 && sec <= 59).then_some((h, m, sec))
}

/// `d[d]/m[m]/y..y` with exactly `year_digits` year digits, as
/// (day, month, year as written); the caller checks the date.
fn date(s: &[u8], year_digits: usize) -> Option<(u32, u32, i64)> {
    let mut i = 0;
    let d = field(s, &mut i, 1, 2)?;
    expect(s, &mut i, b'/')?;
    let m = field(s, &mut i, 1, 2)?;
    expect(s, &mut i, b'/')?;
    let y = field(s, &mut i, year_digits, year_digits)?;
    Some((u32::try_from(d).ok()?, u32::try_from(m).ok()?, y))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(f: &str, input: &str) -> Option<Scanned> {
        scan(f.as_bytes(), input.as_bytes())
    }

    #[test]
    fn integers() {
        assert_eq!(s("I", "+12"), Some(Scanned::Int(12)));
        assert_eq!(s("I", "-"), None);
        assert_eq!(s("I", ""), None);
        assert_eq!(s("I", "   "), None);
        assert_eq!(s("I", "12AB"), Some(Scanned::Int(12)));
        assert_eq!(s("I", "99999999999999999999999"), Some(Scanned::Int(i32::MAX)));
        assert_eq!(s("I", "-2147483648"), Some(Scanned::Int(i32::MIN)));
        assert_eq!(s("I", "-99999999999"), Some(Scanned::Int(i32::MIN)));
        assert_eq!(s("U", "4294967295"), Some(Scanned::Int(-1)));
        assert_eq!(s("U", "+1"), None);
        assert_eq!(s("X", "ff"), Some(Scanned::Int(255)));
        assert_eq!(s("x", "FFFFFFFFFF"), Some(Scanned::Int(-1)));
        assert_eq!(s("B", "102"), Some(Scanned::Int(2)));
        assert_eq!(s("O", "8"), None);
        assert_eq!(s("2000000000000000000000000I", "5"), Some(Scanned::Int(5)));
        assert_eq!(s("E", "1"), None);
        assert_eq!(s("5.2I", "1"), None);
    }

    #[test]
    fn chars_keep_spaces() {
        assert_eq!(s("C", " B"), Some(Scanned::Int(32)));
        assert_eq!(s("C", "\u{7f}"), Some(Scanned::Int(127)));
        assert_eq!(scan(b"C", b"\xF4"), Some(Scanned::Int(244)));
        assert_eq!(s("C", ""), None);
    }

    #[test]
    fn reals() {
        assert_eq!(s("F", "5."), Some(Scanned::Real(5.0)));
        assert_eq!(s("F", ".5"), Some(Scanned::Real(0.5)));
        assert_eq!(s("F", "-.5x"), Some(Scanned::Real(-0.5)));
        assert_eq!(s("F", "-."), None);
        assert_eq!(s("F", "."), None);
        assert_eq!(s("G", "1e5"), Some(Scanned::Real(1e5)));
        assert_eq!(s("G", "5.e1"), Some(Scanned::Real(50.0)));
        assert_eq!(s("G", "2E"), Some(Scanned::Real(2.0)));
        assert_eq!(s("G", "2E+"), Some(Scanned::Real(2.0)));
        assert_eq!(s("G", "1e99"), None);
        assert_eq!(s("G", "1e-99"), Some(Scanned::Real(0.0)));
        assert_eq!(s("F", &"9".repeat(50)), None);
        assert_eq!(s("6.2F", "1.25"), Some(Scanned::Real(1.25)));
    }

    #[test]
    fn times_and_dates() {
        assert_eq!(s("T", "1:2:3"), Some(Scanned::Int(10203)));
        assert_eq!(s("T", "24:00:00"), None);
        assert_eq!(s("T", "12:60:00"), None);
        assert_eq!(s("T", "12:30"), None);
        assert_eq!(s("T", "12.30.00"), None);
        assert_eq!(s("T.", "12.30.00"), Some(Scanned::Int(123000)));
        assert_eq!(s("TP", "23:59:59"), Some(Scanned::Int(86399)));
        assert_eq!(s("D", "29/02/2024"), Some(Scanned::Int(20240229)));
        assert_eq!(s("D", "29/02/2023"), None);
        assert_eq!(s("D", "1/2/0003"), Some(Scanned::Int(30201)));
        assert_eq!(s("D", "01/02/03"), None);
        assert_eq!(s("DP", "01/01/70"), Some(Scanned::Int(0)));
        assert_eq!(s("DP", "31/12/69"), Some(Scanned::Int(-86400)));
        assert_eq!(s("DP", "19/01/38"), Some(Scanned::Int(2_147_472_000)));
        assert_eq!(s("DP", "20/01/38"), None);
        assert_eq!(s("DP", "29/02/00"), Some(Scanned::Int(951_782_400)));
        assert_eq!(s("DP", "29/02/01"), None);
    }

    #[test]
    fn result_kind_follows_the_format_text() {
        assert_eq!(scan_value(b"I", b"5"), Value::Int(5));
        assert_eq!(scan_value(b"If", b"5"), Value::Real(5.0));
        assert_eq!(scan_value(b"F", b"x"), Value::Real(0.0));
        assert_eq!(scan_value(b"Q", b"5"), Value::Int(0));
        assert!(!is_valid(b"Q", b"5"));
    }
}

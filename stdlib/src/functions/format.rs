//! FORMAT(format, value) (§12.6.3).
//!
//! Decisions where the guide is silent:
//!
//! * Integer conversions (`I U x X B O C T TP D DP`) take a REAL value the
//!   way a REAL is stored into an INT (rounded, halves away from zero). A
//!   REAL that is NaN, infinite or outside the 32-bit range cannot be
//!   converted: the result is the null sequence.
//! * `U`, `x`, `X`, `B` and `O` write the 32-bit two's-complement pattern
//!   read as unsigned: FORMAT("5U", 16#FFFF) = '65535' and
//!   FORMAT("U", -1) = '4294967295', FORMAT("X", -1) = 'FFFFFFFF'.
//! * `F`, `e` and `E` default to precision 0 (the guide's FORMAT("F", v) =
//!   '333'); `.` without digits keeps the decimal point ('333.', '3.E+02').
//!   Without a `.` the width still counts one column for the decimal
//!   point, which is then left out: the guide's FORMAT("6F", 1000/3) is
//!   '  333' (five bytes), FORMAT("6.F", ...) '  333.'. So "3F" cannot show
//!   333 ('333.' needs four columns) and gives '***'. `e` and `E` "behave
//!   like `F`" and do the same: FORMAT("10E", 1000/3) = '    3E+02'.
//!   Ties are rounded on the exact binary value, half to even, as C's printf
//!   does. NaN and infinities give the null sequence.
//! * `G` is for SCAN only: FORMAT with `G` gives the null sequence.
//! * `C` needs a value 0–255, else the null sequence.
//! * `T` needs a valid time HHMMSS (hours 0–23, minutes and seconds 0–59)
//!   and `D` a valid date YYYYMMDD (year 0000–9999, a real day of the
//!   month), else the null sequence. `TP` takes the seconds modulo 86,400
//!   (Euclidean, so -1 is 23:59:59); `DP` shows the year modulo 100 and
//!   takes negative seconds as dates before 1970.
//! * Zero padding goes after a leading `-`; for non-numeric output (`C`,
//!   `T`, `D`, ...) the zeros simply go on the left.
//! * A width above 1020 is clipped to 1020; with no width, a text longer
//!   than 1020 bytes (a huge precision) gives the null sequence.

use super::datetime::{civil_from_days, valid_date, DAY};
use super::spec::{parse, Conv, Spec};
use super::MAX_LEN;
use crate::value::round_to_i32;
use crate::Value;

/// FORMAT: `value` converted as `fmt` says, or the null sequence.
pub fn format(fmt: &[u8], value: &Value) -> Vec<u8> {
    let mut out = Vec::new();
    format_into(fmt, value, &mut out);
    out
}

/// [`format`] written into `out` (emptied first), so that a caller that
/// keeps a buffer formats without allocating.
pub fn format_into(fmt: &[u8], value: &Value, out: &mut Vec<u8>) {
    out.clear();
    let Some(mut spec) = parse(fmt) else {
        return;
    };
    // A real format without a decimal point still counts a column for the
    // point: the text is laid out as with `W.` and the point then removed
    // (the guide's FORMAT("6F", 1000/3) = '  333').
    let drop_point = spec.conv.is_real() && !spec.point;
    spec.point |= drop_point;
    if render(&spec, value, out).is_none() {
        out.clear();
        return;
    }
    if fit(&spec, out) && drop_point {
        if let Some(at) = out.iter().position(|&c| c == b'.') {
            out.remove(at);
        }
    }
}

/// Pads the text in `out` to the width, or fills the width with the
/// override character when it does not fit (false).
fn fit(spec: &Spec, out: &mut Vec<u8>) -> bool {
    let Some(width) = spec.width.map(|w| w.min(MAX_LEN)) else {
        if out.len() > MAX_LEN {
            out.clear();
        }
        return true;
    };
    if out.len() > width {
        out.clear();
        out.resize(width, spec.fill);
        return false;
    }
    let pad = width - out.len();
    let (at, with) = if spec.zero { (usize::from(out.first() == Some(&b'-')), b'0') } else { (0, b' ') };
    let end = out.len();
    out.resize(width, with);
    out.copy_within(at..end, at + pad);
    out[at..at + pad].fill(with);
    true
}

/// Writes `v` in decimal (the hot case of FORMAT, kept off the general
/// formatting machinery).
fn decimal(v: i64, out: &mut Vec<u8>) {
    if v < 0 {
        out.push(b'-');
    }
    let mut digits = [0u8; 20];
    let mut n = v.unsigned_abs();
    let mut i = digits.len();
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&digits[i..]);
}

/// The value as an integer for the integer conversions.
fn integer(v: &Value) -> Option<i32> {
    match v {
        Value::Real(r) => {
            let x = f64::from(*r).round();
            let fits = x >= f64::from(i32::MIN) && x <= f64::from(i32::MAX);
            fits.then(|| round_to_i32(*r))
        }
        other => Some(other.as_int()),
    }
}

/// The value as a finite real for the real conversions.
fn real(v: &Value) -> Option<f64> {
    let x = match v {
        Value::Int(i) => f64::from(*i),
        other => f64::from(other.as_real()),
    };
    x.is_finite().then_some(x)
}

/// Writes the text of the value before padding into `out`, or gives
/// `None` if it cannot be converted.
fn render(spec: &Spec, v: &Value, out: &mut Vec<u8>) -> Option<()> {
    use std::io::Write;
    let written = match spec.conv {
        Conv::Int => {
            decimal(i64::from(integer(v)?), out);
            Ok(())
        }
        Conv::Unsigned => {
            decimal(i64::from(integer(v)? as u32), out);
            Ok(())
        }
        Conv::HexLower => write!(out, "{:x}", integer(v)? as u32),
        Conv::HexUpper => write!(out, "{:X}", integer(v)? as u32),
        Conv::Binary => write!(out, "{:b}", integer(v)? as u32),
        Conv::Octal => write!(out, "{:o}", integer(v)? as u32),
        Conv::Fixed => {
            write!(out, "{:.*}", spec.precision.min(MAX_LEN), real(v)?).ok()?;
            if spec.point && spec.precision == 0 {
                out.push(b'.');
            }
            Ok(())
        }
        Conv::ExpLower => return scientific(real(v)?, spec, b'e', out),
        Conv::ExpUpper => return scientific(real(v)?, spec, b'E', out),
        Conv::General => return None,
        Conv::Char => {
            out.push(u8::try_from(integer(v)?).ok()?);
            Ok(())
        }
        Conv::IsoTime => {
            let t = integer(v)?;
            let (h, m, s) = (t / 10_000, t / 100 % 100, t % 100);
            if t < 0 || h > 23 || m > 59 || s > 59 {
                return None;
            }
            clock(i64::from(h), i64::from(m), i64::from(s), spec.sep, out)
        }
        Conv::PosixTime => {
            let t = i64::from(integer(v)?).rem_euclid(DAY);
            clock(t / 3600, t / 60 % 60, t % 60, spec.sep, out)
        }
        Conv::IsoDate => {
            let t = integer(v)?;
            let (y, m, d) = (t / 10_000, t / 100 % 100, t % 100);
            let (m, d) = (u32::try_from(m).ok()?, u32::try_from(d).ok()?);
            if t < 0 || !valid_date(i64::from(y), m, d) {
                return None;
            }
            write!(out, "{d:02}/{m:02}/{y:04}")
        }
        Conv::PosixDate => {
            let days = i64::from(integer(v)?).div_euclid(DAY);
            let (y, m, d) = civil_from_days(days);
            write!(out, "{d:02}/{m:02}/{:02}", y.rem_euclid(100))
        }
    };
    written.ok()
}

/// `hh<sep>mm<sep>ss`; the separator may be any byte.
fn clock(h: i64, m: i64, s: i64, sep: u8, out: &mut Vec<u8>) -> std::io::Result<()> {
    use std::io::Write;
    write!(out, "{h:02}")?;
    out.push(sep);
    write!(out, "{m:02}")?;
    out.push(sep);
    write!(out, "{s:02}")
}

/// Scientific notation with a signed exponent of at least two digits.
fn scientific(x: f64, spec: &Spec, letter: u8, out: &mut Vec<u8>) -> Option<()> {
    use std::io::Write;
    let raw = std::format!("{:.*e}", spec.precision.min(MAX_LEN), x);
    let (mantissa, exp) = raw.split_once('e')?;
    let exp: i32 = exp.parse().ok()?;
    out.extend_from_slice(mantissa.as_bytes());
    if spec.point && spec.precision == 0 {
        out.push(b'.');
    }
    out.push(letter);
    out.push(if exp < 0 { b'-' } else { b'+' });
    write!(out, "{:02}", exp.unsigned_abs()).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn f(fmt: &str, v: Value) -> String {
        String::from_utf8_lossy(&format(fmt.as_bytes(), &v)).into_owned()
    }

    #[test]
    fn padding_and_overrides() {
        assert_eq!(f("5I", Value::Int(7412)), " 7412");
        assert_eq!(f("05I", Value::Int(-123)), "-0123");
        assert_eq!(f("3I!", Value::Int(7412)), "!!!");
        assert_eq!(f("3I", Value::Int(7412)), "***");
        assert_eq!(f("I", Value::Int(i32::MIN)), "-2147483648");
        assert_eq!(f("012I", Value::Int(i32::MIN)), "-02147483648");
        assert_eq!(f("2000I", Value::Int(1)).len(), MAX_LEN);
        assert_eq!(f("3C", Value::Int(65)), "  A");
        assert_eq!(f("03C", Value::Int(65)), "00A");
    }

    #[test]
    fn decimals_at_the_edges() {
        for v in [0, 7, -7, 10, -10, 99, 100, i32::MAX, i32::MIN, i32::MIN + 1] {
            assert_eq!(f("I", Value::Int(v)), v.to_string());
            assert_eq!(f("U", Value::Int(v)), (v as u32).to_string());
            assert_eq!(f("012I", Value::Int(v)), std::format!("{v:012}"));
            assert_eq!(f("12I", Value::Int(v)), std::format!("{v:>12}"));
        }
    }

    #[test]
    fn reals_and_integers_cross() {
        assert_eq!(f("I", Value::Real(2.5)), "3");
        assert_eq!(f("I", Value::Real(-2.5)), "-3");
        assert_eq!(f("I", Value::Real(3e9)), "");
        assert_eq!(f("I", Value::Real(f32::NAN)), "");
        assert_eq!(f("F", Value::Int(123_456_789)), "123456789");
        assert_eq!(f("F", Value::Real(f32::INFINITY)), "");
        assert_eq!(f("E", Value::Real(f32::NAN)), "");
        assert_eq!(f("I", Value::Bool(true)), "1");
    }

    #[test]
    fn scientific_exponents() {
        assert_eq!(f("E", Value::Real(0.0)), "0E+00");
        assert_eq!(f(".2e", Value::Real(-0.01456)), "-1.46e-02");
        assert_eq!(f(".E", Value::Real(333.3)), "3.E+02");
        assert_eq!(f(".1E", Value::Real(3e38)), "3.0E+38");
        assert_eq!(f(".1E", Value::Real(1e-40)), "1.0E-40");
        assert_eq!(f("010.2E", Value::Real(-333.3)), "-03.33E+02");
    }

    #[test]
    fn width_without_point_counts_the_point() {
        let v = Value::Real(1000.0 / 3.0);
        assert_eq!(f("6F", v.clone()), "  333");
        assert_eq!(f("4F", v.clone()), "333");
        assert_eq!(f("3F", v.clone()), "***");
        assert_eq!(f("3F.", v.clone()), "...");
        assert_eq!(f("06F", v.clone()), "00333");
        assert_eq!(f("6F", Value::Real(-333.3)), " -333");
        assert_eq!(f("10E", v.clone()), "    3E+02");
        assert_eq!(f("010E", v), "00003E+02");
    }

    #[test]
    fn huge_precision_is_null_or_override() {
        assert_eq!(f(".99999999999999999999F", Value::Real(1.0)), "");
        assert_eq!(f("5.2000F#", Value::Real(1.0)), "#####");
        assert_eq!(f(".1000F", Value::Real(1.0)).len(), 1002);
    }

    #[test]
    fn times_and_dates_validate() {
        assert_eq!(f("T", Value::Int(235959)), "23:59:59");
        assert_eq!(f("T", Value::Int(0)), "00:00:00");
        for bad in [240000, 126000, 123360, -1, i32::MIN, i32::MAX] {
            assert_eq!(f("T", Value::Int(bad)), "", "{bad}");
        }
        assert_eq!(f("TP", Value::Int(-1)), "23:59:59");
        assert_eq!(f("TP", Value::Int(86_400 + 61)), "00:01:01");
        assert_eq!(f("TP", Value::Int(i32::MIN)), "20:45:52");
        assert_eq!(f("D", Value::Int(20240229)), "29/02/2024");
        for bad in [20230229, 20231301, 20230100, 99_991_232, -20060923, 100_000_101] {
            assert_eq!(f("D", Value::Int(bad)), "", "{bad}");
        }
        assert_eq!(f("D", Value::Int(101)), "01/01/0000");
        assert_eq!(f("DP", Value::Int(-1)), "31/12/69");
        assert_eq!(f("DP", Value::Int(i32::MAX)), "19/01/38");
        assert_eq!(f("DP", Value::Int(i32::MIN)), "13/12/01");
        assert_eq!(f("G", Value::Real(1.0)), "");
    }
}

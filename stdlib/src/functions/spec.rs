//! Conversion format strings of FORMAT, SCAN and IS_VALID (§12.6.3).
//!
//! A format is `[0][width][.[precision]]conversion[separator][override]`:
//!
//! * a width starting with `0` pads with zeros instead of spaces (FORMAT);
//!   for SCAN and IS_VALID the width truncates the input;
//! * `.` and a precision are allowed only with the real conversions
//!   `F`, `e`, `E` (and `G`, where SCAN ignores them);
//! * the conversion is one of `I U x X B O F e E G C T TP D DP`. Except for
//!   `x`/`X` and `e`/`E`, whose case chooses the case of the output, the
//!   letters may be written in either case (`tp`, `Dp`, ...); `P` directly
//!   after `T` or `D` always makes the POSIX form;
//! * `T` and `TP` take an optional separator character (default `:`);
//! * one further optional character replaces `*` as the character FORMAT
//!   writes across the whole width when the value does not fit. SCAN and
//!   IS_VALID accept and ignore it.
//!
//! Anything else (spaces, an unknown letter, more trailing characters, a
//! precision on an integer conversion) makes the format invalid.

/// The conversion letter(s) of a format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Conv {
    /// `I`: signed decimal.
    Int,
    /// `U`: unsigned decimal (the 32-bit pattern read as unsigned).
    Unsigned,
    /// `x`: hexadecimal, lower-case digits.
    HexLower,
    /// `X`: hexadecimal, upper-case digits.
    HexUpper,
    /// `B`: binary.
    Binary,
    /// `O`: octal.
    Octal,
    /// `F`: fixed-point real.
    Fixed,
    /// `e`: scientific real, FORMAT only.
    ExpLower,
    /// `E`: scientific real, FORMAT only.
    ExpUpper,
    /// `G`: real with optional exponent, SCAN and IS_VALID only.
    General,
    /// `C`: one byte 0–255.
    Char,
    /// `T`: ISO 8601 time HHMMSS as an integer.
    IsoTime,
    /// `TP`: seconds (modulo one day).
    PosixTime,
    /// `D`: ISO 8601 date YYYYMMDD as an integer.
    IsoDate,
    /// `DP`: POSIX seconds since 1970-01-01, shown as DD/MM/YY.
    PosixDate,
}

impl Conv {
    /// `F`, `e`, `E` or `G`.
    pub fn is_real(self) -> bool {
        matches!(self, Conv::Fixed | Conv::ExpLower | Conv::ExpUpper | Conv::General)
    }

    fn has_separator(self) -> bool {
        matches!(self, Conv::IsoTime | Conv::PosixTime)
    }
}

/// A parsed format string.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Spec {
    /// The width began with `0`: pad with zeros.
    pub zero: bool,
    /// The width, if one was given and is not zero (saturating).
    pub width: Option<usize>,
    /// A `.` was written after the width.
    pub point: bool,
    /// Digits after the decimal point (0 when none were written).
    pub precision: usize,
    pub conv: Conv,
    /// Separator of `T` and `TP` (default `:`).
    pub sep: u8,
    /// What FORMAT writes across the width when a value does not fit.
    pub fill: u8,
}

/// Reads a run of decimal digits at `*i`, saturating; `None` if there are
/// none.
fn number(f: &[u8], i: &mut usize) -> Option<usize> {
    let start = *i;
    let mut n: usize = 0;
    while let Some(d) = f.get(*i).filter(|c| c.is_ascii_digit()) {
        n = n.saturating_mul(10).saturating_add(usize::from(d - b'0'));
        *i += 1;
    }
    (*i > start).then_some(n)
}

/// Parses a format string; `None` if it is not a valid format.
pub fn parse(f: &[u8]) -> Option<Spec> {
    let mut i = 0;
    let zero = f.first() == Some(&b'0');
    let width = number(f, &mut i).filter(|&w| w > 0);
    let point = f.get(i) == Some(&b'.');
    let mut precision = 0;
    if point {
        i += 1;
        precision = number(f, &mut i).unwrap_or(0);
    }
    let letter = *f.get(i)?;
    i += 1;
    let posix = f.get(i).is_some_and(|c| c.eq_ignore_ascii_case(&b'P'));
    let conv = match letter {
        b'x' => Conv::HexLower,
        b'X' => Conv::HexUpper,
        b'e' => Conv::ExpLower,
        b'E' => Conv::ExpUpper,
        _ => match letter.to_ascii_uppercase() {
            b'I' => Conv::Int,
            b'U' => Conv::Unsigned,
            b'B' => Conv::Binary,
            b'O' => Conv::Octal,
            b'F' => Conv::Fixed,
            b'G' => Conv::General,
            b'C' => Conv::Char,
            b'T' if posix => Conv::PosixTime,
            b'T' => Conv::IsoTime,
            b'D' if posix => Conv::PosixDate,
            b'D' => Conv::IsoDate,
            _ => return None,
        },
    };
    if matches!(conv, Conv::PosixTime | Conv::PosixDate) {
        i += 1;
    }
    if point && !conv.is_real() {
        return None;
    }
    let rest = f.get(i..).unwrap_or(&[]);
    let (sep, fill) = if conv.has_separator() {
        match rest {
            [] => (b':', b'*'),
            [s] => (*s, b'*'),
            [s, o] => (*s, *o),
            _ => return None,
        }
    } else {
        match rest {
            [] => (b':', b'*'),
            [o] => (b':', *o),
            _ => return None,
        }
    };
    Some(Spec { zero, width, point, precision, conv, sep, fill })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(f: &str) -> Option<Spec> {
        parse(f.as_bytes())
    }

    #[test]
    fn widths_flags_and_precision() {
        let s = p("05I").expect("05I");
        assert!(s.zero);
        assert_eq!(s.width, Some(5));
        assert_eq!(s.conv, Conv::Int);
        let s = p("6.2F").expect("6.2F");
        assert!(!s.zero && s.point);
        assert_eq!((s.width, s.precision), (Some(6), 2));
        let s = p("6.F").expect("6.F");
        assert!(s.point);
        assert_eq!(s.precision, 0);
        let s = p("0I").expect("0I");
        assert!(s.zero);
        assert_eq!(s.width, None);
        let s = p("99999999999999999999999X").expect("huge width");
        assert_eq!(s.width, Some(usize::MAX));
    }

    #[test]
    fn conversions_separators_and_overrides() {
        assert_eq!(p("3I!").map(|s| (s.conv, s.fill)), Some((Conv::Int, b'!')));
        assert_eq!(p("T.").map(|s| (s.conv, s.sep)), Some((Conv::IsoTime, b'.')));
        assert_eq!(p("TP.#").map(|s| (s.conv, s.sep, s.fill)), Some((Conv::PosixTime, b'.', b'#')));
        assert_eq!(p("DP").map(|s| s.conv), Some(Conv::PosixDate));
        assert_eq!(p("dp").map(|s| s.conv), Some(Conv::PosixDate));
        assert_eq!(p("D-").map(|s| (s.conv, s.fill)), Some((Conv::IsoDate, b'-')));
        assert_eq!(p("x").map(|s| s.conv), Some(Conv::HexLower));
        assert_eq!(p("e").map(|s| s.conv), Some(Conv::ExpLower));
        assert_eq!(p("g").map(|s| s.conv), Some(Conv::General));
    }

    #[test]
    fn invalid_formats() {
        for f in ["", "5", "5.", "Q", "5.2I", ".X", "3I!!", "TP.##", " I", "05"] {
            assert_eq!(p(f), None, "{f:?}");
        }
    }
}

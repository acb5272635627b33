//! Run-time values as the function library sees them.

/// A value passed to or returned by a library function.
///
/// Strings of every kind travel as bytes: the checker has already decided
/// which kind each is, and `$`-sequences are decoded (or not) before a value
/// gets here (§12.9).
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i32),
    Real(f32),
    Bool(bool),
    Bytes(Vec<u8>),
}

impl Value {
    /// The value as an integer: REAL rounds half away from zero (saturating),
    /// BOOL is 0 or 1, a byte sequence is 0.
    pub fn as_int(&self) -> i32 {
        match self {
            Value::Int(i) => *i,
            Value::Real(r) => round_to_i32(*r),
            Value::Bool(b) => i32::from(*b),
            Value::Bytes(_) => 0,
        }
    }

    /// The value as a REAL.
    pub fn as_real(&self) -> f32 {
        match self {
            Value::Int(i) => *i as f32,
            Value::Real(r) => *r,
            Value::Bool(b) => f32::from(u8::from(*b)),
            Value::Bytes(_) => 0.0,
        }
    }

    pub fn as_bool(&self) -> bool {
        match self {
            Value::Int(i) => *i != 0,
            Value::Real(r) => *r != 0.0,
            Value::Bool(b) => *b,
            Value::Bytes(b) => !b.is_empty(),
        }
    }

    pub fn as_bytes(&self) -> &[u8] {
        match self {
            Value::Bytes(b) => b,
            _ => &[],
        }
    }
}

/// Rounds to the nearest integer, halves away from zero, saturating at the
/// 32-bit limits (NaN gives 0). This is how a REAL is stored into an INT.
pub fn round_to_i32(r: f32) -> i32 {
    if r.is_nan() {
        return 0;
    }
    let x = f64::from(r).round();
    x.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32
}

/// Decodes `$`-sequences (§12.9): `$nn` hex byte, `$$`, `$'`, `$"`, `$L`,
/// `$N` (CR LF), `$P`, `$R`, `$T`, in either case. An unknown or incomplete
/// sequence is kept as written.
pub fn decode_dollar(raw: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity(raw.len());
    let mut i = 0;
    while i < raw.len() {
        let c = raw[i];
        if c != b'$' || i + 1 >= raw.len() {
            out.push(c);
            i += 1;
            continue;
        }
        let n = raw[i + 1];
        let simple = match n.to_ascii_uppercase() {
            b'$' => Some(&b"$"[..]),
            b'\'' => Some(&b"'"[..]),
            b'"' => Some(&b"\""[..]),
            b'L' => Some(&b"\n"[..]),
            b'N' => Some(&b"\r\n"[..]),
            b'P' => Some(&b"\x0c"[..]),
            b'R' => Some(&b"\r"[..]),
            b'T' => Some(&b"\t"[..]),
            _ => None,
        };
        if let Some(s) = simple {
            out.extend_from_slice(s);
            i += 2;
            continue;
        }
        let hex = |b: u8| (b as char).to_digit(16);
        match (hex(n), raw.get(i + 2).and_then(|b| hex(*b))) {
            (Some(h), Some(l)) => {
                out.push((h * 16 + l) as u8);
                i += 3;
            }
            _ => {
                out.push(c);
                i += 1;
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dollar_sequences() {
        assert_eq!(decode_dollar(b"a$62c"), b"abc");
        assert_eq!(decode_dollar(b"r$F4le"), b"r\xF4le");
        assert_eq!(decode_dollar(b"$$$'$L$l$N$P$R$T"), b"$'\n\n\r\n\x0c\r\t");
        assert_eq!(decode_dollar(b"50$"), b"50$");
        assert_eq!(decode_dollar(b"$G1"), b"$G1");
    }

    #[test]
    fn rounding_halves_away_from_zero() {
        assert_eq!(round_to_i32(2.5), 3);
        assert_eq!(round_to_i32(-2.5), -3);
        assert_eq!(round_to_i32(2.4999), 2);
        assert_eq!(round_to_i32(1e20), i32::MAX);
        assert_eq!(round_to_i32(f32::NAN), 0);
    }
}

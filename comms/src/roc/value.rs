//! Parameter values as ROC Plus carries them (docs/roc-protocol.md):
//! integers at their width little-endian, FL an IEEE-754 float32
//! little-endian, AC(n) n bytes of ASCII padded with spaces.

pub use linc_format::db::RocType;

/// A value off or onto the wire, before it meets a field's own type.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f32),
    Text(Vec<u8>),
}

/// The bytes of `v` as type `t`. A whole number outside the type's range is
/// held at the nearest end of it (a read of an INT field of 300 as UINT8
/// gives 255), text is cut or padded with spaces to the width, and a value
/// of the wrong kind is converted as a host would read it (a REAL as a
/// whole number rounds, a number as text is its decimal form).
pub fn encode(t: RocType, v: &Value, out: &mut Vec<u8>) {
    match t {
        RocType::Fl => {
            let x = match v {
                Value::Real(x) => *x,
                Value::Int(i) => *i as f32,
                Value::Text(_) => 0.0,
            };
            out.extend_from_slice(&x.to_le_bytes());
        }
        RocType::Ac(n) => {
            let text: std::borrow::Cow<[u8]> = match v {
                Value::Text(b) => b.into(),
                Value::Int(i) => i.to_string().into_bytes().into(),
                Value::Real(x) => x.to_string().into_bytes().into(),
            };
            pad_ascii(&text, usize::from(n), out);
        }
        _ => {
            let i = match v {
                Value::Int(i) => *i,
                Value::Real(x) if x.is_finite() => x.round() as i64,
                Value::Real(_) | Value::Text(_) => 0,
            };
            let (lo, hi) = t.range().unwrap_or((0, 0));
            let i = i.clamp(lo, hi);
            out.extend_from_slice(&i.to_le_bytes()[..t.size()]);
        }
    }
}

/// `n` bytes of text: cut to `n`, or padded with spaces (the AC types,
/// and the descriptions in log records).
pub fn pad_ascii(text: &[u8], n: usize, out: &mut Vec<u8>) {
    out.extend(text.iter().copied().chain(std::iter::repeat(b' ')).take(n));
}

/// The value `bytes` hold as type `t`; `None` when they are not its size.
/// Text loses its padding (trailing spaces and NULs).
pub fn decode(t: RocType, bytes: &[u8]) -> Option<Value> {
    if bytes.len() != t.size() {
        return None;
    }
    let le = |n: usize| {
        let mut b = [0u8; 8];
        b[..n].copy_from_slice(&bytes[..n]);
        u64::from_le_bytes(b)
    };
    Some(match t {
        RocType::Fl => Value::Real(f32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]])),
        RocType::Ac(_) => {
            let end = bytes.iter().rposition(|&b| b != b' ' && b != 0).map_or(0, |i| i + 1);
            Value::Text(bytes[..end].to_vec())
        }
        RocType::Bin | RocType::Uint8 | RocType::Uint16 | RocType::Uint32 => Value::Int(le(t.size()) as i64),
        RocType::Int8 => Value::Int(i64::from(bytes[0] as i8)),
        RocType::Int16 => Value::Int(i64::from(i16::from_le_bytes([bytes[0], bytes[1]]))),
        RocType::Int32 => Value::Int(i64::from(i32::from_le_bytes([bytes[0], bytes[1], bytes[2], bytes[3]]))),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bytes(t: RocType, v: Value) -> Vec<u8> {
        let mut out = Vec::new();
        encode(t, &v, &mut out);
        out
    }

    #[test]
    fn each_type_at_its_width_little_endian() {
        assert_eq!(bytes(RocType::Fl, Value::Real(1.0)), [0x00, 0x00, 0x80, 0x3F]);
        assert_eq!(bytes(RocType::Int16, Value::Int(-2)), [0xFE, 0xFF]);
        assert_eq!(bytes(RocType::Uint16, Value::Int(500)), [0xF4, 0x01]);
        assert_eq!(bytes(RocType::Int32, Value::Int(1000)), [0xE8, 0x03, 0, 0]);
        assert_eq!(bytes(RocType::Uint32, Value::Int(0x0102_0304)), [4, 3, 2, 1]);
        assert_eq!(bytes(RocType::Bin, Value::Int(1)), [1]);
        assert_eq!(bytes(RocType::Ac(6), Value::Text(b"FST1".to_vec())), b"FST1  ");
        assert_eq!(bytes(RocType::Ac(3), Value::Text(b"TOOLONG".to_vec())), b"TOO");
    }

    #[test]
    fn out_of_range_reads_hold_at_the_ends() {
        assert_eq!(bytes(RocType::Uint8, Value::Int(300)), [255]);
        assert_eq!(bytes(RocType::Uint8, Value::Int(-5)), [0]);
        assert_eq!(bytes(RocType::Int8, Value::Int(-500)), [0x80]);
        assert_eq!(bytes(RocType::Uint16, Value::Real(2.6)), [3, 0]);
    }

    #[test]
    fn decoding_inverts_encoding_and_checks_the_size() {
        for (t, v) in [
            (RocType::Fl, Value::Real(-12.5)),
            (RocType::Int8, Value::Int(-100)),
            (RocType::Int16, Value::Int(-30_000)),
            (RocType::Int32, Value::Int(-2_000_000_000)),
            (RocType::Uint8, Value::Int(200)),
            (RocType::Uint16, Value::Int(60_000)),
            (RocType::Uint32, Value::Int(4_000_000_000)),
            (RocType::Bin, Value::Int(1)),
            (RocType::Ac(10), Value::Text(b"PUMP 1".to_vec())),
        ] {
            assert_eq!(decode(t, &bytes(t, v.clone())), Some(v));
        }
        assert_eq!(decode(RocType::Fl, &[0, 0, 0]), None);
        assert_eq!(decode(RocType::Ac(4), b"AB\0\0"), Some(Value::Text(b"AB".to_vec())));
    }
}

//! EXTRACT_* and REPLACE_* (§12.6, sub-categories Extract and Replace):
//! binary values inside byte sequences, at 1-based byte positions P.
//!
//! Byte orders follow the guide's Order table. With the value's bytes
//! numbered from the least significant (b0) to the most significant (b3),
//! the bytes at positions n, n+1, n+2, n+3 are:
//!
//! | Order | 32-bit values | 16-bit values |
//! |---|---|---|
//! | 0 | b0 b1 b2 b3 (little endian) | b0 b1 |
//! | 1 | b3 b2 b1 b0 (big endian) | b1 b0 |
//! | 2 | b2 b3 b0 b1 (little endian, words swapped) | as 0 |
//! | 3 | b1 b0 b3 b2 (big endian, words swapped) | as 1 |
//!
//! Decisions where the guide is silent: the table gives no 16-bit meaning
//! for orders 2 and 3, so they are the little- and big-endian orders of the
//! 16-bit words; any other Order is invalid (EXTRACT gives 0, REPLACE the
//! null sequence), and so is a bit number B outside 0–7. Bit 0 is the least
//! significant bit of the byte. REPLACE_INT8/UINT8 write the low 8 bits of
//! the value and REPLACE_INT16/UINT16 the low 16 bits. EXTRACT_REAL returns
//! the stored bit pattern as it is, NaN and infinities included.
//!
//! EXTRACT beyond the end of the sequence (or at P <= 0) gives 0, FALSE or
//! 0.0; REPLACE there gives the null sequence.

use super::span;

/// Where each byte of the little-endian value goes, for a byte order.
fn layout32(order: i32) -> Option<[usize; 4]> {
    match order {
        0 => Some([0, 1, 2, 3]),
        1 => Some([3, 2, 1, 0]),
        2 => Some([2, 3, 0, 1]),
        3 => Some([1, 0, 3, 2]),
        _ => None,
    }
}

fn layout16(order: i32) -> Option<[usize; 2]> {
    match order {
        0 | 2 => Some([0, 1]),
        1 | 3 => Some([1, 0]),
        _ => None,
    }
}

/// The `N` bytes at position `p`, in value order (least significant
/// first).
fn read<const N: usize>(s: &[u8], p: i32, layout: [usize; N]) -> Option<[u8; N]> {
    let bytes = s.get(span(s.len(), p, N)?)?;
    let mut le = [0; N];
    for (&b, &at) in bytes.iter().zip(layout.iter()) {
        *le.get_mut(at)? = b;
    }
    Some(le)
}

/// `s` with the value bytes `le` (least significant first) written at `p`.
fn write<const N: usize>(s: &[u8], p: i32, le: [u8; N], layout: [usize; N]) -> Vec<u8> {
    let mut out = s.to_vec();
    let Some(dest) = span(s.len(), p, N).and_then(|r| out.get_mut(r)) else {
        return Vec::new();
    };
    for (d, &at) in dest.iter_mut().zip(layout.iter()) {
        *d = le.get(at).copied().unwrap_or(0);
    }
    out
}

/// EXTRACT_BOOL(s, P, B): bit B (0–7) of byte P.
pub fn extract_bool(s: &[u8], p: i32, b: i32) -> bool {
    let Ok(bit @ 0..=7) = u32::try_from(b) else {
        return false;
    };
    read(s, p, [0]).is_some_and(|[v]| (v >> bit) & 1 == 1)
}

/// EXTRACT_INT8(s, P): byte P as a signed value (-128–127).
pub fn extract_int8(s: &[u8], p: i32) -> i32 {
    read(s, p, [0]).map_or(0, |[v]| i32::from(v as i8))
}

/// EXTRACT_UINT8(s, P): byte P as an unsigned value (0–255).
pub fn extract_uint8(s: &[u8], p: i32) -> i32 {
    read(s, p, [0]).map_or(0, |[v]| i32::from(v))
}

/// EXTRACT_INT16(s, P, Order): a signed 16-bit value.
pub fn extract_int16(s: &[u8], p: i32, order: i32) -> i32 {
    layout16(order).and_then(|l| read(s, p, l)).map_or(0, |le| i32::from(i16::from_le_bytes(le)))
}

/// EXTRACT_UINT16(s, P, Order): an unsigned 16-bit value (0–65535).
pub fn extract_uint16(s: &[u8], p: i32, order: i32) -> i32 {
    layout16(order).and_then(|l| read(s, p, l)).map_or(0, |le| i32::from(u16::from_le_bytes(le)))
}

/// EXTRACT_INT32(s, P, Order): a 32-bit value.
pub fn extract_int32(s: &[u8], p: i32, order: i32) -> i32 {
    layout32(order).and_then(|l| read(s, p, l)).map_or(0, i32::from_le_bytes)
}

/// EXTRACT_REAL(s, P, Order): a 32-bit IEEE 754 REAL.
pub fn extract_real(s: &[u8], p: i32, order: i32) -> f32 {
    layout32(order).and_then(|l| read(s, p, l)).map_or(0.0, f32::from_le_bytes)
}

/// REPLACE_BOOL(s, P, B, V): `s` with bit B (0–7) of byte P set to V.
pub fn replace_bool(s: &[u8], p: i32, b: i32, v: bool) -> Vec<u8> {
    let (Ok(bit @ 0..=7), Some([old])) = (u32::try_from(b), read(s, p, [0])) else {
        return Vec::new();
    };
    let mask = 1u8 << bit;
    let new = if v { old | mask } else { old & !mask };
    write(s, p, [new], [0])
}

/// REPLACE_INT8 / REPLACE_UINT8(s, P, V): `s` with byte P set to the low 8
/// bits of V.
pub fn replace_8(s: &[u8], p: i32, v: i32) -> Vec<u8> {
    write(s, p, [v.to_le_bytes()[0]], [0])
}

/// REPLACE_INT16 / REPLACE_UINT16(s, P, V, Order): the low 16 bits of V.
pub fn replace_16(s: &[u8], p: i32, v: i32, order: i32) -> Vec<u8> {
    let [lo, hi, _, _] = v.to_le_bytes();
    layout16(order).map_or_else(Vec::new, |l| write(s, p, [lo, hi], l))
}

/// REPLACE_INT32(s, P, V, Order).
pub fn replace_int32(s: &[u8], p: i32, v: i32, order: i32) -> Vec<u8> {
    layout32(order).map_or_else(Vec::new, |l| write(s, p, v.to_le_bytes(), l))
}

/// REPLACE_REAL(s, P, V, Order): V as a 32-bit IEEE 754 REAL.
pub fn replace_real(s: &[u8], p: i32, v: f32, order: i32) -> Vec<u8> {
    layout32(order).map_or_else(Vec::new, |l| write(s, p, v.to_le_bytes(), l))
}

#[cfg(test)]
mod tests {
    use super::*;

    const BUF: &[u8] = &[0x11, 0x22, 0x33, 0x44, 0x55];

    #[test]
    fn orders_of_32_bit_values() {
        assert_eq!(extract_int32(BUF, 1, 0), 0x4433_2211);
        assert_eq!(extract_int32(BUF, 1, 1), 0x1122_3344);
        assert_eq!(extract_int32(BUF, 1, 2), 0x2211_4433);
        assert_eq!(extract_int32(BUF, 1, 3), 0x3344_1122);
        assert_eq!(extract_int32(BUF, 2, 1), 0x2233_4455);
        let v = 0x0A0B_0C0D;
        assert_eq!(replace_int32(&[0; 4], 1, v, 0), [0x0D, 0x0C, 0x0B, 0x0A]);
        assert_eq!(replace_int32(&[0; 4], 1, v, 1), [0x0A, 0x0B, 0x0C, 0x0D]);
        assert_eq!(replace_int32(&[0; 4], 1, v, 2), [0x0B, 0x0A, 0x0D, 0x0C]);
        assert_eq!(replace_int32(&[0; 4], 1, v, 3), [0x0C, 0x0D, 0x0A, 0x0B]);
    }

    #[test]
    fn orders_of_16_bit_values() {
        assert_eq!(extract_uint16(BUF, 1, 0), 0x2211);
        assert_eq!(extract_uint16(BUF, 1, 1), 0x1122);
        assert_eq!(extract_uint16(BUF, 1, 2), 0x2211);
        assert_eq!(extract_uint16(BUF, 1, 3), 0x1122);
        assert_eq!(extract_int16(&[0xFF, 0x7F], 1, 1), -129);
        assert_eq!(extract_uint16(&[0xFF, 0x7F], 1, 1), 0xFF7F);
        assert_eq!(replace_16(&[0; 3], 2, 0x1234, 1), [0, 0x12, 0x34]);
        assert_eq!(replace_16(&[0; 3], 2, 0x7FFF_1234, 3), [0, 0x12, 0x34]);
        assert_eq!(replace_16(&[0; 3], 2, -1, 0), [0, 0xFF, 0xFF]);
    }

    #[test]
    fn out_of_range_reads_and_writes() {
        for p in [i32::MIN, -1, 0, 3, 6, i32::MAX] {
            assert_eq!(extract_int32(BUF, p, 0), 0, "{p}");
            assert_eq!(extract_real(BUF, p, 0), 0.0, "{p}");
            assert!(replace_int32(BUF, p, 1, 0).is_empty(), "{p}");
            assert!(replace_real(BUF, p, 1.0, 0).is_empty(), "{p}");
        }
        assert_eq!(extract_uint8(BUF, 5), 0x55);
        assert_eq!(extract_uint8(BUF, 6), 0);
        assert_eq!(extract_int16(BUF, 5, 0), 0);
        assert!(replace_8(BUF, 6, 1).is_empty());
        assert!(replace_16(BUF, 5, 1, 0).is_empty());
        for order in [-1, 4, i32::MIN, i32::MAX] {
            assert_eq!(extract_int32(BUF, 1, order), 0);
            assert_eq!(extract_uint16(BUF, 1, order), 0);
            assert!(replace_16(BUF, 1, 1, order).is_empty());
            assert!(replace_int32(BUF, 1, 1, order).is_empty());
        }
        assert!(replace_8(&[], 1, 1).is_empty());
    }

    #[test]
    fn bits_and_bytes() {
        assert!(extract_bool(&[0b1000_0001], 1, 0));
        assert!(extract_bool(&[0b1000_0001], 1, 7));
        assert!(!extract_bool(&[0b1000_0001], 1, 1));
        assert!(!extract_bool(&[0xFF], 1, 8));
        assert!(!extract_bool(&[0xFF], 1, -1));
        assert!(!extract_bool(&[0xFF], 2, 0));
        assert_eq!(replace_bool(&[0, 0], 2, 3, true), [0, 8]);
        assert_eq!(replace_bool(&[0xFF], 1, 0, false), [0xFE]);
        assert!(replace_bool(&[0xFF], 1, 8, false).is_empty());
        assert!(replace_bool(&[0xFF], 0, 0, false).is_empty());
        assert_eq!(extract_int8(&[0x80], 1), -128);
        assert_eq!(extract_uint8(&[0x80], 1), 128);
        assert_eq!(replace_8(&[1, 2], 1, -1), [0xFF, 2]);
        assert_eq!(replace_8(&[1, 2], 2, 0x1234), [1, 0x34]);
    }

    #[test]
    fn reals() {
        let b = replace_real(&[0; 6], 2, 1.5, 1);
        assert_eq!(b, [0, 0x3F, 0xC0, 0, 0, 0]);
        assert_eq!(extract_real(&b, 2, 1), 1.5);
        assert!(extract_real(&[0xFF; 4], 1, 0).is_nan());
    }
}

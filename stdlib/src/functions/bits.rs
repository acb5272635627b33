//! Bit functions (§12.6, sub-category Bit).
//!
//! The 8- and 16-bit functions first keep only the low 8 or 16 bits of the
//! value and return an unsigned result (0–255, 0–65535); the 32-bit ones work
//! on the whole two's-complement pattern and return it as a signed INT.
//! Shifts are logical (zero filled) in both directions.
//!
//! Decisions where the guide is silent: a shift by the width or more gives
//! 0; a negative shift count leaves the (masked) value unchanged; rotation
//! counts are taken modulo the width (Euclidean), so a negative count
//! rotates the other way: ROL8(X, -1) = ROR8(X, 1).

/// Which way a shift or rotation goes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dir {
    Left,
    Right,
}

/// BIT_INVERT: the one's complement of the 32-bit value.
pub fn bit_invert(v: i32) -> i32 {
    !v
}

/// The mask of a width of 8, 16 or 32 bits.
fn mask(width: u32) -> u32 {
    u32::MAX.checked_shr(32 - width.min(32)).unwrap_or(0)
}

/// The masked result as an INT: unsigned for 8 and 16 bits, the signed
/// pattern for 32.
fn result(v: u32) -> i32 {
    v as i32
}

/// SHL8/16/32 and SHR8/16/32: `v` shifted `n` bits within `width` bits.
pub fn shift(v: i32, n: i32, width: u32, dir: Dir) -> i32 {
    let m = mask(width);
    let x = v as u32 & m;
    let Ok(n) = u32::try_from(n) else {
        return result(x);
    };
    if n >= width {
        return 0;
    }
    let shifted = match dir {
        Dir::Left => x.checked_shl(n),
        Dir::Right => x.checked_shr(n),
    };
    result(shifted.unwrap_or(0) & m)
}

/// ROL8/16/32 and ROR8/16/32: `v` rotated `n` bits within `width` bits.
pub fn rotate(v: i32, n: i32, width: u32, dir: Dir) -> i32 {
    let m = mask(width);
    let x = v as u32 & m;
    let w = i64::from(width.max(1));
    // 0 <= k < width <= 32.
    let k = i64::from(n).rem_euclid(w) as u32;
    let k = match dir {
        Dir::Left => k,
        Dir::Right => (width - k) % width.max(1),
    };
    if k == 0 {
        return result(x);
    }
    let hi = x.checked_shl(k).unwrap_or(0);
    let lo = x.checked_shr(width - k).unwrap_or(0);
    result((hi | lo) & m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use Dir::{Left, Right};

    #[test]
    fn shifts() {
        assert_eq!(shift(0x81, 1, 8, Left), 0x02);
        assert_eq!(shift(0x181, 0, 8, Left), 0x81);
        assert_eq!(shift(0x81, 7, 8, Left), 0x80);
        assert_eq!(shift(0x81, 8, 8, Left), 0);
        assert_eq!(shift(0x81, 1, 8, Right), 0x40);
        assert_eq!(shift(0x8001, 15, 16, Left), 0x8000);
        assert_eq!(shift(-1, 4, 16, Right), 0x0FFF);
        assert_eq!(shift(1, 31, 32, Left), i32::MIN);
        assert_eq!(shift(i32::MIN, 31, 32, Right), 1);
        assert_eq!(shift(-1, 1, 32, Right), i32::MAX);
        assert_eq!(shift(-1, 32, 32, Right), 0);
        assert_eq!(shift(-1, i32::MAX, 32, Left), 0);
        assert_eq!(shift(0x1FF, -1, 8, Left), 0xFF);
        assert_eq!(shift(-5, i32::MIN, 32, Right), -5);
    }

    #[test]
    fn rotations() {
        assert_eq!(rotate(0x81, 1, 8, Left), 0x03);
        assert_eq!(rotate(0x81, 1, 8, Right), 0xC0);
        assert_eq!(rotate(0x81, 9, 8, Left), 0x03);
        assert_eq!(rotate(0x81, -1, 8, Left), 0xC0);
        assert_eq!(rotate(0x8000, 1, 16, Left), 1);
        assert_eq!(rotate(1, 1, 16, Right), 0x8000);
        assert_eq!(rotate(i32::MIN, 1, 32, Left), 1);
        assert_eq!(rotate(1, 1, 32, Right), i32::MIN);
        assert_eq!(rotate(0x1234_5678, 8, 32, Left), 0x3456_7812);
        assert_eq!(rotate(0x1234_5678, i32::MIN, 32, Right), 0x1234_5678);
        assert_eq!(rotate(0x1234_5678, i32::MAX, 32, Left), 0x091A_2B3C);
    }

    #[test]
    fn inversion() {
        assert_eq!(bit_invert(0), -1);
        assert_eq!(bit_invert(0x0000_FFFF), -65536);
        assert_eq!(bit_invert(i32::MIN), i32::MAX);
    }
}

//! BCC and CRC (§12.6, sub-category Checksum, and §12.6.1).

/// BCC(s, Mode, Seed): a block check character.
///
/// * Mode 0: the seed XOR every byte (0–255).
/// * Mode 1: the 8 least significant bits of the seed plus every byte.
/// * Mode 2: the seed plus every byte, not truncated (wrapping at 32 bits).
///
/// Decisions: the guide calls the seed an 8-bit value, so modes 0 and 1 use
/// its low 8 bits; mode 2 uses the whole seed so that sums can be chained
/// across sequences (BCC(b, 2, BCC(a, 2, 0)) = BCC(CONCAT(a, b), 2, 0)).
/// Any other mode gives 0.
pub fn bcc(s: &[u8], mode: i32, seed: i32) -> i32 {
    let low = seed & 0xFF;
    match mode {
        0 => s.iter().fold(low, |acc, &b| acc ^ i32::from(b)),
        1 => s.iter().fold(low, |acc, &b| (acc + i32::from(b)) & 0xFF),
        2 => s.iter().fold(seed, |acc, &b| acc.wrapping_add(i32::from(b))),
        _ => 0,
    }
}

/// The 16-bit mirror image of `x`.
fn reflect16(x: u16) -> u16 {
    x.reverse_bits()
}

/// CRC(s, Mode, Poly, Seed): a 16-bit CRC (0–65535).
///
/// Poly is the generator without its x^16 term and Seed the initial value
/// of the register (both taken modulo 2^16). There is no final XOR.
///
/// * Mode 0: the plain MSB-first CRC (no reflection): each byte is XORed
///   into the high byte of the register, which shifts left.
/// * Mode 1: bits reflected in and out: the LSB-first algorithm with the
///   reversed polynomial, the register shifting right. CRC('123456789', 1,
///   16#8005, 16#FFFF) = 16#4B37 (CRC-16/MODBUS). The seed is loaded into
///   this reflected register as it is, so a catalogue CRC whose `init` is
///   not a palindrome needs Seed = `init` with its 16 bits reversed.
///
/// Decision: any other mode gives 0.
pub fn crc(s: &[u8], mode: i32, poly: i32, seed: i32) -> i32 {
    let poly = (poly & 0xFFFF) as u16;
    let mut reg = (seed & 0xFFFF) as u16;
    match mode {
        0 => {
            for &b in s {
                reg ^= u16::from(b) << 8;
                for _ in 0..8 {
                    reg = if reg & 0x8000 != 0 { (reg << 1) ^ poly } else { reg << 1 };
                }
            }
        }
        1 => {
            let rpoly = reflect16(poly);
            for &b in s {
                reg ^= u16::from(b);
                for _ in 0..8 {
                    reg = if reg & 1 != 0 { (reg >> 1) ^ rpoly } else { reg >> 1 };
                }
            }
        }
        _ => return 0,
    }
    i32::from(reg)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn block_checks() {
        assert_eq!(bcc(b"\x01\x02\x04", 0, 0), 7);
        assert_eq!(bcc(b"\x01\x02\x04", 0, 0x1FF), 0xF8);
        assert_eq!(bcc(b"\xFF\xFF", 1, 3), 1);
        assert_eq!(bcc(b"\xFF\xFF", 2, 3), 513);
        assert_eq!(bcc(b"\xFF", 2, i32::MAX), i32::MIN + 254);
        assert_eq!(bcc(b"", 0, 0x42), 0x42);
        assert_eq!(bcc(b"abc", 3, 0), 0);
        assert_eq!(bcc(b"abc", -1, 0), 0);
        assert_eq!(bcc(b"cd", 2, bcc(b"ab", 2, 0)), bcc(b"abcd", 2, 0));
    }

    #[test]
    fn modbus_and_other_modes() {
        assert_eq!(crc(b"123456789", 1, 0x8005, 0xFFFF), 0x4B37);
        assert_eq!(crc(b"123456789", 1, 0x8005, -1), 0x4B37);
        assert_eq!(crc(b"123456789", 0, 0x1021, 0), 0x31C3);
        assert_eq!(crc(b"", 0, 0x1021, 0x1234), 0x1234);
        // CRC-16/RIELLO: init 16#B2AA, given reflected as the seed.
        assert_eq!(crc(b"123456789", 1, 0x1021, 0x554D), 0x63D0);
        assert_eq!(crc(b"123456789", 2, 0x8005, 0), 0);
        assert_eq!(crc(b"123456789", i32::MIN, 0x8005, 0), 0);
    }
}

//! The ROC protocol of the FloBoss 100-series and ROC300-series devices
//! (docs/roc-protocol.md, "The ROC protocol"): the frame, CRC and opcodes
//! 180/181 are ROC Plus's; the error reply, the clock, the logs, history,
//! the opcode tables and store and forward are its own. Like `ops`, this is
//! layouts only: nothing here knows a database.

pub mod clock;
pub mod forward;
pub mod history;
pub mod logs;
pub mod params;

use super::ops::RocError;
use super::Address;

pub const CONFIG: u8 = 6;
pub const CLOCK_READ: u8 = 7;
pub const CLOCK_SET: u8 = 8;
pub const TABLE_READ: u8 = 10;
pub const TABLE_WRITE: u8 = 11;
pub const LOGIN: u8 = 17;
pub const FORWARD: u8 = 24;
pub const POINTERS: u8 = 120;
pub const ALARMS: u8 = 121;
pub const EVENTS: u8 = 122;
pub const LAST_HOUR: u8 = 126;
pub const DAY: u8 = 128;
pub const FROM_POINTER: u8 = 130;
pub const WRITE_CONTIGUOUS: u8 = 166;
pub const READ_CONTIGUOUS: u8 = 167;
pub const READ: u8 = 180;
pub const WRITE: u8 = 181;
pub const ERROR: u8 = 255;

/// Error codes of the FloBoss 100-series table that ROC Plus's lacks or
/// numbers differently (the shared ones are `ops::code`'s).
pub mod code {
    pub const OUTSIDE_RANGE: u8 = 13;
    pub const INVALID_HISTORY: u8 = 14;
    pub const FORWARD_PATH: u8 = 22;
}

/// The address every ROC-protocol device answers, whatever its own (a
/// host on a direct link need not know the device's address).
pub const UNIVERSAL: Address = Address { unit: 240, group: 240 };

/// How a frame's destination concerns a device.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Addressed {
    /// Its own address, or the universal one: it answers.
    Answer,
    /// Unit 0 of its group: it does what the frame asks, silently.
    Broadcast,
    /// Another device's.
    Other,
}

/// Whether a frame sent to `dst` is for the device at `me`.
pub fn addressed(me: Address, dst: Address) -> Addressed {
    if dst == me || dst == UNIVERSAL {
        Addressed::Answer
    } else if dst.unit == 0 && dst.group == me.group {
        Addressed::Broadcast
    } else {
        Addressed::Other
    }
}

/// An opcode 255 reply's data in this protocol: the code, the opcode of
/// the request, the offset of the byte that caused it.
pub fn error_data(e: RocError, opcode: u8) -> Vec<u8> {
    vec![e.code, opcode, e.offset]
}

/// The point types opcode 6 counts (an FB107's are all below 60).
pub const CONFIG_TYPES: std::ops::RangeInclusive<u8> = 0..=59;
/// The type of ROC opcode 6 reports for a FloBoss 107.
pub const FB107: u8 = 10;

/// Opcode 6's reply: system mode 1, the port (0), security mode, logical
/// compatibility 0, revision 0, subtype 0, eleven reserved bytes, the type
/// of ROC, then the number of points of each type 0–59.
pub fn config_reply(security: bool, count_of: impl Fn(u8) -> u8) -> Vec<u8> {
    let mut out = vec![1, 0, 0, u8::from(security), 0, 0, 0];
    out.extend_from_slice(&[0; 11]);
    out.push(FB107);
    out.extend(CONFIG_TYPES.map(count_of));
    out
}

/// A request's data must be exactly `n` bytes: error 6 or 5 at the length
/// byte otherwise.
pub fn exactly(data: &[u8], n: usize) -> Result<(), RocError> {
    use super::ops::code::{TOO_FEW_BYTES, TOO_MANY_BYTES};
    match data.len().cmp(&n) {
        std::cmp::Ordering::Less => Err(RocError::length(TOO_FEW_BYTES)),
        std::cmp::Ordering::Greater => Err(RocError::length(TOO_MANY_BYTES)),
        std::cmp::Ordering::Equal => Ok(()),
    }
}

/// Splits `bytes` into values of the given sizes, all of them: error 6
/// (too few) or 5 (too many) at the length byte otherwise.
pub fn split_values<'a>(mut bytes: &'a [u8], sizes: &[usize]) -> Result<Vec<&'a [u8]>, RocError> {
    use super::ops::code::{TOO_FEW_BYTES, TOO_MANY_BYTES};
    let mut out = Vec::with_capacity(sizes.len());
    for &n in sizes {
        if bytes.len() < n {
            return Err(RocError::length(TOO_FEW_BYTES));
        }
        let (v, rest) = bytes.split_at(n);
        out.push(v);
        bytes = rest;
    }
    if !bytes.is_empty() {
        return Err(RocError::length(TOO_MANY_BYTES));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const ME: Address = Address { unit: 1, group: 2 };

    #[test]
    fn the_universal_address_and_broadcasts() {
        assert_eq!(addressed(ME, ME), Addressed::Answer);
        assert_eq!(addressed(ME, Address { unit: 240, group: 240 }), Addressed::Answer);
        assert_eq!(addressed(ME, Address { unit: 0, group: 2 }), Addressed::Broadcast);
        assert_eq!(addressed(ME, Address { unit: 0, group: 3 }), Addressed::Other);
        assert_eq!(addressed(ME, Address { unit: 2, group: 2 }), Addressed::Other);
    }

    #[test]
    fn an_error_names_the_opcode_between_code_and_offset() {
        assert_eq!(error_data(RocError { code: 1, offset: 4 }, 99), [1, 99, 4]);
    }

    #[test]
    fn the_configuration_counts_types_below_60() {
        let r = config_reply(true, |t| if t == 16 { 3 } else { 0 });
        assert_eq!(r.len(), 79);
        assert_eq!((r[0], r[3], r[18], r[19 + 16]), (1, 1, FB107, 3));
    }

    #[test]
    fn values_split_by_size() {
        assert_eq!(split_values(&[1, 2, 3], &[1, 2]).unwrap(), vec![&[1u8][..], &[2, 3][..]]);
        assert_eq!(split_values(&[1, 2], &[1, 2]), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(split_values(&[1, 2, 3, 4], &[1, 2]), Err(RocError { code: 5, offset: 5 }));
    }
}

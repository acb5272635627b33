//! Contiguous parameters of one point (opcodes 166 and 167) and the
//! configurable opcode tables (10 and 11): a header naming where, then the
//! values back to back at each parameter's size.

use super::code::OUTSIDE_RANGE;
use super::exactly;
use crate::roc::frame::MAX_DATA;
use crate::roc::ops::{code, RocError};

/// Parameters `first ..` of point `t`, `l`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Contiguous {
    pub t: u8,
    pub l: u8,
    pub count: u8,
    pub first: u8,
}

/// Data offsets of the header's bytes, for errors.
pub const AT_TYPE: usize = 0;
pub const AT_LOGICAL: usize = 1;
pub const AT_COUNT: usize = 2;
pub const AT_FIRST: usize = 3;

fn contiguous(data: &[u8]) -> Result<Contiguous, RocError> {
    if data.len() < 4 {
        return Err(RocError::length(code::TOO_FEW_BYTES));
    }
    let c = Contiguous { t: data[0], l: data[1], count: data[2], first: data[3] };
    if c.count == 0 {
        return Err(RocError::at_data(code::TOO_FEW_BYTES, AT_COUNT));
    }
    if usize::from(c.first) + usize::from(c.count) > 256 {
        return Err(RocError::at_data(code::INVALID_PARAMETER, AT_FIRST));
    }
    Ok(c)
}

/// Opcode 167's request: point type, logical number, parameters, first.
pub fn parse_read(data: &[u8]) -> Result<Contiguous, RocError> {
    exactly(data, 4)?;
    contiguous(data)
}

/// Opcode 166's request: the header, then the values (split by the
/// caller, who knows each parameter's size).
pub fn parse_write(data: &[u8]) -> Result<(Contiguous, &[u8]), RocError> {
    Ok((contiguous(data)?, &data[4..]))
}

/// Opcode 167's reply: the header again, then the values; error 5 if it
/// would pass a frame.
pub fn read_reply(c: &Contiguous, values: &[u8]) -> Result<Vec<u8>, RocError> {
    let mut out = vec![c.t, c.l, c.count, c.first];
    out.extend_from_slice(values);
    fits(out)
}

fn fits(out: Vec<u8>) -> Result<Vec<u8>, RocError> {
    if out.len() > MAX_DATA {
        return Err(RocError::length(code::TOO_MANY_BYTES));
    }
    Ok(out)
}

/// Locations `first ..` of configurable opcode table `table`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TableRequest {
    pub table: u8,
    pub first: u8,
    pub count: u8,
}

fn table(data: &[u8]) -> Result<TableRequest, RocError> {
    use linc_format::db::roc_device::{LOCATIONS, TABLES};
    if data.len() < 3 {
        return Err(RocError::length(code::TOO_FEW_BYTES));
    }
    let r = TableRequest { table: data[0], first: data[1], count: data[2] };
    if r.table >= TABLES {
        return Err(RocError::at_data(OUTSIDE_RANGE, 0));
    }
    if r.first >= LOCATIONS {
        return Err(RocError::at_data(OUTSIDE_RANGE, 1));
    }
    if r.count == 0 || u16::from(r.first) + u16::from(r.count) > u16::from(LOCATIONS) {
        return Err(RocError::at_data(OUTSIDE_RANGE, 2));
    }
    Ok(r)
}

/// Opcode 10's request: table (0–15), first location (0–43), locations;
/// a number out of range is error 13 at its byte.
pub fn parse_table_read(data: &[u8]) -> Result<TableRequest, RocError> {
    exactly(data, 3)?;
    table(data)
}

/// Opcode 11's request: the same header, then the values.
pub fn parse_table_write(data: &[u8]) -> Result<(TableRequest, &[u8]), RocError> {
    Ok((table(data)?, &data[3..]))
}

/// Opcode 10's reply: table, first location, locations, the table's
/// version (FL), then the values.
pub fn table_reply(r: &TableRequest, version: f32, values: &[u8]) -> Result<Vec<u8>, RocError> {
    let mut out = vec![r.table, r.first, r.count];
    out.extend_from_slice(&version.to_le_bytes());
    out.extend_from_slice(values);
    fits(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Go driver abferm/roc asks 167 as type, logical, count, first
    /// and skips the four header bytes of the reply (client.go).
    #[test]
    fn contiguous_both_ways() {
        let c = Contiguous { t: 16, l: 0, count: 2, first: 3 };
        assert_eq!(parse_read(&[16, 0, 2, 3]), Ok(c));
        assert_eq!(read_reply(&c, &[1, 2, 3, 4]).unwrap(), [16, 0, 2, 3, 1, 2, 3, 4]);
        assert_eq!(parse_read(&[16, 0, 2]), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(parse_read(&[16, 0, 0, 3]), Err(RocError { code: 6, offset: 8 }));
        assert_eq!(parse_read(&[16, 0, 2, 255]), Err(RocError { code: 2, offset: 9 }));
        assert_eq!(parse_write(&[16, 0, 1, 3, 9, 9]), Ok((Contiguous { count: 1, ..c }, &[9u8, 9][..])));
        assert_eq!(read_reply(&c, &[0; 252]), Err(RocError { code: 5, offset: 5 }));
    }

    #[test]
    fn tables_both_ways() {
        let r = TableRequest { table: 1, first: 0, count: 2 };
        assert_eq!(parse_table_read(&[1, 0, 2]), Ok(r));
        assert_eq!(table_reply(&r, 1.0, &[7]).unwrap(), [1, 0, 2, 0, 0, 0x80, 0x3F, 7]);
        assert_eq!(parse_table_read(&[16, 0, 1]), Err(RocError { code: 13, offset: 6 }));
        assert_eq!(parse_table_read(&[1, 44, 1]), Err(RocError { code: 13, offset: 7 }));
        assert_eq!(parse_table_read(&[1, 40, 5]), Err(RocError { code: 13, offset: 8 }));
        assert_eq!(parse_table_read(&[1, 0, 0]), Err(RocError { code: 13, offset: 8 }));
        assert_eq!(parse_table_write(&[1, 0, 1, 5]), Ok((TableRequest { count: 1, ..r }, &[5u8][..])));
    }
}

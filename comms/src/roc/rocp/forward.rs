//! Store and forward (opcode 24): a request wrapped with the path it
//! travels, so a host reaches a device behind another (over a radio the
//! host's own does not reach). The data: the host's unit and group, four
//! destinations (a unit of 0 ends the path), the wrapped opcode, its length
//! and its data; a reply carries the same path around the final device's.

use super::code::FORWARD_PATH;
use crate::roc::frame::MAX_DATA;
use crate::roc::ops::{code, RocError};
use crate::roc::Address;

/// Bytes of the path: the host and four destinations.
pub const PATH: usize = 10;
/// Most destinations a path names.
pub const HOPS: usize = 4;

/// Who sent a request and the devices it passes through, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Path {
    pub host: Address,
    pub hops: [Address; HOPS],
}

/// What a device does with a wrapped request.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Route {
    /// It is the last destination: it answers.
    Here,
    /// It passes the frame to this device.
    Next(Address),
}

impl Path {
    pub fn from_bytes(b: &[u8; PATH]) -> Path {
        let a = |i: usize| Address { unit: b[i], group: b[i + 1] };
        Path { host: a(0), hops: [a(2), a(4), a(6), a(8)] }
    }

    pub fn to_bytes(&self) -> [u8; PATH] {
        let mut out = [0u8; PATH];
        for (i, a) in std::iter::once(self.host).chain(self.hops).enumerate() {
            out[2 * i] = a.unit;
            out[2 * i + 1] = a.group;
        }
        out
    }

    /// The destinations up to the first unit 0.
    pub fn destinations(&self) -> &[Address] {
        let n = self.hops.iter().position(|a| a.unit == 0).unwrap_or(HOPS);
        &self.hops[..n]
    }

    /// Where the device at `me` sends the request next: the destination
    /// after its own place in the path (the first when it is not in it),
    /// or itself when none follows. A path naming a device twice could
    /// send a frame round in a circle, so it is error 22.
    pub fn route(&self, me: Address) -> Result<Route, RocError> {
        let d = self.destinations();
        if d.iter().enumerate().any(|(i, a)| d[..i].contains(a)) {
            return Err(RocError::at_data(FORWARD_PATH, 2));
        }
        let next = match d.iter().position(|&a| a == me) {
            Some(i) => d.get(i + 1),
            None => d.first(),
        };
        Ok(next.map_or(Route::Here, |&a| Route::Next(a)))
    }
}

/// A request or reply of opcode 24, taken apart.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Wrapped<'a> {
    pub path: Path,
    pub opcode: u8,
    pub data: &'a [u8],
}

/// Opcode 24's data: the path, the opcode, its length, its data; the
/// length must say what follows (error 6 or 5 at the frame's length byte).
pub fn parse(data: &[u8]) -> Result<Wrapped<'_>, RocError> {
    if data.len() < PATH + 2 {
        return Err(RocError::length(code::TOO_FEW_BYTES));
    }
    let path: &[u8; PATH] = data[..PATH].try_into().map_err(|_| RocError::length(code::TOO_FEW_BYTES))?;
    let inner = &data[PATH + 2..];
    match inner.len().cmp(&usize::from(data[PATH + 1])) {
        std::cmp::Ordering::Less => return Err(RocError::length(code::TOO_FEW_BYTES)),
        std::cmp::Ordering::Greater => return Err(RocError::length(code::TOO_MANY_BYTES)),
        std::cmp::Ordering::Equal => {}
    }
    Ok(Wrapped { path: Path::from_bytes(path), opcode: data[PATH], data: inner })
}

/// Opcode 24's data around `opcode` and `data`; `None` when it would pass
/// a frame (243 bytes of data at most).
pub fn wrap(path: &Path, opcode: u8, data: &[u8]) -> Option<Vec<u8>> {
    let len = u8::try_from(data.len()).ok()?;
    let mut out = Vec::with_capacity(PATH + 2 + data.len());
    out.extend_from_slice(&path.to_bytes());
    out.extend_from_slice(&[opcode, len]);
    out.extend_from_slice(data);
    (out.len() <= MAX_DATA).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    const fn a(unit: u8, group: u8) -> Address {
        Address { unit, group }
    }

    #[test]
    fn a_wrapped_request_round_trips() {
        let path = Path { host: a(3, 1), hops: [a(1, 2), a(5, 2), a(0, 0), a(0, 0)] };
        let data = wrap(&path, 180, &[1, 16, 0, 3]).unwrap();
        assert_eq!(data, [3, 1, 1, 2, 5, 2, 0, 0, 0, 0, 180, 4, 1, 16, 0, 3]);
        let w = parse(&data).unwrap();
        assert_eq!(w, Wrapped { path, opcode: 180, data: &[1, 16, 0, 3] });
        assert_eq!(path.destinations(), [a(1, 2), a(5, 2)]);
        assert_eq!(parse(&data[..15]), Err(RocError { code: 6, offset: 5 }));
        assert_eq!(parse(&[data.as_slice(), &[0]].concat()), Err(RocError { code: 5, offset: 5 }));
        assert_eq!(parse(&data[..11]), Err(RocError { code: 6, offset: 5 }));
        assert!(wrap(&path, 180, &[0; 244]).is_none());
    }

    #[test]
    fn each_device_finds_the_next_one() {
        let path = Path { host: a(3, 1), hops: [a(1, 2), a(5, 2), a(7, 2), a(0, 9)] };
        assert_eq!(path.route(a(1, 2)), Ok(Route::Next(a(5, 2))));
        assert_eq!(path.route(a(5, 2)), Ok(Route::Next(a(7, 2))));
        assert_eq!(path.route(a(7, 2)), Ok(Route::Here));
        assert_eq!(path.route(a(9, 9)), Ok(Route::Next(a(1, 2))), "not in the path: its first");
        let empty = Path { host: a(3, 1), hops: [a(0, 0); 4] };
        assert_eq!(empty.route(a(1, 2)), Ok(Route::Here));
        let circle = Path { host: a(3, 1), hops: [a(1, 2), a(5, 2), a(1, 2), a(0, 0)] };
        assert_eq!(circle.route(a(5, 2)), Err(RocError { code: 22, offset: 8 }));
    }
}

//! Modbus TCP as data: the MBAP framing of a byte stream, requests decoded
//! from their PDUs with every count and length checked, and replies
//! encoded (docs/modbus.md). Written here rather than taken from
//! tokio-modbus, whose 0.17 server decoder panics on two hostile requests
//! (ADR 0019); its client stays as the tests' independent client.

/// The MBAP header's length before the unit: transaction, protocol, length.
const MBAP: usize = 6;
/// The longest PDU (the protocol's 253 bytes).
pub const MAX_PDU: usize = 253;

/// Exception codes a server answers with.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exception {
    IllegalFunction = 1,
    IllegalDataAddress = 2,
    IllegalDataValue = 3,
    ServerDeviceFailure = 4,
}

/// A request, decoded and checked.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Request {
    ReadCoils(u16, u16),
    ReadDiscreteInputs(u16, u16),
    ReadHoldingRegisters(u16, u16),
    ReadInputRegisters(u16, u16),
    WriteSingleCoil(u16, bool),
    WriteSingleRegister(u16, u16),
    WriteMultipleCoils(u16, Vec<bool>),
    WriteMultipleRegisters(u16, Vec<u16>),
}

/// What a request's reply carries.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Response {
    /// Functions 1 and 2.
    Bits(Vec<bool>),
    /// Functions 3 and 4.
    Registers(Vec<u16>),
    /// Functions 5, 6, 15 and 16: an address and a value or a count.
    Echo(u16, u16),
}

/// One frame's header: what the reply repeats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Header {
    pub transaction: u16,
    pub unit: u8,
}

fn be(b: &[u8], at: usize) -> u16 {
    u16::from_be_bytes([b[at], b[at + 1]])
}

/// The request a PDU holds, or the function code and the exception to
/// answer with: 01 for a function not served, 03 for a malformed PDU or a
/// count out of the protocol's limits.
pub fn decode(pdu: &[u8]) -> Result<Request, (u8, Exception)> {
    let Some(&fc) = pdu.first() else { return Err((0, Exception::IllegalFunction)) };
    let bad = Err((fc, Exception::IllegalDataValue));
    let fixed = |len: usize| pdu.len() == len;
    let count_in = |n: u16, max: u16| (1..=max).contains(&n);
    match fc {
        1..=4 => {
            if !fixed(5) {
                return bad;
            }
            let (a, n) = (be(pdu, 1), be(pdu, 3));
            let max = if fc <= 2 { 2000 } else { 125 };
            if !count_in(n, max) {
                return bad;
            }
            Ok(match fc {
                1 => Request::ReadCoils(a, n),
                2 => Request::ReadDiscreteInputs(a, n),
                3 => Request::ReadHoldingRegisters(a, n),
                _ => Request::ReadInputRegisters(a, n),
            })
        }
        5 => match (fixed(5), pdu.get(3..5)) {
            (true, Some([0xFF, 0])) => Ok(Request::WriteSingleCoil(be(pdu, 1), true)),
            (true, Some([0, 0])) => Ok(Request::WriteSingleCoil(be(pdu, 1), false)),
            _ => bad,
        },
        6 if fixed(5) => Ok(Request::WriteSingleRegister(be(pdu, 1), be(pdu, 3))),
        15 | 16 => {
            if pdu.len() < 6 {
                return bad;
            }
            let (a, n, bytes) = (be(pdu, 1), be(pdu, 3), usize::from(pdu[5]));
            let (max, want) = if fc == 15 { (1968, usize::from(n).div_ceil(8)) } else { (123, 2 * usize::from(n)) };
            if !count_in(n, max) || bytes != want || pdu.len() != 6 + bytes {
                return bad;
            }
            let data = &pdu[6..];
            Ok(if fc == 15 {
                Request::WriteMultipleCoils(a, (0..usize::from(n)).map(|i| data[i / 8] >> (i % 8) & 1 == 1).collect())
            } else {
                Request::WriteMultipleRegisters(a, data.chunks_exact(2).map(|w| be(w, 0)).collect())
            })
        }
        6 => bad,
        _ => Err((fc, Exception::IllegalFunction)),
    }
}

impl Request {
    /// The function code.
    pub fn function(&self) -> u8 {
        match self {
            Request::ReadCoils(..) => 1,
            Request::ReadDiscreteInputs(..) => 2,
            Request::ReadHoldingRegisters(..) => 3,
            Request::ReadInputRegisters(..) => 4,
            Request::WriteSingleCoil(..) => 5,
            Request::WriteSingleRegister(..) => 6,
            Request::WriteMultipleCoils(..) => 15,
            Request::WriteMultipleRegisters(..) => 16,
        }
    }
}

/// A whole reply frame: the header repeated, then the function code and
/// its data, or the function code with the high bit set and the exception.
pub fn encode(h: Header, function: u8, reply: &Result<Response, Exception>) -> Vec<u8> {
    let mut pdu = Vec::new();
    match reply {
        Err(e) => pdu.extend_from_slice(&[function | 0x80, *e as u8]),
        Ok(Response::Bits(bits)) => {
            pdu.extend_from_slice(&[function, bits.len().div_ceil(8) as u8]);
            pdu.extend(bits.chunks(8).map(|c| c.iter().enumerate().fold(0u8, |b, (i, &on)| b | u8::from(on) << i)));
        }
        Ok(Response::Registers(words)) => {
            pdu.extend_from_slice(&[function, (2 * words.len()) as u8]);
            pdu.extend(words.iter().flat_map(|w| w.to_be_bytes()));
        }
        Ok(Response::Echo(a, v)) => {
            pdu.push(function);
            pdu.extend_from_slice(&a.to_be_bytes());
            pdu.extend_from_slice(&v.to_be_bytes());
        }
    }
    let mut out = Vec::with_capacity(MBAP + 1 + pdu.len());
    out.extend_from_slice(&h.transaction.to_be_bytes());
    out.extend_from_slice(&[0, 0]);
    out.extend_from_slice(&(pdu.len() as u16 + 1).to_be_bytes());
    out.push(h.unit);
    out.extend_from_slice(&pdu);
    out
}

/// Why a byte stream is not Modbus TCP: a protocol identifier that is not
/// 0, or a length no frame has. A TCP stream can't be resynchronised after
/// either, so the connection is closed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NotModbus {
    Protocol(u16),
    Length(u16),
}

/// Whole frames out of a byte stream.
#[derive(Debug, Default)]
pub struct Deframer {
    buf: Vec<u8>,
}

impl Deframer {
    pub fn push(&mut self, bytes: &[u8]) {
        self.buf.extend_from_slice(bytes);
    }

    /// The next whole frame's header and PDU, if the bytes held make one.
    pub fn next_frame(&mut self) -> Option<Result<(Header, Vec<u8>), NotModbus>> {
        if self.buf.len() < MBAP + 1 {
            return None;
        }
        let (protocol, len) = (be(&self.buf, 2), be(&self.buf, 4));
        if protocol != 0 {
            return Some(Err(NotModbus::Protocol(protocol)));
        }
        if !(2..=MAX_PDU as u16 + 1).contains(&len) {
            return Some(Err(NotModbus::Length(len)));
        }
        let total = MBAP + usize::from(len);
        if self.buf.len() < total {
            return None;
        }
        let h = Header { transaction: be(&self.buf, 0), unit: self.buf[MBAP] };
        let pdu = self.buf[MBAP + 1..total].to_vec();
        self.buf.drain(..total);
        Some(Ok((h, pdu)))
    }

    /// Bytes waiting for the rest of their frame.
    pub fn pending(&self) -> usize {
        self.buf.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Frames from the Modbus application protocol specification's
    /// examples (v1.1b3, §6.1, §6.3, §6.5, §6.6, §6.11, §6.12), in MBAP.
    #[test]
    fn the_specifications_examples() {
        assert_eq!(decode(&[0x01, 0x00, 0x13, 0x00, 0x13]), Ok(Request::ReadCoils(19, 19)));
        assert_eq!(decode(&[0x03, 0x00, 0x6B, 0x00, 0x03]), Ok(Request::ReadHoldingRegisters(107, 3)));
        assert_eq!(decode(&[0x05, 0x00, 0xAC, 0xFF, 0x00]), Ok(Request::WriteSingleCoil(172, true)));
        assert_eq!(decode(&[0x06, 0x00, 0x01, 0x00, 0x03]), Ok(Request::WriteSingleRegister(1, 3)));
        let coils = [true, false, true, true, false, false, true, true, true, false];
        assert_eq!(
            decode(&[0x0F, 0x00, 0x13, 0x00, 0x0A, 0x02, 0xCD, 0x01]),
            Ok(Request::WriteMultipleCoils(19, coils.to_vec()))
        );
        assert_eq!(
            decode(&[0x10, 0x00, 0x01, 0x00, 0x02, 0x04, 0x00, 0x0A, 0x01, 0x02]),
            Ok(Request::WriteMultipleRegisters(1, vec![0x000A, 0x0102]))
        );
        // The read holding registers reply: 555, 0, 100.
        let h = Header { transaction: 1, unit: 17 };
        let reply = encode(h, 3, &Ok(Response::Registers(vec![0x022B, 0x0000, 0x0064])));
        assert_eq!(reply, [0, 1, 0, 0, 0, 9, 17, 0x03, 0x06, 0x02, 0x2B, 0x00, 0x00, 0x00, 0x64]);
        // The read coils reply: 0xCD 0x6B 0x05 for 19 coils.
        let bits: Vec<bool> =
            [0xCDu8, 0x6B, 0x05].iter().flat_map(|b| (0..8).map(move |i| b >> i & 1 == 1)).take(19).collect();
        assert_eq!(&encode(h, 1, &Ok(Response::Bits(bits)))[7..], [0x01, 0x03, 0xCD, 0x6B, 0x05]);
        assert_eq!(&encode(h, 6, &Err(Exception::IllegalDataAddress))[7..], [0x86, 0x02]);
    }

    #[test]
    fn malformed_pdus_are_exception_three_and_unknown_functions_one() {
        for pdu in [
            &[0x03, 0x00, 0x00, 0x00][..],
            &[0x03, 0, 0, 0, 0],
            &[0x03, 0, 0, 0, 126],
            &[0x01, 0, 0, 0x07, 0xD1],
            &[0x05, 0, 0, 0x12, 0x34],
            &[0x0F, 0, 0, 0, 16, 1, 0xFF],
            &[0x0F, 0, 0, 0, 8, 1],
            &[0x10, 0x00, 0x00, 0x80, 0x01, 0x02, 0, 0],
            &[0x10, 0, 0, 0, 2, 4, 0, 1, 0],
            &[0x06, 0, 0, 0],
        ] {
            assert_eq!(decode(pdu).map_err(|e| e.1), Err(Exception::IllegalDataValue), "{pdu:?}");
        }
        assert_eq!(decode(&[0x2B, 0x0E]), Err((0x2B, Exception::IllegalFunction)));
        assert_eq!(decode(&[]), Err((0, Exception::IllegalFunction)));
    }

    #[test]
    fn frames_split_and_packed_and_streams_that_are_not_modbus() {
        let frame = [0, 7, 0, 0, 0, 6, 1, 0x03, 0, 0, 0, 2];
        let mut d = Deframer::default();
        for b in &frame[..11] {
            d.push(std::slice::from_ref(b));
            assert_eq!(d.next_frame(), None);
        }
        d.push(&frame[11..]);
        d.push(&frame);
        for _ in 0..2 {
            assert_eq!(d.next_frame(), Some(Ok((Header { transaction: 7, unit: 1 }, vec![0x03, 0, 0, 0, 2]))));
        }
        assert_eq!(d.pending(), 0);
        d.push(&[0, 1, 0, 5, 0, 6, 1]);
        assert_eq!(d.next_frame(), Some(Err(NotModbus::Protocol(5))));
        let mut d = Deframer::default();
        d.push(&[0, 1, 0, 0, 0xFF, 0xFF, 1]);
        assert_eq!(d.next_frame(), Some(Err(NotModbus::Length(0xFFFF))));
    }
}

//! ROC Plus framing: destination unit and group, source unit and group,
//! opcode, data length (one byte), data, CRC-16/ARC low byte first.
//!
//! A byte stream (TCP, or a serial line) carries frames back to back with
//! nothing between them, and a read may hold part of a frame or several.
//! [`Deframer`] takes whatever arrives and gives back whole frames; when the
//! bytes at the front do not make a frame with a good CRC it drops one byte
//! and looks again, so it finds the next good frame after line noise or a
//! burst of garbage. It never holds more than one frame's bytes beyond what
//! it was last given.

use super::crc::crc16;

/// The bytes before the data: four address bytes, the opcode, the length.
pub const HEADER: usize = 6;
/// The most data a frame carries (its length is one byte).
pub const MAX_DATA: usize = 255;
/// The longest frame on the wire.
pub const MAX_FRAME: usize = HEADER + MAX_DATA + 2;

/// A ROC unit address: unit number and group.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Address {
    pub unit: u8,
    pub group: u8,
}

impl std::fmt::Display for Address {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{},{}", self.unit, self.group)
    }
}

/// One frame, request or reply.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Frame {
    pub dst: Address,
    pub src: Address,
    pub opcode: u8,
    /// At most [`MAX_DATA`] bytes.
    pub data: Vec<u8>,
}

impl Frame {
    /// The frame's bytes on the wire; `None` when the data is longer than a
    /// frame can say.
    pub fn encode(&self) -> Option<Vec<u8>> {
        let len = u8::try_from(self.data.len()).ok()?;
        let mut out = Vec::with_capacity(HEADER + self.data.len() + 2);
        out.extend_from_slice(&[self.dst.unit, self.dst.group, self.src.unit, self.src.group, self.opcode, len]);
        out.extend_from_slice(&self.data);
        let crc = crc16(&out);
        out.extend_from_slice(&crc.to_le_bytes());
        Some(out)
    }

    /// The frame at the start of `bytes` if it is whole and its CRC good:
    /// the frame and its length; `Err(true)` if the bytes are too few yet,
    /// `Err(false)` if they do not start a good frame.
    pub fn decode(bytes: &[u8]) -> Result<(Frame, usize), bool> {
        let Some(&len) = bytes.get(HEADER - 1) else { return Err(true) };
        let total = HEADER + usize::from(len) + 2;
        let Some(whole) = bytes.get(..total) else { return Err(true) };
        let (body, crc) = whole.split_at(total - 2);
        if crc16(body) != u16::from_le_bytes([crc[0], crc[1]]) {
            return Err(false);
        }
        let frame = Frame {
            dst: Address { unit: body[0], group: body[1] },
            src: Address { unit: body[2], group: body[3] },
            opcode: body[4],
            data: body[HEADER..].to_vec(),
        };
        Ok((frame, total))
    }
}

/// Whole frames out of a byte stream (see the module's note).
#[derive(Debug, Default)]
pub struct Deframer {
    buf: Vec<u8>,
    /// Bytes dropped because they began no good frame (line noise, a bad
    /// CRC), for the log.
    pub dropped: u64,
}

impl Deframer {
    /// Takes bytes as they arrive.
    pub fn push(&mut self, bytes: &[u8]) {
        self.buf.extend_from_slice(bytes);
    }

    /// The next whole frame, if the bytes held make one; bytes that start
    /// no good frame are dropped on the way.
    pub fn next_frame(&mut self) -> Option<Frame> {
        let mut start = 0;
        let found = loop {
            match Frame::decode(&self.buf[start..]) {
                Ok((frame, n)) => break Some((frame, start + n)),
                Err(false) => start += 1,
                // Too few bytes for the frame these would start: but if a
                // whole good frame starts further on, these were noise
                // claiming a long length, and waiting for the rest would
                // hold up a host that sends nothing until it is answered.
                // Only the last MAX_FRAME bytes can be in this state, so
                // the look is bounded.
                Err(true) => match (start + 1..self.buf.len()).find(|&s| Frame::decode(&self.buf[s..]).is_ok()) {
                    Some(s) => start = s,
                    None => break None,
                },
            }
        };
        let consumed = found.as_ref().map_or(start, |&(_, n)| n);
        self.dropped += start as u64;
        self.buf.drain(..consumed);
        found.map(|(f, _)| f)
    }

    /// How many bytes wait for the rest of their frame.
    pub fn pending(&self) -> usize {
        self.buf.len()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame(opcode: u8, data: &[u8]) -> Frame {
        Frame { dst: Address { unit: 1, group: 2 }, src: Address { unit: 3, group: 1 }, opcode, data: data.to_vec() }
    }

    #[test]
    fn a_frame_round_trips_with_its_crc_low_byte_first() {
        let f = frame(180, &[1, 3, 0, 2]);
        let bytes = f.encode().unwrap();
        assert_eq!(&bytes[..6], &[1, 2, 3, 1, 180, 4]);
        let crc = crc16(&bytes[..10]);
        assert_eq!(&bytes[10..], &[crc as u8, (crc >> 8) as u8]);
        assert_eq!(Frame::decode(&bytes), Ok((f, 12)));
        assert_eq!(Frame::decode(&bytes[..11]), Err(true));
        let mut bad = bytes.clone();
        bad[7] ^= 1;
        assert_eq!(Frame::decode(&bad), Err(false));
        assert!(frame(1, &[0; 256]).encode().is_none());
    }

    /// Frames published with their CRCs: an opcode 180 request quoted
    /// from a capture (rsdn.org forum, thread 1509298, which also quotes the
    /// specification's CRC paragraph) and the ROC protocol's opcode 17 test
    /// frame of the Go driver abferm/roc (message_test.go), which frames
    /// and checks the same way.
    #[test]
    fn published_frames_decode_with_their_crcs() {
        let capture = [0x01, 0x02, 0x03, 0x01, 0xB4, 0x04, 0x01, 0x2E, 0x00, 0x33, 0xD3, 0xE4];
        let (f, n) = Frame::decode(&capture).unwrap();
        assert_eq!(n, capture.len());
        assert_eq!((f.dst, f.src, f.opcode), (Address { unit: 1, group: 2 }, Address { unit: 3, group: 1 }, 180));
        assert_eq!(f.data, [1, 46, 0, 51], "one parameter: TLP 46,0,51");
        assert_eq!(f.encode().unwrap(), capture);
        let login = [0x01, 0x02, 0x01, 0x00, 0x11, 0x03, b'M', b'O', b'C', 0x85, 0x18];
        let (f, _) = Frame::decode(&login).unwrap();
        assert_eq!((f.opcode, f.data.as_slice()), (17, &b"MOC"[..]));
        assert_eq!(crc16(&capture), 0, "a frame with its CRC checks to zero");
    }

    #[test]
    fn frames_split_over_reads_and_several_in_one_read() {
        let a = frame(180, &[1, 3, 0, 2]);
        let b = frame(7, &[]);
        let mut stream = a.encode().unwrap();
        stream.extend(b.encode().unwrap());
        // Byte by byte.
        let mut d = Deframer::default();
        let mut got = Vec::new();
        for byte in &stream {
            d.push(std::slice::from_ref(byte));
            while let Some(f) = d.next_frame() {
                got.push(f);
            }
        }
        assert_eq!(got, vec![a.clone(), b.clone()]);
        // Both in one read.
        d.push(&stream);
        assert_eq!(d.next_frame(), Some(a));
        assert_eq!(d.next_frame(), Some(b));
        assert_eq!(d.next_frame(), None);
        assert_eq!((d.pending(), d.dropped), (0, 0));
    }

    #[test]
    fn garbage_before_a_frame_is_dropped_and_the_frame_found() {
        let a = frame(180, &[1, 3, 0, 2]);
        let mut d = Deframer::default();
        let mut bad = a.encode().unwrap();
        bad[6] ^= 0xFF; // a bad CRC: no frame
        d.push(&bad);
        d.push(&a.encode().unwrap());
        assert_eq!(d.next_frame(), Some(a));
        assert_eq!(d.dropped, 12);
        assert_eq!(d.next_frame(), None);
    }
}

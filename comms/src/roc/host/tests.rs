//! Every opcode of the module's list run against a scripted device: the
//! request bytes the host sends and the words the reply leaves, each
//! frame written out by hand from docs/roc-protocol.md ("The ROC
//! protocol: FloBoss 107") so that the layouts are checked against the
//! document, not against themselves; then store and forward and every
//! status a command can end with.

use super::commands::{parse, Protocol};
use super::poll::{status, status_text, Host, Link, LinkError};
use super::words::Words;
use crate::roc::{Address, Frame};
use std::collections::VecDeque;

const HEAD: &str = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n";
const ME: Address = Address { unit: 3, group: 1 };
const DEVICE: Address = Address { unit: 25, group: 2 };

/// A reply the device gives: opcode and data, or `None` for silence.
type Reply = Option<(u8, Vec<u8>)>;

/// A device that answers each request with the next scripted reply and
/// keeps every frame it was sent.
struct Script {
    sent: Vec<Frame>,
    replies: VecDeque<Reply>,
}

impl Link for Script {
    fn exchange(&mut self, r: &Frame) -> Result<Frame, LinkError> {
        self.sent.push(r.clone());
        match self.replies.pop_front().flatten() {
            Some((opcode, data)) => Ok(Frame { dst: r.src, src: r.dst, opcode, data }),
            None => Err(LinkError::Timeout),
        }
    }
}

/// What one command did: its status, the frames sent, the words after.
struct Ran {
    code: u16,
    sent: Vec<Frame>,
    words: Vec<u16>,
}

/// Runs the one command of `row` with `words` (runs by start address)
/// against a device answering `replies` in turn.
fn run(row: &str, words: &[(usize, &[u16])], replies: Vec<Reply>) -> Ran {
    let list = parse(&format!("{HEAD}{row}\n"), Protocol::Roc).unwrap();
    let mut table = Words::default();
    for &(at, run) in words {
        table.0[at..at + run.len()].copy_from_slice(run);
    }
    let mut host = Host { me: ME, words: table };
    let mut dev = Script { sent: vec![], replies: replies.into() };
    let code = host.run(&list[0], &mut dev);
    Ran { code, sent: dev.sent, words: host.words.0 }
}

/// The one request frame a run sent to the device, with `opcode`.
fn request(r: &Ran, opcode: u8) -> &[u8] {
    assert_eq!(r.sent.len(), 1, "one request");
    let f = &r.sent[0];
    assert_eq!((f.dst, f.src, f.opcode), (DEVICE, ME, opcode));
    &f.data
}

fn ok(opcode: u8, data: &[u8]) -> Vec<Reply> {
    vec![Some((opcode, data.to_vec()))]
}

/// That nothing but the initial runs is in the words.
fn untouched(r: &Ran, words: &[(usize, &[u16])]) {
    let mut expect = vec![0u16; 4000];
    for &(at, run) in words {
        expect[at..at + run.len()].copy_from_slice(run);
    }
    assert!(r.words == expect, "nothing is stored for a failed command");
}

#[test]
fn opcode_8_sends_cnt_clock_bytes_from_the_words() {
    // 10:15:30 on 14 March 2024: second, minute, hour, day, month, year - 2000.
    let clock: &[u16] = &[30, 15, 10, 14, 3, 24, 0, 5];
    let r = run("1,25,2,8,6,0,0,0,0,0", &[(0, clock)], ok(8, &[]));
    assert_eq!(r.code, status::OK);
    assert_eq!(request(&r, 8), [30, 15, 10, 14, 3, 24]);
    untouched(&r, &[(0, clock)]);
    // CNT 8 adds the leap year and the day of the week.
    let r = run("1,25,2,8,8,0,0,0,0,0", &[(0, clock)], ok(8, &[]));
    assert_eq!(request(&r, 8), [30, 15, 10, 14, 3, 24, 0, 5]);
    // A clock word is a byte; an acknowledgement carries no data.
    let r = run("1,25,2,8,6,0,0,0,0,0", &[(0, &[30, 15, 10, 14, 3, 2024])], ok(8, &[]));
    assert_eq!((r.code, r.sent.len()), (status::BAD_VALUE, 0));
    assert_eq!(run("1,25,2,8,6,0,0,0,0,0", &[(0, clock)], ok(8, &[0])).code, status::INCOMPLETE);
}

#[test]
fn opcode_10_places_the_table_head_and_values_by_type() {
    let ask: &[(usize, &[u16])] = &[(0, &[7, 2, 3])];
    // Version 1.5 (0x3FC00000); three INT values 0x1234, 65535, 1.
    let head = [7, 2, 3, 0x00, 0x00, 0xC0, 0x3F];
    let reply = [&head[..], &[0x34, 0x12, 0xFF, 0xFF, 0x01, 0x00]].concat();
    let r = run("1,25,2,10,3,0,100,2,0,0", ask, ok(10, &reply));
    assert_eq!(r.code, status::OK);
    assert_eq!(request(&r, 10), [7, 2, 3]);
    assert_eq!(r.words[100..109], [7, 2, 3, 0x0000, 0x3FC0, 0x1234, 0xFFFF, 1, 0]);
    // TYPE 4: two words each, low word first (1.0 and -2.0).
    let reply = [&head[..], &[0, 0, 0x80, 0x3F, 0, 0, 0, 0xC0, 1, 2, 3, 4]].concat();
    let r = run("1,25,2,10,3,0,100,4,0,0", ask, ok(10, &reply));
    assert_eq!(r.words[105..112], [0, 0x3F80, 0, 0xC000, 0x0201, 0x0403, 0]);
    // TYPE 1: a byte a word.
    let reply = [&head[..], &[5, 0xAB, 0]].concat();
    let r = run("1,25,2,10,3,0,100,1,0,0", ask, ok(10, &reply));
    assert_eq!(r.words[105..109], [5, 0xAB, 0, 0]);
    // TYPE 0: the values' bytes two a word, an odd last byte low.
    let reply = [&head[..], &[1, 2, 3, 4, 5]].concat();
    let r = run("1,25,2,10,3,0,100,0,0,0", ask, ok(10, &reply));
    assert_eq!((r.code, &r.words[105..109]), (status::OK, &[0x0201, 0x0403, 0x0005, 0][..]));
    for (ty, values, why) in [
        (2, &[0x34, 0x12, 0xFF, 0xFF, 0x01][..], "a byte short of three INT"),
        (2, &[0x34, 0x12, 0xFF, 0xFF, 0x01, 0, 9][..], "a byte long"),
        (0, &[1, 2][..], "fewer bytes than values"),
        (0, &[0; 13][..], "more than 4 bytes a value"),
    ] {
        let r = run(&format!("1,25,2,10,3,0,100,{ty},0,0"), ask, ok(10, &[&head[..], values].concat()));
        assert_eq!(r.code, status::INCOMPLETE, "{why}");
        untouched(&r, ask);
    }
    // Another table's, or another first location's, reply.
    for (i, b) in [(0, 8), (1, 0), (2, 2)] {
        let mut reply = [&head[..], &[0; 6]].concat();
        reply[i] = b;
        assert_eq!(run("1,25,2,10,3,0,100,2,0,0", ask, ok(10, &reply)).code, status::INCOMPLETE, "byte {i}");
    }
}

#[test]
fn opcode_120_fills_the_manuals_layout_word_for_word() {
    // The 26 bytes, each field distinct: alarm pointer 0x0111, event
    // pointer 0x0222, hourly pointers 0x0333 0x0444 0x0555, 2 reserved
    // (0x0666), daily pointers 0x17 0x18 0x19, reserved 0x1A, most
    // alarms and events 240 and 0x0777, days 0x1B 0x1C 0x1D, reserved
    // 0x1E, the audit pointer 0x2F 0x01.
    let reply = [
        0x11, 0x01, 0x22, 0x02, 0x33, 0x03, 0x44, 0x04, 0x55, 0x05, 0x66, 0x06, // six INT
        0x17, 0x18, 0x19, 0x1A, // four BIN
        0xF0, 0x00, 0x77, 0x07, // two INT
        0x1B, 0x1C, 0x1D, 0x1E, 0x2F, 0x01, // six BIN
    ];
    assert_eq!(reply.len(), 26);
    let r = run("1,25,2,120,0,0,200,0,0,0", &[], ok(120, &reply));
    assert_eq!(r.code, status::OK);
    assert_eq!(request(&r, 120), [0u8; 0]);
    // §6.1.2: bytes 0-11 are six INT words; bytes 12-19 four words with
    // the byte in the low byte; 20-23 two INT; 24-35 six BIN words.
    #[rustfmt::skip]
    let words: [u16; 18] = [
        0x0111, 0x0222, 0x0333, 0x0444, 0x0555, 0x0666,
        0x0017, 0x0018, 0x0019, 0x001A,
        0x00F0, 0x0777,
        0x001B, 0x001C, 0x001D, 0x001E, 0x002F, 0x0001,
    ];
    assert_eq!(r.words[200..218], words);
    assert_eq!((r.words[199], r.words[218]), (0, 0), "exactly 18 words");
    for len in [25, 27, 0] {
        let mut short = reply.to_vec();
        short.resize(len, 0);
        let r = run("1,25,2,120,0,0,200,0,0,0", &[], ok(120, &short));
        assert_eq!(r.code, status::INCOMPLETE, "{len} bytes");
        untouched(&r, &[]);
    }
}

/// 128's reply for history point 4 on 15 March at 10:30, the day's first
/// index 0x0102: hour h's value is h (0.0 … 23.0), the daily 1.5, the
/// least 0.0 at 00:00:00 and the greatest 23.0 at 23:00:00, point type 17.
fn day_hours() -> Vec<u8> {
    let mut r = vec![4, 3, 15, 10, 30, 0x02, 0x01];
    for h in 0..24 {
        r.extend((h as f32).to_le_bytes());
    }
    r.extend([0x00, 0x00, 0xC0, 0x3F]); // 1.5
    r.extend([0, 0, 0, 0, 0x00, 0x00, 0xB8, 0x41]); // 0.0, 23.0
    r.extend([0, 0, 0, 15, 3, 0, 0, 23, 15, 3, 17]);
    r.extend([0; 8]);
    r
}

#[test]
fn opcode_128_places_a_days_134_bytes_in_75_words() {
    let ask: &[(usize, &[u16])] = &[(0, &[4, 15, 3])];
    let reply = day_hours();
    assert_eq!(reply.len(), 134);
    let r = run("1,25,2,128,3,0,300,0,0,0", ask, ok(128, &reply));
    assert_eq!(r.code, status::OK);
    assert_eq!(request(&r, 128), [4, 15, 3], "point, day, month");
    let w = &r.words[300..];
    assert_eq!(w[..6], [4, 3, 15, 10, 30, 0x0102]);
    assert_eq!(w[6..12], [0, 0, 0, 0x3F80, 0, 0x4000], "hours 0, 1 and 2: 0.0, 1.0, 2.0, low word first");
    for h in 0..24 {
        let bits = (h as f32).to_bits();
        assert_eq!(w[6 + 2 * h..8 + 2 * h], [bits as u16, (bits >> 16) as u16], "hour {h}");
    }
    assert_eq!(w[54..60], [0, 0x3FC0, 0, 0, 0, 0x41B8], "daily, least, greatest");
    assert_eq!(w[60..71], [0, 0, 0, 15, 3, 0, 0, 23, 15, 3, 17], "the two times, the point type");
    assert_eq!(w[71..76], [0, 0, 0, 0, 0], "8 reserved bytes in 4 words, and no more");
    // A reply for another day (day and month in request order), or short.
    let mut other = reply.clone();
    other.swap(1, 2);
    assert_eq!(run("1,25,2,128,3,0,300,0,0,0", ask, ok(128, &other)).code, status::INCOMPLETE);
    let r = run("1,25,2,128,3,0,300,0,0,0", ask, ok(128, &reply[..133]));
    assert_eq!(r.code, status::INCOMPLETE);
    untouched(&r, ask);
}

#[test]
fn opcode_130_sends_a_word_pointer_and_places_each_value_in_two_words() {
    // Periodic history of point 4: 3 values from pointer 0x1234.
    let ask: &[(usize, &[u16])] = &[(0, &[0, 4, 3, 0x1234])];
    let values = [0, 0, 0x80, 0x3F, 0, 0, 0, 0x40, 0, 0, 0x80, 0xBF]; // 1.0, 2.0, -1.0
    let r = run("1,25,2,130,4,0,400,0,0,0", ask, ok(130, &[&[0, 4, 3][..], &values].concat()));
    assert_eq!(r.code, status::OK);
    assert_eq!(request(&r, 130), [0, 4, 3, 0x34, 0x12]);
    assert_eq!(r.words[400..410], [0, 4, 3, 0, 0x3F80, 0, 0x4000, 0, 0xBF80, 0]);
    // Fewer values than asked (the archive's end): the length follows the count.
    let r = run("1,25,2,130,4,0,400,0,0,0", ask, ok(130, &[&[0, 4, 2][..], &values[..8]].concat()));
    assert_eq!((r.code, &r.words[400..408]), (status::OK, &[0, 4, 2, 0, 0x3F80, 0, 0x4000, 0][..]));
    for (head, body, why) in [
        ([0, 4, 2], &values[..], "12 bytes for 2 values"),
        ([0, 4, 3], &values[..11], "a byte short"),
        ([0, 4, 4], &[&values[..], &[0; 4]].concat()[..], "more values than asked"),
        ([1, 4, 3], &values[..], "daily for periodic"),
        ([0, 5, 3], &values[..], "another point"),
    ] {
        let r = run("1,25,2,130,4,0,400,0,0,0", ask, ok(130, &[&head[..], body].concat()));
        assert_eq!(r.code, status::INCOMPLETE, "{why}");
        untouched(&r, ask);
    }
    // The pointer is a whole word, the others bytes.
    let r = run("1,25,2,130,4,0,400,0,0,0", &[(0, &[0, 300, 3, 0x1234])], vec![]);
    assert_eq!((r.code, r.sent.len()), (status::BAD_VALUE, 0));
}

#[test]
fn values_passing_word_3999_are_status_2_and_nothing_is_stored() {
    let ask: &[(usize, &[u16])] = &[(0, &[0, 4, 2, 0])];
    // From word 3995 one value ends at 3999; two would pass it.
    let r = run("1,25,2,130,4,0,3995,0,0,0", ask, ok(130, &[0, 4, 1, 0, 0, 0x80, 0x3F]));
    assert_eq!((r.code, &r.words[3995..]), (status::OK, &[0, 4, 1, 0, 0x3F80][..]));
    let r = run("1,25,2,130,4,0,3995,0,0,0", ask, ok(130, &[0, 4, 2, 0, 0, 0x80, 0x3F, 0, 0, 0, 0x40]));
    assert_eq!(r.code, status::BAD_ADDRESS);
    untouched(&r, ask);
    let tlps: &[(usize, &[u16])] = &[(0, &[3, 0, 2, 3, 1, 2])];
    let r = run("1,25,2,180,2,0,3999,0,0,0", tlps, ok(180, &[2, 3, 0, 2, 1, 0, 3, 1, 2, 5, 0]));
    assert_eq!(r.code, status::BAD_ADDRESS);
    untouched(&r, tlps);
    let r = run("1,25,2,10,3,0,3995,2,0,0", &[(0, &[7, 0, 1])], ok(10, &[7, 0, 1, 0, 0, 0, 0, 9, 0]));
    assert_eq!(r.code, status::BAD_ADDRESS);
}

#[test]
fn opcodes_180_and_181_run_the_manuals_example() {
    let tlps: &[(usize, &[u16])] = &[(0, &[3, 0, 2, 3, 1, 2]), (100, &[500, 1000])];
    let scan = [2, 3, 0, 2, 1, 0, 3, 1, 2, 5, 0];
    let r = run("1,25,2,180,2,0,50,0,0,0", tlps, ok(180, &scan));
    assert_eq!((r.code, request(&r, 180)), (status::OK, &[2, 3, 0, 2, 3, 1, 2][..]));
    assert_eq!(r.words[50..53], [1, 5, 0]);
    let r = run("1,25,2,180,2,0,50,1,0,0", tlps, ok(180, &scan));
    assert_eq!(r.words[50..59], [3, 0, 2, 1, 3, 1, 2, 5, 0], "TYPE 1 keeps each TLP");
    let r = run("1,25,2,181,2,0,100,2,0,0", tlps, ok(181, &[]));
    assert_eq!((r.code, request(&r, 181)), (status::OK, &[2, 3, 0, 2, 0xF4, 0x01, 3, 1, 2, 0xE8, 0x03][..]));
    let r = run("1,25,2,181,1,0,100,4,0,0", &[(0, &[17, 0, 2]), (100, &[0, 0x4220])], ok(181, &[]));
    assert_eq!(request(&r, 181), [1, 17, 0, 2, 0, 0, 0x20, 0x42], "40.0, low word first");
    let r = run("1,25,2,181,1,0,100,1,0,0", &[(0, &[1, 0, 3]), (100, &[256])], vec![]);
    assert_eq!((r.code, r.sent.len()), (status::BAD_VALUE, 0), "a byte value over 255");
    let mut other = scan;
    other[7] = 9;
    assert_eq!(run("1,25,2,180,2,0,50,0,0,0", tlps, ok(180, &other)).code, status::INCOMPLETE, "another TLP");
    assert_eq!(run("1,25,2,180,2,0,50,0,0,0", tlps, ok(180, &scan[..10])).code, status::INCOMPLETE);
}

/// The path of the store-and-forward tests, at word 40: host 3,1, then
/// relay 10,2, then the device 25,2.
const PATH: [u16; 10] = [3, 1, 10, 2, 25, 2, 0, 0, 0, 0];
const PATH_BYTES: [u8; 10] = [3, 1, 10, 2, 25, 2, 0, 0, 0, 0];
const RELAY: Address = Address { unit: 10, group: 2 };

/// A 180 of TLP 3,0,2 into word 50 by way of the path at word 40.
fn forwarded(replies: Vec<Reply>) -> Ran {
    run("1,10,2,180,1,0,50,0,0,40", &[(0, &[3, 0, 2]), (40, &PATH)], replies)
}

fn wrapped(inner: &[u8]) -> Vec<Reply> {
    ok(24, &[&PATH_BYTES[..], inner].concat())
}

#[test]
fn store_and_forward_wraps_in_24_and_unwraps_the_reply() {
    let r = forwarded(wrapped(&[180, 6, 1, 3, 0, 2, 0xF4, 0x01]));
    assert_eq!(r.code, status::OK);
    assert_eq!(r.sent.len(), 1);
    let f = &r.sent[0];
    assert_eq!((f.dst, f.src, f.opcode), (RELAY, ME, 24), "sent to SLV UNIT, SLV GROUP");
    assert_eq!(f.data, [3, 1, 10, 2, 25, 2, 0, 0, 0, 0, 180, 4, 1, 3, 0, 2]);
    assert_eq!(r.words[50], 500);
    // The final device's error inside, and the relay's own.
    assert_eq!(forwarded(wrapped(&[255, 3, 3, 180, 9])).code, 23);
    assert_eq!(forwarded(ok(255, &[22, 24, 8])).code, 42);
    assert_eq!(status_text(42), "ROC error 22: invalid store and forward path");
    for (reply, why) in [
        (ok(24, &[3, 1, 10, 2, 26, 2, 0, 0, 0, 0, 180, 6, 1, 3, 0, 2, 0xF4, 0x01]), "another path"),
        (wrapped(&[180, 7, 1, 3, 0, 2, 0xF4, 0x01]), "the inner length is not its data's"),
        (wrapped(&[181, 6, 1, 3, 0, 2, 0xF4, 0x01]), "the inner reply is another opcode's"),
        (wrapped(&[180, 4, 1, 3, 0, 2]), "the inner reply has no value"),
        (ok(180, &[1, 3, 0, 2, 0xF4, 0x01]), "not wrapped"),
        (ok(24, &PATH_BYTES[..9]), "shorter than a path"),
    ] {
        let r = forwarded(reply);
        assert_eq!(r.code, status::INCOMPLETE, "{why}");
        assert_eq!(r.words[50], 0, "{why}");
    }
}

#[test]
fn a_path_byte_over_255_and_a_wrap_past_a_frame_are_refused_unsent() {
    let mut bad = PATH;
    bad[4] = 256;
    let r = run("1,10,2,180,1,0,50,0,0,40", &[(0, &[3, 0, 2]), (40, &bad)], vec![]);
    assert_eq!((r.code, r.sent.len()), (status::BAD_VALUE, 0));
    // 81 TLPs are 244 bytes: a frame directly, but not with 12 more.
    let r = run("1,10,2,180,81,0,1000,0,0,0", &[], vec![None]);
    assert_eq!((r.code, r.sent[0].data.len()), (status::TIMEOUT, 244));
    let r = run("1,10,2,180,81,0,1000,0,0,40", &[(40, &PATH)], vec![]);
    assert_eq!((r.code, r.sent.len()), (status::OVERFLOW, 0));
    let r = run("1,10,2,180,85,0,1000,0,0,0", &[], vec![]);
    assert_eq!((r.code, r.sent.len()), (status::OVERFLOW, 0), "85 TLPs pass a frame directly too");
}

#[test]
fn errors_timeouts_and_wrong_replies_have_the_modules_codes() {
    let clock: &[(usize, &[u16])] = &[(0, &[0, 0, 0, 1, 1, 24])];
    let row = "1,25,2,8,6,0,0,0,0,0";
    // The ROC protocol's 255 is code, opcode, offset; ROC Plus's pairs.
    assert_eq!(run(row, clock, ok(255, &[33, 8, 9])).code, 53);
    assert_eq!(run(row, clock, ok(255, &[20, 4])).code, 40);
    assert_eq!(run(row, clock, ok(255, &[])).code, status::INCOMPLETE);
    assert_eq!(run(row, clock, ok(7, &[])).code, status::INCOMPLETE, "another opcode's reply");
    let r = run(row, clock, vec![None, None, None]);
    assert_eq!((r.code, r.sent.len()), (status::TIMEOUT, 3));
    let r = run(row, clock, vec![None, Some((8, vec![]))]);
    assert_eq!((r.code, r.sent.len()), (status::OK, 2), "answered on the second attempt");
    for (code, text) in [
        (33, "outside the valid address range"),
        (34, "invalid history request"),
        (37, "too many alarms"),
        (38, "too many events"),
        (41, "invalid security logon"),
        (83, "requested security level too high"),
    ] {
        assert!(status_text(code).contains(text), "{code}: {}", status_text(code));
    }
}

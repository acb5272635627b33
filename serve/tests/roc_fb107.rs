//! The FB107 example plant as a ROC-protocol device over real TCP on
//! 127.0.0.1, driven by a host written here from the public layouts
//! (docs/roc-protocol.md, "The ROC protocol", after the ROC Protocol
//! Specifications Manual and abferm/roc): its own framing, its CRC from the
//! `crc` crate, its own decoding of every reply — nothing of linc's codec.
//! Values are checked against the monitor's API and the archives against
//! the logger's rules (docs/fst-history.md): an entry at every whole hour,
//! the daily one at midnight, the minute archive by minute of the hour.

mod common;

use common::{api, console_line, T0};
use linc_serve::{Config, Server, Speed};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::{Path, PathBuf};
use std::time::Duration;

const ARC: crc::Crc<u16> = crc::Crc::<u16>::new(&crc::CRC_16_ARC);
const HOST: [u8; 2] = [3, 1];
const DEVICE: [u8; 2] = [1, 2];

/// A copy of examples/roc beside its files, with a task of one second
/// (so a day of plant time is quick to run) and `extra` members added.
fn plant_copy(name: &str, extra: &str) -> PathBuf {
    let dir = Path::new(common::ROOT).join("examples/roc");
    let scratch = linc_test_support::fresh_dir(name);
    for f in ["drain.csv", "sim.stx"] {
        std::fs::copy(dir.join(f), scratch.join(f)).unwrap();
    }
    let text = std::fs::read_to_string(dir.join("plant.json")).unwrap();
    let text = text.replacen('{', &format!(r#"{{ "tasks": {{ "1": {{ "period": 1 }} }}, {extra}"#), 1);
    std::fs::write(scratch.join("plant.json"), text).unwrap();
    scratch.join("plant.json")
}

fn serve_at(db: &Path, unit: u8) -> Server {
    let cfg = Config {
        speed: Speed::Times(0.001),
        allow_writes: true,
        roc: Some(("127.0.0.1:0".parse().unwrap(), linc_comms::roc::Address { unit, group: 2 })),
        ..common::config()
    };
    common::serve(db.to_str().unwrap(), cfg)
}

/// A frame from this host: addresses, opcode, length, data, CRC low first.
fn frame(dst: [u8; 2], opcode: u8, data: &[u8]) -> Vec<u8> {
    let mut f = vec![dst[0], dst[1], HOST[0], HOST[1], opcode, data.len() as u8];
    f.extend_from_slice(data);
    f.extend_from_slice(&ARC.checksum(&f).to_le_bytes());
    f
}

struct Host(TcpStream);

impl Host {
    fn connect(s: &Server) -> Host {
        let t = TcpStream::connect(s.roc_addr().expect("a ROC device")).expect("connect");
        t.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
        Host(t)
    }

    /// One reply: for this host, from `from`, with a good CRC.
    fn reply(&mut self, from: [u8; 2]) -> (u8, Vec<u8>) {
        let mut head = [0u8; 6];
        self.0.read_exact(&mut head).expect("a reply");
        let mut rest = vec![0u8; usize::from(head[5]) + 2];
        self.0.read_exact(&mut rest).expect("the reply's data");
        let (data, crc) = rest.split_at(rest.len() - 2);
        let mut whole = head.to_vec();
        whole.extend_from_slice(data);
        assert_eq!(ARC.checksum(&whole).to_le_bytes(), [crc[0], crc[1]], "the reply's CRC");
        assert_eq!(&head[..4], &[HOST[0], HOST[1], from[0], from[1]], "to the host, from the device");
        (head[4], data.to_vec())
    }

    fn ask_at(&mut self, dst: [u8; 2], opcode: u8, data: &[u8]) -> (u8, Vec<u8>) {
        self.0.write_all(&frame(dst, opcode, data)).unwrap();
        self.reply(DEVICE)
    }

    fn ask(&mut self, opcode: u8, data: &[u8]) -> (u8, Vec<u8>) {
        self.ask_at(DEVICE, opcode, data)
    }

    /// Nothing arrives within `ms`.
    fn silent(&mut self, ms: u64) {
        self.0.set_read_timeout(Some(Duration::from_millis(ms))).unwrap();
        let mut b = [0u8; 1];
        assert!(self.0.read(&mut b).is_err(), "expected no reply");
        self.0.set_read_timeout(Some(Duration::from_secs(10))).unwrap();
    }
}

fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

fn u16_at(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

fn api_f32(s: &Server, block: &str, field: &str) -> f32 {
    api(s, block, field).parse().unwrap()
}

/// Runs the plant `hours` on: ADVANCE lines of two hours (the console's
/// limit is 100,000 scans a line).
fn advance(s: &Server, hours: u32) {
    for _ in 0..hours / 2 {
        console_line(s, "ADVANCE 2h");
    }
    if hours % 2 == 1 {
        console_line(s, "ADVANCE 1h");
    }
}

#[test]
fn configuration_clock_addresses_and_errors() {
    let s = serve_at(&plant_copy("rocp-clock", ""), 1);
    let mut h = Host::connect(&s);
    // Opcode 6: 79 bytes, type of ROC 10, two AIN (type 3) and one SFP (17).
    let (op, d) = h.ask(6, &[]);
    assert_eq!((op, d.len(), d[18], d[19 + 3], d[19 + 17], d[19 + 16]), (6, 79, 10, 2, 1, 1));
    // Opcode 7 at T0, 2026-01-05 06:00:00, a Monday: year 26, 26 mod 4 = 2.
    assert_eq!(T0 % 86_400, 6 * 3600);
    assert_eq!(h.ask(7, &[]), (7, vec![0, 0, 6, 5, 1, 26, 2, 2]));
    // Opcode 8 sets it (six bytes), read back at once.
    assert_eq!(h.ask(8, &[56, 34, 12, 29, 2, 28]), (8, vec![]));
    assert_eq!(h.ask(7, &[]).1[..6], [56, 34, 12, 29, 2, 28]);
    assert_eq!(h.ask(8, &[0, 0, 12, 30, 2, 28]), (255, vec![33, 8, 9]), "30 February");
    // A broadcast to the group sets the clock without a reply; the
    // universal address 240,240 answers from the device's own.
    h.0.write_all(&frame([0, 2], 8, &[0, 0, 9, 1, 3, 28])).unwrap();
    h.silent(300);
    assert_eq!(h.ask_at([240, 240], 7, &[]).1[..6], [0, 0, 9, 1, 3, 28]);
    h.0.write_all(&frame([0, 3], 7, &[])).unwrap();
    h.0.write_all(&frame([7, 2], 7, &[])).unwrap();
    h.silent(300);
    // Errors: code, the request's opcode, the offset of the byte at fault.
    assert_eq!(h.ask(99, &[]), (255, vec![1, 99, 4]));
    assert_eq!(h.ask(7, &[0]), (255, vec![5, 7, 5]));
    assert_eq!(h.ask(180, &[1, 3, 9, 12]), (255, vec![3, 180, 8]));
    // A login of ID and password only (no operators: any is taken).
    assert_eq!(h.ask(17, b"LOI\xE8\x03"), (17, vec![]));
    s.stop();
}

#[test]
fn parameters_contiguous_and_by_configurable_table() {
    let s = serve_at(&plant_copy("rocp-params", ""), 1);
    let mut h = Host::connect(&s);
    // 167: AIN 3-1 (type 3, logical 0) parameter 12 (EU), then 0..=0 (TAG).
    let (op, d) = h.ask(167, &[3, 0, 1, 12]);
    assert_eq!((op, &d[..4]), (167, &[3u8, 0, 1, 12][..]));
    assert_eq!(f32_at(&d, 4), api_f32(&s, "AIN 3-1", "EU"));
    assert_eq!(h.ask(167, &[3, 0, 1, 0]).1[4..], *b"TANK LEVEL");
    assert_eq!(h.ask(167, &[3, 0, 1, 250]), (255, vec![2, 167, 9]), "past the last parameter");
    assert_eq!(h.ask(167, &[3, 7, 1, 0]), (255, vec![3, 167, 7]), "no AIN 3-8");
    // 166: SFP 1 (type 17) DATA1 and DATA2 (parameters 2, 3) in one write.
    let mut w = vec![17, 0, 2, 2];
    w.extend_from_slice(&65.5f32.to_le_bytes());
    w.extend_from_slice(&0.25f32.to_le_bytes());
    assert_eq!(h.ask(166, &w), (166, vec![]));
    assert_eq!((api(&s, "SFP 1", "DATA1"), api(&s, "SFP 1", "DATA2")), ("65.5".into(), "0.25".into()));
    assert_eq!(h.ask(166, &w[..8]), (255, vec![6, 166, 5]), "a value short");
    // 10: table 0 maps the level, the pressure, the setpoint, the cycle
    // count and the level's tag; version 1.0.
    let (op, d) = h.ask(10, &[0, 0, 5]);
    assert_eq!((op, &d[..3], f32_at(&d, 3)), (10, &[0u8, 0, 5][..], 1.0));
    assert_eq!(f32_at(&d, 7), api_f32(&s, "AIN 3-1", "EU"));
    assert_eq!(f32_at(&d, 11), api_f32(&s, "AIN 3-2", "EU"));
    assert_eq!(f32_at(&d, 15), 65.5);
    assert_eq!(f32_at(&d, 19), api_f32(&s, "FST 1", "R2"));
    assert_eq!((&d[23..], d.len()), (&b"TANK LEVEL"[..], 33));
    // 11: the setpoint through the table; an unmapped location is 13.
    let mut w = vec![0, 2, 1];
    w.extend_from_slice(&72.0f32.to_le_bytes());
    assert_eq!(h.ask(11, &w), (11, vec![]));
    assert_eq!(api(&s, "SFP 1", "DATA1"), "72.0");
    assert_eq!(h.ask(10, &[0, 4, 2]), (255, vec![13, 10, 7]));
    assert_eq!(h.ask(10, &[16, 0, 1]), (255, vec![13, 10, 6]));
    s.stop();
}

/// Every whole hour from 07:00 on the first day is in the periodic
/// archive at consecutive indexes; the days' midnights in the daily one.
#[test]
fn history_and_logs_by_pointer_by_day_and_by_minute() {
    let s = serve_at(&plant_copy("rocp-history", ""), 1);
    let mut h = Host::connect(&s);
    // 2026-01-05 06:00 + 43 h = 2026-01-07 01:00.
    advance(&s, 43);
    assert_eq!(h.ask(7, &[]).1[..5], [0, 0, 1, 7, 1]);
    // 120: the logger has written 07:00 (5 Jan) … 01:00 (7 Jan): 43 hourly
    // entries and two midnights; 240 alarms and events at most.
    let (op, p) = h.ask(120, &[]);
    assert_eq!((op, p.len()), (120, 26));
    let (alarm, event, hourly, daily) = (u16_at(&p, 0), u16_at(&p, 2), u16_at(&p, 4), p[12]);
    assert_eq!((hourly, daily, u16_at(&p, 16), u16_at(&p, 18), p[20]), (43, 2, 240, 240, 35));
    // 130, point 254: the stamps (minute, hour, day, month) of 24 entries
    // from index 17, which is 00:00 on 6 January.
    let (op, st) = h.ask(130, &[0, 254, 24, 17, 0]);
    assert_eq!((op, &st[..3]), (130, &[0u8, 254, 24][..]));
    for (i, c) in st[3..].chunks(4).enumerate() {
        assert_eq!(c, [0, i as u8, 6, 1], "entry {} is {i}:00 on 6 January", 17 + i);
    }
    // 128 for 6 January: the 24 hourly values are those 24 entries.
    let (_, by_ptr) = h.ask(130, &[0, 1, 24, 17, 0]);
    let (op, day) = h.ask(128, &[1, 6, 1]);
    assert_eq!((op, day.len(), &day[..7]), (128, 134, &[1u8, 1, 6, 1, 0, 17, 0][..]));
    for i in 0..24 {
        assert_eq!(f32_at(&day, 7 + 4 * i), f32_at(&by_ptr, 3 + 4 * i), "hour {i}");
        assert!((0.0..=100.0).contains(&f32_at(&day, 7 + 4 * i)) && f32_at(&day, 7 + 4 * i) > 0.0);
    }
    let hours: Vec<f32> = (0..24).map(|i| f32_at(&day, 7 + 4 * i)).collect();
    let least = hours.iter().cloned().fold(f32::MAX, f32::min);
    assert_eq!((f32_at(&day, 107), f32_at(&day, 111)), (least, hours.iter().cloned().fold(f32::MIN, f32::max)));
    let at = hours.iter().position(|&v| v == least).unwrap() as u8;
    assert_eq!(day[115..120], [0, 0, at, 6, 1], "the least value's time");
    assert_eq!(day[125], 3, "the archived parameter is an AIN");
    // The daily value of 6 January is the daily entry stamped that
    // midnight (index 0), read by pointer too.
    let (_, d) = h.ask(130, &[1, 1, 1, 0, 0]);
    assert_eq!(f32_at(&day, 103), f32_at(&d, 3));
    assert_eq!(h.ask(130, &[1, 254, 2, 0, 0]).1[3..], [0, 0, 6, 1, 0, 0, 7, 1]);
    // 126: the minute archive, the minute now (01:00 → 0).
    let (op, m) = h.ask(126, &[1]);
    assert_eq!((op, m.len(), m[..2].to_vec()), (126, 242, vec![1, 0]));
    assert!(m[2..].chunks(4).all(|c| f32::from_le_bytes(c.try_into().unwrap()) > 0.0), "every minute logged");
    // 121 and 122: the drain table alarms when the valve opens and logs an
    // event when it closes; the newest record is just before the pointer.
    let newest = (alarm + 239) % 240;
    let (op, a) = h.ask(121, &[1, newest as u8, (newest >> 8) as u8]);
    assert_eq!((op, a[0], u16_at(&a, 1), u16_at(&a, 3), a.len()), (121, 1, newest, alarm, 27));
    assert_eq!((a[5], a[6], &a[13..23]), (0x42, 1, &b"TANK HIGH "[..]));
    assert!(f32_at(&a, 23) >= 72.0, "the level when the valve opened");
    let newest = (event + 239) % 240;
    let (_, e) = h.ask(122, &[1, newest as u8, (newest >> 8) as u8]);
    assert_eq!((e[5], &e[13..23]), (3, &b"DRAIN STOP"[..]));
    assert_eq!(h.ask(121, &[11, 0, 0]), (255, vec![17, 121, 6]));
    // Errors: no history point 9, a type 2, a month 13.
    assert_eq!(h.ask(126, &[9]), (255, vec![14, 126, 6]));
    assert_eq!(h.ask(130, &[2, 1, 1, 0, 0]), (255, vec![14, 130, 6]));
    assert_eq!(h.ask(128, &[1, 1, 13]), (255, vec![14, 128, 8]));
    s.stop();
}

/// The host reaches device 5,2 through 1,2: the relay passes the wrapped
/// request on over its link and brings the answer back.
#[test]
fn store_and_forward_reaches_a_device_behind_another() {
    let far = serve_at(&plant_copy("rocp-far", ""), 5);
    console_line(&far, "M SFP 1.DATA1=55.5");
    let link = format!(r#""roc": {{ "forward": {{ "5,2": "{}" }} }},"#, far.roc_addr().unwrap());
    let relay_db = plant_copy("rocp-relay", &link);
    // The copy now has two "roc" members; the second (the example's) would
    // win, so drop it.
    let text = std::fs::read_to_string(&relay_db).unwrap();
    let example = r#""roc": { "forward": { "5,2": "127.0.0.1:4001" } },"#;
    std::fs::write(&relay_db, text.replace(example, "")).unwrap();
    let relay = serve_at(&relay_db, 1);
    let mut h = Host::connect(&relay);
    // Path: host 3,1, then 1,2 and 5,2; the wrapped request reads SFP 1 DATA1.
    let path = [3, 1, 1, 2, 5, 2, 0, 0, 0, 0];
    let mut req = path.to_vec();
    req.extend_from_slice(&[180, 4, 1, 17, 0, 2]);
    let (op, d) = h.ask(24, &req);
    assert_eq!((op, &d[..10], d[10], d[11]), (24, &path[..], 180, 8), "{d:?}");
    assert_eq!((&d[12..16], f32_at(&d, 16)), (&[1u8, 17, 0, 2][..], 55.5));
    assert_eq!(api(&relay, "SFP 1", "DATA1"), "80.0", "the relay's own is another value");
    // An error at the far device comes back wrapped: opcode 255 inside.
    let mut bad = path.to_vec();
    bad.extend_from_slice(&[180, 4, 1, 17, 9, 2]);
    let (op, d) = h.ask(24, &bad);
    assert_eq!((op, d[10], &d[11..]), (24, 255, &[3u8, 3, 180, 8][..]));
    // No link to 7,2: error 22 from the relay.
    let mut lost = vec![3, 1, 1, 2, 7, 2, 0, 0, 0, 0];
    lost.extend_from_slice(&[7, 0]);
    assert_eq!(h.ask(24, &lost), (255, vec![22, 24, 8]));
    // A path that names a device twice could circle: refused at once.
    let mut circle = vec![3, 1, 1, 2, 5, 2, 1, 2, 0, 0];
    circle.extend_from_slice(&[7, 0]);
    assert_eq!(h.ask(24, &circle), (255, vec![22, 24, 8]));
    // The far device answers a 24 that ends there itself.
    let mut direct = Host::connect(&far);
    direct.0.write_all(&frame([5, 2], 24, &req)).unwrap();
    let (op, d) = direct.reply([5, 2]);
    assert_eq!((op, f32_at(&d, 16)), (24, 55.5));
    relay.stop();
    far.stop();
}

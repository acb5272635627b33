//! The ROC device over real TCP on 127.0.0.1 (ROC Plus for the ROC800
//! plant of examples/fst, the ROC protocol for the FB107 example of
//! examples/roc, whose 180/181, login and error paths these share), driven by a client
//! written here from the public frame layout (its own framing, and its CRC
//! from the `crc` crate's CRC-16/ARC, not the server's table): reads agree
//! with the monitor's API, writes are all or nothing under the console's
//! rules, and bad frames, other addresses, split and packed frames behave
//! as the protocol expects.

mod common;

use common::{api, console_line};
use linc_serve::{Config, Server, Speed};
use serde_json::Value;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::path::Path;
use std::time::Duration;

const ROOT: &str = common::ROOT;
const ARC: crc::Crc<u16> = crc::Crc::<u16>::new(&crc::CRC_16_ARC);

fn serve(db: &str, writes: bool) -> Server {
    serve_traced(db, writes, None)
}

fn serve_traced(db: &str, writes: bool, trace: Option<&Path>) -> Server {
    let cfg = Config {
        // A scan every 100 s of wall time: the values hold still while
        // the test compares the wire with the API.
        speed: Speed::Times(0.001),
        allow_writes: writes,
        roc: Some(("127.0.0.1:0".parse().unwrap(), linc_comms::roc::Address { unit: 1, group: 2 })),
        trace: trace.map(|p| linc_driver::files::AtomicFile::create(p).expect("trace file")),
        ..common::config()
    };
    common::serve(db, cfg)
}

/// A frame from host 3,1 to `dst`, as the layout says: addresses, opcode,
/// length, data, CRC low byte first.
fn frame(dst: [u8; 2], opcode: u8, data: &[u8]) -> Vec<u8> {
    let mut f = vec![dst[0], dst[1], 3, 1, opcode, data.len() as u8];
    f.extend_from_slice(data);
    let crc = ARC.checksum(&f);
    f.extend_from_slice(&crc.to_le_bytes());
    f
}

struct Host(TcpStream);

impl Host {
    fn connect(s: &Server) -> Host {
        let t = TcpStream::connect(s.roc_addr().expect("a ROC device")).expect("connect");
        t.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
        Host(t)
    }

    /// Reads one reply: checks it is for this host, from the device, with
    /// a good CRC; returns its opcode and data.
    fn reply(&mut self) -> (u8, Vec<u8>) {
        let mut head = [0u8; 6];
        self.0.read_exact(&mut head).expect("a reply");
        let mut rest = vec![0u8; usize::from(head[5]) + 2];
        self.0.read_exact(&mut rest).expect("the reply's data");
        let (data, crc) = rest.split_at(rest.len() - 2);
        let mut whole = head.to_vec();
        whole.extend_from_slice(data);
        assert_eq!(ARC.checksum(&whole).to_le_bytes(), [crc[0], crc[1]], "the reply's CRC");
        assert_eq!(&head[..4], &[3, 1, 1, 2], "to the host, from the device");
        (head[4], data.to_vec())
    }

    fn ask(&mut self, opcode: u8, data: &[u8]) -> (u8, Vec<u8>) {
        self.0.write_all(&frame([1, 2], opcode, data)).unwrap();
        self.reply()
    }

    /// Nothing arrives within `ms`.
    fn silent(&mut self, ms: u64) {
        self.0.set_read_timeout(Some(Duration::from_millis(ms))).unwrap();
        let mut b = [0u8; 1];
        let got = self.0.read(&mut b);
        assert!(got.is_err(), "expected no reply, got {got:?}");
        self.0.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    }
}

fn f32_at(b: &[u8], at: usize) -> f32 {
    f32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

#[test]
fn reads_agree_with_the_monitor() {
    let s = serve("examples/roc/plant.json", true);
    let mut h = Host::connect(&s);
    // AIN 3-1 EU (FL), AIN 3-2 EU, SFP 1 DATA1, AIN 3-1 TAG (AC10),
    // FST 1 RUNFLG (UINT8), AIN 3-1 SCANPR (UINT16).
    let (op, d) = h.ask(180, &[6, 3, 0, 12, 3, 1, 12, 17, 0, 2, 3, 0, 0, 16, 0, 24, 3, 0, 2]);
    assert_eq!(op, 180, "{d:?}");
    assert_eq!(d[0], 6);
    assert_eq!(&d[1..4], &[3, 0, 12]);
    assert_eq!(f32_at(&d, 4).to_string(), api(&s, "AIN 3-1", "EU").trim_end_matches(".0"));
    assert_eq!(&d[8..11], &[3, 1, 12]);
    assert_eq!(f32_at(&d, 11), api(&s, "AIN 3-2", "EU").parse::<f32>().unwrap());
    assert_eq!(f32_at(&d, 18), api(&s, "SFP 1", "DATA1").parse::<f32>().unwrap());
    assert_eq!(&d[22..25], &[3, 0, 0]);
    assert_eq!(&d[25..35], b"TANK LEVEL");
    assert_eq!(format!("'{}'", std::str::from_utf8(&d[25..35]).unwrap()), api(&s, "AIN 3-1", "TAG"));
    assert_eq!(&d[35..38], &[16, 0, 24]);
    assert_eq!(i64::from(d[38]).to_string(), api(&s, "FST 1", "RUNFLG"));
    assert_eq!(&d[39..42], &[3, 0, 2]);
    assert_eq!(u16::from_le_bytes([d[42], d[43]]), 1, "SCANPR 1.0 s as a whole number");
    assert_eq!(d.len(), 44);
    s.stop();
}

#[test]
fn writes_are_all_or_nothing_under_the_consoles_rules() {
    let s = serve("examples/roc/plant.json", true);
    let mut h = Host::connect(&s);
    // SFP 1 DATA1 := 65.5 and AIN 3-1 SCANPR := 500 in one request.
    let mut w = vec![2, 17, 0, 2];
    w.extend_from_slice(&65.5f32.to_le_bytes());
    w.extend_from_slice(&[3, 0, 2]);
    w.extend_from_slice(&500u16.to_le_bytes());
    assert_eq!(h.ask(181, &w), (181, vec![]));
    assert_eq!(api(&s, "SFP 1", "DATA1"), "65.5");
    assert_eq!(api(&s, "AIN 3-1", "SCANPR"), "500.0");
    // With a read-only parameter (AIN ALARM, P 14) second: error 19 at its
    // parameter byte, and the first value is not written either.
    let mut w = vec![2, 17, 0, 2];
    w.extend_from_slice(&1.0f32.to_le_bytes());
    w.extend_from_slice(&[3, 0, 14, 0]);
    assert_eq!(h.ask(181, &w), (255, vec![19, 181, 6 + 1 + 7 + 2]));
    assert_eq!(api(&s, "SFP 1", "DATA1"), "65.5");
    // A forced field keeps its forced value: error 51 at the point type.
    console_line(&s, "F SFP 1.DATA2=0.3");
    let mut w = vec![1, 17, 0, 3];
    w.extend_from_slice(&9.0f32.to_le_bytes());
    assert_eq!(h.ask(181, &w), (255, vec![51, 181, 7]));
    assert_eq!(api(&s, "SFP 1", "DATA2"), "0.3");
    // A value the field can't hold (a REAL must be finite): error 25 at
    // the parameter byte; a value of the wrong size is a length error.
    let mut w = vec![1, 17, 0, 2];
    w.extend_from_slice(&f32::NAN.to_le_bytes());
    assert_eq!(h.ask(181, &w), (255, vec![25, 181, 9]));
    assert_eq!(h.ask(181, &[1, 16, 0, 19, 7, 0]), (255, vec![5, 181, 5]), "MISC1 is one byte");
    assert_eq!(h.ask(181, &[1, 17, 0, 2, 0, 0]), (255, vec![6, 181, 5]), "DATA1 is four bytes");
    // An unknown point type, logical number and parameter.
    assert_eq!(h.ask(181, &[1, 99, 0, 2, 0, 0, 0, 0]), (255, vec![4, 181, 7]));
    assert_eq!(h.ask(180, &[1, 3, 5, 12]), (255, vec![3, 180, 8]));
    assert_eq!(h.ask(180, &[2, 3, 0, 12, 3, 0, 99]), (255, vec![2, 180, 12]));
    // An opcode the device does not know.
    assert_eq!(h.ask(99, &[]), (255, vec![1, 99, 4]));
    s.stop();
}

#[test]
fn a_read_only_server_refuses_writes_with_a_security_error() {
    let s = serve("examples/roc/plant.json", false);
    let mut h = Host::connect(&s);
    let mut w = vec![1, 17, 0, 2];
    w.extend_from_slice(&1.0f32.to_le_bytes());
    assert_eq!(h.ask(181, &w), (255, vec![20, 181, 4]));
    assert_eq!(api(&s, "SFP 1", "DATA1"), "80.0");
    assert_eq!(h.ask(8, &[0, 0, 12, 1, 6, 25]), (255, vec![20, 8, 4]));
    s.stop();
}

#[test]
fn bad_crcs_and_other_addresses_get_no_reply_and_frames_may_split_or_pack() {
    let s = serve("examples/roc/plant.json", true);
    let mut h = Host::connect(&s);
    let read = frame([1, 2], 180, &[1, 17, 0, 2]);
    let mut bad = read.clone();
    *bad.last_mut().unwrap() ^= 0xFF;
    h.0.write_all(&bad).unwrap();
    h.silent(300);
    h.0.write_all(&frame([9, 9], 180, &[1, 17, 0, 2])).unwrap();
    h.silent(300);
    // Byte by byte.
    for b in &read {
        h.0.write_all(std::slice::from_ref(b)).unwrap();
        std::thread::sleep(Duration::from_millis(5));
    }
    assert_eq!(h.reply().0, 180);
    // Two in one write, the second after noise.
    let mut two = read.clone();
    two.extend_from_slice(&[0x55, 0xAA, 0x00]);
    two.extend_from_slice(&frame([1, 2], 7, &[]));
    h.0.write_all(&two).unwrap();
    assert_eq!(h.reply().0, 180);
    assert_eq!(h.reply().0, 7);
    s.stop();
}

#[test]
fn the_clock_is_set_and_read_and_the_configuration_counts_points() {
    let s = serve("examples/fst/plant.json", true);
    let mut h = Host::connect(&s);
    let (op, d) = h.ask(7, &[]);
    assert_eq!((op, &d[..7]), (7, &[0, 0, 6, 5, 1, 0xEA, 0x07][..]), "2026-01-05 06:00:00");
    assert_eq!(d[7], 2, "a Monday");
    assert_eq!(h.ask(8, &[30, 15, 12, 29, 2, 0xE8, 0x07]), (8, vec![]), "2024-02-29 12:15:30");
    let (_, d) = h.ask(7, &[]);
    assert_eq!(&d[..7], &[30, 15, 12, 29, 2, 0xE8, 0x07]);
    assert_eq!(d[7], 5, "a Thursday");
    assert_eq!(h.ask(8, &[0, 0, 0, 30, 2, 0xE8, 0x07]), (255, vec![33, 9]), "no 30 February");
    let (op, d) = h.ask(6, &[]);
    assert_eq!((op, d.len(), d[18]), (6, 215, 6));
    let count = |t: usize| d[19 + t - 60];
    assert_eq!((count(96), count(98), count(102), count(103), count(104)), (4, 2, 3, 2, 0));
    // ROC Plus (this plant is a ROC800) answers an error with code and
    // offset; the FB107 example above adds the opcode between them.
    assert_eq!(h.ask(99, &[]), (255, vec![1, 4]));
    s.stop();
}

#[test]
fn the_trace_records_each_write_and_refusal_with_the_clients_address() {
    let dir = linc_test_support::fresh_dir("roc-trace");
    let path = dir.join("trace.jsonl");
    let s = serve_traced("examples/roc/plant.json", true, Some(&path));
    let mut h = Host::connect(&s);
    let me = h.0.local_addr().unwrap().to_string();
    let mut w = vec![1, 17, 0, 2];
    w.extend_from_slice(&65.5f32.to_le_bytes());
    assert_eq!(h.ask(181, &w), (181, vec![]));
    console_line(&s, "F SFP 1.DATA2=0.3");
    let mut w = vec![1, 17, 0, 3];
    w.extend_from_slice(&9.0f32.to_le_bytes());
    assert_eq!(h.ask(181, &w).0, 255);
    // A value the field can't hold (not a number) is refused and traced too.
    let mut w = vec![1, 17, 0, 3];
    w.extend_from_slice(&f32::NAN.to_le_bytes());
    assert_eq!(h.ask(181, &w).0, 255);
    let done = s.stop();
    assert_eq!(done.trace_error, None);
    let text = std::fs::read_to_string(&path).expect("the trace was written at the stop");
    let lines: Vec<Value> = text.lines().map(|l| serde_json::from_str(l).expect("JSON line")).collect();
    let client = format!("roc {me}");
    let wrote =
        lines.iter().find(|l| l["client"] == client.as_str() && l["field"] == "SFP 1.DATA1").expect("the write");
    assert_eq!((wrote["old"].as_str(), wrote["new"].as_str()), (Some("80.0"), Some("65.5")));
    let refused = lines.iter().find(|l| l["refused"] == "forced").expect("the refused write");
    assert_eq!((refused["client"].as_str(), refused["field"].as_str()), (Some(client.as_str()), Some("SFP 1.DATA2")));
    let refused = lines.iter().find(|l| l["refused"] == "value").expect("the write refused for its value");
    assert_eq!((refused["client"].as_str(), refused["field"].as_str()), (Some(client.as_str()), Some("SFP 1.DATA2")));
}

#[test]
fn the_logs_and_archives_the_fsts_wrote_are_collected() {
    let s = serve("examples/fst/plant.json", true);
    // Two hours, then a stuck level transmitter reads high (FST 1 logs
    // its HIGH LEVEL alarm), then an hour more.
    console_line(&s, "ADVANCE 2h");
    console_line(&s, "F AIN 2-1.EU=95");
    console_line(&s, "ADVANCE 1h");
    let mut h = Host::connect(&s);
    // Events: PUMP ON and PUMP OFF from FST 1 (the first FST point).
    let (op, d) = h.ask(119, &[10, 0, 0]);
    assert_eq!(op, 119, "{d:?}");
    let (sent, current) = (d[0], u16::from_le_bytes([d[3], d[4]]));
    assert_eq!((sent, &d[1..3]), (10, &[0u8, 0][..]));
    assert!(current >= 2, "events logged: {current}");
    let first = &d[5..27];
    assert_eq!((first[0], first[5]), (3, 1), "an FST event from FST 1");
    assert_eq!(&first[10..20], b"PUMP ON   ");
    let start = 1_767_592_800u32; // 2026-01-05 06:00, the run's start
    let t = u32::from_le_bytes(first[1..5].try_into().unwrap());
    assert!(t > start && t < start + 3 * 3600, "{t}");
    // Slots past the current index were never written: zeros.
    assert!(d[5 + 22 * usize::from(current)..5 + 22 * (usize::from(current) + 1)].iter().all(|&b| b == 0));
    // Alarms: FST 1's high level alarm, as an FST alarm (set).
    let (op, d) = h.ask(118, &[1, 0, 0]);
    assert_eq!(op, 118);
    let a = &d[5..28];
    assert_eq!((a[0], a[5], &a[6..19]), (0x42, 1, &b"HIGH LEVEL   "[..]), "{a:?}");
    assert_eq!(f32::from_le_bytes(a[19..23].try_into().unwrap()), 95.0);
    assert_eq!(u32::from_le_bytes(a[1..5].try_into().unwrap()), start + 7200);
    assert_eq!(h.ask(118, &[11, 0, 0]), (255, vec![17, 6]));
    // History point 3 samples the tank level every 60 minutes: three
    // periodic entries, stamped on the hour.
    let (op, d) = h.ask(135, &[0, 3, 3, 0, 0, 3]);
    assert_eq!(op, 135, "{d:?}");
    assert_eq!((d[0], d[1], u16::from_le_bytes([d[2], d[3]]), d[4]), (0, 3, 3, 3));
    let stamps: Vec<u32> = d[5..].chunks(4).map(|c| u32::from_le_bytes(c.try_into().unwrap())).collect();
    assert_eq!(stamps, vec![start + 3600, start + 7200, start + 10800]);
    let (_, d) = h.ask(135, &[0, 3, 1, 0, 0, 3]);
    let levels: Vec<f32> = d[5..].chunks(4).map(|c| f32::from_le_bytes(c.try_into().unwrap())).collect();
    assert!(levels.iter().all(|l| (0.0..=100.0).contains(l) && *l != 0.0), "{levels:?}");
    // 136: the same point, one period at a time, stamped.
    let (op, d) = h.ask(136, &[0, 0, 0, 1, 3, 1, 3]);
    assert_eq!(op, 136, "{d:?}");
    assert_eq!(d[5], 6, "(1 point + 1 stamp) x 3 periods");
    assert_eq!(u32::from_le_bytes(d[6..10].try_into().unwrap()), start + 3600);
    assert_eq!(f32::from_le_bytes(d[10..14].try_into().unwrap()), levels[0]);
    assert_eq!(h.ask(135, &[0, 77, 1, 0, 0, 1]), (255, vec![30, 7]), "no history point 77");
    s.stop();
}

/// Opcode 135's timestamps of history point 3 from index 0, and the
/// current index.
fn stamps(h: &mut Host, count: u8) -> (Vec<u32>, u16) {
    let (op, d) = h.ask(135, &[0, 3, 3, 0, 0, count]);
    assert_eq!(op, 135, "{d:?}");
    (d[5..].chunks(4).map(|c| u32::from_le_bytes(c.try_into().unwrap())).collect(), u16::from_le_bytes([d[2], d[3]]))
}

#[test]
fn setting_the_clock_ahead_fills_the_history_it_jumped_and_back_logs_nothing() {
    let s = serve("examples/fst/plant.json", true);
    let start = 1_767_592_800u32; // 2026-01-05 06:00
    console_line(&s, "ADVANCE 1h");
    let mut h = Host::connect(&s);
    // 07:00:00 to 10:00:00 the same day: 08:00, 09:00 and 10:00 are filled
    // at the next instant a task runs.
    assert_eq!(h.ask(8, &[0, 0, 10, 5, 1, 0xEA, 0x07]), (8, vec![]));
    console_line(&s, "ADVANCE 1s");
    let hour = |n: u32| start + n * 3600;
    assert_eq!(stamps(&mut h, 4), (vec![hour(1), hour(2), hour(3), hour(4)], 4));
    // Back to 08:30: nothing is logged until 09:00 comes round again,
    // which is logged at the next index.
    assert_eq!(h.ask(8, &[0, 30, 8, 5, 1, 0xEA, 0x07]), (8, vec![]));
    console_line(&s, "ADVANCE 20m");
    assert_eq!(stamps(&mut h, 4).1, 4, "nothing logged going back");
    console_line(&s, "ADVANCE 20m");
    assert_eq!(stamps(&mut h, 5), (vec![hour(1), hour(2), hour(3), hour(4), hour(3)], 5));
    s.stop();
}

#[test]
fn with_operators_a_host_logs_in_before_it_reads_or_writes() {
    // The example plant with two operators, beside its files.
    let dir = Path::new(ROOT).join("examples/roc");
    let text = std::fs::read_to_string(dir.join("plant.json")).unwrap();
    let with_users = text.replacen(
        '{',
        r#"{ "users": { "LOI": { "password": 1000, "level": 5 }, "RO": { "password": 7, "level": 0 } },"#,
        1,
    );
    let scratch = linc_test_support::fresh_dir("roc-users");
    for f in ["drain.csv", "sim.stx"] {
        std::fs::copy(dir.join(f), scratch.join(f)).unwrap();
    }
    std::fs::write(scratch.join("plant.json"), with_users).unwrap();
    let s = serve(scratch.join("plant.json").to_str().unwrap(), true);
    let mut h = Host::connect(&s);
    let read = [1, 17, 0, 2];
    assert_eq!(h.ask(180, &read), (255, vec![20, 180, 4]), "not logged in");
    assert_eq!(h.ask(6, &[]).0, 6, "the configuration needs no login");
    assert_eq!(h.ask(17, &[b'L', b'O', b'I', 0xE9, 0x03, 5]), (255, vec![21, 17, 6]), "wrong password");
    assert_eq!(h.ask(17, &[b'R', b'O', b' ', 7, 0, 1]), (255, vec![63, 17, 11]), "level too high");
    assert_eq!(h.ask(17, &[b'R', b'O', b' ', 7, 0, 0]), (17, vec![]));
    assert_eq!(h.ask(180, &read).0, 180, "level 0 reads");
    let mut w = vec![1, 17, 0, 2];
    w.extend_from_slice(&1.0f32.to_le_bytes());
    assert_eq!(h.ask(181, &w), (255, vec![20, 181, 4]), "level 0 does not write");
    assert_eq!(h.ask(17, &[b'L', b'O', b'I', 0xE8, 0x03, 5]), (17, vec![]));
    assert_eq!(h.ask(181, &w), (181, vec![]));
    assert_eq!(h.ask(17, b"LOI\xE8\x03LOGOFF"), (255, vec![77, 17, 11]));
    assert_eq!(h.ask(17, b"LOI\xE8\x03LOGOUT"), (17, vec![]));
    assert_eq!(h.ask(180, &read), (255, vec![20, 180, 4]), "logged out");
    // The ROC protocol's short login (ID and password, no level) takes the
    // operator's own level: RO reads and may not write.
    assert_eq!(h.ask(17, b"RO \x07\x00"), (17, vec![]));
    assert_eq!(h.ask(180, &read).0, 180);
    assert_eq!(h.ask(181, &w), (255, vec![20, 181, 4]), "RO is level 0");
    // The login belongs to the connection: another starts logged out.
    let mut other = Host::connect(&s);
    assert_eq!(other.ask(180, &read), (255, vec![20, 180, 4]));
    s.stop();
}

//! The ROC device (the FB107 example: the ROC protocol) on a serial port (`--roc-serial`), over a
//! pseudo-terminal pair the test opens itself: the server opens the slave
//! by its path, as it would `/dev/ttyUSB0`, and the test is the host on
//! the master side, with its own framing and CRC (the `crc` crate's
//! CRC-16/ARC, not the server's table). Frames are found in the byte
//! stream as over TCP, a quiet line is kept, and a line that fails is
//! opened again without stopping the server.
#![cfg(unix)]

mod common;

use common::{api, eventually};
use linc_comms::roc::Address;
use linc_comms::serial::Line;
use linc_serve::{Config, Server, Speed};
use serialport::{SerialPort, TTYPort};
use std::io::{Read, Write};
use std::sync::{Arc, Mutex};
use std::time::Duration;

const ARC: crc::Crc<u16> = crc::Crc::<u16>::new(&crc::CRC_16_ARC);
const ME: Address = Address { unit: 1, group: 2 };

/// AIN 3-1 EU, AIN 3-2 EU and SFP 1 DATA1 (all floats): opcode 180's data.
const READ3: [u8; 10] = [3, 3, 0, 12, 3, 1, 12, 17, 0, 2];

/// A frame from host 3,1 to `dst`: addresses, opcode, length, data, CRC
/// low byte first.
fn frame(dst: [u8; 2], opcode: u8, data: &[u8]) -> Vec<u8> {
    let mut f = vec![dst[0], dst[1], 3, 1, opcode, data.len() as u8];
    f.extend_from_slice(data);
    f.extend_from_slice(&ARC.checksum(&f).to_le_bytes());
    f
}

/// A served example plant whose ROC device is on a fresh pseudo-terminal
/// (and on TCP too), with its log kept. The slave end stays open in the
/// test as well, so the terminal is not hung up between the server's
/// opens of it.
struct Line1 {
    server: Server,
    master: TTYPort,
    _slave: TTYPort,
    log: Arc<Mutex<Vec<String>>>,
}

fn serve(idle: Duration) -> Line1 {
    let (mut master, slave) = TTYPort::pair().expect("a pseudo-terminal pair");
    master.set_timeout(Duration::from_secs(5)).unwrap();
    let path = slave.name().expect("the slave's path");
    let log = Arc::new(Mutex::new(Vec::new()));
    let kept = log.clone();
    let cfg = Config {
        // A scan every 100 s of wall time: the values hold still while
        // the test compares the wire with the API.
        speed: Speed::Times(0.001),
        allow_writes: true,
        roc: Some(("127.0.0.1:0".parse().unwrap(), ME)),
        roc_serial: Some((path.into(), Line::new(19200), ME)),
        limits: linc_serve::Limits { idle, ..Default::default() },
        log: Arc::new(move |l| kept.lock().unwrap().push(l)),
        ..common::config()
    };
    Line1 { server: common::serve("examples/roc/plant.json", cfg), master, _slave: slave, log }
}

impl Line1 {
    /// Reads one reply off the line: for this host, from the device, with
    /// a good CRC; its opcode and data.
    fn reply(&mut self) -> (u8, Vec<u8>) {
        let mut head = [0u8; 6];
        self.master.read_exact(&mut head).expect("a reply");
        let mut rest = vec![0u8; usize::from(head[5]) + 2];
        self.master.read_exact(&mut rest).expect("the reply's data");
        let (data, crc) = rest.split_at(rest.len() - 2);
        let mut whole = head.to_vec();
        whole.extend_from_slice(data);
        assert_eq!(ARC.checksum(&whole).to_le_bytes(), [crc[0], crc[1]], "the reply's CRC");
        assert_eq!(&head[..4], &[3, 1, 1, 2], "to the host, from the device");
        (head[4], data.to_vec())
    }

    /// Nothing arrives within `ms`.
    fn silent(&mut self, ms: u64) {
        self.master.set_timeout(Duration::from_millis(ms)).unwrap();
        let mut b = [0u8; 1];
        let got = self.master.read(&mut b);
        assert!(got.is_err(), "expected no reply, got {got:?} ({b:?})");
        self.master.set_timeout(Duration::from_secs(5)).unwrap();
    }

    /// Checks a reply to [`READ3`] against the monitor's API.
    fn check_read3(&mut self) {
        let (op, d) = self.reply();
        assert_eq!((op, d.len()), (180, 22), "{d:?}");
        let value = |at: usize| f32::from_le_bytes(d[at..at + 4].try_into().unwrap());
        let s = &self.server;
        assert_eq!(&d[..4], &[3, 3, 0, 12]);
        assert_eq!(value(4), api(s, "AIN 3-1", "EU").parse::<f32>().unwrap());
        assert_eq!(&d[8..11], &[3, 1, 12]);
        assert_eq!(value(11), api(s, "AIN 3-2", "EU").parse::<f32>().unwrap());
        assert_eq!(&d[15..18], &[17, 0, 2]);
        assert_eq!(value(18), api(s, "SFP 1", "DATA1").parse::<f32>().unwrap());
    }

    fn log_has(&self, text: &str) -> bool {
        self.log.lock().unwrap().iter().any(|l| l.contains(text))
    }
}

#[test]
fn frames_split_packed_and_after_noise_are_answered_from_the_plant() {
    let mut l = serve(Duration::from_secs(60));
    let req = frame([1, 2], 180, &READ3);
    // Noise, then the request in three pieces with gaps between them (a
    // slow radio, a UART's FIFO emptied in bits).
    l.master.write_all(&[0x00, 0xFF, 0x13, 0x55]).unwrap();
    for piece in [&req[..3], &req[3..9], &req[9..]] {
        l.master.write_all(piece).unwrap();
        std::thread::sleep(Duration::from_millis(150));
    }
    l.check_read3();
    // Two frames in one write: two replies, in order.
    l.master.write_all(&[req.clone(), req.clone()].concat()).unwrap();
    l.check_read3();
    l.check_read3();
    // A frame for another device on the line: no reply, and the line is
    // still in step for the next request.
    l.master.write_all(&frame([9, 9], 180, &READ3)).unwrap();
    l.silent(300);
    l.master.write_all(&req).unwrap();
    l.check_read3();
    // One device on both links: a write over TCP is read on the line.
    let mut tcp = std::net::TcpStream::connect(l.server.roc_addr().unwrap()).unwrap();
    tcp.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    let mut w = vec![1, 17, 0, 2];
    w.extend_from_slice(&42.5f32.to_le_bytes());
    tcp.write_all(&frame([1, 2], 181, &w)).unwrap();
    let mut ack = [0u8; 8];
    tcp.read_exact(&mut ack).unwrap();
    assert_eq!((ack[4], ack[5]), (181, 0), "acknowledged: {ack:?}");
    assert_eq!(api(&l.server, "SFP 1", "DATA1"), "42.5");
    l.master.write_all(&req).unwrap();
    l.check_read3();
    l.server.stop();
}

#[test]
fn a_quiet_line_is_kept_and_a_failed_one_is_reopened_while_the_server_runs() {
    let mut l = serve(Duration::from_secs(1));
    // Quiet for longer than the client timeout: a TCP client would be
    // dropped; the line is still served.
    std::thread::sleep(Duration::from_millis(1600));
    l.master.write_all(&frame([1, 2], 180, &READ3)).unwrap();
    l.check_read3();
    assert!(!l.log_has("idle"), "{:?}", l.log.lock().unwrap());
    // The far end goes away: the failure is logged, the port is tried
    // again a second later (the terminal is gone, so that fails, once in
    // the log), and the server answers all along.
    drop(std::mem::replace(&mut l.master, TTYPort::pair().unwrap().0));
    eventually("the failure logged", || l.log_has("opening it again in 1 s"));
    eventually("the reopening tried", || l.log_has("can't open the serial port again"));
    assert!(api(&l.server, "SFP 1", "DATA1").parse::<f32>().is_ok());
    std::thread::sleep(Duration::from_millis(2500));
    let again = l.log.lock().unwrap().iter().filter(|x| x.contains("can't open the serial port again")).count();
    assert_eq!(again, 1, "each failed try is not logged: {:?}", l.log.lock().unwrap());
    l.server.stop();
}

#[test]
fn a_port_that_cant_be_opened_is_a_located_e0905() {
    let cfg = Config { roc_serial: Some(("/dev/linc-no-such-tty".into(), Line::new(9600), ME)), ..common::config() };
    let Err(p) = linc_serve::start(common::plant("examples/roc/plant.json"), cfg) else {
        panic!("a port that does not exist was opened")
    };
    assert!(p.is_refused());
    let short = p.render(linc_compiler::diag::Format::Short);
    // Shown against the port's path, as an unreadable file is.
    let want = "/dev/linc-no-such-tty:1:1: error[E0905]: can't open the serial port `/dev/linc-no-such-tty`: ";
    assert!(short.starts_with(want), "{short}");
}

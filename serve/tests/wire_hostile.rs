//! The wire servers under load and under hostile traffic, while the example
//! plant runs in real time: clients hammering both protocols, a client
//! sending a byte a second, a 64 KB garbage burst, and a thousand idle
//! connections. Every well-formed request is answered right, every abuse
//! is logged, and what keeps scans on time is counted: however many
//! clients, at most one request per connection waits for the plant. (The
//! timeouts are tested at exact instants in paused time, in
//! `serve/src/wire/net.rs`; late scans are a measurement of the machine,
//! which `cargo run --release -p linc-serve --example wire_load` and the
//! README's hour-long runs make.)

mod common;

use linc_comms::roc::{Address, Frame};
use linc_serve::{Config, Limits, Server, Speed};
use std::io::{Read, Write};
use std::net::TcpStream;
use std::sync::{Arc, Mutex};
use std::time::Duration;

fn serve(log: Arc<Mutex<Vec<String>>>) -> Server {
    serve_db("examples/roc/plant.json", log)
}

fn serve_db(db: &str, log: Arc<Mutex<Vec<String>>>) -> Server {
    let cfg = Config {
        speed: Speed::Times(1.0),
        allow_writes: true,
        roc: Some(("127.0.0.1:0".parse().unwrap(), Address { unit: 1, group: 2 })),
        modbus: Some("127.0.0.1:0".parse().unwrap()),
        limits: Limits { max_clients: 64, idle: Duration::from_secs(2), request: Duration::from_secs(1) },
        log: Arc::new(move |line| log.lock().unwrap().push(line)),
        ..common::config()
    };
    common::serve(db, cfg)
}

/// One ROC read of SFP 1,DATA1 and its reply's value.
fn roc_read(t: &mut TcpStream) -> f32 {
    let f = Frame {
        dst: Address { unit: 1, group: 2 },
        src: Address { unit: 3, group: 1 },
        opcode: 180,
        data: vec![1, 17, 0, 2],
    };
    t.write_all(&f.encode().unwrap()).unwrap();
    let mut reply = [0u8; 6 + 8 + 2];
    t.read_exact(&mut reply).unwrap();
    assert_eq!((reply[4], reply[5]), (180, 8), "{reply:?}");
    f32::from_le_bytes(reply[10..14].try_into().unwrap())
}

/// One Modbus read of holding registers 0-1 (the setpoint).
fn modbus_read(t: &mut TcpStream, id: u16) -> f32 {
    let mut req = id.to_be_bytes().to_vec();
    req.extend_from_slice(&[0, 0, 0, 6, 1, 3, 0, 0, 0, 2]);
    t.write_all(&req).unwrap();
    let mut reply = [0u8; 13];
    t.read_exact(&mut reply).unwrap();
    assert_eq!(&reply[..2], &id.to_be_bytes());
    f32::from_bits(u32::from_be_bytes(reply[9..13].try_into().unwrap()))
}

#[test]
fn hostile_traffic_never_stalls_the_plant_and_is_logged() {
    let log = Arc::new(Mutex::new(Vec::new()));
    let s = serve(log.clone());
    let (roc, mb) = (s.roc_addr().unwrap(), s.modbus_addr().unwrap());
    // A byte a second, and 64 KB of garbage, on each protocol.
    let slow: Vec<_> = [roc, mb]
        .into_iter()
        .map(|a| {
            // Connected before the flood below takes every place.
            let mut t = TcpStream::connect(a).unwrap();
            std::thread::spawn(move || {
                for b in [1u8, 2, 0, 0, 0] {
                    if t.write_all(&[b]).is_err() {
                        return;
                    }
                    std::thread::sleep(Duration::from_millis(600));
                }
            })
        })
        .collect();
    let mut rng = linc_test_support::Rng::new(64);
    let garbage: Vec<u8> = (0..65536).map(|_| rng.below(256) as u8).collect();
    for a in [roc, mb] {
        if let Ok(mut t) = TcpStream::connect(a) {
            let _ = t.write_all(&garbage);
        }
    }
    // A thousand idle connections, half on each port: 64 are held, the rest
    // refused (and logged once a second, not a thousand times).
    let mut idle = Vec::new();
    for i in 0..1000 {
        if let Ok(t) = TcpStream::connect(if i % 2 == 0 { roc } else { mb }) {
            idle.push(t);
        }
    }
    let lines = |needle: &str| log.lock().unwrap().iter().filter(|l| l.contains(needle)).count();
    // The held ones are dropped when they have been idle too long, which
    // frees the places; real clients are then served right.
    common::eventually("the idle clients' drop", || lines("roc 127.0.0.1") >= 64 && lines("modbus 127.0.0.1") >= 64);
    drop(idle);
    let mut r = TcpStream::connect(roc).unwrap();
    r.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    assert_eq!(roc_read(&mut r), 80.0);
    let mut m = TcpStream::connect(mb).unwrap();
    m.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    assert_eq!(modbus_read(&mut m, 7), 80.0);
    for t in slow {
        t.join().unwrap();
    }
    common::eventually("the slow clients' drop", || lines("took more than 1 s") >= 2);
    let done = s.stop();
    assert!(done.busiest <= 2 * 64, "{} requests waited for a scan: more than one per connection", done.busiest);
    // Every due scan ran: one per period of the fastest task so far.
    let s = &done.console.strategy;
    let due = s.elapsed_us() / s.fastest_period_us().expect("a task");
    assert!(done.scans >= due, "{} scans for {due} instants", done.scans);
    eprintln!("hostile traffic: {} scans, {} late, {} waiting at most", done.scans, done.late, done.busiest);
    let log = log.lock().unwrap().join("\n");
    for needle in [
        "roc: refused",
        "modbus: refused",
        "dropped: idle for 2 s",
        "dropped: a request took more than 1 s to arrive",
        "made no frame",
        "dropped: not Modbus TCP",
    ] {
        assert!(log.contains(needle), "the log lacks `{needle}`:\n{log}");
    }
    let refusals = log.lines().filter(|l| l.contains(": refused ")).count();
    assert!(refusals < 100, "hundreds of refused connections make a line a second, not one each: {refusals}");
}

#[test]
fn many_clients_at_once_are_answered_right_one_request_each_at_a_time() {
    let s = serve(Arc::new(Mutex::new(Vec::new())));
    let (roc, mb) = (s.roc_addr().unwrap(), s.modbus_addr().unwrap());
    let clients: Vec<_> = (0..16)
        .map(|i| {
            std::thread::spawn(move || {
                let mut t = TcpStream::connect(if i % 2 == 0 { roc } else { mb }).unwrap();
                t.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
                for n in 0..200u16 {
                    let v = if i % 2 == 0 { roc_read(&mut t) } else { modbus_read(&mut t, n) };
                    assert_eq!(v, 80.0);
                }
            })
        })
        .collect();
    for c in clients {
        c.join().unwrap();
    }
    let done = s.stop();
    assert!(done.busiest <= 16, "{} requests of 16 clients waited for a scan", done.busiest);
    eprintln!("16 clients: {} scans, {} late", done.scans, done.late);
}

/// Store and forward to a device that never answers (a link that accepts
/// and stays silent): each relayed request waits off the plant thread and
/// ends in error 22 with a log line, while reads on other connections are
/// answered at once and every due scan runs.
#[test]
fn store_and_forward_into_a_black_hole_holds_no_scan() {
    let hole = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let hole_addr = hole.local_addr().unwrap();
    let held = std::thread::spawn(move || hole.incoming().take(20).filter_map(Result::ok).collect::<Vec<_>>());
    let dir = std::path::Path::new(common::ROOT).join("examples/roc");
    let scratch = linc_test_support::fresh_dir("roc-hole");
    for f in ["drain.csv", "sim.stx"] {
        std::fs::copy(dir.join(f), scratch.join(f)).unwrap();
    }
    let text =
        std::fs::read_to_string(dir.join("plant.json")).unwrap().replace("127.0.0.1:4001", &hole_addr.to_string());
    std::fs::write(scratch.join("plant.json"), text).unwrap();
    let log = Arc::new(Mutex::new(Vec::new()));
    let s = serve_db(scratch.join("plant.json").to_str().unwrap(), log.clone());
    let roc = s.roc_addr().unwrap();
    let forward = Frame {
        dst: Address { unit: 1, group: 2 },
        src: Address { unit: 3, group: 1 },
        opcode: 24,
        data: vec![3, 1, 1, 2, 5, 2, 0, 0, 0, 0, 7, 0],
    };
    let relays: Vec<_> = (0..20)
        .map(|_| {
            let bytes = forward.encode().unwrap();
            std::thread::spawn(move || {
                let mut t = TcpStream::connect(roc).unwrap();
                t.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
                t.write_all(&bytes).unwrap();
                let mut reply = [0u8; 6 + 3 + 2];
                t.read_exact(&mut reply).unwrap();
                (reply[4], reply[6..9].to_vec())
            })
        })
        .collect();
    let mut r = TcpStream::connect(roc).unwrap();
    r.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let asked = std::time::Instant::now();
    assert_eq!(roc_read(&mut r), 80.0);
    let read_took = asked.elapsed();
    for t in relays {
        assert_eq!(t.join().unwrap(), (255, vec![22, 24, 8]));
    }
    let done = s.stop();
    drop(held.join());
    let s = &done.console.strategy;
    let due = s.elapsed_us() / s.fastest_period_us().expect("a task");
    assert!(done.scans >= due, "{} scans for {due} instants", done.scans);
    let refused = log.lock().unwrap().iter().filter(|l| l.contains("did not answer within 3 s")).count();
    assert_eq!(refused, 20, "each relay that timed out is logged");
    eprintln!("20 relays into a black hole: a read beside them took {read_took:?}; {} late scans", done.late);
}

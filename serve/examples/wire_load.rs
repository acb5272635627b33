//! Load on the wire servers for the README: 50 clients × 1,000 requests
//! (25 on the FB107 example's ROC protocol reading three parameters, 25 on Modbus reading five
//! registers) against the example plant running at speed 1, each client
//! one request at a time. Prints the latency percentiles per protocol, the
//! late scans, and a native baseline measured in the same run: the same
//! clients against a plain TCP echo of the same sizes.
//!
//! `cargo run --release -p linc-serve --example wire_load [CLIENTS] [REQUESTS]`

use linc_comms::roc::{Address, Frame};
use linc_serve::{Config, Speed};
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpListener, TcpStream};
use std::path::Path;
use std::time::{Duration, Instant};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

fn roc_request() -> Vec<u8> {
    let f = Frame {
        dst: Address { unit: 1, group: 2 },
        src: Address { unit: 3, group: 1 },
        opcode: 180,
        data: vec![3, 3, 0, 12, 17, 0, 2, 16, 0, 1],
    };
    f.encode().unwrap()
}

const ROC_REPLY: usize = 6 + 1 + 3 * 7 + 2; // three FL parameters
const MB_REPLY: usize = 9 + 10;

fn modbus_request(id: u16) -> Vec<u8> {
    let mut r = id.to_be_bytes().to_vec();
    r.extend_from_slice(&[0, 0, 0, 6, 1, 4, 0, 0, 0, 5]);
    r
}

/// Runs `clients` threads of `n` requests each; returns every latency.
fn run(clients: usize, n: usize, addr: impl Fn(usize) -> (SocketAddr, bool) + Sync) -> Vec<Duration> {
    std::thread::scope(|s| {
        let handles: Vec<_> = (0..clients)
            .map(|c| {
                let (a, roc) = addr(c);
                s.spawn(move || {
                    let mut t = TcpStream::connect(a).expect("connect");
                    t.set_nodelay(true).unwrap();
                    let mut lat = Vec::with_capacity(n);
                    let mut buf = [0u8; 64];
                    for i in 0..n {
                        let (req, len) =
                            if roc { (roc_request(), ROC_REPLY) } else { (modbus_request(i as u16), MB_REPLY) };
                        let t0 = Instant::now();
                        t.write_all(&req).unwrap();
                        t.read_exact(&mut buf[..len]).unwrap();
                        lat.push(t0.elapsed());
                    }
                    lat
                })
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().unwrap()).collect()
    })
}

fn pct(mut v: Vec<Duration>) -> String {
    v.sort();
    let at = |p: f64| v[((v.len() as f64 * p) as usize).min(v.len() - 1)];
    format!("p50 {:?}, p99 {:?}, max {:?} ({} requests)", at(0.5), at(0.99), v[v.len() - 1], v.len())
}

/// A plain echo of the reply sizes: the machine's loopback round trip.
fn echo() -> SocketAddr {
    let l = TcpListener::bind("127.0.0.1:0").unwrap();
    let a = l.local_addr().unwrap();
    std::thread::spawn(move || {
        for t in l.incoming().flatten() {
            std::thread::spawn(move || {
                let mut t = t;
                t.set_nodelay(true).unwrap();
                let mut buf = [0u8; 64];
                while let Ok(n) = t.read(&mut buf) {
                    if n == 0 {
                        return;
                    }
                    let len = if buf[0] == 1 { ROC_REPLY } else { MB_REPLY };
                    if t.write_all(&[0u8; 64][..len]).is_err() {
                        return;
                    }
                }
            });
        }
    });
    a
}

fn main() {
    let args: Vec<usize> = std::env::args().skip(1).filter_map(|a| a.parse().ok()).collect();
    let (clients, n) = (args.first().copied().unwrap_or(50), args.get(1).copied().unwrap_or(1000));
    let path = Path::new(ROOT).join("examples/roc/plant.json");
    let plant = linc_driver::plant::build(&linc_driver::plant::PlantSpec::strategy(path)).expect("plant");
    let cfg = Config {
        speed: Speed::Times(1.0),
        roc: Some(("127.0.0.1:0".parse().unwrap(), Address { unit: 1, group: 2 })),
        modbus: Some("127.0.0.1:0".parse().unwrap()),
        log: std::sync::Arc::new(|_| {}),
        ..Config::new("127.0.0.1:0".parse().unwrap())
    };
    let server = linc_serve::start(plant, cfg).expect("start");
    let (roc, mb) = (server.roc_addr().unwrap(), server.modbus_addr().unwrap());
    let t = Instant::now();
    let all = run(clients, n, |c| if c % 2 == 0 { (roc, true) } else { (mb, false) });
    let wall = t.elapsed();
    // Clients alternate, so latencies come in per-client blocks: split them.
    let (mut r_lat, mut m_lat) = (Vec::new(), Vec::new());
    for (c, chunk) in all.chunks(n).enumerate() {
        if c % 2 == 0 {
            r_lat.extend_from_slice(chunk)
        } else {
            m_lat.extend_from_slice(chunk)
        }
    }
    let done = server.stop();
    println!(
        "{clients} clients x {n} requests in {wall:.2?} ({:.0} requests/s), plant at speed 1",
        all.len() as f64 / wall.as_secs_f64()
    );
    println!("ROC protocol 180 (FB107, 3 parameters): {}", pct(r_lat));
    println!("Modbus 04 (5 registers):     {}", pct(m_lat));
    println!("plant: {} scans, {} late", done.scans, done.late);
    let e = echo();
    let base = run(clients, n, |c| (e, c % 2 == 0));
    println!("native baseline, TCP echo of the same sizes: {}", pct(base));
}

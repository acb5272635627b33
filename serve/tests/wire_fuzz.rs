//! Fuzz of the decoders on the server side, in process: random and
//! mutated ROC Plus and ROC-protocol byte streams through the deframer, the
//! store-and-forward routing and the device, and
//! random and mutated Modbus TCP streams through the deframer, the request
//! decoder and the device, against a running example plant. Nothing may panic, and
//! memory stays bounded (the deframer holds at most a frame beyond the last
//! read; the whole run's peak heap is measured).
//!
//! `cargo test` runs a few thousand cases of each; the long run is
//! `LINC_WIRE_FUZZ=1000000 cargo test --release -p linc-serve --test wire_fuzz`.

mod common;

use linc_comms::roc::frame::MAX_FRAME;
use linc_comms::roc::{Address, Deframer, Frame};
use linc_engines::console::Console;
use linc_serve::wire::modbus::ModbusDevice;
use linc_serve::wire::roc::{Dialect, RocDevice};
use linc_test_support::alloc::{peak_of, serial, Counting};
use linc_test_support::Rng;

#[global_allocator]
static A: Counting = Counting;

fn cases() -> usize {
    std::env::var("LINC_WIRE_FUZZ").ok().and_then(|v| v.parse().ok()).unwrap_or(3000)
}

fn console(db: &str) -> Console {
    Console::new(common::plant(db).into_strategy().expect("a strategy"))
}

/// The ROC800 example plant after three hours with a high alarm: its
/// alarm and event logs and history archives hold entries to read.
fn roc_console() -> Console {
    let mut c = console("examples/fst/plant.json");
    for line in ["ADVANCE 2h", "F AIN 2-1.EU=95", "ADVANCE 1h"] {
        assert!(c.execute(line).iter().all(Result::is_ok), "{line}");
    }
    c
}

/// Requests a host could send: the seeds the mutations start from.
fn roc_seeds() -> Vec<Frame> {
    let f = |opcode, data: &[u8]| Frame {
        dst: Address { unit: 1, group: 2 },
        src: Address { unit: 3, group: 1 },
        opcode,
        data: data.to_vec(),
    };
    vec![
        f(180, &[3, 103, 0, 12, 98, 0, 2, 96, 0, 0]),
        f(181, &[2, 98, 0, 2, 0, 0, 0x80, 0x3F, 103, 0, 2, 0xF4, 0x01]),
        f(181, &[1, 96, 0, 19, 7]),
        f(7, &[]),
        f(8, &[0, 0, 12, 1, 6, 0xE9, 0x07]),
        f(6, &[]),
        f(118, &[10, 0, 0]),
        f(119, &[10, 238, 0]),
        f(135, &[0, 3, 1, 0, 0, 60]),
        f(135, &[0, 3, 4, 0xFF, 0xFF, 3]),
        f(136, &[0, 0, 0, 1, 1, 3, 10]),
        f(17, &[b'L', b'O', b'I', 0xE8, 0x03, 5]),
        f(17, b"LOI\xE8\x03LOGOUT"),
    ]
}

fn mutate(rng: &mut Rng, mut b: Vec<u8>) -> Vec<u8> {
    for _ in 0..=rng.below(3) {
        match rng.below(4) {
            0 if !b.is_empty() => {
                let i = rng.below(b.len());
                b[i] ^= 1 << rng.below(8);
            }
            1 if !b.is_empty() => b.truncate(rng.below(b.len())),
            2 => {
                let i = rng.below(b.len() + 1);
                b.insert(i, rng.below(256) as u8);
            }
            _ => {
                let i = rng.below(b.len() + 1);
                b.splice(i..i, (0..rng.below(40)).map(|_| rng.below(256) as u8));
            }
        }
    }
    b
}

#[test]
fn random_and_mutated_roc_streams_never_panic_and_stay_bounded() {
    let _one = serial();
    let mut c = roc_console();
    let device = RocDevice { address: Address { unit: 1, group: 2 }, allow_writes: true, dialect: Dialect::RocPlus };
    let seeds = roc_seeds();
    let mut rng = Rng::new(0x524F_4331);
    let (mut frames, mut replies) = (0usize, 0usize);
    let peak = peak_of(|| {
        let mut d = Deframer::default();
        for _ in 0..cases() {
            let bytes = match rng.below(3) {
                // A valid request, its CRC fixed after the data changed.
                0 => {
                    let mut f = seeds[rng.below(seeds.len())].clone();
                    f.data = mutate(&mut rng, f.data);
                    f.data.truncate(255);
                    f.encode().unwrap()
                }
                // A frame mutated after its CRC: mostly noise to resync on.
                1 => {
                    let seed = seeds[rng.below(seeds.len())].encode().unwrap();
                    mutate(&mut rng, seed)
                }
                _ => (0..rng.below(300)).map(|_| rng.below(256) as u8).collect(),
            };
            for chunk in bytes.chunks(1 + rng.below(64)) {
                d.push(chunk);
                while let Some(f) = d.next_frame() {
                    frames += 1;
                    if f.dst == device.address {
                        let a = device.answer(&mut c, &f, "fuzz", None, None);
                        assert!(a.reply.encode().is_some(), "every reply fits a frame: {f:?}");
                        replies += 1;
                    }
                }
                assert!(d.pending() < MAX_FRAME + 64, "the deframer holds {} bytes", d.pending());
            }
        }
    });
    assert!(frames > cases() / 4 && replies > cases() / 5, "{frames} frames, {replies} replies");
    assert!(peak < 4 << 20, "peak heap {peak} bytes");
}

/// The FB107 example plant after three hours: its logs and archives hold
/// entries for the ROC protocol's history opcodes.
fn fb107_console() -> Console {
    let mut c = console("examples/roc/plant.json");
    assert!(c.execute("ADVANCE 3h").iter().all(Result::is_ok));
    c
}

/// ROC-protocol requests: every opcode the FB107 answers, store and
/// forward ending here and passing on, broadcasts and the universal address.
fn fb107_seeds() -> Vec<Frame> {
    let f = |dst: [u8; 2], opcode, data: &[u8]| Frame {
        dst: Address { unit: dst[0], group: dst[1] },
        src: Address { unit: 3, group: 1 },
        opcode,
        data: data.to_vec(),
    };
    let me = [1, 2];
    let wrapped = |hops: &[u8], inner: &[u8]| [&[3u8, 1][..], hops, inner].concat();
    vec![
        f(me, 6, &[]),
        f(me, 7, &[]),
        f([240, 240], 7, &[]),
        f([0, 2], 8, &[0, 0, 12, 1, 6, 26]),
        f(me, 10, &[0, 0, 5]),
        f(me, 11, &[0, 2, 1, 0, 0, 0x90, 0x42]),
        f(me, 17, b"LOI\xE8\x03"),
        f(me, 120, &[]),
        f(me, 121, &[10, 0, 0]),
        f(me, 122, &[10, 230, 0]),
        f(me, 126, &[1]),
        f(me, 128, &[1, 5, 1]),
        f(me, 130, &[0, 1, 60, 0, 0]),
        f(me, 130, &[1, 254, 3, 0xFF, 0xFF]),
        f(me, 166, &[17, 0, 2, 2, 0, 0, 0x80, 0x3F, 0, 0, 0, 0]),
        f(me, 167, &[3, 0, 16, 0]),
        f(me, 180, &[2, 3, 0, 12, 17, 0, 2]),
        f(me, 181, &[1, 17, 0, 2, 0, 0, 0x80, 0x3F]),
        f(me, 24, &wrapped(&[1, 2, 0, 0, 0, 0, 0, 0], &[180, 4, 1, 17, 0, 2])),
        f(me, 24, &wrapped(&[1, 2, 5, 2, 0, 0, 0, 0], &[128, 3, 1, 5, 1])),
        f(me, 24, &wrapped(&[5, 2, 1, 2, 5, 2, 0, 0], &[7, 0])),
    ]
}

#[test]
fn random_and_mutated_roc_protocol_streams_never_panic_and_stay_bounded() {
    use linc_comms::roc::rocp::{self, forward, Addressed};
    let _one = serial();
    let mut c = fb107_console();
    let me = Address { unit: 1, group: 2 };
    let device = RocDevice { address: me, allow_writes: true, dialect: Dialect::Roc };
    let seeds = fb107_seeds();
    let mut rng = Rng::new(0x524F_4350);
    let (mut frames, mut replies, mut relayed) = (0usize, 0usize, 0usize);
    let peak = peak_of(|| {
        let mut d = Deframer::default();
        for _ in 0..cases() {
            let seed = &seeds[rng.below(seeds.len())];
            let bytes = match rng.below(3) {
                0 => {
                    let mut f = seed.clone();
                    f.data = mutate(&mut rng, f.data);
                    f.data.truncate(255);
                    f.encode().unwrap()
                }
                1 => mutate(&mut rng, seed.encode().unwrap()),
                _ => (0..rng.below(300)).map(|_| rng.below(256) as u8).collect(),
            };
            for chunk in bytes.chunks(1 + rng.below(64)) {
                d.push(chunk);
                while let Some(f) = d.next_frame() {
                    frames += 1;
                    if rocp::addressed(me, f.dst) == Addressed::Other {
                        continue;
                    }
                    // What the connection decides for a 24: pass it on
                    // (counted, not sent) or let the device answer it.
                    let route = forward::parse(&f.data).ok().map(|w| w.path.route(me));
                    if f.opcode == rocp::FORWARD && matches!(route, Some(Ok(forward::Route::Next(_)))) {
                        relayed += 1;
                        continue;
                    }
                    let a = device.answer(&mut c, &f, "fuzz", None, None);
                    assert!(a.reply.encode().is_some(), "every reply fits a frame: {f:?}");
                    if a.reply.opcode == rocp::ERROR {
                        assert_eq!((a.reply.data.len(), a.reply.data[1]), (3, f.opcode), "{f:?}");
                    }
                    replies += 1;
                }
                assert!(d.pending() < MAX_FRAME + 64, "the deframer holds {} bytes", d.pending());
            }
        }
    });
    assert!(frames > cases() / 4 && replies > cases() / 5 && relayed > 0, "{frames} frames, {replies} replies");
    assert!(peak < 4 << 20, "peak heap {peak} bytes");
}

#[test]
fn random_and_mutated_modbus_streams_never_panic_and_stay_bounded() {
    use linc_comms::modbus::{decode, encode, Deframer as Mbap};
    let _one = serial();
    let mut c = console("examples/roc/plant.json");
    let device = ModbusDevice { allow_writes: true };
    let seeds: Vec<Vec<u8>> = vec![
        vec![0x03, 0, 0, 0, 5],
        vec![0x04, 0, 0, 0, 6],
        vec![0x01, 0, 0, 0, 1],
        vec![0x02, 0, 0, 0, 1],
        vec![0x05, 0, 0, 0xFF, 0],
        vec![0x06, 0, 4, 0, 9],
        vec![0x0F, 0, 0, 0, 1, 1, 1],
        vec![0x10, 0, 0, 0, 2, 4, 0x42, 0x20, 0, 0],
        // What tokio-modbus 0.17's server decoder panics on (ADR 0019).
        vec![0x0F, 0, 0, 0, 16, 1, 0xFF],
        vec![0x10, 0, 0, 0x80, 0x01, 0x02, 0, 0],
    ];
    let mut rng = Rng::new(0x4D42_5553);
    let (mut frames, mut decoded, mut closed) = (0usize, 0usize, 0usize);
    let peak = peak_of(|| {
        let mut d = Mbap::default();
        for _ in 0..cases() {
            let pdu = match rng.below(3) {
                // A well-formed request at a random address.
                0 => {
                    let mut seed = seeds[rng.below(seeds.len())].clone();
                    seed[1] = rng.below(2) as u8;
                    seed[2] = rng.below(8) as u8;
                    seed
                }
                1 => {
                    let seed = seeds[rng.below(seeds.len())].clone();
                    mutate(&mut rng, seed)
                }
                _ => (0..rng.below(260)).map(|_| rng.below(256) as u8).collect(),
            };
            let mut frame = vec![0, 1, 0, 0];
            frame.extend_from_slice(&((pdu.len() + 1) as u16).to_be_bytes());
            frame.push(1);
            frame.extend_from_slice(&pdu);
            // Now and then the header itself is damaged.
            let bytes = if rng.below(10) == 0 { mutate(&mut rng, frame) } else { frame };
            for chunk in bytes.chunks(1 + rng.below(64)) {
                d.push(chunk);
                while let Some(next) = d.next_frame() {
                    let Ok((head, pdu)) = next else {
                        // Not Modbus TCP: the server closes the connection.
                        closed += 1;
                        d = Mbap::default();
                        break;
                    };
                    frames += 1;
                    let reply = match decode(&pdu) {
                        Ok(req) => {
                            decoded += 1;
                            let a = device.answer(&mut c, &req, "fuzz", None);
                            encode(head, a.function, &a.reply)
                        }
                        Err((f, e)) => encode(head, f, &Err(e)),
                    };
                    assert!(reply.len() <= 7 + 253, "a reply fits a frame");
                }
                assert!(d.pending() <= 7 + 253 + 64, "the deframer holds {} bytes", d.pending());
            }
        }
    });
    assert!(
        frames > cases() / 2 && decoded > cases() / 5 && closed > 0,
        "{frames} frames, {decoded} decoded, {closed} closed"
    );
    assert!(peak < 4 << 20, "peak heap {peak} bytes");
}

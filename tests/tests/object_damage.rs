//! A damaged object file is refused with a clear error or runs without
//! panicking: no byte of it can crash the loader, verifier or VM.
use linc_conformance::exec::compile;
use linc_conformance::guide_db;
use linc_runtime::object::crc32;
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Vm};
use linc_runtime::Program;

const SOURCE: &str = "Counters.N0 := 0;\nFOR Counters.N1 := 0 TO 6 DO\n  Block_5.Val1{Counters.N1} := Block_5.Val1{Counters.N1 + 1} * 2.0;\n  IF Counters.N1 MOD 2 = 0 THEN Dig_A.Out.Bit0{Counters.N0} := 1; END_IF;\nEND_FOR;\nRAW_COM.Buffer1 := CONCAT('a$62', FORMAT('05I', Counters.N1));\nPIC_004.Mode := 'auto';\nANIN_005.Alarms.HiLevel.Suppress := 60;\nWHILE Counters.N0 < 3 DO Counters.N0 := Counters.N0 + 1; END_WHILE;\n";

fn small() -> Vec<u8> {
    compile(SOURCE, guide_db())
}

/// Loads and, if accepted, runs; returns whether it was accepted.
fn try_run(bytes: &[u8]) -> bool {
    let Ok(verified) = linc_runtime::load(bytes) else {
        return false;
    };
    let mut store = Store::new(guide_db().clone());
    for unit in 0..verified.object().units.len() {
        if let Ok(linked) = verified.clone().link(&store, &[Program { unit, own: None }]) {
            for block in 0..linked.unit(0).map_or(0, |u| u.blocks.len()) {
                let mut vm = Vm::new(100_000, Clock::new(7, 0));
                let mut act = Activation::new(&linked, 0, block);
                let _ = vm.run(&linked, &mut act, &mut store, None);
            }
        }
    }
    true
}

/// Rewrites the checksum so that damage reaches the decoder and verifier.
fn reseal(bytes: &mut [u8]) {
    if bytes.len() >= 20 {
        bytes[12..16].fill(0);
        let crc = crc32(bytes);
        bytes[12..16].copy_from_slice(&crc.to_le_bytes());
    }
}

#[test]
fn the_object_itself_runs() {
    assert!(try_run(&small()));
}

#[test]
fn every_single_byte_flip_is_rejected_by_the_checksum() {
    let good = small();
    for i in 0..good.len() {
        let mut bad = good.clone();
        bad[i] ^= 0xFF;
        assert!(linc_runtime::load(&bad).is_err(), "flip at {i} was accepted");
    }
}

#[test]
fn every_truncation_is_rejected() {
    let good = small();
    for n in 0..good.len() {
        let e = linc_runtime::load(&good[..n]).expect_err("truncated file accepted");
        assert!(matches!(e.code().as_str(), "E0700" | "E0703"), "{n}: {e}");
    }
}

#[test]
fn resealed_damage_is_rejected_or_runs_without_panic() {
    let good = small();
    let mut accepted = 0;
    for i in 20..good.len() {
        for mask in [0x01u8, 0x80, 0xFF, 0x10] {
            let mut bad = good.clone();
            bad[i] ^= mask;
            reseal(&mut bad);
            accepted += usize::from(try_run(&bad));
        }
        // Every value at a few positions, to reach each opcode and operand.
        if i % 7 == 0 {
            for v in 0..=255u8 {
                let mut bad = good.clone();
                bad[i] = v;
                reseal(&mut bad);
                try_run(&bad);
            }
        }
    }
    // Some damage is harmless (a constant, a line number); the rest is refused.
    assert!(accepted > 0 && accepted < (good.len() - 20) * 4);
}

#[test]
fn header_errors_have_their_own_codes() {
    let good = small();
    let mut magic = good.clone();
    magic[0] = b'X';
    assert_eq!(linc_runtime::load(&magic).map(|_| ()).map_err(|e| e.code().as_str()), Err("E0700"));
    let mut version = good.clone();
    version[8] = 9;
    assert_eq!(linc_runtime::load(&version).map(|_| ()).map_err(|e| e.code().as_str()), Err("E0701"));
    let mut body = good.clone();
    let last = body.len() - 1;
    body[last] ^= 1;
    let e = linc_runtime::load(&body).map(|_| ()).expect_err("damaged");
    assert_eq!(e.code(), "E0702");
    assert!(e.to_string().contains("checksum"), "{e}");
}

#[test]
fn crc_matches_an_independent_implementation() {
    let crc = crc::Crc::<u32>::new(&crc::CRC_32_ISO_HDLC);
    for data in [&b""[..], b"123456789", &small()] {
        assert_eq!(crc32(data), crc.checksum(data));
    }
    assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
}

/// `PowRKeep` (FST `**`, NaN instead of a fault) is refused outside an FST
/// table: in an action a NaN would reach the database unchecked.
#[test]
fn the_quiet_power_belongs_to_fst_tables_only() {
    use linc_runtime::isa::Op::*;
    use linc_runtime::object::{CodeBlock, ObjectFile, Unit, UnitKind};
    let ops = vec![PushR { v: 2.0 }, PushR { v: 1000.0 }, PowRKeep {}, StoreLoc { n: 0 }, Ret {}];
    let block = CodeBlock { locals: 1, ops: linc_runtime::wire::Code(ops), ..CodeBlock::default() };
    let unit = Unit {
        kind: UnitKind::Action,
        name: "A".into(),
        file: "a.st".into(),
        block_type: String::new(),
        retained: 0,
        blocks: vec![block],
        charts: Vec::new(),
        steps: Vec::new(),
    };
    let obj = ObjectFile { source: "a.st".into(), symbols: vec![], strings: vec![], units: vec![unit] };
    let e = linc_runtime::verify::verify(obj).expect_err("refused");
    assert_eq!(e.code(), "E0710");
    assert!(e.to_string().contains("PowRKeep belongs to FST tables only"), "{e}");
}

//! The program lifecycle (ADR 0005) and object format 2: verified once,
//! linked per program, state kept in the caller's activation.
use linc_conformance::exec::{compile, run, run_in};
use linc_conformance::guide_db;
use linc_runtime::isa::Op;
use linc_runtime::object::{crc32, Class, CodeBlock, LineEntry, ObjectFile, Sub, Symbol, Unit, UnitKind};
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Outcome, Vm};
use linc_runtime::wire::{Bytes, Code};
use linc_runtime::{verify, Program};

fn n0() -> Symbol {
    Symbol { block: "Counters".into(), field: "N0".into(), sub: Sub::Field, class: Class::Int }
}

fn object(ops: Vec<Op>, labels: Vec<u32>, locals: u8, retained: u16) -> ObjectFile {
    let block = CodeBlock { name: String::new(), locals, ops: Code(ops), labels, lines: vec![], loops: vec![] };
    let unit = Unit {
        kind: UnitKind::Action,
        name: "hand".into(),
        file: "hand.st".into(),
        block_type: String::new(),
        retained,
        blocks: vec![block],
        charts: vec![],
        steps: Vec::new(),
    };
    ObjectFile { source: "hand.st".into(), symbols: vec![n0()], strings: vec![], units: vec![unit] }
}

/// Runs unit 0 of `obj` `runs` times in one activation; returns N0 after each run.
fn n0_after_runs(obj: ObjectFile, runs: usize) -> Vec<(i32, Outcome)> {
    let v = verify::verify(obj).expect("verifies");
    let mut store = Store::new(guide_db().clone());
    let linked = v.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut act = Activation::new(&linked, 0, 0);
    let mut vm = Vm::new(1000, Clock::new(1, 0));
    let cell = store.cell_of(store.db.block("Counters").unwrap(), "N0").unwrap();
    (0..runs)
        .map(|_| {
            let o = vm.run(&linked, &mut act, &mut store, None).expect("runs");
            (store.show(cell).parse().unwrap(), o)
        })
        .collect()
}

#[test]
fn a_yield_inside_a_loop_keeps_the_loop_local() {
    use Op::*;
    // local0 := 0; L0: local0 := local0 + 1; N0 := local0; Yield; IF local0 < 3 GOTO L0; Ret
    let ops = vec![
        PushI { v: 0 },
        StoreLoc { n: 0 },
        LoadLoc { n: 0 },
        PushI { v: 1 },
        AddI {},
        StoreLoc { n: 0 },
        LoadLoc { n: 0 },
        StoreI { sym: 0 },
        Yield {},
        LoadLoc { n: 0 },
        PushI { v: 3 },
        LtI {},
        JumpIfTrue { to: 0 },
        Ret {},
    ];
    let got = n0_after_runs(object(ops, vec![2], 1, 0), 5);
    use Outcome::*;
    assert_eq!(got, [(1, Suspended), (2, Suspended), (3, Suspended), (3, Done), (1, Suspended)]);
}

#[test]
fn retained_slots_survive_from_run_to_run() {
    use Op::*;
    let ops =
        vec![LoadRet { n: 0 }, PushI { v: 1 }, AddI {}, StoreRet { n: 0 }, LoadRet { n: 0 }, StoreI { sym: 0 }, Ret {}];
    let got: Vec<i32> = n0_after_runs(object(ops, vec![], 0, 1), 3).into_iter().map(|(v, _)| v).collect();
    assert_eq!(got, [1, 2, 3]);
}

fn verify_code(ops: Vec<Op>, labels: Vec<u32>) -> Option<&'static str> {
    verify::verify(object(ops, labels, 0, 0)).err().map(|e| e.code().as_str())
}

#[test]
fn the_verifier_proves_the_reference_register_is_set() {
    use Op::*;
    assert_eq!(verify_code(vec![LoadRefI { sym: 0 }, StoreI { sym: 0 }, Ret {}], vec![]), Some("E0713"));
    // Set on one path only: `IF N0 THEN Ref END_IF; LoadRef`.
    let one_path =
        vec![LoadI { sym: 0 }, JumpIfFalse { to: 0 }, Ref { sym: 0 }, LoadRefI { sym: 0 }, StoreI { sym: 0 }, Ret {}];
    assert_eq!(verify_code(one_path, vec![3]), Some("E0713"));
    // Unset again after a suspension.
    assert_eq!(
        verify_code(vec![Ref { sym: 0 }, Yield {}, LoadRefI { sym: 0 }, StoreI { sym: 0 }, Ret {}], vec![]),
        Some("E0713")
    );
    assert_eq!(verify_code(vec![Ref { sym: 0 }, LoadRefI { sym: 0 }, StoreI { sym: 0 }, Ret {}], vec![]), None);
}

#[test]
fn the_reference_register_is_used_with_the_symbol_it_was_set_from() {
    use Op::*;
    // Found by the object fuzz test: the register set from an INT field, then
    // read as a bit of another (BITS8) symbol; the VM met an INT cell (R0099).
    let mut obj = object(
        vec![Ref { sym: 0 }, PushI { v: 0 }, RefBitOff { bit: 0 }, LoadRefBit { sym: 1 }, StoreI { sym: 0 }, Ret {}],
        vec![],
        0,
        0,
    );
    obj.symbols.push(Symbol { block: "Dig_A".into(), field: "Out".into(), sub: Sub::Field, class: Class::Bits8 });
    assert_eq!(verify::verify(obj.clone()).err().map(|e| e.code().as_str()), Some("E0713"));
    // Set from the bitfield itself, it verifies.
    obj.units[0].blocks[0].ops.0[0] = Ref { sym: 1 };
    obj.units[0].blocks[0].ops.0[4] = StoreI { sym: 0 };
    assert!(verify::verify(obj.clone()).is_ok());
    // A bit beyond the held bitfield's width (found by the fuzz test too).
    let mut wide = obj.clone();
    wide.units[0].blocks[0].ops.0[2] = RefBitOff { bit: 8 };
    assert_eq!(verify::verify(wide).err().map(|e| e.code().as_str()), Some("E0713"));
    // Paths that set it from different symbols meet: unknown, refused.
    let meet = vec![
        LoadI { sym: 0 },
        JumpIfFalse { to: 0 },
        Ref { sym: 0 },
        Jump { to: 1 },
        Ref { sym: 1 },
        LoadRefI { sym: 0 },
        StoreI { sym: 0 },
        Ret {},
    ];
    let mut obj = object(meet, vec![4, 5], 0, 0);
    obj.symbols.push(Symbol { block: "Dig_A".into(), field: "Out".into(), sub: Sub::Field, class: Class::Bits8 });
    assert_eq!(verify::verify(obj).err().map(|e| e.code().as_str()), Some("E0713"));
}

#[test]
fn labels_retained_slots_and_tables_are_checked() {
    use Op::*;
    assert_eq!(verify_code(vec![Jump { to: 1 }, Ret {}], vec![1]), Some("E0705"), "label id out of range");
    assert_eq!(verify_code(vec![Jump { to: 0 }, Ret {}], vec![2]), Some("E0705"), "label past the code");
    assert_eq!(verify_code(vec![LoadRet { n: 0 }, StoreI { sym: 0 }, Ret {}], vec![]), Some("E0711"));
    let mut obj = object(vec![Ret {}], vec![], 0, 0);
    obj.units[0].blocks[0].lines = vec![LineEntry { op: 5, line: 1, col: 1 }];
    assert_eq!(verify::verify(obj).err().map(|e| e.code().as_str()), Some("E0712"));
    let mut obj = object(vec![PushI { v: 1 }, StoreI { sym: 0 }, Ret {}], vec![], 0, 0);
    obj.units[0].blocks[0].lines = vec![LineEntry { op: 1, line: 2, col: 1 }, LineEntry { op: 0, line: 1, col: 1 }];
    assert_eq!(verify::verify(obj).err().map(|e| e.code().as_str()), Some("E0712"), "out of order");
}

#[test]
fn a_load_verifies_once() {
    let bytes = compile("Counters.N0 := Counters.N0 + 1;\n", guide_db());
    let before = verify::verifications();
    let v = linc_runtime::load(&bytes).expect("loads");
    assert_eq!(verify::verifications() - before, 1, "loading verifies once");
    let mut store = Store::new(guide_db().clone());
    let linked = v.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut act = Activation::new(&linked, 0, 0);
    for _ in 0..3 {
        Vm::new(1000, Clock::new(1, 0)).run(&linked, &mut act, &mut store, None).expect("runs");
    }
    assert_eq!(verify::verifications() - before, 1, "linking and running verify nothing more");
}

#[test]
fn an_object_of_version_1_is_refused_naming_both_versions() {
    let mut bytes = compile("Counters.N0 := 1;\n", guide_db());
    bytes[8] = 1;
    bytes[12..16].fill(0);
    let crc = crc32(&bytes);
    bytes[12..16].copy_from_slice(&crc.to_le_bytes());
    let e = linc_runtime::load(&bytes).expect_err("version 1");
    assert_eq!(e.code(), "E0701");
    assert_eq!(e.to_string(), "object format version 1 is not supported (this linc reads version 3)");
}

#[test]
fn a_direct_write_to_a_read_only_field_is_refused_at_link() {
    let obj = ObjectFile {
        symbols: vec![Symbol { block: "PIC_004".into(), field: "SP".into(), sub: Sub::Field, class: Class::Real }],
        ..object(vec![Op::PushR { v: 1.0 }, Op::StoreR { sym: 0 }, Op::Ret {}], vec![], 0, 0)
    };
    let store = Store::new(guide_db().clone());
    let e =
        verify::verify(obj).expect("verifies").link(&store, &[Program { unit: 0, own: None }]).expect_err("read-only");
    assert_eq!(e.code(), "E0709");
    assert!(e.to_string().contains("PIC_004.SP") && e.to_string().contains("read-only"), "{e}");
}

#[test]
fn an_offset_write_into_a_read_only_field_is_a_runtime_error() {
    // The checker refuses offsets whose run holds a read-only field (E0108);
    // a hand-made object is stopped by the VM. V{1} is W, which the block computes.
    let db = linc_runtime::Database::from_json(
        r#"{"templates": {"T": {"fields": {"V": "REAL", "W": {"type": "REAL", "readonly": true}, "X": "REAL"}}},
            "blocks": {"B": {"type": "T"}}}"#,
    )
    .expect("db");
    let r = run_in(&db, "B.X := 3.0;\n", 1, 1.0);
    assert_eq!(r.get("B.X"), "3.0");
    use Op::*;
    let obj = ObjectFile {
        symbols: vec![Symbol { block: "B".into(), field: "V".into(), sub: Sub::Field, class: Class::Real }],
        ..object(vec![PushR { v: 50.0 }, PushI { v: 1 }, RefOff { sym: 0 }, StoreRefR { sym: 0 }, Ret {}], vec![], 0, 0)
    };
    let mut store = Store::new(db);
    let linked = verify::verify(obj).unwrap().link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut act = Activation::new(&linked, 0, 0);
    let e = Vm::new(100, Clock::new(1, 0)).run(&linked, &mut act, &mut store, None).expect_err("read-only");
    assert_eq!(e.code.as_str(), "R0008");
    assert!(e.message.contains("B.W is read-only"), "{e}");
}

#[test]
fn an_action_for_one_block_type_refuses_another() {
    let bytes = compile("ACTION m : PID\nSL := 1.0;\nEND_ACTION\n", guide_db());
    let store = Store::new(guide_db().clone());
    let anin = store.db.block("ANIN_004").unwrap();
    let e =
        linc_runtime::load(&bytes).unwrap().link(&store, &[Program { unit: 0, own: Some(anin) }]).expect_err("type");
    assert!(e.to_string().contains("runs on a PID block, but `ANIN_004` is a ANIN block"), "{e}");
}

#[test]
fn a_doubling_concat_loop_is_a_located_runtime_error() {
    let r = run("RAW_COM.Buffer1 := 'x';\nWHILE 1 DO\n  RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, RAW_COM.Buffer1);\nEND_WHILE;\n");
    let e = r.error.as_ref().expect("stops");
    assert_eq!((e.code.as_str(), e.line), ("R0007", 3), "{e}");
    assert_eq!(r.get("RAW_COM.Buffer1").len(), 32_768 + 2, "the last good value stays");
}

#[test]
fn the_string_budget_holds_for_a_hand_made_object() {
    use Op::*;
    // A verified object that pushes a 60,000-byte constant forever.
    let mut obj = object(vec![PushS { k: 0 }, Decode {}, StoreS { sym: 0 }, Jump { to: 0 }, Ret {}], vec![0], 0, 0);
    obj.symbols =
        vec![Symbol { block: "RAW_COM".into(), field: "Buffer1".into(), sub: Sub::Field, class: Class::Bseq }];
    obj.strings = vec![Bytes(vec![b'a'; 60_000])];
    let v = verify::verify(obj).expect("verifies");
    let mut store = Store::new(guide_db().clone());
    let linked = v.link(&store, &[Program { unit: 0, own: None }]).expect("links");
    let mut act = Activation::new(&linked, 0, 0);
    let e = Vm::new(u64::MAX, Clock::new(1, 0)).run(&linked, &mut act, &mut store, None).expect_err("budget");
    assert_eq!(e.code.as_str(), "R0007");
    assert!(e.message.contains("16777216 bytes"), "{e}");
}

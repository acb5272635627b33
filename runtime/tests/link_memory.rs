//! Loading, linking and running an object needs memory in proportion to
//! the file: at most [`FACTOR`] times its size, the file's own bytes
//! included (issue 30). A counting allocator measures the peak of live heap
//! bytes while an object of one-byte instructions that jump and name
//! fields, the densest code the format has, is loaded, linked and run.
//! Linking used to copy such a block, at 8 bytes per instruction, on top of
//! the 8 the loaded object holds.

use linc_runtime::isa::Op;
use linc_runtime::object::{Class, CodeBlock, ObjectFile, Sub, Symbol, Unit};
use linc_runtime::vm::{Activation, Clock, Vm};
use linc_runtime::wire::Code;
use linc_runtime::{Database, Program, Store};
use linc_test_support::alloc::{peak_of, serial, Counting};

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The most heap loading, linking and running may need, in multiples of
/// the file's size.
const FACTOR: usize = 10;

/// A block `B` with INT fields `N` (0) and `M`, on top of the built-in
/// library.
fn store() -> Store {
    let text = r#"{ "templates": { "T": { "fields": { "N": "INT", "M": "INT" } } },
                    "blocks": { "B": { "type": "T" } } }"#;
    Store::new(Database::from_json(text).expect("the database loads"))
}

fn symbol(block: &str, field: &str) -> Symbol {
    Symbol { block: block.into(), field: field.into(), sub: Sub::Field, class: Class::Int }
}

/// An action of about `n` one-byte instructions: `B.N` (0) negated `n`
/// times (odd: TRUE), a jump back to the start when that is FALSE, then
/// `B.M := NOT B.N`. A run executes every instruction once and leaves 1 in
/// `B.M`.
fn dense(n: usize, block: &str) -> Vec<u8> {
    let mut ops = vec![Op::LoadI { sym: 0 }];
    ops.resize((n | 1) + 1, Op::Not {});
    ops.extend([Op::JumpIfFalse { to: 0 }, Op::LoadI { sym: 0 }, Op::Not {}, Op::StoreI { sym: 1 }, Op::Ret {}]);
    let code = CodeBlock { ops: Code(ops), labels: vec![0], ..CodeBlock::default() };
    let unit = Unit { name: "A".into(), blocks: vec![code], ..Unit::default() };
    let symbols = vec![symbol(block, "N"), symbol(block, "M")];
    ObjectFile { source: "x.st".into(), symbols, strings: Vec::new(), units: vec![unit] }.to_bytes()
}

/// Loads, links and runs `bytes` (an action on `B`, whose `B.M` it sets to
/// 1): the peak of live heap bytes beyond the store's, and `B.M` after.
fn load_link_run(bytes: &[u8]) -> (usize, String) {
    let mut store = store();
    let mut vm = Vm::new(1 << 40, Clock::new(1, 0));
    let peak = peak_of(|| {
        let linked = linc_runtime::load(bytes).expect("loads").link(&store, &[Program { unit: 0, own: None }]);
        let linked = linked.expect("links");
        let mut act = Activation::new(&linked, 0, 0);
        vm.run(&linked, &mut act, &mut store, None).expect("runs");
    });
    let m = store.cell_of(store.db.block("B").expect("B"), "M").expect("B.M");
    (peak, store.show(m))
}

/// The sizes measured, in MiB of instructions: 1 and 4 by default (a
/// second each in a debug build); `LINC_OBJECT_MB=200` measures 4 and 200
/// (about 40 s and 2 GB in a release build: `cargo test --release -p
/// linc-runtime --test link_memory`).
fn sizes() -> [usize; 2] {
    match std::env::var("LINC_OBJECT_MB").ok().and_then(|v| v.parse::<usize>().ok()) {
        Some(mb) if mb > 4 => [4 << 20, mb << 20],
        _ => [1 << 20, 4 << 20],
    }
}

#[test]
fn loading_linking_and_running_need_at_most_ten_times_the_file() {
    let _one = serial();
    let mut peaks = Vec::new();
    for n in sizes() {
        let bytes = dense(n, "B");
        let size = bytes.len();
        let (peak, m) = load_link_run(&bytes);
        eprintln!("{size} bytes: peak {peak} + the file ({:.1}x)", (peak + size) as f64 / size as f64);
        assert_eq!(m, "1", "the program ran to its end");
        assert!(peak + size <= size * FACTOR, "peak heap {peak} bytes (and the file's) for a {size}-byte object");
        peaks.push((size, peak));
    }
    // Linear: k times the code takes at most a little over k times the
    // memory.
    let [(small, p1), (large, p4)] = peaks[..] else { unreachable!() };
    assert!(p4 * small <= p1 * large * 11 / 10, "{p1} bytes for {small}, {p4} for {large}");
}

/// A unit linked as two programs (one action run by two blocks) is linked
/// in place for the last and in a copy for the first: each runs against
/// its own block, and both run the same instructions.
#[test]
fn a_unit_linked_twice_runs_on_each_block() {
    let _one = serial();
    let text = r#"{ "templates": { "T": { "fields": { "N": "INT", "M": "INT" } } },
                    "blocks": { "B": { "type": "T" }, "C": { "type": "T", "values": { "N": 1 } } } }"#;
    let mut store = Store::new(Database::from_json(text).expect("the database loads"));
    let mut obj = ObjectFile::from_bytes(&dense(9, "")).expect("decodes");
    obj.units[0].block_type = "T".into();
    let verified = linc_runtime::verify::verify(obj).expect("verifies");
    let (b, c) = (store.db.block("B").expect("B"), store.db.block("C").expect("C"));
    let programs = [Program { unit: 0, own: Some(b) }, Program { unit: 0, own: Some(c) }];
    let linked = verified.link(&store, &programs).expect("links");
    assert_eq!(linked.ops(0, 0), linked.ops(1, 0));
    assert_eq!(linked.ops(0, 0).map(|ops| ops[ops.len() - 2]), Some(Op::StoreI { sym: 1 }));
    let mut vm = Vm::new(1000, Clock::new(1, 0));
    let mut act = Activation::new(&linked, 0, 0);
    vm.run(&linked, &mut act, &mut store, None).expect("B runs");
    // C.N is 1: negated 9 times it is FALSE, and the program loops until
    // the watchdog stops it.
    let mut act = Activation::new(&linked, 1, 0);
    let e = vm.run(&linked, &mut act, &mut store, None).expect_err("C loops");
    assert_eq!(e.code.as_str(), "R0006", "{e}");
    let show = |block, field| store.show(store.cell_of(block, field).expect("a field"));
    assert_eq!((show(b, "M"), show(c, "M")), ("1".to_string(), "0".to_string()));
}

//! Loading an object (decoding and verifying it) needs memory in
//! proportion to the file: at most [`FACTOR`] times its size, whatever its
//! tables hold. A counting allocator measures the peak of live heap bytes
//! while objects built to be as dense as the format allows are loaded: many
//! one-byte instructions, empty names, empty constants, empty records.

use linc_runtime::isa::Op;
use linc_runtime::object::{
    ActionRec, AssocRec, ChartRec, Class, CodeBlock, LineEntry, ObjectFile, StepRec, Sub, Symbol, TransitionRec, Unit,
    UnitKind,
};
use linc_runtime::wire::{Bytes, Code};
use linc_test_support::alloc::{serial, Counting};

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// The peak of live heap bytes while `f` runs, beyond what was live before,
/// with its result (callers hold [`serial`]).
fn peak_of<T>(f: impl FnOnce() -> T) -> (usize, T) {
    let mut out = None;
    let peak = linc_test_support::alloc::peak_of(|| out = Some(f()));
    (peak, out.expect("the closure ran"))
}

/// The most heap a load may need, in multiples of the file's size.
const FACTOR: usize = 10;

fn object(units: Vec<Unit>) -> ObjectFile {
    ObjectFile { source: "x.st".into(), symbols: Vec::new(), strings: Vec::new(), units }
}

fn empty_symbol() -> Symbol {
    Symbol { block: String::new(), field: String::new(), sub: Sub::Field, class: Class::Int }
}

fn block(ops: Vec<Op>) -> CodeBlock {
    CodeBlock { ops: Code(ops), labels: vec![0], ..CodeBlock::default() }
}

fn unit(blocks: Vec<CodeBlock>) -> Unit {
    Unit { name: "A".into(), blocks, ..Unit::default() }
}

/// Objects of about `n` bytes, each dense in one kind of record.
fn dense(n: usize) -> Vec<(&'static str, ObjectFile)> {
    let ret = || block(vec![Op::Ret {}]);
    let mut out = Vec::new();
    // Code: one-byte instructions (a value pushed, negated over and over,
    // popped by a jump back to the start).
    let mut ops = vec![Op::PushI { v: 1 }];
    ops.resize(n, Op::Not {});
    ops.extend([Op::JumpIfFalse { to: 0 }, Op::Ret {}]);
    out.push(("code", object(vec![unit(vec![block(ops)])])));
    // As many symbols as instructions can name (each takes 88 bytes for 6 in
    // the file, so the count is limited), the rest of the file a constant.
    let mut o = object(vec![unit(vec![ret()])]);
    o.symbols = vec![empty_symbol(); 1 << 16];
    o.strings = vec![Bytes(vec![b'x'; n.saturating_sub(6 << 16)])];
    out.push(("symbols", o));
    let mut o = object(vec![unit(vec![ret()])]);
    o.strings = vec![Bytes(Vec::new()); n / 4];
    out.push(("strings", o));
    out.push(("units", object((0..n / 30).map(|_| unit(vec![ret()])).collect())));
    // Blocks: a unit has at most 65,536 (charts name them by a u16).
    let blocks: Vec<CodeBlock> = (0..n / 25).map(|_| ret()).collect();
    out.push(("blocks", object(blocks.chunks(1 << 16).map(|c| unit(c.to_vec())).collect())));
    let mut b = ret();
    b.lines = vec![LineEntry { op: 0, line: 1, col: 1 }; n / 12];
    b.labels = vec![0; n / 4];
    out.push(("tables", object(vec![unit(vec![b])])));
    // Likewise an FST table's step names (24 bytes for 2).
    let mut u = Unit { kind: UnitKind::Fst, ..unit(vec![ret()]) };
    u.steps = vec![String::new(); 1 << 16];
    let mut o = object(vec![u]);
    o.strings = vec![Bytes(vec![b'x'; n.saturating_sub(2 << 16)])];
    out.push(("fst steps", o));
    let mut u = Unit { kind: UnitKind::Sequence, retained: u16::MAX, ..unit(vec![ret()]) };
    let step =
        |i: usize| StepRec { name: String::new(), initial: u8::from(i == 0), slot: 0, assocs: Vec::new(), line: 0 };
    let chart = ChartRec {
        steps: (0..n / 27).map(step).collect(),
        transitions: vec![
            TransitionRec {
                name: String::new(),
                from: vec![],
                to: vec![],
                priority: 0,
                block: 0,
                line: 0
            };
            n / 54
        ],
        actions: vec![ActionRec { name: String::new(), kind: 0, index: 0 }; n / 54],
    };
    u.charts = vec![chart];
    out.push(("charts", object(vec![u])));
    let mut u = Unit { kind: UnitKind::Sequence, retained: u16::MAX, ..unit(vec![ret()]) };
    let assocs = vec![AssocRec { action: 0, qualifier: b'N', time_us: 0 }; n / 11];
    let steps = vec![StepRec { name: String::new(), initial: 1, slot: 0, assocs, line: 0 }];
    u.charts = vec![ChartRec { steps, transitions: Vec::new(), actions: Vec::new() }];
    out.push(("associations", object(vec![u])));
    out
}

#[test]
fn loading_needs_at_most_ten_times_the_file() {
    let _one = serial();
    for (what, obj) in dense(2 << 20) {
        let bytes = obj.to_bytes();
        drop(obj);
        let (peak, loaded) = peak_of(|| linc_runtime::load(&bytes).map(drop));
        let size = bytes.len();
        eprintln!("{what}: {size} bytes, peak {peak} ({:.1}x), {loaded:?}", peak as f64 / size as f64);
        assert!(peak <= size * FACTOR, "{what}: peak heap {peak} bytes loading a {size}-byte object");
    }
}

/// A table longer than what can name its entries is refused before it is
/// read: 65,537 symbols (a `u16` names 65,536), code blocks of a unit, FST
/// steps.
#[test]
fn tables_longer_than_their_names_allow_are_refused_unread() {
    let _one = serial();
    let mut o = object(vec![unit(vec![block(vec![Op::Ret {}])])]);
    o.symbols = vec![empty_symbol(); (1 << 16) + 1];
    let bytes = o.to_bytes();
    let (peak, loaded) = peak_of(|| linc_runtime::load(&bytes).map(drop));
    assert!(matches!(&loaded, Err(e) if e.code() == "E0703" && e.to_string().contains("65537 entries")), "{loaded:?}");
    assert!(peak < 1024, "refused after allocating {peak} bytes");
    let bytes = object(vec![unit(vec![block(vec![Op::Ret {}]); (1 << 16) + 1])]).to_bytes();
    let (peak, loaded) = peak_of(|| linc_runtime::load(&bytes).map(drop));
    assert!(matches!(&loaded, Err(e) if e.code() == "E0703"), "{loaded:?}");
    assert!(peak < 1024, "refused after allocating {peak} bytes");
    let mut u = Unit { kind: UnitKind::Fst, ..unit(vec![block(vec![Op::Ret {}])]) };
    u.steps = vec![String::new(); (1 << 16) + 1];
    let bytes = object(vec![u]).to_bytes();
    let (peak, loaded) = peak_of(|| linc_runtime::load(&bytes).map(drop));
    assert!(matches!(&loaded, Err(e) if e.code() == "E0703"), "{loaded:?}");
    assert!(peak < 1024, "refused after allocating {peak} bytes");
}

/// Translating a block takes memory in proportion to it (a 100 MB block
/// took 21 GB in Cranelift), so a block of more than `MAX_BLOCK_OPS`
/// instructions stays on the interpreter; the same code, shorter, compiles.
#[test]
fn a_block_too_large_to_translate_is_left_to_the_interpreter() {
    use linc_runtime::{Database, Program, Store};
    // It measures nothing, but its allocations would count in the others'.
    let _one = serial();
    let code = |n: usize| {
        let mut ops = vec![Op::PushI { v: 1 }];
        ops.resize(n - 2, Op::Not {});
        ops.extend([Op::JumpIfFalse { to: 0 }, Op::Ret {}]);
        object(vec![unit(vec![block(ops)])]).to_bytes()
    };
    let store = Store::new(Database::builtin());
    let compiles = |bytes: &[u8]| {
        let linked = linc_runtime::load(bytes).expect("loads").link(&store, &[Program { unit: 0, own: None }]);
        linc_runtime::jit::compile(&linked.expect("links"), &store, 0, 0).is_some()
    };
    assert!(compiles(&code(100)));
    assert!(!compiles(&code(linc_runtime::jit::MAX_BLOCK_OPS + 1)));
}

/// Linking copies only the blocks it changes (those with symbols or jumps):
/// a block it does not change runs the object's instructions, so a program
/// of one-byte instructions is not held twice.
#[test]
fn linking_copies_no_block_it_does_not_change() {
    use linc_runtime::{Database, Program, Store};
    let _one = serial();
    let mut ops = vec![Op::PushI { v: 1 }];
    ops.resize(1 << 20, Op::Not {});
    ops.extend([Op::StoreLoc { n: 0 }, Op::Ret {}]);
    let bytes = object(vec![unit(vec![CodeBlock { locals: 1, ..block(ops) }])]).to_bytes();
    let store = Store::new(Database::builtin());
    let verified = linc_runtime::load(&bytes).expect("loads");
    let (peak, linked) = peak_of(|| verified.link(&store, &[Program { unit: 0, own: None }]).expect("links"));
    assert!(peak < bytes.len() / 4, "linking took {peak} bytes for a {}-byte object", bytes.len());
    assert_eq!(linked.ops(0, 0).map(<[Op]>::len), Some((1 << 20) + 2));
}

/// A database declares at most `MAX_CELLS` fields: 300 blocks of a template
/// of 10,000 fields (170 kB of JSON) made a store of 3 million cells. Blocks
/// now cost memory in proportion to their own text, not to their fields.
#[test]
fn blocks_need_memory_in_proportion_to_their_text() {
    use linc_runtime::{Database, Store};
    let _one = serial();
    let fields: Vec<String> = (0..10_000).map(|i| format!("\"F{i}\": \"REAL\"")).collect();
    let text = |n: usize| {
        let blocks: Vec<String> = (0..n).map(|i| format!("\"B{i}\": {{ \"type\": \"BIG\" }}")).collect();
        format!(
            "{{ \"templates\": {{ \"BIG\": {{ \"fields\": {{ {} }} }} }}, \"blocks\": {{ {} }} }}",
            fields.join(", "),
            blocks.join(", ")
        )
    };
    let (one, many) = (text(1), text(300));
    let (base, cells) = peak_of(|| Database::from_json(&one).map(|db| Store::new(db).cells.len()));
    assert_eq!(cells, Ok(10_000));
    let (peak, cells) = peak_of(|| Database::from_json(&many).map(|db| Store::new(db).cells.len()));
    assert_eq!(cells.map_err(|e| e.code.as_str()), Err("E0819"));
    // The JSON tree and the database hold about 20 bytes per byte of block
    // text (a remaining factor of the JSON loader); the cells of the 3
    // million fields were some 12,000 times the text.
    let blocks = many.len() - one.len();
    assert!(peak < base + blocks * 32, "{peak} bytes with 300 blocks, {base} with one; the blocks are {blocks} bytes");
}

//! Mutation fuzzing of the object loader, verifier, linker and VM.
//!
//! Objects compiled from realistic actions are damaged (bytes, and fields of
//! the decoded `ObjectFile` re-encoded by `to_bytes`), with the checksum
//! resealed so that the damage reaches the decoder, the verifier and the VM.
//! Every accepted object is linked and run under a small watchdog. The house
//! rule is that bad input never panics and never exhausts memory: a panic
//! fails this test (nothing here catches one; a hook only names the case),
//! and the peak of live heap bytes is asserted below a budget.
//!
//! `LINC_OBJECT_FUZZ_CASES=N` sets the number of cases (default 20,000, a
//! few seconds in a debug build); `LINC_OBJECT_FUZZ_ONLY=N` reruns case N;
//! `LINC_TIER=compiled|interpreter` chooses the tier (default: as `linc run`).
use linc_conformance::rng::Rng;
use linc_runtime::isa::{Op, OPCODES};
use linc_runtime::object::{crc32, Class, CodeBlock, LineEntry, LoopEntry, ObjectFile, Sub};
use linc_runtime::store::Store;
use linc_runtime::vm::{Activation, Clock, Outcome, Vm};
use linc_runtime::wire::Bytes;
use linc_runtime::Program;
use linc_test_support::alloc::Counting;
use std::cell::RefCell;
use std::collections::BTreeMap;
use std::time::{Duration, Instant};

#[path = "object_fuzz/corpus.rs"]
mod corpus;
use corpus::{corpus, fuzz_db, Seed};

/// Counts live heap bytes and their peak, so the memory assertion measures
/// what the loader and VM hold, independent of how the allocator keeps pages.
#[global_allocator]
static GLOBAL: Counting = Counting;

/// Budget for live heap bytes at any moment of the run. An object is at most
/// a few MiB here, the VM allows 16 MiB of strings per run and the store is
/// fixed in size, so a fuzz run that needs more than this is leaking or
/// allocating from a damaged count.
const LIVE_BUDGET: usize = 256 << 20;
/// Budget for the process's resident peak (`VmHWM`, Linux), which also
/// counts the test harness, code and allocator slack.
const RESIDENT_BUDGET_KIB: u64 = 512 << 10;
/// Instructions per run: enough for the corpus's loops, small enough that
/// mutated endless loops cost little.
const WATCHDOG: u64 = 20_000;
/// Runs per code block, so suspensions resume and retained slots carry over.
const RUNS: usize = 3;

/// What the fuzz test draws besides plain numbers.
trait Draw {
    fn byte(&mut self) -> u8;
    fn number(&mut self) -> u32;
}

impl Draw for Rng {
    fn byte(&mut self) -> u8 {
        self.next_u64() as u8
    }
    /// Mostly small numbers, sometimes boundary values, sometimes anything.
    fn number(&mut self) -> u32 {
        const EDGES: [u32; 12] = [0, 1, 2, 7, 8, 0x7F, 0x80, 0xFF, 0xFFFF, 0x1_0000, 0x7FFF_FFFF, 0xFFFF_FFFF];
        match self.below(4) {
            0 | 1 => self.below(16) as u32,
            2 => EDGES[self.below(EDGES.len())],
            _ => self.next_u64() as u32,
        }
    }
}

thread_local! {
    /// The case being run, for the panic hook.
    static CURRENT: RefCell<(u64, Vec<&'static str>, Vec<u8>)> = const { RefCell::new((0, Vec::new(), Vec::new())) };
}

/// Names the failing case when anything panics (the panic still fails the
/// test): its number, its mutations, and the object, saved to a file.
fn install_hook() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let _ = CURRENT.try_with(|c| {
            if let Some(c) = c.try_borrow().ok().filter(|c| !c.2.is_empty()) {
                let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("object_fuzz_{}.sto", c.0));
                let _ = std::fs::write(&path, &c.2);
                let hex: String = c.2.iter().take(2048).map(|b| format!("{b:02x}")).collect();
                eprintln!(
                    "object_fuzz: case {} panicked (rerun with LINC_OBJECT_FUZZ_ONLY={}); mutations {:?}; object ({} bytes) saved to {}: {hex}",
                    c.0,
                    c.0,
                    c.1,
                    c.2.len(),
                    path.display()
                );
            }
        });
        default(info);
    }));
}

/// A position in the body (rarely in the header).
fn pos(rng: &mut Rng, len: usize) -> usize {
    if len > 20 && !rng.one_in(20) {
        20 + rng.below(len - 20)
    } else {
        rng.below(len.max(1))
    }
}

/// One byte-level mutation; returns its name.
fn mutate_bytes(rng: &mut Rng, data: &mut Vec<u8>, other: &[u8]) -> &'static str {
    if data.is_empty() {
        data.extend_from_slice(other);
    }
    let len = data.len();
    let at = pos(rng, len);
    match rng.below(10) {
        0 => {
            data[at] ^= 1 << rng.below(8);
            "flip bit"
        }
        1 => {
            data[at] = rng.byte();
            "random byte"
        }
        2 => {
            data[at] = OPCODES[rng.below(OPCODES.len())];
            "opcode byte"
        }
        3 => {
            let n = if rng.one_in(8) { rng.below(300) } else { 1 + rng.below(16) };
            let fill: Vec<u8> = (0..n).map(|_| rng.byte()).collect();
            data.splice(at..at, fill);
            "insert bytes"
        }
        4 => {
            let end = (at + 1 + rng.below(16)).min(len);
            data.drain(at..end);
            "delete bytes"
        }
        5 => {
            let end = (at + 1 + rng.below(64)).min(len);
            let slice = data[at..end].to_vec();
            let to = pos(rng, len);
            data.splice(to..to, slice);
            "duplicate slice"
        }
        6 if at + 4 <= len => {
            data[at..at + 4].copy_from_slice(&rng.number().to_le_bytes());
            "set u32"
        }
        7 if at + 2 <= len => {
            data[at..at + 2].copy_from_slice(&(rng.number() as u16).to_le_bytes());
            "set u16"
        }
        8 => {
            let from = pos(rng, other.len());
            data.truncate(at);
            data.extend_from_slice(&other[from..]);
            "splice objects"
        }
        _ => {
            data.truncate(at);
            "truncate"
        }
    }
}

/// Rewrites the length field and the checksum (almost always), so that the
/// damage reaches the decoder and the verifier instead of the CRC check.
fn fix_header(rng: &mut Rng, data: &mut [u8]) {
    if data.len() < 20 {
        return;
    }
    if !rng.one_in(16) {
        let len = data.len() as u32;
        data[16..20].copy_from_slice(&len.to_le_bytes());
    }
    if !rng.one_in(32) {
        data[12..16].fill(0);
        let crc = crc32(data);
        data[12..16].copy_from_slice(&crc.to_le_bytes());
    }
}

/// A REAL constant, often a special one.
fn real(rng: &mut Rng) -> f32 {
    const SPECIAL: [f32; 9] =
        [0.0, -0.0, 1.0, -1.5, f32::NAN, f32::INFINITY, f32::NEG_INFINITY, f32::MAX, f32::MIN_POSITIVE];
    if rng.one_in(2) {
        SPECIAL[rng.below(SPECIAL.len())]
    } else {
        f32::from_bits(rng.next_u64() as u32)
    }
}

/// The same instruction with one operand changed.
fn tweak(rng: &mut Rng, op: Op, obj: &ObjectFile, labels: usize) -> Op {
    let small = |rng: &mut Rng, n: usize| if rng.one_in(4) { rng.number() } else { rng.below(n.max(1)) as u32 };
    match op {
        Op::PushI { .. } => Op::PushI { v: rng.number() as i32 },
        Op::PushR { .. } => Op::PushR { v: real(rng) },
        Op::PushS { .. } => Op::PushS { k: small(rng, obj.strings.len() + 1) },
        Op::LoadLoc { .. } => Op::LoadLoc { n: rng.number() as u8 },
        Op::StoreLoc { .. } => Op::StoreLoc { n: rng.number() as u8 },
        Op::LoadRet { .. } => Op::LoadRet { n: rng.number() as u16 },
        Op::StoreRet { .. } => Op::StoreRet { n: rng.number() as u16 },
        Op::LoadBit { sym, .. } => Op::LoadBit { sym, bit: rng.number() as u8 },
        Op::StoreBit { sym, .. } => Op::StoreBit { sym, bit: rng.number() as u8 },
        Op::RefBit { .. } => Op::RefBit { bit: rng.number() as u8 },
        Op::RefBitOff { .. } => Op::RefBitOff { bit: rng.number() as u8 },
        Op::Return { .. } => Op::Return { kind: rng.number() as u8 },
        Op::Call { func, argc, ret, types } => match rng.below(4) {
            0 => Op::Call { func: rng.number() as u8, argc, ret, types },
            1 => Op::Call { func, argc: rng.number() as u8, ret, types },
            2 => Op::Call { func, argc, ret: rng.number() as u8, types },
            _ => Op::Call { func, argc, ret, types: types ^ (3 << (2 * rng.below(16))) },
        },
        op if op.symbol().is_some() => op.with_symbol(small(rng, obj.symbols.len()) as u16),
        op if op.target().is_some() => op.retarget(small(rng, labels)),
        op => op,
    }
}

/// Any instruction, with operands mostly in range.
fn random_op(rng: &mut Rng, obj: &ObjectFile, labels: usize) -> Op {
    let mut code = vec![OPCODES[rng.below(OPCODES.len())]];
    code.extend((0..12).map(|_| if rng.one_in(2) { 0 } else { rng.below(4) as u8 }));
    let op = Op::decode(&code, &mut 0).unwrap_or(Op::Ret {});
    let op = op.with_symbol(rng.below(obj.symbols.len().max(1)) as u16);
    let op = if op.target().is_some() { op.retarget(rng.below(labels.max(1)) as u32) } else { op };
    if rng.one_in(3) {
        tweak(rng, op, obj, labels)
    } else {
        op
    }
}

/// Indices of a random unit and code block, if the object has one.
fn pick_block(rng: &mut Rng, obj: &ObjectFile) -> Option<(usize, usize)> {
    let u = rng.below(obj.units.len());
    let b = rng.below(obj.units.get(u)?.blocks.len());
    obj.units[u].blocks.get(b).map(|_| (u, b))
}

/// Inserts `ops` before instruction `at`, moving the labels, line and loop
/// entries after it, so the tables stay consistent and the verifier looks
/// at the new code itself.
fn insert_ops(block: &mut CodeBlock, at: usize, ops: &[Op]) {
    let (at32, k) = (at as u32, ops.len() as u32);
    block.ops.0.splice(at..at, ops.iter().copied());
    block.labels.iter_mut().filter(|l| **l > at32).for_each(|l| *l += k);
    block.lines.iter_mut().filter(|e| e.op > at32).for_each(|e| e.op += k);
    for lp in &mut block.loops {
        lp.start += k * u32::from(lp.start > at32);
        lp.end += k * u32::from(lp.end >= at32);
    }
}

/// A random instruction with the given stack effect, if one turns up soon.
fn op_with_effect(rng: &mut Rng, obj: &ObjectFile, labels: usize, want: [u32; 4]) -> Option<Op> {
    (0..64).map(|_| random_op(rng, obj, labels)).find(|op| {
        let e = op.effect();
        [e.num_pop, e.num_push, e.str_pop, e.str_push] == want
    })
}

/// Instructions that keep the stacks balanced when inserted at the start of
/// a statement: a suspension, or a push followed by a pop of the same stack.
fn balanced(rng: &mut Rng, obj: &ObjectFile, labels: usize) -> Vec<Op> {
    let (push, pop) = if rng.one_in(2) { ([0, 1, 0, 0], [1, 0, 0, 0]) } else { ([0, 0, 0, 1], [0, 0, 1, 0]) };
    match rng.below(3) {
        0 => vec![Op::Yield {}],
        _ => op_with_effect(rng, obj, labels, push).into_iter().chain(op_with_effect(rng, obj, labels, pop)).collect(),
    }
}

/// A mutation of one code block's instructions.
fn mutate_code(rng: &mut Rng, obj: &mut ObjectFile) -> &'static str {
    let Some((u, b)) = pick_block(rng, obj) else { return "no block" };
    let block = &obj.units[u].blocks[b];
    let (n, labels) = (block.ops.len(), block.labels.len());
    let at = rng.below(n);
    let mut ops = block.ops.0.clone();
    let name = match rng.below(8) {
        0 | 1 if n > 0 => {
            ops[at] = tweak(rng, ops[at], obj, labels);
            "operand"
        }
        2 if n > 0 => {
            ops[at] = random_op(rng, obj, labels);
            "replace op"
        }
        3 if n > 0 => {
            ops.swap(at, rng.below(n));
            "swap ops"
        }
        4 if n > 0 => {
            ops.remove(at);
            "delete op"
        }
        5 if n > 0 => {
            ops.insert(at, ops[rng.below(n)]);
            "duplicate op"
        }
        6 => {
            // At the start of a statement, where both stacks are empty.
            let starts: Vec<usize> = block.lines.iter().map(|e| e.op as usize).collect();
            let at = starts.get(rng.below(starts.len())).copied().unwrap_or(0).min(n);
            let new = balanced(rng, obj, labels);
            insert_ops(&mut obj.units[u].blocks[b], at, &new);
            return "insert balanced ops";
        }
        _ => {
            let new: Vec<Op> = (0..1 + rng.below(3)).map(|_| random_op(rng, obj, labels)).collect();
            insert_ops(&mut obj.units[u].blocks[b], at, &new);
            return "insert ops";
        }
    };
    obj.units[u].blocks[b].ops.0 = ops;
    name
}

/// A mutation of a block's labels, locals, line or loop table, or its unit's
/// retained slots.
fn mutate_tables(rng: &mut Rng, obj: &mut ObjectFile) -> &'static str {
    let Some((u, b)) = pick_block(rng, obj) else { return "no block" };
    let unit = &mut obj.units[u];
    let block = &mut unit.blocks[b];
    let n = block.ops.len() as u32;
    let near = |rng: &mut Rng| if rng.one_in(4) { rng.number() } else { rng.below(n as usize + 2) as u32 };
    match rng.below(8) {
        0 if !block.labels.is_empty() => {
            let l = rng.below(block.labels.len());
            block.labels[l] = near(rng);
            "label"
        }
        1 => {
            block.labels.push(near(rng));
            "add label"
        }
        2 => {
            block.labels.pop();
            "drop label"
        }
        3 => {
            block.locals = rng.number() as u8;
            "locals"
        }
        4 => {
            unit.retained = rng.number() as u16;
            "retained"
        }
        5 if !block.lines.is_empty() && rng.one_in(2) => {
            let l = rng.below(block.lines.len());
            let e = &mut block.lines[l];
            match rng.below(3) {
                0 => e.op = near(rng),
                1 => e.line = rng.number(),
                _ => e.col = rng.number(),
            }
            "line entry"
        }
        5 => {
            let at = rng.below(block.lines.len() + 1);
            block.lines.insert(at, LineEntry { op: near(rng), line: rng.number(), col: rng.number() });
            "add line entry"
        }
        6 if !block.loops.is_empty() => {
            let l = rng.below(block.loops.len());
            let e = &mut block.loops[l];
            match rng.below(4) {
                0 => e.start = near(rng),
                1 => e.end = near(rng),
                2 => e.line = rng.number(),
                _ => std::mem::swap(&mut e.start, &mut e.end),
            }
            "loop entry"
        }
        _ => {
            let (s, e) = (near(rng), near(rng));
            block.loops.push(LoopEntry { start: s.min(e), end: s.max(e), line: rng.number(), col: 1 });
            "add loop entry"
        }
    }
}

/// A mutation of the symbol table.
fn mutate_symbols(rng: &mut Rng, obj: &mut ObjectFile) -> &'static str {
    const CLASSES: [Class; 12] = [
        Class::Real,
        Class::Int,
        Class::Bool,
        Class::Bits8,
        Class::Bits16,
        Class::Enum,
        Class::String,
        Class::Date,
        Class::Time,
        Class::Bseq,
        Class::Wstr,
        Class::Alarms,
    ];
    let n = obj.symbols.len();
    if n == 0 || rng.one_in(10) {
        let s = obj.symbols.get(rng.below(n)).cloned();
        obj.symbols.extend(s);
        return "duplicate symbol";
    }
    let other = obj.symbols[rng.below(n)].clone();
    let sym = &mut obj.symbols[rng.below(n)];
    match rng.below(6) {
        0 => sym.class = CLASSES[rng.below(CLASSES.len())],
        1 => {
            sym.sub = match rng.below(4) {
                0 => Sub::Field,
                1 => Sub::Alarm("HiLevel".into()),
                2 => Sub::Suppress(Some(["HiLevel", "LoLevel", "Nope"][rng.below(3)].into())),
                _ => Sub::Suppress(None),
            }
        }
        2 => sym.field = other.field,
        3 => sym.block = other.block,
        4 => sym.block.clear(),
        _ => {
            obj.symbols.swap(rng.below(n), rng.below(n));
            return "swap symbols";
        }
    }
    "symbol"
}

/// A mutation of the constant pool, sometimes to large sizes.
fn mutate_strings(rng: &mut Rng, obj: &mut ObjectFile) -> &'static str {
    let len = match rng.below(8) {
        0 => 65_535 + rng.below(3),
        1 if rng.one_in(16) => 1 << 20,
        2 => 1000 + rng.below(70_000),
        _ => rng.below(40),
    };
    let fill = match rng.below(4) {
        0 => vec![b'$'; len],
        1 => b"$N$L$R$P$T$$$'$0A$FF$".iter().cycle().take(len).copied().collect(),
        2 => (0..len).map(|_| rng.byte()).collect(),
        _ => vec![b'a'; len],
    };
    if obj.strings.is_empty() || rng.one_in(4) {
        obj.strings.push(Bytes(fill));
        "add constant"
    } else {
        let k = rng.below(obj.strings.len());
        obj.strings[k] = Bytes(fill);
        "constant"
    }
}

/// A mutation of the units: duplicate, drop, swap, block type, extra code
/// blocks, or a unit of another object (whose symbols do not match).
fn mutate_units(rng: &mut Rng, obj: &mut ObjectFile, other: &ObjectFile) -> &'static str {
    const TYPES: [&str; 6] = ["", "PID", "RAW_COM", "ANIN", "RECIPE", "NOSUCH"];
    let n = obj.units.len();
    let u = rng.below(n);
    match rng.below(7) {
        0 if n > 0 => {
            obj.units.push(obj.units[u].clone());
            "duplicate unit"
        }
        1 if n > 0 => {
            obj.units.remove(u);
            "drop unit"
        }
        2 if n > 0 => {
            obj.units.swap(u, rng.below(n));
            "swap units"
        }
        3 if n > 0 => {
            obj.units[u].block_type = TYPES[rng.below(TYPES.len())].into();
            "block type"
        }
        4 if n > 0 => {
            let unit = &mut obj.units[u];
            let b = unit.blocks.get(rng.below(unit.blocks.len())).cloned();
            unit.blocks.extend(b);
            "add code block"
        }
        5 if n > 0 => {
            obj.units[u].blocks.clear();
            "no code blocks"
        }
        _ => {
            if let Some(unit) = other.units.get(rng.below(other.units.len())) {
                obj.units.push(unit.clone());
            }
            "foreign unit"
        }
    }
}

/// One structural mutation of a decoded object.
fn mutate_object(rng: &mut Rng, obj: &mut ObjectFile, other: &ObjectFile) -> &'static str {
    match rng.below(10) {
        0..=3 => mutate_code(rng, obj),
        4 | 5 => mutate_tables(rng, obj),
        6 => mutate_symbols(rng, obj),
        7 => mutate_strings(rng, obj),
        _ => mutate_units(rng, obj, other),
    }
}

/// Runs a linked sequence unit through the engine for a few scans.
fn exercise_sequence(linked: &linc_runtime::Linked, vm: &mut Vm, store: &mut Store, t: &mut Tally) {
    use linc_engines::sequence::{chart::Chart, host::VmHost, Command, Sequence};
    let Some(unit) = linked.unit(0) else { return };
    let mut seq = Sequence::new(Chart::from_unit(unit, 0));
    seq.command(Command::Run);
    let mut act = Activation::new(linked, 0, 0);
    for scan in 0..RUNS as u64 * 4 {
        t.runs += 1;
        let mut host = VmHost { vm: &mut *vm, linked, act: &mut act, store: &mut *store, trace: None };
        match seq.scan(scan * 500_000, &mut host) {
            Ok(()) => t.done += 1,
            Err(e) => {
                *t.faults.entry(e.code.as_str()).or_default() += 1;
                seq.command(Command::Reset);
                seq.command(Command::Run);
            }
        }
    }
}

/// The object of case `case` and the names of its mutations: mostly
/// structural (re-encoded and resealed by `to_bytes`), otherwise bytes.
fn make_case(case: u64, corpus: &[Seed]) -> (Vec<u8>, Vec<&'static str>) {
    let mut rng = Rng::new(case);
    let a = &corpus[rng.below(corpus.len())];
    let b = &corpus[rng.below(corpus.len())];
    let mut names = Vec::new();
    let mut bytes = if rng.below(10) < 7 {
        let mut obj = a.obj.clone();
        for _ in 0..1 + rng.below(3) {
            names.push(mutate_object(&mut rng, &mut obj, &b.obj));
        }
        let bytes = obj.to_bytes();
        if !rng.one_in(6) {
            return (bytes, names);
        }
        bytes
    } else {
        a.bytes.clone()
    };
    let most = if rng.one_in(4) { 8 } else { 2 };
    for _ in 0..1 + rng.below(most) {
        names.push(mutate_bytes(&mut rng, &mut bytes, &b.bytes));
    }
    fix_header(&mut rng, &mut bytes);
    (bytes, names)
}

/// What happened to the cases.
#[derive(Default, Debug)]
struct Tally {
    cases: u64,
    /// Refused by the decoder or verifier, by error code.
    rejected: BTreeMap<&'static str, u64>,
    accepted: u64,
    link_failed: u64,
    runs: u64,
    done: u64,
    suspended: u64,
    /// Runtime errors, by code.
    faults: BTreeMap<&'static str, u64>,
    slowest: Duration,
}

impl Tally {
    fn rejected_total(&self) -> u64 {
        self.rejected.values().sum()
    }
    /// Rejections by framing or decoding: the rest reached the verifier.
    fn undecoded(&self) -> u64 {
        ["E0700", "E0701", "E0702", "E0703", "E0704"].iter().map(|c| self.rejected.get(c).copied().unwrap_or(0)).sum()
    }
}

/// The block that runs an `ACTION name : TYPE` unit: the first of its type.
fn own_block(store: &Store, block_type: &str) -> Option<usize> {
    if block_type.is_empty() {
        return None;
    }
    (0..store.db.blocks.len()).find(|&b| store.db.block_template(b).name.eq_ignore_ascii_case(block_type))
}

/// Loads `bytes`; if accepted, links each unit to a fresh copy of `base`
/// and runs each of its code blocks a few times.
fn exercise(case: u64, bytes: &[u8], base: &Store, t: &mut Tally) {
    let verified = match linc_runtime::load(bytes) {
        Ok(v) => v,
        Err(e) => {
            *t.rejected.entry(e.code().as_str()).or_default() += 1;
            return;
        }
    };
    t.accepted += 1;
    let mut vm = Vm::new(WATCHDOG, Clock::new(case, 0));
    vm.set_tier(tier());
    for unit in 0..verified.object().units.len().min(16) {
        let mut store = base.clone();
        let own = own_block(&store, &verified.object().units[unit].block_type);
        let Ok(linked) = verified.clone().link(&store, &[Program { unit, own }]) else {
            t.link_failed += 1;
            continue;
        };
        if linked.unit(0).is_some_and(|u| !u.charts.is_empty()) {
            exercise_sequence(&linked, &mut vm, &mut store, t);
            continue;
        }
        for block in 0..linked.unit(0).map_or(0, |u| u.blocks.len()).min(16) {
            let mut act = Activation::new(&linked, 0, block);
            for _ in 0..RUNS {
                t.runs += 1;
                // An FST unit's steps per run (ignored by other units).
                act.steps_left = 20;
                match vm.run(&linked, &mut act, &mut store, None) {
                    Ok(Outcome::Done) => t.done += 1,
                    Ok(Outcome::Suspended) => t.suspended += 1,
                    Err(e) => *t.faults.entry(e.code.as_str()).or_default() += 1,
                }
                store.now += 1.0;
            }
        }
    }
}

/// The tier the objects run on: `LINC_TIER=compiled` compiles every block
/// at its first run, `interpreter` none; by default, as `linc run` does.
fn tier() -> linc_runtime::vm::Tier {
    use linc_runtime::vm::Tier;
    match std::env::var("LINC_TIER").as_deref() {
        Ok("compiled") => Tier::Compiled,
        Ok("interpreter") => Tier::Interpreter,
        _ => Tier::Auto,
    }
}

/// The process's resident peak in KiB (`VmHWM`), where /proc has it.
fn resident_peak_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn env_u64(name: &str) -> Option<u64> {
    std::env::var(name).ok().map(|v| v.replace(['_', ','], "").parse().unwrap_or_else(|_| panic!("{name}={v}")))
}

#[test]
fn mutated_objects_never_panic_and_stay_within_memory() {
    install_hook();
    let corpus = corpus();
    let mut base = Store::new(fuzz_db().clone());
    base.now = 1_000_000.0;
    let cases: Vec<u64> = match env_u64("LINC_OBJECT_FUZZ_ONLY") {
        Some(one) => vec![one],
        None => (0..env_u64("LINC_OBJECT_FUZZ_CASES").unwrap_or(20_000)).collect(),
    };
    let mut t = Tally::default();
    let start = Instant::now();
    for &case in &cases {
        let (bytes, names) = make_case(case, &corpus);
        CURRENT.with(|c| *c.borrow_mut() = (case, names, bytes));
        // Processor time on this thread: a busy machine does not count.
        let ((), took) =
            linc_test_support::work::thread_cpu(|| CURRENT.with(|c| exercise(case, &c.borrow().2, &base, &mut t)));
        t.slowest = t.slowest.max(took);
        t.cases += 1;
    }
    let elapsed = start.elapsed();
    let peak = linc_test_support::alloc::peak();
    let resident = resident_peak_kib();
    eprintln!(
        "object_fuzz: {} cases in {:.1} s; rejected {} ({} before the verifier) {:?}; accepted {}, link failed {}; {} runs: {} done, {} suspended, faults {:?}; slowest case {:?}; peak live heap {:.1} MiB, resident peak {:?} KiB",
        t.cases,
        elapsed.as_secs_f64(),
        t.rejected_total(),
        t.undecoded(),
        t.rejected,
        t.accepted,
        t.link_failed,
        t.runs,
        t.done,
        t.suspended,
        t.faults,
        t.slowest,
        peak as f64 / f64::from(1 << 20),
        resident,
    );
    assert!(peak < LIVE_BUDGET, "peak live heap {peak} bytes exceeds the budget of {LIVE_BUDGET}");
    if let Some(kib) = resident {
        assert!(kib < RESIDENT_BUDGET_KIB, "resident peak {kib} KiB exceeds {RESIDENT_BUDGET_KIB} KiB");
    }
    // A hang guard: the watchdog bounds each run, so no case may take much
    // work.
    assert!(t.slowest < Duration::from_secs(5), "a case took {:?}", t.slowest);
    // The verifier proves every cell an instruction reaches has the type it
    // expects, so "object and database disagree" can't happen at run time.
    assert_eq!(t.faults.get("R0099"), None, "{:?}", t.faults);
    if cases.len() >= 1000 {
        // Not vacuous: most damage reaches the verifier, some of it is
        // accepted and runs (some to a clean end, some to a runtime error).
        assert!(
            t.undecoded() * 2 < t.cases,
            "only {} of {} cases reached the verifier",
            t.cases - t.undecoded(),
            t.cases
        );
        assert!(t.accepted * 10 > t.cases && t.rejected_total() * 10 > t.cases, "{t:?}");
        assert!(t.done > 0 && t.faults.values().sum::<u64>() > 0 && t.link_failed > 0, "{t:?}");
    }
}

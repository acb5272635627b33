//! The load-time verifier.
//!
//! Verification is separate from decoding, linking and execution. It proves,
//! for every code block of every unit, that jumps name labels and labels land
//! on instructions; constants, symbols, locals, retained slots and bits are
//! in range and of the right kind; calls name real functions with acceptable
//! arguments; both stacks are balanced on every path (never popped below
//! empty, equal where paths meet, empty at `Ret` and `Yield`, so the state at
//! every resume point is known); the reference register is set on every path
//! before it is used, from the symbol the using instruction names; and line
//! and loop tables stay inside the code.
//!
//! Only [`verify`] makes a [`Verified`] object, and linking takes one, so an
//! object is verified exactly once on its way to the VM (ADR 0005).

use crate::errors::LoadError;
use crate::isa::{Flag, Kind, Op, MAX_CALL_ARGS};
use crate::object::{Class, CodeBlock, ObjectFile, Sub, Symbol, Unit, UnitKind};
use linc_format::Code;
use linc_stdlib::SIGNATURES;
use std::cell::Cell;

/// Stack sizes a code block needs, found by the verifier.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Limits {
    pub max_num: usize,
    pub max_str: usize,
}

/// The numeric stack where paths meet (at a label), as the verifier found
/// it: its depth and which entries are REAL (bit `i` for entry `i` from the
/// bottom). `known` is false when paths bring different types, or the
/// stack is deeper than the 64 entries typed: the values are 32-bit words
/// either way, so that is no error, but the compiling tier, which keeps
/// REALs in float registers, leaves such a block to the interpreter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shape {
    pub depth: u32,
    pub reals: u64,
    pub known: bool,
}

/// A block's shapes at its reached labels, by instruction.
type LabelShapes = Box<[(u32, Shape)]>;

/// Deepest numeric stack whose types [`Shape`] records.
pub const TYPED_DEPTH: u32 = 64;

/// An object that passed the verifier; the fields are private so that no
/// other path can make one.
#[derive(Clone, Debug)]
pub struct Verified {
    obj: ObjectFile,
    /// Per code block, the units' blocks one after another (one table, not
    /// one per unit: an object of many small units holds no more): the
    /// stack sizes it needs, and the numeric stack's shape at each
    /// instruction a label points at and some path reaches.
    blocks: Vec<(Limits, LabelShapes)>,
    /// Where each unit's blocks start in `blocks`.
    first: Vec<u32>,
}

impl Verified {
    pub fn object(&self) -> &ObjectFile {
        &self.obj
    }

    pub fn limits(&self, unit: usize, block: usize) -> Limits {
        self.index(unit, block).and_then(|i| self.blocks.get(i)).map(|b| b.0).unwrap_or_default()
    }

    /// The numeric stack's shape at each reached label of a block, sorted
    /// by instruction.
    pub fn shapes(&self, unit: usize, block: usize) -> &[(u32, Shape)] {
        self.index(unit, block).and_then(|i| self.blocks.get(i)).map_or(&[], |b| &b.1[..])
    }

    fn index(&self, unit: usize, block: usize) -> Option<usize> {
        let at = self.first.get(unit).map(|&f| f as usize + block);
        let inside = self.first.get(unit + 1).map_or(self.blocks.len(), |&f| f as usize);
        at.filter(|&i| i < inside)
    }

    /// The units to link in place, and the symbols they name: only linking
    /// changes a verified object, into the code it runs (jumps to
    /// instruction indices, symbols to a program's table).
    pub(crate) fn units_and_symbols(&mut self) -> (&mut [Unit], &[Symbol]) {
        (&mut self.obj.units, &self.obj.symbols)
    }

    /// The unit called `name` (names ignore case).
    pub fn unit_named(&self, name: &str) -> Option<usize> {
        self.obj.units.iter().position(|u| u.name.eq_ignore_ascii_case(name))
    }
}

thread_local! {
    static RUNS: Cell<u64> = const { Cell::new(0) };
}

/// How many objects this thread has verified (tests prove that a load
/// verifies once and that linking and running verify nothing).
pub fn verifications() -> u64 {
    RUNS.with(Cell::get)
}

/// Verifies every unit of an object.
pub fn verify(obj: ObjectFile) -> Result<Verified, LoadError> {
    RUNS.with(|n| n.set(n.get() + 1));
    let mut blocks = Vec::with_capacity(obj.units.iter().map(|u| u.blocks.len()).sum());
    let mut first = Vec::with_capacity(obj.units.len());
    for u in &obj.units {
        if u.blocks.is_empty() {
            return Err(LoadError::Invalid {
                code: Code::E0708,
                action: u.name.clone(),
                op: 0,
                what: "no code".into(),
            });
        }
        first.push(blocks.len() as u32);
        for b in &u.blocks {
            blocks.push(verify_block(&obj, u, b)?);
        }
        crate::verify_chart::check_charts(u)?;
    }
    Ok(Verified { obj, blocks, first })
}

/// Where a finding is: the unit, and the block when the unit has several.
fn place(u: &Unit, b: &CodeBlock) -> String {
    if u.blocks.len() == 1 || b.name.is_empty() {
        u.name.clone()
    } else {
        format!("{}/{}", u.name, b.name)
    }
}

fn invalid(code: Code, u: &Unit, b: &CodeBlock, op: usize, what: impl Into<String>) -> LoadError {
    LoadError::Invalid { code, action: place(u, b), op, what: what.into() }
}

/// Checks the block's label, line and loop tables against its code.
fn check_tables(u: &Unit, b: &CodeBlock) -> Result<(), LoadError> {
    let n = b.ops.len();
    if n == 0 {
        return Err(invalid(Code::E0708, u, b, 0, "empty code (a block ends with Ret)"));
    }
    if let Some(l) = b.labels.iter().position(|&at| at as usize >= n) {
        return Err(invalid(Code::E0705, u, b, 0, format!("label {l} is past the last instruction")));
    }
    let mut last = 0;
    for e in &b.lines {
        if e.op as usize >= n || e.op < last {
            return Err(invalid(Code::E0712, u, b, e.op as usize, "line table out of order or past the code"));
        }
        last = e.op;
    }
    if let Some(lp) = b.loops.iter().find(|lp| lp.start > lp.end || lp.end as usize > n) {
        return Err(invalid(Code::E0712, u, b, lp.start as usize, "loop table entry outside the code"));
    }
    Ok(())
}

/// Checks one instruction's operands against the object's tables.
fn check_operands(obj: &ObjectFile, u: &Unit, b: &CodeBlock, pc: usize, op: &Op) -> Result<(), LoadError> {
    if let Some(t) = op.target() {
        if t as usize >= b.labels.len() {
            return Err(invalid(
                Code::E0705,
                u,
                b,
                pc,
                format!("jump to label {t}, but the block has {}", b.labels.len()),
            ));
        }
    }
    match *op {
        Op::PushS { k } if k as usize >= obj.strings.len() => {
            return Err(invalid(Code::E0706, u, b, pc, format!("string constant {k} does not exist")));
        }
        Op::Return { kind } if kind > 3 => {
            return Err(invalid(Code::E0710, u, b, pc, format!("result kind {kind} does not exist")));
        }
        Op::LoadLoc { n } | Op::StoreLoc { n } if n >= b.locals => {
            return Err(invalid(
                Code::E0711,
                u,
                b,
                pc,
                format!("local {n} does not exist (the block has {})", b.locals),
            ));
        }
        Op::LoadRet { n } | Op::StoreRet { n } if n >= u.retained => {
            let what = format!("retained slot {n} does not exist (the unit has {})", u.retained);
            return Err(invalid(Code::E0711, u, b, pc, what));
        }
        Op::Call { func, argc, ret, types } => check_call(u, b, pc, func, argc, ret, types)?,
        _ if fst_only(op) && u.kind != UnitKind::Fst => {
            return Err(invalid(Code::E0710, u, b, pc, format!("{} belongs to FST tables only", op.name())));
        }
        Op::Step { n } if usize::from(n) >= u.steps.len() || usize::from(n) >= b.labels.len() => {
            let what = format!("step {n} does not exist (the table lists {})", u.steps.len());
            return Err(invalid(Code::E0710, u, b, pc, what));
        }
        Op::Pause { why: 2.. } | Op::DayTime { what: 2.. } | Op::Log { which: 2.. } | Op::HistWrite { time: 2.. } => {
            return Err(invalid(Code::E0710, u, b, pc, format!("{} has no variant {:?}", op.name(), op.operands())));
        }
        Op::HistRead { f } if crate::roc::HistFn::from_u8(f).is_none() => {
            return Err(invalid(Code::E0710, u, b, pc, format!("history read {f} does not exist")));
        }
        Op::Clamp { hi, .. } if hi < 0 => {
            return Err(invalid(Code::E0710, u, b, pc, format!("Clamp to an empty range 0..={hi}")));
        }
        _ => {}
    }
    if let Some(s) = op.symbol() {
        let sym = obj
            .symbols
            .get(usize::from(s))
            .ok_or_else(|| invalid(Code::E0707, u, b, pc, format!("symbol {s} does not exist")))?;
        if !symbol_fits(op, sym) {
            let what = format!("{} can't use `{}` ({:?})", op.name(), sym.text(), sym.class);
            return Err(invalid(Code::E0707, u, b, pc, what));
        }
    }
    Ok(())
}

fn check_call(u: &Unit, b: &CodeBlock, pc: usize, func: u8, argc: u8, ret: u8, types: u32) -> Result<(), LoadError> {
    let sig = SIGNATURES
        .get(usize::from(func))
        .ok_or_else(|| invalid(Code::E0710, u, b, pc, format!("function {func} does not exist")))?;
    let argc = usize::from(argc);
    if argc > MAX_CALL_ARGS || !sig.arity_ok(argc) || ret > 3 {
        return Err(invalid(Code::E0710, u, b, pc, format!("{} can't be called with {argc} arguments", sig.name)));
    }
    for i in 0..argc {
        let k = Kind::arg(types, i);
        let ok = match sig.param(i) {
            Some(linc_stdlib::Param::Bytes) => k == Kind::Bytes,
            Some(_) => k != Kind::Bytes,
            None => false,
        };
        if !ok {
            let what = format!("argument {} of {} has the wrong kind", i + 1, sig.name);
            return Err(invalid(Code::E0710, u, b, pc, what));
        }
    }
    Ok(())
}

/// Whether an instruction may use a symbol of this kind.
fn symbol_fits(op: &Op, sym: &Symbol) -> bool {
    let field = sym.sub == Sub::Field;
    let c = sym.class;
    match *op {
        Op::LoadI { .. } | Op::StoreI { .. } | Op::LoadRefI { .. } | Op::StoreRefI { .. } => field && c.is_int(),
        Op::LoadR { .. } | Op::StoreR { .. } | Op::StoreRKeep { .. } | Op::LoadRefR { .. } | Op::StoreRefR { .. } => {
            field && c == Class::Real
        }
        Op::LoadS { .. } | Op::StoreS { .. } | Op::LoadRefS { .. } | Op::StoreRefS { .. } => field && c.is_string(),
        Op::AppendS { .. } => field && matches!(c, Class::Bseq | Class::Wstr),
        Op::LoadBit { bit, .. } | Op::StoreBit { bit, .. } => field && c.bits().is_some_and(|w| bit < w),
        Op::LoadRefBit { .. } | Op::StoreRefBit { .. } => field && c.bits().is_some(),
        Op::LoadAlarm { .. } => matches!(sym.sub, Sub::Alarm(_)) && c == Class::Alarms,
        Op::LoadSuppress { .. } | Op::StoreSuppress { .. } => matches!(sym.sub, Sub::Suppress(_)) && c == Class::Alarms,
        Op::Ref { .. } | Op::RefOff { .. } => field && c != Class::Alarms,
        _ => true,
    }
}

/// What the verifier knows at an instruction: both stack depths and which
/// symbol's run the reference register points into on every path to it
/// (`None`: unset, or different symbols on different paths).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct State {
    num: u32,
    strs: u32,
    ref_sym: Option<u16>,
    /// Which numeric entries are REAL ([`Shape`]); 0 when `mixed`.
    reals: u64,
    mixed: bool,
}

/// Instructions that only an FST unit may hold (the FST engine gives them
/// their step budget and reads their pauses; `PowRKeep` leaves a NaN that
/// only FST math's `StoreRKeep` drops).
fn fst_only(op: &Op) -> bool {
    op.has(Flag::Fst)
}

/// Instructions where a run may end, so both stacks must be empty there: a
/// resumed run starts with empty stacks.
fn suspends(op: &Op) -> bool {
    op.has(Flag::Suspends)
}

fn uses_ref(op: &Op) -> bool {
    op.has(Flag::UsesRef)
}

/// The state after one instruction, or why it is not allowed there. An
/// instruction that uses the reference register must name the symbol the
/// register was set from (the compiler always does), so its class is the
/// one `symbol_fits` checked and the VM never meets a cell of another type.
fn step(obj: &ObjectFile, u: &Unit, b: &CodeBlock, pc: usize, s: State) -> Result<State, LoadError> {
    let op = &b.ops[pc];
    let e = op.effect();
    if s.num < e.num_pop || s.strs < e.str_pop {
        return Err(invalid(Code::E0708, u, b, pc, format!("{} pops an empty stack", op.name())));
    }
    if uses_ref(op) {
        let Some(held) = s.ref_sym else {
            let what = format!("{} uses the reference register before it is set", op.name());
            return Err(invalid(Code::E0713, u, b, pc, what));
        };
        let width = obj.symbols.get(usize::from(held)).and_then(|sym| sym.class.bits());
        let bits_ok = match *op {
            Op::RefBit { bit } | Op::RefBitOff { bit } => width.is_some_and(|w| bit < w),
            _ => true,
        };
        if op.symbol().is_some_and(|named| named != held) || !bits_ok {
            let what = format!("{} does not fit the field the reference register points at", op.name());
            return Err(invalid(Code::E0713, u, b, pc, what));
        }
    }
    let num = s.num - e.num_pop + e.num_push;
    let strs = s.strs - e.str_pop + e.str_push;
    if suspends(op) && (num, strs) != (0, 0) {
        return Err(invalid(Code::E0708, u, b, pc, format!("{} with values left on the stack", op.name())));
    }
    let ref_sym = match *op {
        Op::Ref { sym } | Op::RefOff { sym } => Some(sym),
        // The register does not survive a suspension.
        _ if suspends(op) => None,
        _ => s.ref_sym,
    };
    let (reals, mixed) = types_after(op, &s, num);
    Ok(State { num, strs, ref_sym, reals, mixed })
}

/// The numeric stack's types after `op` (which leaves `num` entries).
fn types_after(op: &Op, s: &State, num: u32) -> (u64, bool) {
    let e = op.effect();
    let kept = s.num - e.num_pop;
    if s.mixed || num > TYPED_DEPTH || e.num_push > 1 {
        return (0, true);
    }
    let mut reals = if kept >= 64 { s.reals } else { s.reals & ((1u64 << kept) - 1) };
    if e.num_push == 1 && op.pushes_real() {
        reals |= 1 << kept;
    }
    (reals, false)
}

/// Verifies one code block; returns the stack sizes it needs and the
/// numeric stack's shape at its reached labels.
fn verify_block(obj: &ObjectFile, u: &Unit, b: &CodeBlock) -> Result<(Limits, LabelShapes), LoadError> {
    check_tables(u, b)?;
    for (pc, op) in b.ops.iter().enumerate() {
        check_operands(obj, u, b, pc, op)?;
    }
    // Abstract interpretation: depths must agree where paths meet; the
    // reference symbol only falls from known to unknown and the types from
    // known to mixed, so each label is walked from at most three times and
    // the walk is linear. Jumps land only on
    // labels, so only the states at labels are kept (a state per
    // instruction took 16 bytes for each byte of one-byte instructions).
    let mut targets: Vec<u32> = b.labels.clone();
    targets.sort_unstable();
    targets.dedup();
    let mut w =
        Walk { obj, u, b, states: vec![None; targets.len()], targets, work: Vec::new(), limits: Limits::default() };
    w.walk(0, State { num: 0, strs: 0, ref_sym: None, reals: 0, mixed: false }, false)?;
    while let Some(i) = w.work.pop() {
        if let Some(s) = w.states[i] {
            w.walk(w.targets[i] as usize, s, true)?;
        }
    }
    let shapes = (w.targets.iter().zip(&w.states))
        .filter_map(|(&pc, s)| s.map(|s| (pc, Shape { depth: s.num, reals: s.reals, known: !s.mixed })))
        .collect();
    Ok((w.limits, shapes))
}

/// The verifier's walk over one block: the state at each label, and the
/// labels still to walk from.
struct Walk<'a> {
    obj: &'a ObjectFile,
    u: &'a Unit,
    b: &'a CodeBlock,
    /// The instructions labels point at, sorted, without repeats.
    targets: Vec<u32>,
    states: Vec<Option<State>>,
    work: Vec<usize>,
    limits: Limits,
}

impl Walk<'_> {
    /// Walks straight code from `pc` in state `s` until it ends, jumps, or
    /// reaches a label (whose state then takes `s` in). `from_label`: `pc`
    /// is a label being walked from, with its own state.
    fn walk(&mut self, mut pc: usize, mut s: State, from_label: bool) -> Result<(), LoadError> {
        let n = self.b.ops.len();
        let mut next = self.targets.partition_point(|&t| (t as usize) < pc);
        if from_label {
            next += 1;
        }
        loop {
            if self.targets.get(next).is_some_and(|&t| t as usize == pc) {
                return self.meet(next, s);
            }
            let after = step(self.obj, self.u, self.b, pc, s)?;
            self.limits.max_num = self.limits.max_num.max(after.num as usize);
            self.limits.max_str = self.limits.max_str.max(after.strs as usize);
            match self.b.ops[pc] {
                Op::Ret {} | Op::Return { .. } => return Ok(()),
                Op::Jump { to } => return self.meet_label(to, after),
                Op::JumpIfFalse { to } | Op::JumpIfTrue { to } => self.meet_label(to, after)?,
                _ => {}
            }
            if pc + 1 >= n {
                return Err(invalid(Code::E0708, self.u, self.b, pc, "execution runs past the last instruction"));
            }
            (pc, s) = (pc + 1, after);
        }
    }

    fn meet_label(&mut self, label: u32, s: State) -> Result<(), LoadError> {
        let at = self.b.labels[label as usize];
        let i = self.targets.partition_point(|&t| t < at);
        self.meet(i, s)
    }

    /// State `s` arrives at the label of `targets[i]`.
    fn meet(&mut self, i: usize, s: State) -> Result<(), LoadError> {
        match self.states[i] {
            None => {
                self.states[i] = Some(s);
                self.work.push(i);
            }
            Some(d) if (d.num, d.strs) != (s.num, s.strs) => {
                let what = format!("stack depths {:?} and {:?} meet here", (d.num, d.strs), (s.num, s.strs));
                return Err(invalid(Code::E0708, self.u, self.b, self.targets[i] as usize, what));
            }
            Some(d) => {
                let ref_sym = if d.ref_sym == s.ref_sym { d.ref_sym } else { None };
                let mixed = d.mixed || s.mixed || d.reals != s.reals;
                let met = State { ref_sym, mixed, reals: if mixed { 0 } else { d.reals }, ..d };
                if met != d {
                    self.states[i] = Some(met);
                    self.work.push(i);
                }
            }
        }
        Ok(())
    }
}

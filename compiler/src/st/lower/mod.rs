//! Lowering of the checked program to the runtime's instruction set.
//!
//! Types are fixed here: every arithmetic, comparison, load and store gets
//! its typed opcode, conversions are explicit instructions, constant
//! sub-expressions are folded, and database references become symbols of
//! the object file. Statements record where they start (the line table) and
//! loops record their extent (for watchdog errors).

mod expr;
pub mod sequence;

use crate::diag::span::Span;
use crate::diag::Diagnostic;
use crate::st::hir::{self, Place, Stmt, Target};
use linc_format::isa::Op;
use linc_format::object::{Class, CodeBlock, LineEntry, LoopEntry, ObjectFile, Sub, Symbol, Unit as ObjUnit, UnitKind};
use linc_format::wire::{self, Bytes};
use linc_format::Code;
use linc_stdlib::Ty;
use std::collections::HashMap;

/// Why a checked program could not be lowered.
#[derive(Clone, Debug, PartialEq)]
pub enum LowerError {
    /// A name whose type is unknown because no database was given.
    Unresolved {
        span: Span,
        path: String,
    },
    StepVariable {
        span: Span,
        path: String,
    },
    TooMany {
        span: Span,
        what: &'static str,
    },
    /// A chart action whose chart uses the action itself (directly or not),
    /// or an association naming no action of the sequence.
    ChartAction {
        span: Span,
        name: String,
        why: &'static str,
    },
}

impl LowerError {
    pub fn to_diagnostic(&self) -> Diagnostic {
        match self {
            LowerError::Unresolved { span, path } => {
                Diagnostic::error(Code::E0130, format!("the type of `{path}` is unknown"), *span)
                    .label("not resolved")
                    .help("compiling needs the database that defines this block: pass --db")
            }
            LowerError::StepVariable { span, path } => Diagnostic::error(
                Code::E0131,
                format!("step variable `{path}` can't be compiled into a plain action"),
                *span,
            )
            .label("only sequences have steps"),
            LowerError::ChartAction { span, name, why } => {
                Diagnostic::error(Code::E0133, format!("chart action `{name}` {why}"), *span)
                    .label("used here")
                    .help("a chart action's chart may use other actions, but not itself")
            }
            LowerError::TooMany { span, what } => {
                Diagnostic::error(Code::E0132, format!("too many {what} in one object file"), *span)
                    .label("limit reached here")
            }
        }
    }
}

/// Line and column (1-based) of byte offsets in one source.
#[derive(Clone, Debug, Default)]
pub struct Lines {
    starts: Vec<usize>,
}

impl Lines {
    pub fn new(src: &str) -> Lines {
        let mut starts = vec![0];
        starts.extend(src.match_indices('\n').map(|(i, _)| i + 1));
        Lines { starts }
    }

    pub fn at(&self, offset: usize) -> (u32, u32) {
        let line = self.starts.partition_point(|&s| s <= offset).max(1);
        let col = offset - self.starts[line - 1] + 1;
        (line as u32, col as u32)
    }
}

/// Builds an object file from checked actions.
pub struct Lowerer {
    lines: Lines,
    /// A sequence's steps (upper case) and their slots; empty elsewhere.
    steps: HashMap<String, u16>,
    file: String,
    symbols: Vec<Symbol>,
    symbol_index: HashMap<(String, String, String, u8), u16>,
    strings: Vec<Vec<u8>>,
    string_index: HashMap<Vec<u8>, u32>,
    errors: Vec<LowerError>,
    // Per action:
    ops: Vec<Op>,
    line_table: Vec<LineEntry>,
    loops: Vec<LoopEntry>,
    exits: Vec<Vec<usize>>,
    locals: u8,
}

/// One checked source file to lower: its program, name and line index.
pub struct Unit<'a> {
    pub program: &'a hir::Program,
    pub file: &'a str,
    pub lines: &'a Lines,
}

/// Lowers checked files into one object file. Each error comes with the
/// index of the unit it belongs to.
pub fn lower_units(units: &[Unit]) -> Result<ObjectFile, Vec<(usize, LowerError)>> {
    let mut stream = Stream::default();
    for (k, u) in units.iter().enumerate() {
        stream.begin_file(k, u.file, u.lines.clone());
        for a in &u.program.actions {
            stream.action(a);
        }
    }
    stream.finish()
}

/// Lowering as the checker goes: actions, or the statements of a file
/// without headers, are lowered as soon as they are checked and their
/// checked form is dropped, so compiling holds the object being built, not
/// every file's checked program (a 50 MB source compiles in a few hundred
/// MB instead of gigabytes).
#[derive(Default)]
pub struct Stream {
    l: Lowerer,
    units: Vec<ObjUnit>,
    /// For each error of `l`, the index of the file it belongs to.
    owners: Vec<usize>,
    file: usize,
    source: Option<String>,
}

impl Stream {
    /// Starts file number `index` (as the caller counts files).
    pub fn begin_file(&mut self, index: usize, name: &str, lines: Lines) {
        self.file = index;
        self.source.get_or_insert_with(|| name.to_string());
        self.l.file = name.to_string();
        self.l.lines = lines;
    }

    /// Lowers one whole checked action.
    pub fn action(&mut self, a: &hir::Action) {
        let unit = self.l.action(a);
        self.units.push(unit);
        self.tag();
    }

    /// Starts the one action of a file without headers.
    pub fn begin_statements(&mut self) {
        self.l.locals = 0;
    }

    /// Lowers one statement of the action begun by [`Stream::begin_statements`].
    pub fn statement(&mut self, s: &Stmt) {
        self.l.stmt(s);
        self.tag();
    }

    /// Ends that action, named after its file.
    pub fn end_statements(&mut self, name: &str) {
        let unit = self.l.take_action(name, "");
        self.units.push(unit);
    }

    fn tag(&mut self) {
        self.owners.resize(self.l.errors.len(), self.file);
    }

    /// The object, or the lowering errors with the index of their file.
    pub fn finish(self) -> Result<ObjectFile, Vec<(usize, LowerError)>> {
        let source = self.source.unwrap_or_default();
        let owners = self.owners;
        self.l.finish(&source, self.units).map_err(|errors| owners.into_iter().zip(errors).collect())
    }
}

/// Lowers a whole checked file.
pub fn lower_program(p: &hir::Program, source: &str, lines: &Lines) -> Result<ObjectFile, Vec<LowerError>> {
    lower_units(&[Unit { program: p, file: source, lines }]).map_err(|e| e.into_iter().map(|(_, e)| e).collect())
}

/// Lowers one expression into an action named `eval` that returns its value.
pub fn lower_eval(e: &hir::Expr, lines: &Lines) -> Result<ObjectFile, Vec<LowerError>> {
    let mut l = Lowerer { lines: lines.clone(), ..Lowerer::default() };
    l.mark(e.span);
    l.expr(e);
    l.emit(Op::Return { kind: expr::kind_of(e.ty) as u8 });
    let action = l.take_action("eval", "");
    l.finish("<eval>", vec![action])
}

/// Lowers a BOOL expression that may read the step variables of `steps`
/// (slot order) into a unit named `expect` whose retained slots are those
/// step variables (`.X` at `2 × slot`, `.T` at `2 × slot + 1`), so a
/// scenario can evaluate it over a copy of the sequences' slots.
pub fn lower_expectation(e: &hir::Expr, lines: &Lines, steps: &[String]) -> Result<ObjectFile, Vec<LowerError>> {
    let mut l = Lowerer { lines: lines.clone(), ..Lowerer::default() };
    // A step name two sequences share means the first one's step.
    for (i, s) in steps.iter().enumerate() {
        l.steps.entry(s.to_ascii_uppercase()).or_insert(i as u16);
    }
    l.mark(e.span);
    l.expr_as(e, Ty::Bool);
    l.emit(Op::Return { kind: expr::kind_of(Ty::Bool) as u8 });
    let mut unit = l.take_action("expect", "");
    unit.retained = u16::try_from(2 * steps.len()).unwrap_or(u16::MAX);
    l.finish("<expect>", vec![unit])
}

impl Default for Lowerer {
    fn default() -> Lowerer {
        Lowerer {
            lines: Lines::default(),
            steps: HashMap::new(),
            file: "<eval>".to_string(),
            symbols: Vec::new(),
            symbol_index: HashMap::new(),
            strings: Vec::new(),
            string_index: HashMap::new(),
            errors: Vec::new(),
            ops: Vec::new(),
            line_table: Vec::new(),
            loops: Vec::new(),
            exits: Vec::new(),
            locals: 0,
        }
    }
}

impl Lowerer {
    fn finish(self, source: &str, units: Vec<ObjUnit>) -> Result<ObjectFile, Vec<LowerError>> {
        if !self.errors.is_empty() {
            return Err(self.errors);
        }
        let strings = self.strings.into_iter().map(Bytes).collect();
        Ok(ObjectFile { source: source.to_string(), symbols: self.symbols, strings, units })
    }

    /// Ends the code of an action as a one-block unit.
    fn take_action(&mut self, name: &str, block_type: &str) -> ObjUnit {
        self.ops.push(Op::Ret {});
        let block = self.take_block(String::new());
        ObjUnit {
            kind: UnitKind::Action,
            name: name.to_string(),
            file: self.file.clone(),
            block_type: block_type.to_string(),
            retained: 0,
            blocks: vec![block],
            charts: Vec::new(),
            steps: Vec::new(),
        }
    }

    /// Ends the code emitted so far (which ends as the caller made it end)
    /// as a block: jumps, emitted with instruction indices, name labels in
    /// the object (one label per distinct target).
    fn take_block(&mut self, name: String) -> CodeBlock {
        let mut ops = std::mem::take(&mut self.ops);
        let mut labels: Vec<u32> = ops.iter().filter_map(Op::target).collect();
        labels.sort_unstable();
        labels.dedup();
        for op in &mut ops {
            if let Some(to) = op.target() {
                let label = labels.partition_point(|&l| l < to) as u32;
                *op = op.retarget(label);
            }
        }
        CodeBlock {
            name,
            locals: std::mem::take(&mut self.locals),
            ops: wire::Code(ops),
            labels,
            lines: std::mem::take(&mut self.line_table),
            loops: std::mem::take(&mut self.loops),
        }
    }

    fn action(&mut self, a: &hir::Action) -> ObjUnit {
        self.locals = 0;
        self.stmts(&a.body);
        self.take_action(&a.name, a.block_type.as_deref().unwrap_or(""))
    }

    fn here(&self) -> u32 {
        self.ops.len() as u32
    }

    fn emit(&mut self, op: Op) -> usize {
        self.ops.push(op);
        self.ops.len() - 1
    }

    /// Points a jump emitted earlier at `to`.
    fn patch(&mut self, at: usize, to: u32) {
        match &mut self.ops[at] {
            Op::Jump { to: t } | Op::JumpIfFalse { to: t } | Op::JumpIfTrue { to: t } => *t = to,
            _ => {}
        }
    }

    fn mark(&mut self, span: Span) {
        let (line, col) = self.lines.at(span.start);
        let op = self.here();
        self.line_table.push(LineEntry { op, line, col });
    }

    fn string(&mut self, bytes: &[u8], span: Span) -> u32 {
        if let Some(&k) = self.string_index.get(bytes) {
            return k;
        }
        let k = self.strings.len() as u32;
        if k == u32::MAX {
            self.errors.push(LowerError::TooMany { span, what: "string constants" });
        }
        self.strings.push(bytes.to_vec());
        self.string_index.insert(bytes.to_vec(), k);
        k
    }

    fn symbol(&mut self, block: &str, field: &str, sub: Sub, class: Class, span: Span) -> u16 {
        let sub_key = match &sub {
            Sub::Field => String::new(),
            Sub::Alarm(a) => format!("A:{}", a.to_ascii_uppercase()),
            Sub::Suppress(a) => format!("S:{}", a.as_deref().unwrap_or("").to_ascii_uppercase()),
        };
        let key = (block.to_ascii_uppercase(), field.to_ascii_uppercase(), sub_key, class as u8);
        if let Some(&i) = self.symbol_index.get(&key) {
            return i;
        }
        let Ok(i) = u16::try_from(self.symbols.len()) else {
            self.errors.push(LowerError::TooMany { span, what: "database references" });
            return 0;
        };
        self.symbols.push(Symbol { block: block.to_string(), field: field.to_string(), sub, class });
        self.symbol_index.insert(key, i);
        i
    }

    fn stmts(&mut self, list: &[Stmt]) {
        for s in list {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match s {
            Stmt::Assign { place, value, span } => {
                self.mark(*span);
                self.store_value(place, value);
            }
            Stmt::If { arms, otherwise, span } => {
                self.mark(*span);
                let mut to_end = Vec::new();
                for (cond, body) in arms {
                    self.mark(cond.span);
                    self.expr_as(cond, Ty::Int);
                    let skip = self.emit(Op::JumpIfFalse { to: 0 });
                    self.stmts(body);
                    to_end.push(self.emit(Op::Jump { to: 0 }));
                    let next = self.here();
                    self.patch(skip, next);
                }
                self.stmts(otherwise);
                let end = self.here();
                for j in to_end {
                    self.patch(j, end);
                }
            }
            Stmt::While { cond, body, span } => {
                self.mark(*span);
                let top = self.here();
                self.expr_as(cond, Ty::Int);
                let out = self.emit(Op::JumpIfFalse { to: 0 });
                self.loop_body(
                    body,
                    *span,
                    top,
                    |l, end| l.patch(out, end),
                    |l| {
                        l.emit(Op::Jump { to: top });
                    },
                );
            }
            Stmt::Repeat { body, until, span } => {
                self.mark(*span);
                let top = self.here();
                self.loop_body(
                    body,
                    *span,
                    top,
                    |_, _| {},
                    |l| {
                        l.mark(until.span);
                        l.expr_as(until, Ty::Int);
                        l.emit(Op::JumpIfFalse { to: top });
                    },
                );
            }
            Stmt::For { place, from, to, by, body, span } => self.for_loop(place, from, to, by.as_ref(), body, *span),
            Stmt::Exit { span } => {
                self.mark(*span);
                let j = self.emit(Op::Jump { to: 0 });
                if let Some(exits) = self.exits.last_mut() {
                    exits.push(j);
                }
            }
            Stmt::Error { .. } => {}
        }
    }

    /// Emits a loop body between `top` and the end, wiring EXITs to the end.
    fn loop_body(
        &mut self,
        body: &[Stmt],
        span: Span,
        top: u32,
        at_end: impl FnOnce(&mut Self, u32),
        after_body: impl FnOnce(&mut Self),
    ) {
        self.exits.push(Vec::new());
        self.stmts(body);
        after_body(self);
        let end = self.here();
        at_end(self, end);
        for j in self.exits.pop().unwrap_or_default() {
            self.patch(j, end);
        }
        let (line, col) = self.lines.at(span.start);
        self.loops.push(LoopEntry { start: top, end, line, col });
    }

    fn for_loop(
        &mut self,
        place: &Place,
        from: &hir::Expr,
        to: &hir::Expr,
        by: Option<&hir::Expr>,
        body: &[Stmt],
        span: Span,
    ) {
        self.mark(span);
        let ty = if place.ty == Ty::Real { Ty::Real } else { Ty::Int };
        self.store_value(place, from);
        let local = self.locals;
        self.locals = self.locals.saturating_add(1);
        if self.locals == u8::MAX {
            self.errors.push(LowerError::TooMany { span, what: "FOR loops in one action (254 at most)" });
        }
        self.expr_as(to, ty);
        self.emit(Op::StoreLoc { n: local });
        let step = by.and_then(expr::constant).unwrap_or(expr::Const::I(1));
        let top = self.here();
        self.load(place);
        self.emit(Op::LoadLoc { n: local });
        let positive = step.is_positive();
        let exit_test = match (ty, positive) {
            (Ty::Real, true) => Op::GtR {},
            (Ty::Real, false) => Op::LtR {},
            (_, true) => Op::GtI {},
            (_, false) => Op::LtI {},
        };
        self.emit(exit_test);
        let out = self.emit(Op::JumpIfTrue { to: 0 });
        self.loop_body(
            body,
            span,
            top,
            |l, end| l.patch(out, end),
            |l| {
                l.load(place);
                match ty {
                    Ty::Real => {
                        l.emit(Op::PushR { v: step.real() });
                        l.emit(Op::AddR {});
                    }
                    _ => {
                        l.emit(Op::PushI { v: step.int() });
                        l.emit(Op::AddI {});
                    }
                }
                l.store(place);
                l.emit(Op::Jump { to: top });
            },
        );
    }

    /// Evaluates `value` converted to the place's type and stores it.
    fn store_value(&mut self, place: &Place, value: &hir::Expr) {
        match place.class {
            Some(class @ (Class::Bseq | Class::Wstr)) if !matches!(place.target, Target::Suppress { .. }) => {
                if let (Some(tail), Target::Field { block, field, offset: None }) =
                    (appended(place, value), &place.target)
                {
                    self.expr_as_bytes(tail);
                    let sym = self.symbol(block, field, Sub::Field, class, place.span);
                    self.emit(Op::AppendS { sym });
                    return;
                }
                self.expr_as_bytes(value);
            }
            _ => self.expr_as(value, place.ty),
        }
        self.store(place);
    }

    /// Resolves the symbol of a field place and emits offset code; returns
    /// the symbol and whether the reference register is in use.
    fn address(&mut self, place: &Place) -> Option<(u16, bool)> {
        let class = place.class?;
        match &place.target {
            Target::Field { block, field, offset } => {
                let sym = self.symbol(block, field, Sub::Field, class, place.span);
                if let Some(o) = offset {
                    self.expr_as(o, Ty::Int);
                    self.emit(Op::RefOff { sym });
                    return Some((sym, true));
                }
                Some((sym, false))
            }
            Target::Bit { block, field, offset, bit, bit_offset } => {
                let sym = self.symbol(block, field, Sub::Field, class, place.span);
                if offset.is_none() && bit_offset.is_none() {
                    return Some((sym, false));
                }
                // Offsets are evaluated before the reference register is
                // set, since they may use it themselves; the bit offset goes
                // first so that RefOff pops the field offset above it.
                if let Some(o) = bit_offset {
                    self.expr_as(o, Ty::Int);
                }
                match offset {
                    Some(o) => {
                        self.expr_as(o, Ty::Int);
                        self.emit(Op::RefOff { sym });
                    }
                    None => {
                        self.emit(Op::Ref { sym });
                    }
                }
                self.emit(match bit_offset {
                    Some(_) => Op::RefBitOff { bit: *bit },
                    None => Op::RefBit { bit: *bit },
                });
                Some((sym, true))
            }
            Target::Alarm { block, field, alarm } => {
                Some((self.symbol(block, field, Sub::Alarm(alarm.to_string()), class, place.span), false))
            }
            Target::Suppress { block, field, alarm } => Some((
                self.symbol(block, field, Sub::Suppress(alarm.as_ref().map(|a| a.to_string())), class, place.span),
                false,
            )),
            Target::Step { .. } | Target::Unknown => None,
        }
    }

    fn unaddressable(&mut self, place: &Place) {
        let e = match place.target {
            Target::Step { .. } => LowerError::StepVariable { span: place.span, path: place.path.clone() },
            _ => LowerError::Unresolved { span: place.span, path: place.path.clone() },
        };
        self.errors.push(e);
    }

    /// Pushes a place's value (INT/BOOL/bits on the numeric stack as INT,
    /// REAL as REAL, strings on the string stack).
    fn load(&mut self, place: &Place) {
        self.access(place, false);
    }

    /// Stores the value on top of the stack into a place.
    fn store(&mut self, place: &Place) {
        self.access(place, true);
    }

    /// Emits the load or store instruction for a place's kind of cell.
    fn access(&mut self, place: &Place, store: bool) {
        if let (Target::Step { step, x }, false) = (&place.target, store) {
            // In a sequence, `.X` and `.T` are the step's retained slots.
            if let Some(&slot) = self.steps.get(step.as_str().to_ascii_uppercase().as_str()) {
                self.emit(Op::LoadRet { n: 2 * slot + u16::from(!*x) });
                return;
            }
        }
        let Some((sym, via_ref)) = self.address(place) else {
            return self.unaddressable(place);
        };
        let pick = |load: Op, save: Op| if store { save } else { load };
        let op = match (&place.target, place.class, via_ref) {
            (Target::Alarm { .. }, ..) => Op::LoadAlarm { sym },
            (Target::Suppress { .. }, ..) => pick(Op::LoadSuppress { sym }, Op::StoreSuppress { sym }),
            (Target::Bit { bit, .. }, _, false) => {
                pick(Op::LoadBit { sym, bit: *bit }, Op::StoreBit { sym, bit: *bit })
            }
            (Target::Bit { .. }, _, true) => pick(Op::LoadRefBit { sym }, Op::StoreRefBit { sym }),
            (_, Some(Class::Real), false) => pick(Op::LoadR { sym }, Op::StoreR { sym }),
            (_, Some(Class::Real), true) => pick(Op::LoadRefR { sym }, Op::StoreRefR { sym }),
            (_, Some(c), false) if c.is_string() => pick(Op::LoadS { sym }, Op::StoreS { sym }),
            (_, Some(c), true) if c.is_string() => pick(Op::LoadRefS { sym }, Op::StoreRefS { sym }),
            (_, _, false) => pick(Op::LoadI { sym }, Op::StoreI { sym }),
            (_, _, true) => pick(Op::LoadRefI { sym }, Op::StoreRefI { sym }),
        };
        self.emit(op);
    }
}

/// `e` when `value` is `CONCAT(X, e)` and `place` is the field X itself
/// (named directly): the assignment appends in place (`AppendS`).
fn appended<'a>(place: &Place, value: &'a hir::Expr) -> Option<&'a hir::Expr> {
    let hir::ExprKind::Call { index, args } = &value.kind else { return None };
    let [head, tail] = &args[..] else { return None };
    let hir::ExprKind::Load(from) = &head.kind else { return None };
    let same = matches!(place.target, Target::Field { offset: None, .. }) && from.target == place.target;
    (Some(*index) == linc_stdlib::signatures::index_of("CONCAT") && same).then_some(tail)
}

//! Lowering of a checked FST table to one FST unit of the shared
//! instruction set (`docs/fst.md`).
//!
//! Step `n` begins at label `n` with `Step n`, which counts the step
//! against the cycle's budget; a step falls through to the next. The FST
//! registers are fields of the FST block that runs the table (symbols of
//! the empty block), so ST, the console and `--show` see them. Math stores
//! with `StoreRKeep`, so a result that is not a finite number leaves RR as
//! it was, as division by zero does on the device.

use super::{Arg, Checked, Cmd, Param};
use crate::diag::span::Span;
use crate::st::lower::LowerError;
use linc_format::isa::{HistFn, Kind, Op, Zero};
use linc_format::object::{Class, CodeBlock, LineEntry, ObjectFile, Sub, Symbol, Unit, UnitKind};
use linc_format::wire::{Bytes, Code};
use std::collections::HashMap;

/// Most steps one table may have (step numbers are 16-bit in the code).
pub const MAX_STEPS: usize = 10_000;

/// Largest RR whose exponential is a single-precision number.
const EXP_LIMIT: f32 = 88.72;

struct Lowering {
    ops: Vec<Op>,
    /// Instruction index of each label: steps first, then internal ones.
    labels: Vec<u32>,
    lines: Vec<LineEntry>,
    symbols: Vec<Symbol>,
    symbol_index: HashMap<(String, String), u16>,
    strings: Vec<Bytes>,
}

/// The object holding table `name` (from `file`) as one FST unit.
pub fn lower(table: &Checked, name: &str, file: &str) -> Result<ObjectFile, Vec<LowerError>> {
    if table.steps.is_empty() || table.steps.len() > MAX_STEPS {
        return Err(vec![LowerError::TooMany { span: Span::new(0, 0), what: "steps" }]);
    }
    let n = table.steps.len();
    let mut l = Lowering {
        ops: Vec::new(),
        labels: vec![0; n],
        lines: Vec::with_capacity(n),
        symbols: Vec::new(),
        symbol_index: HashMap::new(),
        strings: Vec::new(),
    };
    let mut listing = Vec::with_capacity(n);
    for (i, step) in table.steps.iter().enumerate() {
        l.labels[i] = l.ops.len() as u32;
        l.lines.push(LineEntry { op: l.ops.len() as u32, line: step.line, col: step.col });
        l.ops.push(Op::Step { n: i as u16 });
        l.step(step.cmd, &step.arg1, &step.arg2);
        listing.push(describe(step.cmd, &step.arg1, &step.arg2));
    }
    // A table whose last step is not END or GO ends its cycle there, as
    // if END followed (END may stand earlier, with branches after it).
    l.ops.push(Op::Ret {});
    if l.symbols.len() > usize::from(u16::MAX) {
        return Err(vec![LowerError::TooMany { span: Span::new(0, 0), what: "database references" }]);
    }
    let block = CodeBlock {
        name: String::new(),
        locals: 1,
        ops: Code(l.ops),
        labels: l.labels,
        lines: l.lines,
        loops: Vec::new(),
    };
    let unit = Unit {
        kind: UnitKind::Fst,
        name: name.to_string(),
        file: file.to_string(),
        block_type: "FST".to_string(),
        retained: 0,
        blocks: vec![block],
        charts: Vec::new(),
        steps: listing,
    };
    Ok(ObjectFile { source: file.to_string(), symbols: l.symbols, strings: l.strings, units: vec![unit] })
}

/// A step as the listing and traces show it: `CMD ARG1 ARG2`.
pub(crate) fn describe(cmd: Cmd, a1: &Arg, a2: &Arg) -> String {
    let text = |a: &Arg| match a {
        Arg::None => None,
        Arg::Const(c) => Some(c.to_string()),
        Arg::Label(s) => Some(format!("step {s}")),
        Arg::Text(t) => Some(format!("\"{t}\"")),
        Arg::Param(p) => Some(p.written.clone()),
    };
    [Some(cmd.text().to_string()), text(a1), text(a2)].into_iter().flatten().collect::<Vec<_>>().join(" ")
}

/// A field of the FST running the table.
fn own(field: &str, class: Class) -> Param {
    Param { block: String::new(), field: field.to_string(), class, readonly: false, written: field.to_string() }
}

fn rr() -> Param {
    own("RR", Class::Real)
}

fn cf() -> Param {
    own("CMPFLG", Class::Bits8)
}

impl Lowering {
    fn symbol(&mut self, p: &Param) -> u16 {
        let key = (p.block.to_ascii_uppercase(), p.field.to_ascii_uppercase());
        if let Some(&s) = self.symbol_index.get(&key) {
            return s;
        }
        let s = self.symbols.len() as u16;
        self.symbols.push(Symbol { block: p.block.clone(), field: p.field.clone(), sub: Sub::Field, class: p.class });
        self.symbol_index.insert(key, s);
        s
    }

    fn string(&mut self, text: &str) -> u32 {
        self.strings.push(Bytes(text.as_bytes().to_vec()));
        (self.strings.len() - 1) as u32
    }

    /// A new internal label, placed later with [`Lowering::place`].
    fn label(&mut self) -> u32 {
        self.labels.push(u32::MAX);
        (self.labels.len() - 1) as u32
    }

    fn place(&mut self, label: u32) {
        self.labels[label as usize] = self.ops.len() as u32;
    }

    /// Pushes an argument's value as REAL.
    fn push(&mut self, a: &Arg) {
        match a {
            Arg::Const(c) => self.ops.push(Op::PushR { v: *c }),
            Arg::Param(p) => self.load(p),
            // The checker lets no other argument reach a value position.
            _ => self.ops.push(Op::PushR { v: 0.0 }),
        }
    }

    /// Pushes a parameter as REAL.
    fn load(&mut self, p: &Param) {
        let sym = self.symbol(p);
        if p.class == Class::Real {
            self.ops.push(Op::LoadR { sym });
        } else {
            self.ops.push(Op::LoadI { sym });
            self.ops.push(Op::IToR {});
        }
    }

    /// Pops a REAL into a parameter, converted to its type: rounded, and
    /// limited to what an 8- or 16-bit field holds.
    fn store(&mut self, p: &Param) {
        let sym = self.symbol(p);
        match p.class {
            Class::Real => self.ops.push(Op::StoreR { sym }),
            c => {
                self.ops.push(Op::RToI {});
                match c {
                    Class::Bits8 => self.ops.push(Op::Clamp { lo: Zero, hi: 255 }),
                    Class::Bits16 => self.ops.push(Op::Clamp { lo: Zero, hi: 65_535 }),
                    Class::Bool => self.ops.push(Op::Truth {}),
                    _ => {}
                }
                self.ops.push(Op::StoreI { sym });
            }
        }
    }

    /// Pops a REAL math result into RR unless it is not a finite number.
    fn keep_rr(&mut self) {
        let sym = self.symbol(&rr());
        self.ops.push(Op::StoreRKeep { sym });
    }

    fn jump_to_step(&mut self, op: fn(u32) -> Op, target: &Arg) {
        if let Arg::Label(s) = target {
            self.ops.push(op(*s));
        }
    }

    /// `RR op ARG1` into RR.
    fn arith(&mut self, a: &Arg, op: Op) {
        self.load(&rr());
        self.push(a);
        self.ops.push(op);
        self.keep_rr();
    }

    /// A one-argument library function of RR, only when `guard(RR)` holds.
    fn guarded_call(&mut self, name: &str, guard: Op, limit: f32) {
        let skip = self.label();
        self.load(&rr());
        self.ops.push(Op::PushR { v: limit });
        self.ops.push(guard);
        self.ops.push(Op::JumpIfFalse { to: skip });
        self.load(&rr());
        let func = linc_stdlib::signatures::index_of(name).unwrap_or(0) as u8;
        self.ops.push(Op::Call { func, argc: 1, ret: Kind::Real as u8, types: Kind::Real as u32 });
        self.keep_rr();
        self.place(skip);
    }

    /// CF = CF op (ARG1 as an 8-bit value).
    fn logical(&mut self, a: &Arg, op: Op) {
        let sym = self.symbol(&cf());
        self.ops.push(Op::LoadI { sym });
        self.push(a);
        self.ops.push(Op::RToI {});
        self.ops.push(Op::Clamp { lo: Zero, hi: 255 });
        self.ops.push(op);
        self.ops.push(Op::StoreI { sym });
    }

    fn compare(&mut self, a: &Arg, target: &Arg, op: Op) {
        self.load(&rr());
        self.push(a);
        self.ops.push(op);
        self.jump_to_step(|to| Op::JumpIfTrue { to }, target);
    }

    fn step(&mut self, cmd: Cmd, a1: &Arg, a2: &Arg) {
        match cmd {
            Cmd::Add => self.arith(a1, Op::AddR {}),
            Cmd::Sub => self.arith(a1, Op::SubR {}),
            Cmd::Mul => self.arith(a1, Op::MulR {}),
            Cmd::Div => self.divide(a1),
            Cmd::Pow => self.power(a1),
            Cmd::Abs => self.absolute(),
            Cmd::Exp => self.guarded_call("EXP", Op::LeR {}, EXP_LIMIT),
            Cmd::Int => {
                self.load(&rr());
                self.ops.push(Op::TruncR {});
                self.keep_rr();
            }
            Cmd::Log => self.guarded_call("LOG", Op::GtR {}, 0.0),
            Cmd::Ln => self.guarded_call("LN", Op::GtR {}, 0.0),
            Cmd::Sqr => self.guarded_call("SQRT", Op::GeR {}, 0.0),
            Cmd::P3 => self.polynomial(),
            Cmd::Not => {
                let sym = self.symbol(&cf());
                self.ops.push(Op::LoadI { sym });
                self.ops.push(Op::Not {});
                self.ops.push(Op::StoreI { sym });
            }
            Cmd::And => self.logical(a1, Op::And {}),
            Cmd::Or => self.logical(a1, Op::Or {}),
            Cmd::Xor => self.logical(a1, Op::Xor {}),
            // == and != compare the single-precision bits (Table B-13).
            Cmd::Eq => self.compare(a1, a2, Op::EqI {}),
            Cmd::Ne => self.compare(a1, a2, Op::NeI {}),
            Cmd::Lt => self.compare(a1, a2, Op::LtR {}),
            Cmd::Le => self.compare(a1, a2, Op::LeR {}),
            Cmd::Gt => self.compare(a1, a2, Op::GtR {}),
            Cmd::Ge => self.compare(a1, a2, Op::GeR {}),
            _ => self.other(cmd, a1, a2),
        }
    }

    fn other(&mut self, cmd: Cmd, a1: &Arg, a2: &Arg) {
        match cmd {
            Cmd::St => {
                if let Arg::Param(timer) = a1 {
                    self.push(a2);
                    self.ops.push(Op::RToI {});
                    self.ops.push(Op::Clamp { lo: Zero, hi: i32::MAX });
                    self.ops.push(Op::IToR {});
                    self.store(timer);
                }
            }
            Cmd::Ct => {
                if let Arg::Param(timer) = a1 {
                    self.load(timer);
                    self.ops.push(Op::PushR { v: 0.0 });
                    self.ops.push(Op::GtR {});
                    self.jump_to_step(|to| Op::JumpIfTrue { to }, a2);
                }
            }
            Cmd::Wt => {
                self.push(a1);
                self.ops.push(Op::Pause { why: 0 });
            }
            Cmd::Dwk | Cmd::Mnd => {
                self.ops.push(Op::DayTime { what: u8::from(cmd == Cmd::Mnd) });
                self.keep_rr();
            }
            Cmd::Ao | Cmd::Do | Cmd::Tdo => self.output(cmd, a1, a2),
            Cmd::Val => {
                self.push(a1);
                self.keep_rr();
            }
            Cmd::Sav => {
                if let Arg::Param(p) = a1 {
                    self.load(&rr());
                    self.store(p);
                }
            }
            Cmd::Wdb | Cmd::Wtm | Cmd::Rdb => self.history_index(cmd, a1, a2),
            Cmd::Go => self.jump_to_step(|to| Op::Jump { to }, a1),
            Cmd::Msg => {
                if let Arg::Text(t) = a1 {
                    let k = self.string(&t.chars().take(30).collect::<String>());
                    self.ops.push(Op::PushS { k });
                    let sym = self.symbol(&own("MSG1", Class::String));
                    self.ops.push(Op::StoreS { sym });
                }
                self.push(a2);
                self.store(&own("MSGDAT", Class::Real));
            }
            Cmd::End => self.ops.push(Op::Ret {}),
            Cmd::Brk => {
                let brk = own("BRK", Class::Int);
                self.push(a1);
                self.ops.push(Op::RToI {});
                self.ops.push(Op::Clamp { lo: Zero, hi: 65_535 });
                self.ops.push(Op::IToR {});
                self.store(&brk);
                self.load(&brk);
                self.ops.push(Op::Pause { why: 1 });
            }
            Cmd::Alm | Cmd::Evt => {
                self.push(a2);
                let text = if let Arg::Text(t) = a1 { t.chars().take(10).collect() } else { String::new() };
                let k = self.string(&text);
                self.ops.push(Op::PushS { k });
                self.ops.push(Op::Log { which: u8::from(cmd == Cmd::Evt) });
            }
            _ => self.history_read(cmd, a1, a2),
        }
    }

    /// RR / ARG1, leaving RR as it was when ARG1 is 0.
    fn divide(&mut self, a: &Arg) {
        let skip = self.label();
        self.push(a);
        self.ops.push(Op::StoreLoc { n: 0 });
        self.ops.push(Op::LoadLoc { n: 0 });
        self.ops.push(Op::PushR { v: 0.0 });
        self.ops.push(Op::EqR {});
        self.ops.push(Op::JumpIfTrue { to: skip });
        self.load(&rr());
        self.ops.push(Op::LoadLoc { n: 0 });
        self.ops.push(Op::DivR {});
        self.keep_rr();
        self.place(skip);
    }

    /// RR ** ARG1, only for RR above 0 (B.4: no operation otherwise); a
    /// result too large for a REAL leaves RR as it was (`PowRKeep` gives
    /// NaN where ST's `PowR` faults).
    fn power(&mut self, a: &Arg) {
        let skip = self.label();
        self.load(&rr());
        self.ops.push(Op::PushR { v: 0.0 });
        self.ops.push(Op::GtR {});
        self.ops.push(Op::JumpIfFalse { to: skip });
        self.arith(a, Op::PowRKeep {});
        self.place(skip);
    }

    fn absolute(&mut self) {
        let skip = self.label();
        self.load(&rr());
        self.ops.push(Op::PushR { v: 0.0 });
        self.ops.push(Op::LtR {});
        self.ops.push(Op::JumpIfFalse { to: skip });
        self.load(&rr());
        self.ops.push(Op::NegR {});
        self.keep_rr();
        self.place(skip);
    }

    /// R1·RR³ + R2·RR² + R3·RR + R4, by Horner's rule.
    fn polynomial(&mut self) {
        let reg = |n: u8| own(&format!("R{n}"), Class::Real);
        self.load(&reg(1));
        for n in 2..=4 {
            self.load(&rr());
            self.ops.push(Op::MulR {});
            self.load(&reg(n));
            self.ops.push(Op::AddR {});
        }
        self.keep_rr();
    }

    /// AO, DO and TDO: nothing is sent to a point in manual (MODE non-zero).
    fn output(&mut self, cmd: Cmd, a1: &Arg, a2: &Arg) {
        let Arg::Param(p) = a1 else { return };
        let skip = self.label();
        let field = |f: &str, class| Param { block: p.block.clone(), field: f.to_string(), class, ..p.clone() };
        self.load(&field("MODE", Class::Int));
        self.ops.push(Op::PushR { v: 0.0 });
        self.ops.push(Op::NeR {});
        self.ops.push(Op::JumpIfTrue { to: skip });
        match cmd {
            Cmd::Ao => {
                self.push(a2);
                self.store(p);
            }
            Cmd::Do => {
                // Any non-zero value turns the output on.
                self.push(a2);
                self.ops.push(Op::PushR { v: 0.0 });
                self.ops.push(Op::NeR {});
                self.ops.push(Op::IToR {});
                self.store(p);
            }
            _ => {
                // TDO: on for ARGUMENT2 seconds; the device turns it off.
                for f in ["TDOON", "TDOREM"] {
                    self.push(a2);
                    self.store(&field(f, Class::Real));
                }
                self.push(a2);
                self.ops.push(Op::PushR { v: 0.0 });
                self.ops.push(Op::GtR {});
                self.ops.push(Op::IToR {});
                self.store(&field("STATUS", Class::Int));
            }
        }
        self.place(skip);
    }

    /// Drops the next index, or advances a register index (WDB, WTM, RDB).
    fn advance(&mut self, index: &Arg) {
        match index {
            Arg::Param(p) => self.store(p),
            _ => self.ops.push(Op::StoreLoc { n: 0 }),
        }
    }

    fn history_index(&mut self, cmd: Cmd, a1: &Arg, a2: &Arg) {
        if cmd == Cmd::Rdb {
            self.push(a1);
            self.push(a2);
            self.ops.push(Op::HistRead { f: HistFn::Rdb as u8 });
            self.advance(a2);
            self.keep_rr();
            return;
        }
        self.load(&rr());
        self.push(a1);
        self.push(a2);
        self.ops.push(Op::HistWrite { time: u8::from(cmd == Cmd::Wtm) });
        self.advance(a2);
    }

    fn history_read(&mut self, cmd: Cmd, a1: &Arg, a2: &Arg) {
        let f = match cmd {
            Cmd::Dhv => HistFn::Dhv,
            Cmd::Dht => HistFn::Dht,
            Cmd::Phv => HistFn::Phv,
            Cmd::Pht => HistFn::Pht,
            Cmd::Mhv => HistFn::Mhv,
            Cmd::Dis => HistFn::Dis,
            Cmd::Din => HistFn::Din,
            Cmd::Pis => HistFn::Pis,
            Cmd::Pin => HistFn::Pin,
            _ => HistFn::Gte,
        };
        self.push(a1);
        self.push(a2);
        self.ops.push(Op::HistRead { f: f as u8 });
        self.ops.push(Op::StoreLoc { n: 0 });
        self.keep_rr();
    }
}

//! Lowering of expressions: typed opcodes, conversions and constant folding.

use super::Lowerer;
use crate::st::ast::BinOp;
use crate::st::hir::{Expr, ExprKind};
use linc_format::isa::{Kind, Op};
use linc_stdlib::{Param, Ty, SIGNATURES};

/// A folded numeric constant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Const {
    I(i32),
    R(f32),
}

impl Const {
    pub fn int(self) -> i32 {
        match self {
            Const::I(i) => i,
            Const::R(r) => linc_stdlib::value::round_to_i32(r),
        }
    }

    pub fn real(self) -> f32 {
        match self {
            Const::I(i) => i as f32,
            Const::R(r) => r,
        }
    }

    pub fn is_positive(self) -> bool {
        match self {
            Const::I(i) => i >= 0,
            Const::R(r) => r >= 0.0,
        }
    }
}

/// The value of a constant numeric expression, folded as the VM would
/// compute it; `None` if it is not constant or would fault at run time
/// (division by zero, `**` outside its domain, a REAL that overflows to
/// infinity and would be stored or converted), which is left to the VM so
/// that it raises its located runtime error.
pub fn constant(e: &Expr) -> Option<Const> {
    folded(e).filter(|c| !matches!(c, Const::R(r) if !r.is_finite()))
}

fn folded(e: &Expr) -> Option<Const> {
    match &e.kind {
        ExprKind::Int(i) => Some(Const::I(*i)),
        ExprKind::Real(r) => Some(Const::R(*r)),
        ExprKind::Bool(b) => Some(Const::I(i32::from(*b))),
        ExprKind::Neg(a) => match constant(a)? {
            Const::I(i) => Some(Const::I(i.wrapping_neg())),
            Const::R(r) => Some(Const::R(-r)),
        },
        ExprKind::Not(a) => Some(Const::I(i32::from(constant(a)?.int() == 0))),
        ExprKind::Binary(op, a, b) => {
            let (x, y) = (constant(a)?, constant(b)?);
            fold(*op, x, y, a.ty == Ty::Real || b.ty == Ty::Real)
        }
        _ => None,
    }
}

/// A comparison folded over either kind of number.
fn compare<T: PartialOrd>(op: BinOp, a: T, c: T) -> Option<Const> {
    let v = match op {
        BinOp::Eq => a == c,
        BinOp::Ne => a != c,
        BinOp::Lt => a < c,
        BinOp::Gt => a > c,
        BinOp::Le => a <= c,
        BinOp::Ge => a >= c,
        _ => return None,
    };
    Some(Const::I(i32::from(v)))
}

fn fold(op: BinOp, x: Const, y: Const, real: bool) -> Option<Const> {
    if real || op == BinOp::Pow {
        let (a, c) = (x.real(), y.real());
        return match op {
            BinOp::Add => Some(Const::R(a + c)),
            BinOp::Sub => Some(Const::R(a - c)),
            BinOp::Mul => Some(Const::R(a * c)),
            BinOp::Div if c != 0.0 => Some(Const::R(a / c)),
            BinOp::Pow => linc_stdlib::power(a, c).ok().map(Const::R),
            _ => compare(op, a, c),
        };
    }
    let (a, c) = (x.int(), y.int());
    match op {
        BinOp::Add => Some(Const::I(a.wrapping_add(c))),
        BinOp::Sub => Some(Const::I(a.wrapping_sub(c))),
        BinOp::Mul => Some(Const::I(a.wrapping_mul(c))),
        BinOp::Div if c != 0 => Some(Const::I(a.wrapping_div(c))),
        BinOp::Mod if c != 0 => Some(Const::I(a.wrapping_rem(c))),
        BinOp::And => Some(Const::I(i32::from((a & c) as i16))),
        BinOp::Or => Some(Const::I(i32::from((a | c) as i16))),
        BinOp::Xor => Some(Const::I(i32::from((a ^ c) as i16))),
        _ => compare(op, a, c),
    }
}

/// How a value of type `ty` travels on the stacks.
pub fn kind_of(ty: Ty) -> Kind {
    match ty {
        Ty::Real => Kind::Real,
        Ty::Bool => Kind::Bool,
        Ty::Text | Ty::Bytes | Ty::WStr => Kind::Bytes,
        Ty::Int | Ty::Any => Kind::Int,
    }
}

fn is_real(ty: Ty) -> bool {
    ty == Ty::Real
}

impl Lowerer {
    /// Emits `e` converted to `want` (numeric types convert; strings stay).
    pub(super) fn expr_as(&mut self, e: &Expr, want: Ty) {
        if let Some(c) = constant(e) {
            match want {
                Ty::Real => self.emit(Op::PushR { v: c.real() }),
                Ty::Bool => self.emit(Op::PushI { v: i32::from(c.int() != 0) }),
                _ if e.ty == Ty::Real && want == Ty::Int => self.emit(Op::PushI { v: c.int() }),
                _ => match c {
                    Const::I(i) => self.emit(Op::PushI { v: i }),
                    Const::R(r) => self.emit(Op::PushR { v: r }),
                },
            };
            return;
        }
        self.expr(e);
        match (e.ty, want) {
            (Ty::Int | Ty::Bool, Ty::Real) => {
                self.emit(Op::IToR {});
            }
            (Ty::Real, Ty::Int | Ty::Bool) => {
                self.emit(Op::RToI {});
            }
            _ => {}
        }
        if want == Ty::Bool && e.ty == Ty::Int {
            self.emit(Op::Truth {});
        }
    }

    /// Emits `e` as its own type.
    pub(super) fn expr(&mut self, e: &Expr) {
        if matches!(e.ty, Ty::Int | Ty::Real | Ty::Bool) {
            if let Some(c) = constant(e) {
                match (c, e.ty) {
                    (c, Ty::Real) => self.emit(Op::PushR { v: c.real() }),
                    (c, _) => self.emit(Op::PushI { v: c.int() }),
                };
                return;
            }
        }
        match &e.kind {
            ExprKind::Int(i) => {
                self.emit(Op::PushI { v: *i });
            }
            ExprKind::Real(r) => {
                self.emit(Op::PushR { v: *r });
            }
            ExprKind::Bool(b) => {
                self.emit(Op::PushI { v: i32::from(*b) });
            }
            ExprKind::Str(s) => {
                let k = self.string(s, e.span);
                self.emit(Op::PushS { k });
            }
            ExprKind::Load(place) => self.load(place),
            ExprKind::Neg(a) => {
                let want = if is_real(e.ty) { Ty::Real } else { Ty::Int };
                self.expr_as(a, want);
                self.emit(if is_real(e.ty) { Op::NegR {} } else { Op::NegI {} });
            }
            ExprKind::Not(a) => {
                self.expr_as(a, Ty::Int);
                self.emit(Op::Not {});
            }
            ExprKind::Binary(op, a, b) => self.binary(*op, a, b),
            ExprKind::Call { index, args } => self.call(*index, args, e.ty),
            ExprKind::Error => {
                self.emit(Op::PushI { v: 0 });
            }
        }
    }

    /// Evaluates `e` where bytes are wanted: a STRING value has its
    /// `$`-sequences decoded (`Decode`), except a literal without `$`, which
    /// is its bytes already.
    pub(super) fn expr_as_bytes(&mut self, e: &Expr) {
        self.expr(e);
        let plain = matches!(&e.kind, ExprKind::Str(s) if !s.contains(&b'$'));
        if e.ty == Ty::Text && !plain {
            self.emit(Op::Decode {});
        }
    }

    fn binary(&mut self, op: BinOp, a: &Expr, b: &Expr) {
        let stringy = a.ty.is_stringy() && a.ty != Ty::Any && b.ty.is_stringy() && b.ty != Ty::Any;
        if stringy {
            // A STRING compared with a byte sequence is decoded first, as it
            // would be when passed to EQUAL or STRCOMP.
            let decode = a.ty != b.ty && (a.ty == Ty::Text || b.ty == Ty::Text);
            for x in [a, b] {
                if decode {
                    self.expr_as_bytes(x);
                } else {
                    self.expr(x);
                }
            }
            // `=` ignores case only between STRING items (§12.6, EQUAL);
            // with a byte sequence or wide string it is strict.
            if op == BinOp::Eq && (a.ty != Ty::Text || b.ty != Ty::Text) {
                self.emit(Op::NeS {});
                self.emit(Op::Not {});
                return;
            }
            self.emit(match op {
                BinOp::Eq => Op::EqS {},
                BinOp::Ne => Op::NeS {},
                BinOp::Lt => Op::LtS {},
                BinOp::Gt => Op::GtS {},
                BinOp::Le => Op::LeS {},
                _ => Op::GeS {},
            });
            return;
        }
        let real = op == BinOp::Pow
            || (!matches!(op, BinOp::Mod | BinOp::And | BinOp::Or | BinOp::Xor) && (is_real(a.ty) || is_real(b.ty)));
        let want = if real { Ty::Real } else { Ty::Int };
        self.expr_as(a, want);
        self.expr_as(b, want);
        let op = match (op, real) {
            (BinOp::Add, true) => Op::AddR {},
            (BinOp::Sub, true) => Op::SubR {},
            (BinOp::Mul, true) => Op::MulR {},
            (BinOp::Div, true) => Op::DivR {},
            (BinOp::Pow, _) => Op::PowR {},
            (BinOp::Eq, true) => Op::EqR {},
            (BinOp::Ne, true) => Op::NeR {},
            (BinOp::Lt, true) => Op::LtR {},
            (BinOp::Gt, true) => Op::GtR {},
            (BinOp::Le, true) => Op::LeR {},
            (BinOp::Ge, true) => Op::GeR {},
            (BinOp::Add, false) => Op::AddI {},
            (BinOp::Sub, false) => Op::SubI {},
            (BinOp::Mul, false) => Op::MulI {},
            (BinOp::Div, false) => Op::DivI {},
            (BinOp::Mod, _) => Op::ModI {},
            (BinOp::Eq, false) => Op::EqI {},
            (BinOp::Ne, false) => Op::NeI {},
            (BinOp::Lt, false) => Op::LtI {},
            (BinOp::Gt, false) => Op::GtI {},
            (BinOp::Le, false) => Op::LeI {},
            (BinOp::Ge, false) => Op::GeI {},
            (BinOp::And, _) => Op::And {},
            (BinOp::Or, _) => Op::Or {},
            (BinOp::Xor, _) => Op::Xor {},
        };
        self.emit(op);
    }

    fn call(&mut self, index: usize, args: &[Expr], ty: Ty) {
        let Some(sig) = SIGNATURES.get(index) else {
            return;
        };
        if args.len() > linc_format::isa::MAX_CALL_ARGS {
            let span = args.last().map(|a| a.span).unwrap_or_default();
            self.errors.push(super::LowerError::TooMany { span, what: "arguments in one call (16 at most)" });
            return;
        }
        let mut types = 0u32;
        for (i, a) in args.iter().enumerate() {
            let kind = match sig.param(i) {
                Some(Param::Bytes) => {
                    self.expr_as_bytes(a);
                    Kind::Bytes
                }
                Some(Param::Int) => {
                    self.expr_as(a, Ty::Int);
                    Kind::Int
                }
                Some(Param::Bool) => {
                    self.expr_as(a, Ty::Bool);
                    Kind::Bool
                }
                _ => {
                    let k = if is_real(a.ty) { Kind::Real } else { Kind::Int };
                    self.expr_as(a, if k == Kind::Real { Ty::Real } else { Ty::Int });
                    k
                }
            };
            types |= (kind as u32) << (2 * i);
        }
        self.emit(Op::Call { func: index as u8, argc: args.len() as u8, ret: kind_of(ty) as u8, types });
    }
}

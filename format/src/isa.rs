//! The instruction set, described once.
//!
//! One table below gives each instruction its opcode byte, operands, stack
//! effect and meaning; the enum, the encoder, the decoder, the disassembler
//! names and the verifier's stack effects all follow from it (the wasmi way).
//! See `docs/adr/0003-bytecode-and-vm.md` for why the machine looks like this.
//!
//! The VM has two stacks: a numeric stack of 32-bit cells (INT and BOOL as
//! `i32`, REAL as `f32` bits) and a string stack of byte sequences. Typed
//! instructions are chosen by the compiler, so arithmetic never inspects a
//! value's type at run time.

/// Reads and writes one operand, little-endian.
pub trait Operand: Sized + Copy {
    fn read(code: &[u8], at: &mut usize) -> Option<Self>;
    fn write(self, out: &mut Vec<u8>);
}

macro_rules! le_operand {
    ($($t:ty),*) => {$(
        impl Operand for $t {
            fn read(code: &[u8], at: &mut usize) -> Option<Self> {
                const N: usize = std::mem::size_of::<$t>();
                let bytes: [u8; N] = code.get(*at..*at + N)?.try_into().ok()?;
                *at += N;
                Some(<$t>::from_le_bytes(bytes))
            }
            fn write(self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
        }
    )*};
}
le_operand!(u8, u16, u32, i32, f32);

/// An operand that is always 0: its four bytes stay in the encoding (so
/// objects read as before), but it takes no room in memory. `Clamp`'s lower
/// bound is one; with it `Op` is 8 bytes instead of 12, and decoded code
/// needs at most 8 bytes per byte of a file (see `wire::Code`).
#[derive(Clone, Copy, Default, PartialEq, Eq)]
pub struct Zero;

impl std::fmt::Debug for Zero {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("0")
    }
}

impl Operand for Zero {
    fn read(code: &[u8], at: &mut usize) -> Option<Self> {
        (i32::read(code, at)? == 0).then_some(Zero)
    }
    fn write(self, out: &mut Vec<u8>) {
        0i32.write(out);
    }
}

/// A property of an instruction, given once in the table's flags column
/// and read by the verifier, the VM, the compiling tier and the tracer,
/// instead of each keeping its own list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Flag {
    /// Writes the database through its symbol or the reference register.
    Writes,
    /// Only an FST unit may hold it (the FST engine budgets and reads it).
    Fst,
    /// A run may end here, so both stacks must be empty (a resumed run
    /// starts with empty stacks).
    Suspends,
    /// Reads or writes through the reference register.
    UsesRef,
    /// The compiling tier translates it (`Return` only of a numeric kind).
    Compiled,
    /// Pushes a REAL (the compiling tier's value type; `Call` says so in
    /// its `ret`).
    Real,
}

/// How an instruction changes the two stacks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Effect {
    pub num_pop: u32,
    pub num_push: u32,
    pub str_pop: u32,
    pub str_push: u32,
}

macro_rules! instructions {
    ($( $code:literal $name:ident { $($field:ident : $ty:ty),* } [$np:literal $nq:literal $sp:literal $sq:literal] ($($flag:ident)*) $doc:literal ;)*) => {
        /// One instruction. In an object file a jump names a label of its
        /// code block; linking replaces it by the label's instruction index.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub enum Op {
            $( #[doc = $doc] $name { $($field: $ty),* }, )*
        }

        impl Op {
    /// Whether the value this instruction pushes on the numeric stack is a
    /// REAL (the table's `Real` flag; `Call` says so in its `ret`). The
    /// verifier records the types at every label from this, and the
    /// compiling tier keeps REALs in float registers by it.
    pub fn pushes_real(&self) -> bool {
        match self {
            Op::Call { ret, .. } => Kind::from_bits(u32::from(*ret)) == Kind::Real,
            _ => self.has(Flag::Real),
        }
    }

            /// The opcode byte.
            pub fn code(&self) -> u8 {
                match self { $( Op::$name { .. } => $code, )* }
            }

            /// The mnemonic, for listings.
            pub fn name(&self) -> &'static str {
                match self { $( Op::$name { .. } => stringify!($name), )* }
            }

            /// Appends the encoded instruction.
            pub fn encode(&self, out: &mut Vec<u8>) {
                match *self {
                    $( Op::$name { $($field),* } => {
                        out.push($code);
                        $( Operand::write($field, out); )*
                    } )*
                }
            }

            /// Decodes the instruction at `*at`, advancing it. `None` means an
            /// unknown opcode or a truncated operand.
            pub fn decode(code: &[u8], at: &mut usize) -> Option<Op> {
                let op = *code.get(*at)?;
                *at += 1;
                match op {
                    $( $code => Some(Op::$name { $($field: <$ty as Operand>::read(code, at)?),* }), )*
                    _ => None,
                }
            }

            /// The operands as text, for listings.
            pub fn operands(&self) -> Vec<String> {
                match self {
                    $( Op::$name { $($field),* } => vec![$(format!("{}={:?}", stringify!($field), $field)),*], )*
                }
            }

            /// The instruction's properties, from the table's flags column.
            pub fn flags(&self) -> &'static [Flag] {
                match self { $( Op::$name { .. } => &[$(Flag::$flag),*], )* }
            }

            /// Whether the table gives this instruction `flag`.
            pub fn has(&self, flag: Flag) -> bool {
                self.flags().contains(&flag)
            }

            fn fixed_effect(&self) -> Effect {
                match self {
                    $( Op::$name { .. } => Effect { num_pop: $np, num_push: $nq, str_pop: $sp, str_push: $sq }, )*
                }
            }
        }

        /// Every opcode byte, for tests and the fuzzing of loaders.
        pub const OPCODES: &[u8] = &[$($code),*];
    };
}

instructions! {
    0x01 PushI { v: i32 }            [0 1 0 0] (Compiled) "Push an INT constant.";
    0x02 PushR { v: f32 }            [0 1 0 0] (Compiled Real) "Push a REAL constant.";
    0x03 PushS { k: u32 }            [0 0 0 1] (Compiled) "Push string constant `k` of the pool.";
    0x04 LoadLoc { n: u8 }           [0 1 0 0] (Compiled) "Push numeric local `n` (FOR limits).";
    0x05 StoreLoc { n: u8 }          [1 0 0 0] (Compiled) "Pop into numeric local `n`.";
    0x06 LoadRet { n: u16 }          [0 1 0 0] (Compiled) "Push retained slot `n` of the running program.";
    0x07 StoreRet { n: u16 }         [1 0 0 0] (Compiled) "Pop into retained slot `n` (kept from run to run).";
    0x10 LoadI { sym: u16 }          [0 1 0 0] (Compiled) "Push an INT, BOOL or bitfield field as INT.";
    0x11 LoadR { sym: u16 }          [0 1 0 0] (Compiled Real) "Push a REAL field.";
    0x12 LoadS { sym: u16 }          [0 0 0 1] (Compiled) "Push a string-family, ENUM (its name), BSEQ or WSTR field.";
    0x13 LoadBit { sym: u16, bit: u8 } [0 1 0 0] () "Push one bit of a bitfield as 0 or 1.";
    0x14 LoadAlarm { sym: u16 }      [0 1 0 0] () "Push an alarm's In_Alarm state.";
    0x15 LoadSuppress { sym: u16 }   [0 1 0 0] () "Push the remaining suppression time in seconds.";
    0x16 StoreI { sym: u16 }         [1 0 0 0] (Writes Compiled) "Pop an INT into an INT, BOOL or bitfield field.";
    0x17 StoreR { sym: u16 }         [1 0 0 0] (Writes Compiled) "Pop a REAL into a REAL field (must be finite).";
    0x18 StoreS { sym: u16 }         [0 0 1 0] (Writes Compiled) "Pop bytes into a string-family, ENUM, BSEQ or WSTR field.";
    0x19 StoreBit { sym: u16, bit: u8 } [1 0 0 0] (Writes) "Pop an INT into one bit (non-zero is 1).";
    0x1A StoreSuppress { sym: u16 }  [1 0 0 0] (Writes) "Pop seconds of suppression (§18.3.1).";
    0x1B StoreRKeep { sym: u16 }     [1 0 0 0] (Writes) "Pop a REAL into a REAL field; a non-finite one leaves the field as it was (FST math).";
    0x1C AppendS { sym: u16 }        [0 0 1 0] (Writes Compiled) "Pop bytes and append them to a BSEQ or WSTR field: `X := CONCAT(X, s)` without copying X.";
    0x20 Ref { sym: u16 }            [0 0 0 0] (Compiled) "Point the reference register at a field.";
    0x21 RefOff { sym: u16 }         [1 0 0 0] (Compiled) "Pop n; point at the field n places after `sym`, within its run.";
    0x22 RefBit { bit: u8 }          [0 0 0 0] (UsesRef) "Select a bit of the referenced bitfield.";
    0x23 RefBitOff { bit: u8 }       [1 0 0 0] (UsesRef) "Pop n; select bit `bit` + n of the referenced bitfield.";
    0x24 LoadRefI { sym: u16 }       [0 1 0 0] (UsesRef Compiled) "Push the referenced INT, BOOL or bitfield.";
    0x25 LoadRefR { sym: u16 }       [0 1 0 0] (UsesRef Compiled Real) "Push the referenced REAL.";
    0x26 LoadRefS { sym: u16 }       [0 0 0 1] (UsesRef) "Push the referenced string-family field.";
    0x27 LoadRefBit { sym: u16 }     [0 1 0 0] (UsesRef) "Push the referenced bit.";
    0x28 StoreRefI { sym: u16 }      [1 0 0 0] (Writes UsesRef Compiled) "Pop into the referenced INT, BOOL or bitfield.";
    0x29 StoreRefR { sym: u16 }      [1 0 0 0] (Writes UsesRef Compiled) "Pop into the referenced REAL.";
    0x2A StoreRefS { sym: u16 }      [0 0 1 0] (Writes UsesRef) "Pop into the referenced string-family field.";
    0x2B StoreRefBit { sym: u16 }    [1 0 0 0] (Writes UsesRef) "Pop into the referenced bit.";
    0x30 IToR {}                     [1 1 0 0] (Compiled Real) "INT to REAL.";
    0x31 RToI {}                     [1 1 0 0] (Compiled) "REAL to INT, rounding halves away from zero.";
    0x32 Decode {}                   [0 0 1 1] (Compiled) "Decode the $-sequences of a string constant or STRING value.";
    0x33 Truth {}                    [1 1 0 0] (Compiled) "INT to BOOL: non-zero is 1.";
    0x34 Clamp { lo: Zero, hi: i32 } [1 1 0 0] () "Limit an INT to `0..=hi` (FST values into 8-bit flags); `lo` is encoded, and 0.";
    0x35 TruncR {}                   [1 1 0 0] () "REAL to its integer part, as REAL (FST INT).";
    0x40 AddI {}                     [2 1 0 0] (Compiled) "INT +, wrapping.";
    0x41 SubI {}                     [2 1 0 0] (Compiled) "INT -, wrapping.";
    0x42 MulI {}                     [2 1 0 0] (Compiled) "INT *, wrapping.";
    0x43 DivI {}                     [2 1 0 0] (Compiled) "INT /, truncating; dividing by 0 is an error.";
    0x44 ModI {}                     [2 1 0 0] (Compiled) "INT MOD; by 0 is an error.";
    0x45 NegI {}                     [1 1 0 0] (Compiled) "INT negation, wrapping.";
    0x48 AddR {}                     [2 1 0 0] (Compiled Real) "REAL +.";
    0x49 SubR {}                     [2 1 0 0] (Compiled Real) "REAL -.";
    0x4A MulR {}                     [2 1 0 0] (Compiled Real) "REAL *.";
    0x4B DivR {}                     [2 1 0 0] (Compiled Real) "REAL /; dividing by 0 is an error.";
    0x4C PowR {}                     [2 1 0 0] () "REAL **; needs A > 0 (or A = 0 with B > 0).";
    0x4D NegR {}                     [1 1 0 0] (Compiled Real) "REAL negation.";
    0x4E PowRKeep {}                 [2 1 0 0] (Fst) "FST REAL **: NaN where `PowR` faults, which `StoreRKeep` then drops (an FST never faults on arithmetic).";
    0x50 EqI {}                      [2 1 0 0] (Compiled) "INT =.";
    0x51 NeI {}                      [2 1 0 0] (Compiled) "INT <>.";
    0x52 LtI {}                      [2 1 0 0] (Compiled) "INT <.";
    0x53 GtI {}                      [2 1 0 0] (Compiled) "INT >.";
    0x54 LeI {}                      [2 1 0 0] (Compiled) "INT <=.";
    0x55 GeI {}                      [2 1 0 0] (Compiled) "INT >=.";
    0x58 EqR {}                      [2 1 0 0] (Compiled) "REAL =.";
    0x59 NeR {}                      [2 1 0 0] (Compiled) "REAL <>.";
    0x5A LtR {}                      [2 1 0 0] (Compiled) "REAL <.";
    0x5B GtR {}                      [2 1 0 0] (Compiled) "REAL >.";
    0x5C LeR {}                      [2 1 0 0] (Compiled) "REAL <=.";
    0x5D GeR {}                      [2 1 0 0] (Compiled) "REAL >=.";
    0x60 EqS {}                      [0 1 2 0] (Compiled) "String = (ignores ASCII case).";
    0x61 NeS {}                      [0 1 2 0] (Compiled) "String <> (bytes).";
    0x62 LtS {}                      [0 1 2 0] (Compiled) "String < (bytes).";
    0x63 GtS {}                      [0 1 2 0] (Compiled) "String > (bytes).";
    0x64 LeS {}                      [0 1 2 0] (Compiled) "String <= (bytes).";
    0x65 GeS {}                      [0 1 2 0] (Compiled) "String >= (bytes).";
    0x68 And {}                      [2 1 0 0] (Compiled) "AND: 16-bit bitwise (logical on 0/1).";
    0x69 Or {}                       [2 1 0 0] (Compiled) "OR: 16-bit bitwise.";
    0x6A Xor {}                      [2 1 0 0] (Compiled) "XOR: 16-bit bitwise.";
    0x6B Not {}                      [1 1 0 0] (Compiled) "Logical NOT: 0 becomes 1, anything else 0.";
    0x70 Jump { to: u32 }            [0 0 0 0] (Compiled) "Continue at label `to`.";
    0x71 JumpIfFalse { to: u32 }     [1 0 0 0] (Compiled) "Pop; continue at label `to` if it is 0.";
    0x72 JumpIfTrue { to: u32 }      [1 0 0 0] (Compiled) "Pop; continue at label `to` if it is not 0.";
    0x73 Yield {}                    [0 0 0 0] (Suspends) "Suspend: end this run here and resume after it next time (FST WT); locals survive.";
    0x74 Ret {}                      [0 0 0 0] (Suspends Compiled) "End the run.";
    0x75 Return { kind: u8 }         [0 0 0 0] (Suspends Compiled) "Pop a value of `kind` as the run's result and end (linc eval).";
    0x79 Step { n: u16 }             [0 0 0 0] (Fst Suspends) "FST: begin step `n`; when the run's step budget is spent, end the run here (it resumes at this step).";
    0x7A Pause { why: u8 }           [1 0 0 0] (Fst Suspends) "FST: pop a REAL; end the run after this instruction for WT (why 0: seconds) or BRK (why 1: 100 ms units).";
    0x7B DayTime { what: u8 }        [0 1 0 0] (Fst) "FST: push the device clock's day of week (0; 1 = Sunday) or minutes since midnight (1), as REAL.";
    0x7C Log { which: u8 }           [1 0 1 0] (Fst) "FST: pop a message and a REAL; append them to the alarm (0) or event (1) log.";
    0x7D HistWrite { time: u8 }      [3 1 0 0] (Fst) "FST: pop index, history point, value; WDB (0) or WTM (1); push the next index.";
    0x7E HistRead { f: u8 }          [2 2 0 0] (Fst) "FST: pop ARGUMENT2 and ARGUMENT1 of history read `f`; push the result and the next index.";
    0x78 Call { func: u8, argc: u8, ret: u8, types: u32 } [0 0 0 0] (Compiled) "Call library function `func`; argument kinds in `types` (2 bits each), result kind `ret`.";
}

/// Kinds of call arguments and results, as packed into `Call`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Int = 0,
    Real = 1,
    Bool = 2,
    Bytes = 3,
}

impl Kind {
    pub fn from_bits(b: u32) -> Kind {
        match b & 3 {
            0 => Kind::Int,
            1 => Kind::Real,
            2 => Kind::Bool,
            _ => Kind::Bytes,
        }
    }

    /// Kind of argument `i` of a packed `types` word.
    pub fn arg(types: u32, i: usize) -> Kind {
        Kind::from_bits(types >> (2 * i))
    }

    fn on_string_stack(self) -> bool {
        self == Kind::Bytes
    }
}

/// Most arguments a `Call` can carry (2 bits each in a `u32`).
pub const MAX_CALL_ARGS: usize = 16;

impl Op {
    /// The instruction's effect on the two stacks.
    pub fn effect(&self) -> Effect {
        match *self {
            Op::Call { argc, ret, types, .. } => {
                let n = usize::from(argc).min(MAX_CALL_ARGS);
                let strs = (0..n).filter(|&i| Kind::arg(types, i).on_string_stack()).count() as u32;
                let ret_str = Kind::from_bits(u32::from(ret)).on_string_stack();
                Effect {
                    num_pop: n as u32 - strs,
                    num_push: u32::from(!ret_str),
                    str_pop: strs,
                    str_push: u32::from(ret_str),
                }
            }
            Op::Return { kind } => {
                let s = Kind::from_bits(u32::from(kind)).on_string_stack();
                Effect { num_pop: u32::from(!s), num_push: 0, str_pop: u32::from(s), str_push: 0 }
            }
            _ => self.fixed_effect(),
        }
    }

    /// The jump target, if this instruction can jump.
    pub fn target(&self) -> Option<u32> {
        match *self {
            Op::Jump { to } | Op::JumpIfFalse { to } | Op::JumpIfTrue { to } => Some(to),
            _ => None,
        }
    }

    /// The same jump with another target (labels become instruction indices
    /// when a program is linked).
    pub fn retarget(self, to: u32) -> Op {
        match self {
            Op::Jump { .. } => Op::Jump { to },
            Op::JumpIfFalse { .. } => Op::JumpIfFalse { to },
            Op::JumpIfTrue { .. } => Op::JumpIfTrue { to },
            other => other,
        }
    }

    /// The same instruction naming symbol `n` instead (linking renumbers
    /// symbols per program).
    pub fn with_symbol(self, n: u16) -> Op {
        match self {
            Op::LoadI { .. } => Op::LoadI { sym: n },
            Op::LoadR { .. } => Op::LoadR { sym: n },
            Op::LoadS { .. } => Op::LoadS { sym: n },
            Op::LoadBit { bit, .. } => Op::LoadBit { sym: n, bit },
            Op::LoadAlarm { .. } => Op::LoadAlarm { sym: n },
            Op::LoadSuppress { .. } => Op::LoadSuppress { sym: n },
            Op::StoreI { .. } => Op::StoreI { sym: n },
            Op::StoreR { .. } => Op::StoreR { sym: n },
            Op::StoreS { .. } => Op::StoreS { sym: n },
            Op::StoreBit { bit, .. } => Op::StoreBit { sym: n, bit },
            Op::StoreSuppress { .. } => Op::StoreSuppress { sym: n },
            Op::StoreRKeep { .. } => Op::StoreRKeep { sym: n },
            Op::AppendS { .. } => Op::AppendS { sym: n },
            Op::Ref { .. } => Op::Ref { sym: n },
            Op::RefOff { .. } => Op::RefOff { sym: n },
            Op::LoadRefI { .. } => Op::LoadRefI { sym: n },
            Op::LoadRefR { .. } => Op::LoadRefR { sym: n },
            Op::LoadRefS { .. } => Op::LoadRefS { sym: n },
            Op::LoadRefBit { .. } => Op::LoadRefBit { sym: n },
            Op::StoreRefI { .. } => Op::StoreRefI { sym: n },
            Op::StoreRefR { .. } => Op::StoreRefR { sym: n },
            Op::StoreRefS { .. } => Op::StoreRefS { sym: n },
            Op::StoreRefBit { .. } => Op::StoreRefBit { sym: n },
            other => other,
        }
    }

    /// Whether this instruction writes the database through its symbol.
    pub fn writes(&self) -> bool {
        self.has(Flag::Writes)
    }

    /// The database symbol this instruction names, if any.
    pub fn symbol(&self) -> Option<u16> {
        match *self {
            Op::LoadI { sym }
            | Op::LoadR { sym }
            | Op::LoadS { sym }
            | Op::LoadBit { sym, .. }
            | Op::LoadAlarm { sym }
            | Op::LoadSuppress { sym }
            | Op::StoreI { sym }
            | Op::StoreR { sym }
            | Op::StoreS { sym }
            | Op::StoreBit { sym, .. }
            | Op::StoreSuppress { sym }
            | Op::StoreRKeep { sym }
            | Op::AppendS { sym }
            | Op::Ref { sym }
            | Op::RefOff { sym }
            | Op::LoadRefI { sym }
            | Op::LoadRefR { sym }
            | Op::LoadRefS { sym }
            | Op::LoadRefBit { sym }
            | Op::StoreRefI { sym }
            | Op::StoreRefR { sym }
            | Op::StoreRefS { sym }
            | Op::StoreRefBit { sym } => Some(sym),
            _ => None,
        }
    }
}

/// The operand of `HistRead`: a read command of the FST manual's Tables
/// B-16/B-17, numbered for the instruction set.
#[repr(u8)]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum HistFn {
    Rdb = 0,
    Dhv,
    Dht,
    Phv,
    Pht,
    Mhv,
    Dis,
    Din,
    Pis,
    Pin,
    Gte,
}

impl HistFn {
    pub const ALL: [HistFn; 11] = [
        HistFn::Rdb,
        HistFn::Dhv,
        HistFn::Dht,
        HistFn::Phv,
        HistFn::Pht,
        HistFn::Mhv,
        HistFn::Dis,
        HistFn::Din,
        HistFn::Pis,
        HistFn::Pin,
        HistFn::Gte,
    ];

    /// The function with this operand byte; `None` past the last.
    pub fn from_u8(b: u8) -> Option<HistFn> {
        Self::ALL.get(usize::from(b)).copied()
    }

    /// The FST command's name.
    pub fn name(self) -> &'static str {
        ["RDB", "DHV", "DHT", "PHV", "PHT", "MHV", "DIS", "DIN", "PIS", "PIN", "GTE"][self as usize]
    }
}

#[cfg(test)]
mod tests {
    /// Every instruction, with zero operands.
    fn every_op() -> Vec<Op> {
        OPCODES.iter().map(|&c| Op::decode(&[c, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], &mut 0).expect("decodes")).collect()
    }

    #[test]
    fn the_flags_agree_with_the_rest_of_the_table() {
        for op in every_op() {
            let e = op.effect();
            if op.has(Flag::Writes) {
                assert!(op.symbol().is_some(), "{op:?} writes through a symbol");
                assert!(e.num_pop + e.str_pop >= 1, "{op:?} writes a popped value");
            }
            if op.has(Flag::Real) {
                assert_eq!(e.num_push, 1, "{op:?} pushes its REAL");
            }
            assert!(!(op.has(Flag::Fst) && op.has(Flag::Compiled)), "{op:?}: FST units stay interpreted");
            assert_eq!(
                op.has(Flag::UsesRef),
                op.name().contains("Ref") && !matches!(op, Op::Ref { .. } | Op::RefOff { .. }),
                "{op:?}"
            );
        }
        let suspending: Vec<&str> = every_op().iter().filter(|o| o.has(Flag::Suspends)).map(Op::name).collect();
        assert_eq!(suspending, ["Yield", "Ret", "Return", "Step", "Pause"]);
    }

    use super::*;

    #[test]
    fn every_opcode_round_trips() {
        let samples = [
            Op::PushI { v: -7 },
            Op::PushR { v: 2.5 },
            Op::LoadBit { sym: 3, bit: 7 },
            Op::Jump { to: 99 },
            Op::Call { func: 5, argc: 2, ret: 3, types: 0b1101 },
            Op::Ret {},
        ];
        for op in samples {
            let mut buf = Vec::new();
            op.encode(&mut buf);
            let mut at = 0;
            assert_eq!(Op::decode(&buf, &mut at), Some(op));
            assert_eq!(at, buf.len());
            // Every truncation fails cleanly.
            for cut in 0..buf.len() {
                let mut at = 0;
                assert_eq!(Op::decode(&buf[..cut], &mut at), None);
            }
        }
        let mut unique = OPCODES.to_vec();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), OPCODES.len(), "opcodes are unique");
    }

    #[test]
    fn call_effect_counts_string_arguments() {
        let op = Op::Call { func: 0, argc: 3, ret: Kind::Bytes as u8, types: 3 | (3 << 4) };
        assert_eq!(op.effect(), Effect { num_pop: 1, num_push: 0, str_pop: 2, str_push: 1 });
    }
}

//! The VM's string stack and library calls.
//!
//! String values lie end to end in one buffer ([`StrStack`]). LEN, LEFT,
//! RIGHT, MID and CONCAT work there (`linc_stdlib::call::InPlace`), so
//! they copy only the bytes they keep and build no argument list; a store
//! copies the value into the cell's own buffer. The other library functions
//! take their string arguments in buffers kept as spares from call to call,
//! so a loop that builds a string (`S := CONCAT(S, FORMAT(...))`) settles
//! to no allocation per pass. Reuse changes nothing that a program can see:
//! every value pushed is still counted against the string budget as if it
//! were new.

use super::cells::{cell_text, corrupt, store_str};
use super::Vm;
use crate::errors::Fault;
use crate::isa::{Kind, Op};
use crate::store::{Cell, Store};
use crate::vm::MAX_STRING;
use crate::wire::Bytes;
use linc_format::Code;
use linc_stdlib::call::InPlace;
use linc_stdlib::value::decode_dollar;
use linc_stdlib::{FnError, Value};

/// Spare buffers kept at most; with strings of at most [`MAX_STRING`]
/// bytes that bounds what the spares hold to about 1 MiB.
const SPARES: usize = 16;

/// Counts a string value of `len` bytes into `used`; whether it is within
/// the limits: at most [`MAX_STRING`] bytes, and at most `limit` bytes made
/// in the run so far.
#[inline(always)]
pub(super) fn fits(used: &mut usize, limit: usize, len: usize) -> bool {
    *used += len;
    len <= MAX_STRING && *used <= limit
}

impl Vm {
    /// Pushes a string value produced by this run, within the budgets,
    /// keeping its buffer as a spare.
    pub(super) fn push_s(&mut self, s: Vec<u8>) -> Result<(), Fault> {
        let pushed = self.push_copy(&s);
        self.recycle(s);
        pushed
    }

    /// Counts a string value of `len` bytes made by this run against the
    /// limits.
    #[inline]
    pub(super) fn count(&mut self, len: usize) -> Result<(), Fault> {
        if self.fits(len) {
            return Ok(());
        }
        Err(self.over(len))
    }

    /// Counts `len` bytes; whether they are within the limits ([`Vm::over`]
    /// says why not).
    #[inline(always)]
    pub(super) fn fits(&mut self, len: usize) -> bool {
        fits(&mut self.string_used, self.string_budget, len)
    }

    /// The fault of a string over a limit ([`Vm::count`]).
    #[cold]
    #[inline(never)]
    pub(super) fn over(&self, len: usize) -> Fault {
        if len > MAX_STRING {
            return Fault::new(Code::R0007, format!("a string of {len} bytes; the limit is {MAX_STRING}"));
        }
        Fault::new(Code::R0007, format!("more than {} bytes of strings made in one run", self.string_budget))
    }

    /// `AppendS`: `X := CONCAT(X, s)` for string cell `c` and the top
    /// string `s`, appending in place. The budgets count what the long form
    /// (`LoadS`, `Call CONCAT`, `StoreS`) makes: a copy of X and the result.
    pub(crate) fn append_s(&mut self, store: &mut Store, c: u32) -> Result<(), Fault> {
        let len = match store.cells.get(c as usize) {
            Some(Cell::Bseq(t) | Cell::Wstr(t)) => t.len(),
            _ => return Err(corrupt()),
        };
        let tail = self.strs.top().len();
        let counted = self.count(len).and_then(|()| self.count(len + tail));
        if counted.is_ok() && !store.refuse_forced(c) {
            if let Some(Cell::Bseq(t) | Cell::Wstr(t)) = store.cells.get_mut(c as usize) {
                t.extend_from_slice(self.strs.top());
            }
        }
        self.strs.drop_top();
        counted
    }

    /// Pushes a copy of `s` (a constant, a field's value or a result).
    fn push_copy(&mut self, s: &[u8]) -> Result<(), Fault> {
        self.count(s.len())?;
        self.strs.push(s);
        Ok(())
    }

    /// `PushS`: string constant `k` of the object.
    pub(crate) fn push_const(&mut self, consts: &[Bytes], k: u32) -> Result<(), Fault> {
        self.push_copy(consts.get(k as usize).map_or(&[][..], |b| &b.0[..]))
    }

    /// `LoadS`: the value of string cell `c` (an enumerated field reads as
    /// its value's name).
    pub(crate) fn load_s(&mut self, store: &Store, c: u32) -> Result<(), Fault> {
        self.push_copy(cell_text(store, c).ok_or_else(corrupt)?)
    }

    /// `StoreS`: the top string into cell `c`.
    pub(crate) fn store_s(&mut self, store: &mut Store, c: u32) -> Result<(), Fault> {
        let stored = store_str(store, c, self.strs.top());
        self.strs.drop_top();
        stored
    }

    /// `EqS` … `GeS`: compares the two top strings (`=` ignores case, as
    /// EQUAL does between STRING items).
    pub(crate) fn compare_s(&mut self, op: Op) -> i32 {
        let (a, b) = self.strs.top_two();
        let v = match op {
            Op::EqS {} => a.eq_ignore_ascii_case(b),
            Op::NeS {} => a != b,
            Op::LtS {} => a < b,
            Op::GtS {} => a > b,
            Op::LeS {} => a <= b,
            _ => a >= b,
        };
        self.strs.drop_top();
        self.strs.drop_top();
        i32::from(v)
    }

    /// The top string, removed, in a buffer of its own (a spare if there
    /// is one).
    pub(super) fn pop_s(&mut self) -> Vec<u8> {
        let mut buf = self.spare_for(self.strs.top().len());
        self.strs.pop_into(&mut buf);
        buf
    }

    /// A spare buffer that holds `len` bytes without growing if there is
    /// one, else the last one kept (or a new one).
    fn spare_for(&mut self, len: usize) -> Vec<u8> {
        match self.spare.iter().rposition(|b| b.capacity() >= len) {
            Some(i) => self.spare.swap_remove(i),
            None => self.spare.pop().unwrap_or_default(),
        }
    }

    /// Keeps a buffer the run no longer needs for a later string.
    pub(super) fn recycle(&mut self, buf: Vec<u8>) {
        if self.spare.len() < SPARES && buf.capacity() > 0 && buf.capacity() <= MAX_STRING + 1 {
            self.spare.push(buf);
        }
    }

    /// Empties the string stack at the start of a run.
    pub(super) fn clear_strs(&mut self) {
        self.strs.clear();
    }

    /// `Decode`: the `$`-sequences of the top string decoded. Without a `$`
    /// the text is already decoded: it stays as it is and, being no new
    /// string, is not counted again against the string budget.
    pub(crate) fn decode(&mut self) -> Result<(), Fault> {
        if self.strs.len() > 0 && !self.strs.top().contains(&b'$') {
            return Ok(());
        }
        let decoded = decode_dollar(self.strs.top());
        self.strs.drop_top();
        self.push_s(decoded)
    }

    /// Whether `Call func` runs on the string stack's own buffers
    /// ([`InPlace`]): a string function of the signature's argument kinds
    /// (the INT ones not given as REAL), and how many INT arguments it
    /// takes. Decided by the instruction alone, so the compiling tier
    /// decides it when translating.
    pub(crate) fn in_place_of(func: u8, argc: u8, ret: u8, types: u32) -> Option<(InPlace, usize)> {
        // Argument kinds two bits each, the first lowest: INT 0, BYTES 3.
        const S: u32 = 3;
        let how = InPlace::of(usize::from(func))?;
        let (want, ints) = match how {
            InPlace::Len => ((1, S, Kind::Int), 0),
            InPlace::Left | InPlace::Right => ((2, S, Kind::Bytes), 1),
            InPlace::Mid => ((3, S, Kind::Bytes), 2),
            InPlace::Concat => ((2, S | S << 2, Kind::Bytes), 0),
        };
        let mask = (1u32 << (2 * want.0)) - 1;
        let fits = argc == want.0 && types & mask == want.1 && Kind::from_bits(u32::from(ret)) == want.2;
        fits.then_some((how, ints))
    }

    /// A string function in place with its INT arguments in order: the
    /// values and the budget counts are the general path's (its result is
    /// counted as a new string; a missing string argument is the null
    /// string, as the general path pops it).
    pub(crate) fn call_in_place(&mut self, how: InPlace, ints: [i32; 2]) -> Result<Option<u32>, Fault> {
        let len = match how {
            InPlace::Len => {
                let n = linc_stdlib::functions::strings::len(self.strs.top());
                self.strs.drop_top();
                return Ok(Some(n as u32));
            }
            InPlace::Concat => {
                self.strs.at_least(2);
                self.strs.join()
            }
            _ => {
                self.strs.at_least(1);
                self.strs.cut(how, ints)
            }
        };
        self.count(len)?;
        Ok(None)
    }

    /// `Call`: pops the arguments (numeric ones through `pop_num`, so that
    /// compiled code can hand over its own), calls library function `func`
    /// and pushes a string result or returns a numeric one as bits. A
    /// domain error is R0005.
    pub(crate) fn call(
        &mut self,
        func: u8,
        argc: u8,
        ret: u8,
        types: u32,
        mut pop_num: impl FnMut(&mut Vm) -> u32,
    ) -> Result<Option<u32>, Fault> {
        if let Some((how, n)) = Vm::in_place_of(func, argc, ret, types) {
            let mut ints = [0i32; 2];
            for i in (0..n).rev() {
                ints[i] = pop_num(self) as i32;
            }
            return self.call_in_place(how, ints);
        }
        let n = usize::from(argc);
        let mut args = std::mem::take(&mut self.args);
        args.clear();
        // Popped last argument first, then put in order.
        for i in (0..n).rev() {
            args.push(match Kind::arg(types, i) {
                Kind::Int => Value::Int(pop_num(self) as i32),
                Kind::Real => Value::Real(f32::from_bits(pop_num(self))),
                Kind::Bool => Value::Bool(pop_num(self) != 0),
                Kind::Bytes => Value::Bytes(self.pop_s()),
            });
        }
        args.reverse();
        let mut spare = if Kind::from_bits(u32::from(ret)) == Kind::Bytes { self.spare_for(0) } else { Vec::new() };
        let result = linc_stdlib::call::call_owned(usize::from(func), &mut args, &mut self.clock, &mut spare);
        self.recycle(spare);
        for a in args.drain(..) {
            if let Value::Bytes(b) = a {
                self.recycle(b);
            }
        }
        self.args = args;
        let v = result.map_err(|FnError::Domain(why)| Fault::new(Code::R0005, why))?;
        Ok(match Kind::from_bits(u32::from(ret)) {
            Kind::Int => Some(v.as_int() as u32),
            Kind::Real => Some(v.as_real().to_bits()),
            Kind::Bool => Some(u32::from(v.as_bool())),
            Kind::Bytes => {
                self.push_s(match v {
                    Value::Bytes(b) => b,
                    _ => Vec::new(),
                })?;
                None
            }
        })
    }
}

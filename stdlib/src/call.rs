//! Calling library functions at run time.
//!
//! The runtime passes arguments already converted to the parameter kinds of
//! the function's [`crate::Signature`] (INT parameters get `Value::Int`,
//! byte-sequence parameters get `Value::Bytes` with `$`-sequences decoded,
//! ANY_NUM parameters keep INT or REAL). Functions are pure except for the
//! environment: the random generator and the clock.
//!
//! [`call`] never panics: an unknown function index or a wrong number of
//! arguments is a [`FnError::Domain`], and an argument of the wrong kind
//! reads as 0, FALSE, 0.0 or the null sequence.

use crate::functions::{
    bits::{self, Dir},
    checksum, convert, datetime, extract, format, numeric, scan, search, select, strings, Args,
};
use crate::{Value, SIGNATURES};

pub use crate::functions::numeric::power;

/// What a function may need from its surroundings.
pub trait Env {
    /// A uniformly distributed number in `[0, 1)`.
    fn random(&mut self) -> f64;
    /// Local time as seconds since 1970-01-01 00:00:00 (mode 0).
    fn local_time(&self) -> i64;
    /// System (UTC) time as seconds since 1970-01-01 00:00:00 (mode 1).
    fn system_time(&self) -> i64;
}

/// A run-time failure of a function; the VM turns it into a located error.
#[derive(Clone, Debug, PartialEq)]
pub enum FnError {
    /// Outside the function's mathematical domain (SQRT(-1), LN(0), ...),
    /// or a result that is not a finite number.
    Domain(String),
}

type Res = Result<Value, FnError>;
type Imp = fn(Args<'_>, &mut dyn Env) -> Res;

fn int(i: i32) -> Res {
    Ok(Value::Int(i))
}

fn bytes(b: Vec<u8>) -> Res {
    Ok(Value::Bytes(b))
}

fn boolean(b: bool) -> Res {
    Ok(Value::Bool(b))
}

fn real(r: Result<f32, FnError>) -> Res {
    r.map(Value::Real)
}

fn math(name: &str, a: Args<'_>) -> Res {
    real(numeric::unary(name, a.real(0)))
}

/// The first argument, or INT 0 if there is none.
fn first(a: Args<'_>) -> Value {
    a.get(0).cloned().unwrap_or(Value::Int(0))
}

/// The implementations, in the order of [`SIGNATURES`].
#[rustfmt::skip]
static TABLE: [(&str, Imp); 77] = [
    ("ABS", |a, _| Ok(convert::abs(&first(a)))),
    ("FLOAT", |a, _| Ok(convert::float(&first(a)))),
    ("ROUND", |a, _| Ok(convert::round(&first(a)))),
    ("TRUNC", |a, _| Ok(convert::trunc(&first(a)))),
    ("FORMAT", |a, _| bytes(format::format(a.bytes(0), a.get(1).unwrap_or(&Value::Int(0))))),
    ("SCAN", |a, _| Ok(scan::scan_value(a.bytes(0), a.bytes(1)))),
    ("IS_VALID", |a, _| boolean(scan::is_valid(a.bytes(0), a.bytes(1)))),
    ("ACOS", |a, _| math("ACOS", a)),
    ("ASIN", |a, _| math("ASIN", a)),
    ("ATAN2", |a, _| real(numeric::atan2(a.real(0), a.real(1)))),
    ("COS", |a, _| math("COS", a)),
    ("DEG", |a, _| math("DEG", a)),
    ("EXP", |a, _| math("EXP", a)),
    ("LN", |a, _| math("LN", a)),
    ("LOG", |a, _| math("LOG", a)),
    ("RAD", |a, _| math("RAD", a)),
    ("SIN", |a, _| math("SIN", a)),
    ("SQRT", |a, _| math("SQRT", a)),
    ("TAN", |a, _| math("TAN", a)),
    ("RANDOM", |a, env| real(select::random(a.real(0), env))),
    ("AVG", |a, _| real(select::avg(a.0))),
    ("MAX", |a, _| Ok(select::extreme(a.0, true))),
    ("MIN", |a, _| Ok(select::extreme(a.0, false))),
    ("SWITCH", |a, _| Ok(select::switch(a.get(0), a.get(1), a.int(2)))),
    ("EQUAL", |a, _| boolean(strings::equal(a.bytes(0), a.bytes(1)))),
    ("LEN", |a, _| int(strings::len(a.bytes(0)))),
    ("LEFT", |a, _| bytes(strings::left(a.bytes(0), a.int(1)))),
    ("RIGHT", |a, _| bytes(strings::right(a.bytes(0), a.int(1)))),
    ("MID", |a, _| bytes(strings::mid(a.bytes(0), a.int(1), a.int(2)))),
    ("CONCAT", |a, _| bytes(strings::concat(a.bytes(0), a.bytes(1)))),
    ("INSERT", |a, _| bytes(strings::insert(a.bytes(0), a.bytes(1), a.int(2)))),
    ("DELETE", |a, _| bytes(strings::delete(a.bytes(0), a.int(1), a.int(2)))),
    ("REPLACE", |a, _| bytes(strings::replace(a.bytes(0), a.bytes(1), a.int(2), a.int(3)))),
    ("FIND", |a, _| int(search::find(a.bytes(0), a.bytes(1), a.get(2).map_or(1, Value::as_int)))),
    ("DELIMIT", |a, _| bytes(search::delimit(a.bytes(0), a.bytes(1), a.int(2)))),
    ("JUSTIFY_LEFT", |a, _| bytes(strings::justify_left(a.bytes(0), a.int(1)))),
    ("JUSTIFY_RIGHT", |a, _| bytes(strings::justify_right(a.bytes(0), a.int(1)))),
    ("JUSTIFY_CENTRE", |a, _| bytes(strings::justify_centre(a.bytes(0), a.int(1)))),
    ("LTRIM", |a, _| bytes(strings::ltrim(a.bytes(0)))),
    ("RTRIM", |a, _| bytes(strings::rtrim(a.bytes(0)))),
    ("TRIM", |a, _| bytes(strings::trim(a.bytes(0)))),
    ("UCASE", |a, _| bytes(strings::ucase(a.bytes(0)))),
    ("LCASE", |a, _| bytes(strings::lcase(a.bytes(0)))),
    ("STRING", |a, _| bytes(strings::string(a.int(0), a.bytes(1)))),
    ("SPACE", |a, _| bytes(strings::space(a.int(0)))),
    ("STRCOMP", |a, _| int(strings::strcomp(a.bytes(0), a.bytes(1)))),
    ("PURGE", |a, _| bytes(strings::purge(a.bytes(0), a.bytes(1)))),
    ("DATEANDTIMENOW", |a, env| bytes(datetime::dateandtimenow(a.get(0).map(Value::as_int), env))),
    ("EXTRACT_BOOL", |a, _| boolean(extract::extract_bool(a.bytes(0), a.int(1), a.int(2)))),
    ("EXTRACT_INT8", |a, _| int(extract::extract_int8(a.bytes(0), a.int(1)))),
    ("EXTRACT_UINT8", |a, _| int(extract::extract_uint8(a.bytes(0), a.int(1)))),
    ("EXTRACT_INT16", |a, _| int(extract::extract_int16(a.bytes(0), a.int(1), a.int(2)))),
    ("EXTRACT_UINT16", |a, _| int(extract::extract_uint16(a.bytes(0), a.int(1), a.int(2)))),
    ("EXTRACT_INT32", |a, _| int(extract::extract_int32(a.bytes(0), a.int(1), a.int(2)))),
    ("EXTRACT_REAL", |a, _| Ok(Value::Real(extract::extract_real(a.bytes(0), a.int(1), a.int(2))))),
    ("REPLACE_BOOL", |a, _| bytes(extract::replace_bool(a.bytes(0), a.int(1), a.int(2), a.boolean(3)))),
    ("REPLACE_INT8", |a, _| bytes(extract::replace_8(a.bytes(0), a.int(1), a.int(2)))),
    ("REPLACE_UINT8", |a, _| bytes(extract::replace_8(a.bytes(0), a.int(1), a.int(2)))),
    ("REPLACE_INT16", |a, _| bytes(extract::replace_16(a.bytes(0), a.int(1), a.int(2), a.int(3)))),
    ("REPLACE_UINT16", |a, _| bytes(extract::replace_16(a.bytes(0), a.int(1), a.int(2), a.int(3)))),
    ("REPLACE_INT32", |a, _| bytes(extract::replace_int32(a.bytes(0), a.int(1), a.int(2), a.int(3)))),
    ("REPLACE_REAL", |a, _| bytes(extract::replace_real(a.bytes(0), a.int(1), a.real(2), a.int(3)))),
    ("BIT_INVERT", |a, _| int(bits::bit_invert(a.int(0)))),
    ("SHL8", |a, _| int(bits::shift(a.int(0), a.int(1), 8, Dir::Left))),
    ("SHL16", |a, _| int(bits::shift(a.int(0), a.int(1), 16, Dir::Left))),
    ("SHL32", |a, _| int(bits::shift(a.int(0), a.int(1), 32, Dir::Left))),
    ("SHR8", |a, _| int(bits::shift(a.int(0), a.int(1), 8, Dir::Right))),
    ("SHR16", |a, _| int(bits::shift(a.int(0), a.int(1), 16, Dir::Right))),
    ("SHR32", |a, _| int(bits::shift(a.int(0), a.int(1), 32, Dir::Right))),
    ("ROL8", |a, _| int(bits::rotate(a.int(0), a.int(1), 8, Dir::Left))),
    ("ROL16", |a, _| int(bits::rotate(a.int(0), a.int(1), 16, Dir::Left))),
    ("ROL32", |a, _| int(bits::rotate(a.int(0), a.int(1), 32, Dir::Left))),
    ("ROR8", |a, _| int(bits::rotate(a.int(0), a.int(1), 8, Dir::Right))),
    ("ROR16", |a, _| int(bits::rotate(a.int(0), a.int(1), 16, Dir::Right))),
    ("ROR32", |a, _| int(bits::rotate(a.int(0), a.int(1), 32, Dir::Right))),
    ("BCC", |a, _| int(checksum::bcc(a.bytes(0), a.int(1), a.int(2)))),
    ("CRC", |a, _| int(checksum::crc(a.bytes(0), a.int(1), a.int(2), a.int(3)))),
];

/// Calls function number `index` of [`SIGNATURES`] with `args`.
///
/// An index outside the table or an argument count the signature does not
/// allow is a [`FnError::Domain`]; nothing here panics.
pub fn call(index: usize, args: &[Value], env: &mut dyn Env) -> Result<Value, FnError> {
    let (Some(sig), Some((_, imp))) = (SIGNATURES.get(index), TABLE.get(index)) else {
        return Err(FnError::Domain(format!("there is no library function number {index}")));
    };
    if !sig.arity_ok(args.len()) {
        return Err(FnError::Domain(format!("{sig} cannot be called with {} argument(s)", args.len())));
    }
    imp(Args(args), env)
}

/// Where CONCAT is in [`TABLE`].
const CONCAT: usize = 29;
/// Where LEN, LEFT, RIGHT and MID are in [`TABLE`].
const LEN: usize = 25;
const LEFT: usize = 26;
const RIGHT: usize = 27;
const MID: usize = 28;

/// The string functions a caller can run on the buffer of their first
/// argument, as it lies on the caller's own stack, with no argument list
/// and no new buffer (a loop of LEFT, RIGHT, MID, CONCAT and LEN then
/// copies only the bytes it keeps). Each gives exactly what [`call`]
/// gives; the argument kinds are the signature's (a string, then INTs, or
/// two strings for CONCAT).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum InPlace {
    /// LEN(s): the length; `s` is no longer needed.
    Len,
    /// LEFT(s, l), RIGHT(s, l): `s` becomes the result.
    Left,
    Right,
    /// MID(s, l, p): `s` becomes the result.
    Mid,
    /// CONCAT(a, b): `b` is appended to `a`.
    Concat,
}

impl InPlace {
    /// Function number `index` run in place, if it can be.
    pub fn of(index: usize) -> Option<InPlace> {
        Some(match index {
            LEN => InPlace::Len,
            LEFT => InPlace::Left,
            RIGHT => InPlace::Right,
            MID => InPlace::Mid,
            CONCAT => InPlace::Concat,
            _ => return None,
        })
    }

    /// The bytes of a string of `len` bytes that LEFT, RIGHT or MID keeps
    /// with its INT arguments in order (all of them for LEN and CONCAT,
    /// which keep their first argument whole).
    #[inline]
    pub fn keep(self, len: usize, ints: [i32; 2]) -> std::ops::Range<usize> {
        match self {
            InPlace::Left => strings::left_range(len, ints[0]),
            InPlace::Right => strings::right_range(len, ints[0]),
            InPlace::Mid => strings::mid_range(len, ints[0], ints[1]),
            InPlace::Len | InPlace::Concat => 0..len,
        }
    }
}

/// Where FORMAT is in [`TABLE`].
const FORMAT: usize = 4;

/// [`call`] for a caller that gives up its arguments and offers a spare
/// buffer, so that building a string in a loop does not allocate at every
/// pass: CONCAT appends its second argument to its first in place
/// (`S := CONCAT(S, x)` grows one buffer instead of copying both into a
/// new one) and FORMAT writes into `spare` (taking it). The results are
/// [`call`]'s.
pub fn call_owned(index: usize, args: &mut [Value], env: &mut dyn Env, spare: &mut Vec<u8>) -> Result<Value, FnError> {
    match (index, &mut *args) {
        (CONCAT, [Value::Bytes(a), Value::Bytes(b)]) => {
            let mut out = std::mem::take(a);
            out.extend_from_slice(b);
            Ok(Value::Bytes(out))
        }
        (FORMAT, [Value::Bytes(fmt), value]) => {
            let mut out = std::mem::take(spare);
            format::format_into(fmt, value, &mut out);
            Ok(Value::Bytes(out))
        }
        _ => call(index, args, env),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct NoEnv;
    impl Env for NoEnv {
        fn random(&mut self) -> f64 {
            0.0
        }
        fn local_time(&self) -> i64 {
            0
        }
        fn system_time(&self) -> i64 {
            0
        }
    }

    #[test]
    fn table_follows_signatures() {
        assert_eq!(TABLE.len(), SIGNATURES.len());
        for ((name, _), sig) in TABLE.iter().zip(SIGNATURES) {
            assert_eq!(*name, sig.name);
        }
    }

    #[test]
    fn call_owned_gives_what_call_gives() {
        assert_eq!(TABLE[CONCAT].0, "CONCAT");
        assert_eq!(TABLE[FORMAT].0, "FORMAT");
        let mut env = NoEnv;
        let b = |s: &str| Value::Bytes(s.as_bytes().to_vec());
        for (i, (name, _)) in TABLE.iter().enumerate() {
            let cases: [&[Value]; 4] =
                [&[b("ab"), b("cd")], &[b(""), b("x")], &[b("ab"), Value::Int(3)], &[b("05I"), Value::Real(-7.5)]];
            for args in cases {
                let want = call(i, args, &mut env);
                let mut spare = b"left over".to_vec();
                assert_eq!(call_owned(i, &mut args.to_vec(), &mut env, &mut spare), want, "{name}");
            }
        }
        let mut spare = Vec::new();
        assert_eq!(call_owned(CONCAT, &mut [b("ab"), b("cd")], &mut env, &mut spare), Ok(b("abcd")));
        assert_eq!(call_owned(FORMAT, &mut [b("05I"), Value::Int(42)], &mut env, &mut spare), Ok(b("00042")));
    }

    #[test]
    fn in_place_gives_what_call_gives() {
        let mut env = NoEnv;
        for (i, name) in [(LEN, "LEN"), (LEFT, "LEFT"), (RIGHT, "RIGHT"), (MID, "MID"), (CONCAT, "CONCAT")] {
            assert_eq!(TABLE[i].0, name);
            assert!(InPlace::of(i).is_some(), "{name}");
        }
        assert_eq!(InPlace::of(FORMAT), None);
        let texts: [&[u8]; 4] = [b"", b"a", b"abcdef", b"0123456789"];
        let ns = [i32::MIN, -1, 0, 1, 2, 3, 6, 7, 10, 11, i32::MAX];
        for s in texts {
            for l in ns {
                for (i, how) in [(LEFT, InPlace::Left), (RIGHT, InPlace::Right)] {
                    let want = call(i, &[Value::Bytes(s.to_vec()), Value::Int(l)], &mut env);
                    let got = s[how.keep(s.len(), [l, 0])].to_vec();
                    assert_eq!(Ok(Value::Bytes(got)), want, "{}({s:?}, {l})", TABLE[i].0);
                }
                for p in ns {
                    let want = call(MID, &[Value::Bytes(s.to_vec()), Value::Int(l), Value::Int(p)], &mut env);
                    let got = s[InPlace::Mid.keep(s.len(), [l, p])].to_vec();
                    assert_eq!(Ok(Value::Bytes(got)), want, "MID({s:?}, {l}, {p})");
                }
            }
        }
    }

    #[test]
    fn bad_index_and_arity_are_errors() {
        let mut env = NoEnv;
        assert!(matches!(call(77, &[], &mut env), Err(FnError::Domain(_))));
        assert!(matches!(call(usize::MAX, &[], &mut env), Err(FnError::Domain(_))));
        assert!(matches!(call(0, &[], &mut env), Err(FnError::Domain(_))));
        let two = [Value::Int(1), Value::Int(2)];
        assert!(matches!(call(0, &two, &mut env), Err(FnError::Domain(_))));
        assert_eq!(call(0, &two[..1], &mut env), Ok(Value::Int(1)));
    }
}

//! Signatures of the LIN ST function table (guide §12.6).
//!
//! One table drives the checker's arity and type checks and the text of its
//! diagnostics, so a function is described exactly once.

use crate::Ty;
use std::fmt;

/// What a parameter accepts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Param {
    /// Any number (INT, REAL or BOOL).
    Num,
    /// An integer; a REAL argument is converted as a REAL stored into an INT.
    Int,
    /// A boolean or integer (non-zero is TRUE).
    Bool,
    /// A byte sequence: STRING, BSEQ or WSTR.
    Bytes,
}

impl Param {
    /// Whether an argument of type `ty` may be passed here.
    pub fn accepts(self, ty: Ty) -> bool {
        match self {
            Param::Num | Param::Int | Param::Bool => ty.is_numeric(),
            Param::Bytes => ty.is_stringy(),
        }
    }

    /// How the parameter is written in a signature (`ANY_NUM`, `BSEQ`).
    pub fn name(self) -> &'static str {
        match self {
            Param::Num => "ANY_NUM",
            Param::Int => "INT",
            Param::Bool => "BOOL",
            Param::Bytes => "BSEQ",
        }
    }
}

/// How the result type follows from the arguments.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Returns {
    Fixed(Ty),
    /// REAL if any argument is REAL, else INT (ABS, MAX, MIN, SWITCH).
    NumericOfArgs,
    /// WSTR if any argument is WSTR, else BSEQ (CONCAT).
    BytesOrWStr,
    /// Depends on the conversion letter of SCAN's format (`F`/`G` give REAL).
    ScanValue,
}

/// One entry of the function table.
#[derive(Clone, Copy, Debug)]
pub struct Signature {
    pub name: &'static str,
    /// Parameters in order; the first `required` must be given.
    pub params: &'static [Param],
    pub required: usize,
    /// When true the last parameter repeats (AVG, MAX, MIN).
    pub variadic: bool,
    pub returns: Returns,
    /// The guide's sub-category, for `linc explain` and docs.
    pub category: &'static str,
}

impl Signature {
    /// Whether `n` arguments is a valid count.
    pub fn arity_ok(&self, n: usize) -> bool {
        if self.variadic {
            n >= self.required
        } else {
            n >= self.required && n <= self.params.len()
        }
    }

    /// The parameter an argument at `index` is checked against.
    pub fn param(&self, index: usize) -> Option<Param> {
        match self.params.get(index) {
            Some(p) => Some(*p),
            None if self.variadic => self.params.last().copied(),
            None => None,
        }
    }

    /// Result type for the given argument types.
    pub fn result(&self, args: &[Ty], scan_format: Option<&[u8]>) -> Ty {
        match self.returns {
            Returns::Fixed(t) => t,
            Returns::NumericOfArgs => {
                let relevant: &[Ty] = if self.name == "SWITCH" { &args[..args.len().min(2)] } else { args };
                if relevant.contains(&Ty::Real) {
                    Ty::Real
                } else if relevant.contains(&Ty::Any) {
                    Ty::Any
                } else {
                    Ty::Int
                }
            }
            Returns::BytesOrWStr => {
                if args.contains(&Ty::WStr) {
                    Ty::WStr
                } else {
                    Ty::Bytes
                }
            }
            Returns::ScanValue => match scan_format {
                Some(f) if f.iter().any(|c| matches!(c, b'F' | b'f' | b'G' | b'g')) => Ty::Real,
                Some(_) => Ty::Int,
                None => Ty::Any,
            },
        }
    }
}

impl fmt::Display for Signature {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}(", self.name)?;
        for (i, p) in self.params.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            if i >= self.required && !self.variadic {
                write!(f, "[{}]", p.name())?;
            } else {
                f.write_str(p.name())?;
            }
        }
        if self.variadic {
            write!(f, ", ...")?;
        }
        let ret = match self.returns {
            Returns::Fixed(t) => t.name(),
            Returns::NumericOfArgs => "ANY_NUM",
            Returns::BytesOrWStr => "BSEQ",
            Returns::ScanValue => "ANY_NUM",
        };
        write!(f, ") : {ret}")
    }
}

use Param::{Bool as B, Bytes as S, Int as I, Num as N};

const fn sig(
    name: &'static str,
    params: &'static [Param],
    required: usize,
    returns: Returns,
    category: &'static str,
) -> Signature {
    Signature { name, params, required, variadic: false, returns, category }
}

const fn var(name: &'static str, returns: Returns) -> Signature {
    Signature { name, params: &[N, N], required: 2, variadic: true, returns, category: "Selector" }
}

const INT: Returns = Returns::Fixed(Ty::Int);
const REAL: Returns = Returns::Fixed(Ty::Real);
const BOOL: Returns = Returns::Fixed(Ty::Bool);
const BYTES: Returns = Returns::Fixed(Ty::Bytes);

/// The whole function table of §12.6, in the guide's order.
pub static SIGNATURES: &[Signature] = &[
    sig("ABS", &[N], 1, Returns::NumericOfArgs, "Convert"),
    sig("FLOAT", &[N], 1, REAL, "Convert"),
    sig("ROUND", &[N], 1, INT, "Convert"),
    sig("TRUNC", &[N], 1, INT, "Convert"),
    sig("FORMAT", &[S, N], 2, BYTES, "Convert"),
    sig("SCAN", &[S, S], 2, Returns::ScanValue, "Convert"),
    sig("IS_VALID", &[S, S], 2, BOOL, "Convert"),
    sig("ACOS", &[N], 1, REAL, "Numeric"),
    sig("ASIN", &[N], 1, REAL, "Numeric"),
    sig("ATAN2", &[N, N], 2, REAL, "Numeric"),
    sig("COS", &[N], 1, REAL, "Numeric"),
    sig("DEG", &[N], 1, REAL, "Numeric"),
    sig("EXP", &[N], 1, REAL, "Numeric"),
    sig("LN", &[N], 1, REAL, "Numeric"),
    sig("LOG", &[N], 1, REAL, "Numeric"),
    sig("RAD", &[N], 1, REAL, "Numeric"),
    sig("SIN", &[N], 1, REAL, "Numeric"),
    sig("SQRT", &[N], 1, REAL, "Numeric"),
    sig("TAN", &[N], 1, REAL, "Numeric"),
    sig("RANDOM", &[N], 1, REAL, "Random"),
    var("AVG", REAL),
    var("MAX", Returns::NumericOfArgs),
    var("MIN", Returns::NumericOfArgs),
    sig("SWITCH", &[N, N, I], 3, Returns::NumericOfArgs, "Selector"),
    sig("EQUAL", &[S, S], 2, BOOL, "String basics"),
    sig("LEN", &[S], 1, INT, "String basics"),
    sig("LEFT", &[S, I], 2, BYTES, "String basics"),
    sig("RIGHT", &[S, I], 2, BYTES, "String basics"),
    sig("MID", &[S, I, I], 3, BYTES, "String basics"),
    sig("CONCAT", &[S, S], 2, Returns::BytesOrWStr, "String basics"),
    sig("INSERT", &[S, S, I], 3, BYTES, "String basics"),
    sig("DELETE", &[S, I, I], 3, BYTES, "String basics"),
    sig("REPLACE", &[S, S, I, I], 4, BYTES, "String basics"),
    sig("FIND", &[S, S, I], 2, INT, "String basics"),
    sig("DELIMIT", &[S, S, I], 3, BYTES, "String basics"),
    sig("JUSTIFY_LEFT", &[S, I], 2, BYTES, "String basics"),
    sig("JUSTIFY_RIGHT", &[S, I], 2, BYTES, "String basics"),
    sig("JUSTIFY_CENTRE", &[S, I], 2, BYTES, "String basics"),
    sig("LTRIM", &[S], 1, BYTES, "String basics"),
    sig("RTRIM", &[S], 1, BYTES, "String basics"),
    sig("TRIM", &[S], 1, BYTES, "String basics"),
    sig("UCASE", &[S], 1, BYTES, "String basics"),
    sig("LCASE", &[S], 1, BYTES, "String basics"),
    sig("STRING", &[I, S], 2, BYTES, "String basics"),
    sig("SPACE", &[I], 1, BYTES, "String basics"),
    sig("STRCOMP", &[S, S], 2, INT, "String basics"),
    sig("PURGE", &[S, S], 2, BYTES, "String basics"),
    sig("DATEANDTIMENOW", &[I], 0, BYTES, "Date and time"),
    sig("EXTRACT_BOOL", &[S, I, I], 3, BOOL, "Extract"),
    sig("EXTRACT_INT8", &[S, I], 2, INT, "Extract"),
    sig("EXTRACT_UINT8", &[S, I], 2, INT, "Extract"),
    sig("EXTRACT_INT16", &[S, I, I], 3, INT, "Extract"),
    sig("EXTRACT_UINT16", &[S, I, I], 3, INT, "Extract"),
    sig("EXTRACT_INT32", &[S, I, I], 3, INT, "Extract"),
    sig("EXTRACT_REAL", &[S, I, I], 3, REAL, "Extract"),
    sig("REPLACE_BOOL", &[S, I, I, B], 4, BYTES, "Replace"),
    sig("REPLACE_INT8", &[S, I, I], 3, BYTES, "Replace"),
    sig("REPLACE_UINT8", &[S, I, I], 3, BYTES, "Replace"),
    sig("REPLACE_INT16", &[S, I, I, I], 4, BYTES, "Replace"),
    sig("REPLACE_UINT16", &[S, I, I, I], 4, BYTES, "Replace"),
    sig("REPLACE_INT32", &[S, I, I, I], 4, BYTES, "Replace"),
    sig("REPLACE_REAL", &[S, I, N, I], 4, BYTES, "Replace"),
    sig("BIT_INVERT", &[I], 1, INT, "Bit"),
    sig("SHL8", &[I, I], 2, INT, "Bit"),
    sig("SHL16", &[I, I], 2, INT, "Bit"),
    sig("SHL32", &[I, I], 2, INT, "Bit"),
    sig("SHR8", &[I, I], 2, INT, "Bit"),
    sig("SHR16", &[I, I], 2, INT, "Bit"),
    sig("SHR32", &[I, I], 2, INT, "Bit"),
    sig("ROL8", &[I, I], 2, INT, "Bit"),
    sig("ROL16", &[I, I], 2, INT, "Bit"),
    sig("ROL32", &[I, I], 2, INT, "Bit"),
    sig("ROR8", &[I, I], 2, INT, "Bit"),
    sig("ROR16", &[I, I], 2, INT, "Bit"),
    sig("ROR32", &[I, I], 2, INT, "Bit"),
    sig("BCC", &[S, I, I], 3, INT, "Checksum"),
    sig("CRC", &[S, I, I, I], 4, INT, "Checksum"),
];

/// Position of a function in [`SIGNATURES`], ignoring case as ST does.
pub fn index_of(name: &str) -> Option<usize> {
    SIGNATURES.iter().position(|s| s.name.eq_ignore_ascii_case(name))
}

/// Finds a function by name, ignoring case as ST does.
pub fn lookup(name: &str) -> Option<&'static Signature> {
    index_of(name).map(|i| &SIGNATURES[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique_and_upper_case() {
        for (i, a) in SIGNATURES.iter().enumerate() {
            assert_eq!(a.name, a.name.to_ascii_uppercase());
            for b in &SIGNATURES[i + 1..] {
                assert_ne!(a.name, b.name);
            }
        }
        // 7 convert, 12 numeric, 1 random, 4 selector, 23 string, 1 date, 7 + 7 extract/replace, 13 bit, 2 checksum.
        assert_eq!(SIGNATURES.len(), 77);
    }

    #[test]
    fn optional_and_variadic_arities() {
        let find = lookup("find").expect("FIND");
        assert!(find.arity_ok(2) && find.arity_ok(3) && !find.arity_ok(4) && !find.arity_ok(1));
        let avg = lookup("AVG").expect("AVG");
        assert!(!avg.arity_ok(1) && avg.arity_ok(2) && avg.arity_ok(9));
        let now = lookup("DateAndTimeNow").expect("DATEANDTIMENOW");
        assert!(now.arity_ok(0) && now.arity_ok(1) && !now.arity_ok(2));
    }

    #[test]
    fn signature_display_names_optional_parameters() {
        assert_eq!(lookup("FIND").map(|s| s.to_string()).as_deref(), Some("FIND(BSEQ, BSEQ, [INT]) : INT"));
        assert_eq!(lookup("MAX").map(|s| s.to_string()).as_deref(), Some("MAX(ANY_NUM, ANY_NUM, ...) : ANY_NUM"));
    }

    #[test]
    fn result_types_follow_arguments() {
        let concat = lookup("CONCAT").expect("CONCAT");
        assert_eq!(concat.result(&[Ty::Text, Ty::WStr], None), Ty::WStr);
        assert_eq!(concat.result(&[Ty::Text, Ty::Bytes], None), Ty::Bytes);
        let scan = lookup("SCAN").expect("SCAN");
        assert_eq!(scan.result(&[Ty::Text, Ty::Bytes], Some(b"6.2F")), Ty::Real);
        assert_eq!(scan.result(&[Ty::Text, Ty::Bytes], Some(b"04X")), Ty::Int);
        let max = lookup("MAX").expect("MAX");
        assert_eq!(max.result(&[Ty::Int, Ty::Real, Ty::Int], None), Ty::Real);
        assert_eq!(max.result(&[Ty::Int, Ty::Int], None), Ty::Int);
    }
}

//! Static types of ST values as the checker sees them.

use std::fmt;

/// The type of an ST expression.
///
/// LIN ST has no declarations: every type comes from a database field, a
/// constant or a function result. `Text` is the STRING family (STRING, DATE,
/// TIME and ENUM fields, and string constants) whose `$`-sequences are kept
/// as written; `Bytes` and `WStr` are byte sequences and wide strings, whose
/// contents are already decoded. `Any` stands for "unknown" so that one error
/// does not cascade into many.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Ty {
    Bool,
    Int,
    Real,
    Text,
    Bytes,
    WStr,
    Any,
}

impl Ty {
    /// Numbers and booleans mix freely in LIN arithmetic (a boolean is 0 or 1).
    pub fn is_numeric(self) -> bool {
        matches!(self, Ty::Bool | Ty::Int | Ty::Real | Ty::Any)
    }

    /// Anything a string function accepts as a byte sequence.
    pub fn is_stringy(self) -> bool {
        matches!(self, Ty::Text | Ty::Bytes | Ty::WStr | Ty::Any)
    }

    /// Integer-valued (for MOD, bit functions and offsets).
    pub fn is_integral(self) -> bool {
        matches!(self, Ty::Bool | Ty::Int | Ty::Any)
    }

    /// The name an engineer reads in a diagnostic.
    pub fn name(self) -> &'static str {
        match self {
            Ty::Bool => "BOOL",
            Ty::Int => "INT",
            Ty::Real => "REAL",
            Ty::Text => "STRING",
            Ty::Bytes => "BSEQ",
            Ty::WStr => "WSTR",
            Ty::Any => "any",
        }
    }
}

impl fmt::Display for Ty {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

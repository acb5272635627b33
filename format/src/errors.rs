//! Why an object file was refused, as plain data (the loader's error: it
//! belongs to the format, which the compiler shares).

use crate::code::Code;
use std::fmt;

/// Why an object file was refused. Each has a code with an explanation page.
#[derive(Clone, Debug, PartialEq)]
pub enum LoadError {
    BadMagic,
    BadVersion {
        found: u16,
        supported: u16,
    },
    BadChecksum {
        stored: u32,
        actual: u32,
    },
    Truncated {
        what: String,
    },
    Malformed {
        what: String,
    },
    /// An opcode that does not exist or an instruction cut short, at byte
    /// `at` of the file.
    BadInstruction {
        at: usize,
        opcode: u8,
    },
    /// A verifier finding: `what` says which rule, at instruction `op`.
    Invalid {
        code: Code,
        action: String,
        op: usize,
        what: String,
    },
    /// A symbol the database does not have, or has with another type.
    Link {
        symbol: String,
        why: String,
    },
}

impl LoadError {
    pub fn code(&self) -> Code {
        match self {
            LoadError::BadMagic => Code::E0700,
            LoadError::BadVersion { .. } => Code::E0701,
            LoadError::BadChecksum { .. } => Code::E0702,
            LoadError::Truncated { .. } | LoadError::Malformed { .. } => Code::E0703,
            LoadError::BadInstruction { .. } => Code::E0704,
            LoadError::Invalid { code, .. } => *code,
            LoadError::Link { .. } => Code::E0709,
        }
    }
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            LoadError::BadMagic => write!(f, "not a linc object file (wrong magic number)"),
            LoadError::BadVersion { found, supported } => {
                write!(f, "object format version {found} is not supported (this linc reads version {supported})")
            }
            LoadError::BadChecksum { stored, actual } => {
                write!(f, "checksum mismatch: the file says {stored:#010x}, its contents give {actual:#010x}; the file is damaged")
            }
            LoadError::Truncated { what } => {
                write!(f, "the object file is truncated in its {what}")
            }
            LoadError::Malformed { what } => write!(f, "malformed object file: {what}"),
            LoadError::BadInstruction { at, opcode } => {
                write!(f, "unknown or incomplete instruction {opcode:#04x} at byte {at} of the file")
            }
            LoadError::Invalid { action, op, what, .. } => write!(f, "`{action}`, instruction {op}: {what}"),
            LoadError::Link { symbol, why } => write!(f, "can't link `{symbol}`: {why}"),
        }
    }
}

impl std::error::Error for LoadError {}

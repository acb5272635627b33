//! Errors of loading an object and of running it, as plain data.

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
        code: &'static str,
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
    pub fn code(&self) -> &'static str {
        match self {
            LoadError::BadMagic => "E0700",
            LoadError::BadVersion { .. } => "E0701",
            LoadError::BadChecksum { .. } => "E0702",
            LoadError::Truncated { .. } | LoadError::Malformed { .. } => "E0703",
            LoadError::BadInstruction { .. } => "E0704",
            LoadError::Invalid { code, .. } => code,
            LoadError::Link { .. } => "E0709",
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

/// A fault while running an action. Runtime faults are values: the action
/// stops at the failing statement and writes made before it stay.
#[derive(Clone, Debug, PartialEq)]
pub struct RuntimeError {
    pub code: &'static str,
    pub message: String,
    pub action: String,
    pub file: String,
    pub line: u32,
    pub col: u32,
}

impl fmt::Display for RuntimeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}: {}: in `{}`: {}", self.file, self.line, self.col, self.code, self.action, self.message)
    }
}

impl std::error::Error for RuntimeError {}

impl RuntimeError {
    /// A fault that belongs to no source position (a program that can't start).
    pub fn unlocated(f: Fault) -> RuntimeError {
        RuntimeError { code: f.code, message: f.message, action: String::new(), file: String::new(), line: 0, col: 0 }
    }
}

/// A fault before it is located: the VM adds action, file and position.
#[derive(Clone, Debug, PartialEq)]
pub struct Fault {
    pub code: &'static str,
    pub message: String,
}

impl Fault {
    pub fn new(code: &'static str, message: impl Into<String>) -> Fault {
        Fault { code, message: message.into() }
    }
}

//! Errors of loading an object and of running it, as plain data.

use linc_format::Code;
use std::fmt;

pub use linc_format::errors::LoadError;

/// A fault while running an action. Runtime faults are values: the action
/// stops at the failing statement and writes made before it stay.
#[derive(Clone, Debug, PartialEq)]
pub struct RuntimeError {
    pub code: Code,
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
    pub code: Code,
    pub message: String,
}

impl Fault {
    pub fn new(code: Code, message: impl Into<String>) -> Fault {
        Fault { code, message: message.into() }
    }
}

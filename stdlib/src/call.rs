//! Calling library functions at run time.
//!
//! The runtime passes arguments already converted to the parameter kinds of
//! the function's [`crate::Signature`] (INT parameters get `Value::Int`,
//! byte-sequence parameters get `Value::Bytes` with `$`-sequences decoded,
//! ANY_NUM parameters keep INT or REAL). Functions are pure except for the
//! environment: the random generator and the clock.

use crate::Value;

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

//! The LIN Structured Text function library.
//!
//! This crate owns what the compiler and the runtime must agree on: the
//! static types of checked expressions ([`Ty`]), the signature of every
//! function in the guide's function table ([`signatures`]), run-time values
//! ([`Value`]) and the implementations the runtime calls ([`call`]).

/// Calling a function of the library on run-time values.
pub mod call;
/// The functions' implementations, by family (strings, numbers, bits, dates …).
pub mod functions;
/// Every function's signature: what the checker types calls against.
pub mod signatures;
/// The static types of checked expressions.
pub mod types;
/// Run-time values and their conversions.
pub mod value;

pub use call::{call, power, Env, FnError};
pub use signatures::{lookup, Param, Returns, Signature, SIGNATURES};
pub use types::Ty;
pub use value::Value;

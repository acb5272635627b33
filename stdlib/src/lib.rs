//! The LIN Structured Text function library.
//!
//! This crate owns what the compiler and the runtime must agree on: the
//! static types of checked expressions ([`Ty`]), the signature of every
//! function in the guide's function table ([`signatures`]), run-time values
//! ([`Value`]) and the implementations the runtime calls ([`call`]).

pub mod call;
pub mod functions;
pub mod signatures;
pub mod types;
pub mod value;

pub use call::{call, power, Env, FnError};
pub use signatures::{lookup, Param, Returns, Signature, SIGNATURES};
pub use types::Ty;
pub use value::Value;

//! The LIN Structured Text function library.
//!
//! This crate owns two things the rest of the toolchain must agree on: the
//! static types a checked expression can have ([`Ty`]) and the signature of
//! every function in the guide's function table ([`signatures`]). The
//! compiler checks calls against these signatures; the runtime (later) calls
//! the implementations that live beside them.

pub mod signatures;
pub mod types;

pub use signatures::{lookup, Param, Returns, Signature, SIGNATURES};
pub use types::Ty;

//! The linc runtime: the function-block database, the instruction set, the
//! `.sto` object format with its verifier and linker, and the VM that runs
//! compiled programs against a live database.
//!
//! Lifecycle, in the types (ADR 0005): bytes → [`ObjectFile::from_bytes`]
//! (framing, checksum) → [`verify::verify`] → [`Verified`] →
//! [`Verified::link`] to a [`Store`] → [`Linked`] → [`vm::Vm::run`] of an
//! [`vm::Activation`] that the caller owns. [`load`] does the first two.

pub mod console;
pub use linc_format::{db, isa, object, records, text, wire};
pub mod errors;
pub mod jit;
pub mod link;
pub mod roc;
pub mod scenario;
pub mod sequence;
pub mod store;
pub mod strategy;
pub mod verify;
mod verify_chart;
pub mod vm;

pub use db::{Database, DbError, FieldDef, FieldType, Template};
pub use errors::{LoadError, RuntimeError};
pub use linc_format::Code;
pub use link::{Linked, Program};
pub use object::ObjectFile;
pub use store::Store;
pub use verify::Verified;
pub use verify_chart::MAX_CHART_DEPTH;

/// Decodes and verifies an object file.
pub fn load(bytes: &[u8]) -> Result<Verified, LoadError> {
    verify::verify(ObjectFile::from_bytes(bytes)?)
}

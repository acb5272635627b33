//! The linc runtime: the verifier and linker of `.sto` objects, the live
//! store of a database, the VM that runs programs against it (with its
//! compiling tier, feature `jit`) and the ROC device state FST programs
//! use. The engines that schedule programs (strategies, sequences, FST
//! tables, the console, scenarios) are `linc-engines`, above this crate;
//! the format both read is `linc-format`, beneath it (ADR 0013).
//!
//! Lifecycle, in the types (ADR 0005): bytes → [`ObjectFile::from_bytes`]
//! (framing, checksum) → [`verify::verify`] → [`Verified`] →
//! [`Verified::link`] to a [`Store`] → [`Linked`] → [`vm::Vm::run`] of an
//! [`vm::Activation`] that the caller owns. [`load`] does the first two.

pub use linc_format::{db, isa, object, records, text, wire};
/// Coverage counts of a run (ADR 0020).
pub mod cover;
/// Load errors and runtime faults, as data.
pub mod errors;
/// The compiling tier (Cranelift, feature `jit`; ADR 0011).
pub mod jit;
/// Linking a verified object to a store: [`Linked`].
pub mod link;
/// The ROC device's state FST tables use: logs, history archives, its clock.
pub mod roc;
/// The live store of a database's values.
pub mod store;
/// The verifier: [`Verified`] objects only.
pub mod verify;
mod verify_chart;
/// The VM that runs an activation of linked code.
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

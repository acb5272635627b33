//! The linc runtime: the function-block database, the instruction set, the
//! `.sto` object format with its verifier, and the VM that runs compiled
//! actions against a live database.
//!
//! Lifecycle: bytes → [`ObjectFile::from_bytes`] (framing, checksum) →
//! [`load`] (verified) → [`prepare`] (linked to a [`Store`]) → [`vm::Vm::run`].

pub mod db;
pub mod errors;
pub mod isa;
pub mod object;
pub mod store;
pub mod text;
pub mod verify;
pub mod vm;

pub use db::{Database, DbError, FieldDef, FieldType, Template};
pub use errors::{LoadError, RuntimeError};
pub use object::ObjectFile;
pub use store::Store;

/// Decodes and verifies an object file.
pub fn load(bytes: &[u8]) -> Result<ObjectFile, LoadError> {
    let obj = ObjectFile::from_bytes(bytes)?;
    for a in &obj.actions {
        verify::verify_action(&obj, a)?;
    }
    Ok(obj)
}

/// Links action `index` of a verified object to a store, ready to run.
/// `own` is the block that runs an `ACTION name : TYPE` action.
pub fn prepare<'a>(
    obj: &'a ObjectFile,
    index: usize,
    store: &Store,
    own: Option<usize>,
) -> Result<vm::Loaded<'a>, LoadError> {
    let action = obj.actions.get(index).ok_or_else(|| LoadError::Malformed { what: format!("no action {index}") })?;
    let limits = verify::verify_action(obj, action)?;
    let targets = verify::link_action(obj, action, store, own)?;
    Ok(vm::Loaded { obj, action, targets, limits })
}

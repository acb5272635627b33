//! The engines that run programs (ADR 0013): the strategy scheduler with
//! its tasks, qualifiers, error status and retentive state, the sequence
//! engine, the FST engine, the console and scenario tests. They drive the
//! runtime's VM over its store scan by scan; the VM, the verifier and the
//! linker know nothing of them.

pub mod console;
pub mod scenario;
pub mod sequence;
pub mod strategy;

// The runtime's modules under their own names, so that the engines read
// `crate::vm`, `crate::store` … as they did inside the runtime.
#[cfg(test)]
pub(crate) use linc_runtime::Database;
pub(crate) use linc_runtime::{db, errors, isa, link, object, roc, store, verify, vm};
pub(crate) use linc_runtime::{Linked, Program, RuntimeError};

//! The engines that run programs (ADR 0013): the strategy scheduler with
//! its tasks, qualifiers, error status and retentive state, the sequence
//! engine, the FST engine, the console and scenario tests. They drive the
//! runtime's VM over its store scan by scan; the VM, the verifier and the
//! linker know nothing of them.

/// The console: a PLC kernel's command interpreter over a strategy.
pub mod console;
/// Scenario tests: console commands and expectations on simulated time.
pub mod scenario;
/// The sequence engine: SFC charts scan by scan.
pub mod sequence;
/// The strategy scheduler: tasks, qualifiers, error status, retentive state, FST tables.
pub mod strategy;

// The runtime's modules under their own names, so that the engines read
// `crate::vm`, `crate::store` … as they did inside the runtime.
#[cfg(test)]
pub(crate) use linc_runtime::Database;
pub(crate) use linc_runtime::{db, errors, isa, link, object, roc, store, verify, vm};
pub(crate) use linc_runtime::{Linked, Program, RuntimeError};

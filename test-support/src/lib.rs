//! What linc's test suites share, written once: a counting allocator for
//! the tests that prove a hot loop allocates nothing or that memory stays
//! in proportion to the input, the processor time work takes (for tests of
//! linear growth that a busy machine can't decide), deterministic random
//! numbers for generated cases (a failing case is reproducible from its
//! seed), and scratch directories. It depends on no linc crate, so every crate can use it as a
//! dev-dependency.

pub mod alloc;
pub mod rng;
pub mod scratch;
pub mod work;

pub use rng::Rng;
pub use scratch::{fresh_dir, temp_dir};

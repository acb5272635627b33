//! What linc's test suites share, written once: a counting allocator for
//! the tests that prove a hot loop allocates nothing or that memory stays
//! in proportion to the input, deterministic random numbers for generated
//! cases (a failing case is reproducible from its seed), and scratch
//! directories. It depends on no linc crate, so every crate can use it as a
//! dev-dependency.

pub mod alloc;
pub mod rng;

pub use rng::Rng;

/// The directory `tag` of this process's tests, made if missing; a test
/// may ask for it again and find its files.
pub fn temp_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("linc-test-{}-{tag}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// [`temp_dir`], emptied first: a fresh directory for one test.
pub fn fresh_dir(tag: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("linc-test-{}-{tag}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    temp_dir(tag)
}

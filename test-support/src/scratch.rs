//! Scratch directories that do not outlive the test process.
//!
//! Every directory lives under one root per process, `linc-test-PID`, which
//! is removed when the process exits (an `atexit` handler: the test harness
//! leaves through `exit` whether the tests passed or not). Before this, each
//! suite run left its directories behind, and a machine that runs the suite
//! many times filled its temporary directory — CI runs on such a machine.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

static ROOT: OnceLock<PathBuf> = OnceLock::new();

extern "C" {
    /// The C library's exit hook; std links the C library on every target
    /// linc's tests run on.
    fn atexit(callback: extern "C" fn()) -> std::os::raw::c_int;
}

extern "C" fn remove_root() {
    if let Some(root) = ROOT.get() {
        let _ = std::fs::remove_dir_all(root);
    }
}

/// This process's scratch root, made (and its removal at exit arranged) on
/// first use.
pub fn root() -> &'static Path {
    ROOT.get_or_init(|| {
        let root = std::env::temp_dir().join(format!("linc-test-{}", std::process::id()));
        std::fs::create_dir_all(&root).expect("scratch root");
        // SAFETY: `remove_root` is a plain function that touches only a
        // static already set when it can run; registering it has no other
        // precondition.
        unsafe {
            atexit(remove_root);
        }
        root
    })
}

/// The directory `tag` of this process's tests, made if missing; a test
/// may ask for it again and find its files.
pub fn temp_dir(tag: &str) -> PathBuf {
    let dir = root().join(tag);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    dir
}

/// [`temp_dir`], emptied first: a fresh directory for one test.
pub fn fresh_dir(tag: &str) -> PathBuf {
    let _ = std::fs::remove_dir_all(root().join(tag));
    temp_dir(tag)
}

//! The long chart of the timing test and the benchmark.

use std::fmt::Write;

/// A chain of `n` steps with a loop back to the start.
pub fn long_chart(n: usize) -> String {
    let mut src = String::from("INITIAL_STEP S0: END_STEP\n");
    for i in 1..n {
        let _ = writeln!(src, "STEP S{i}: A{i}(N); END_STEP");
    }
    for i in 0..n {
        let _ = writeln!(src, "TRANSITION FROM S{i} TO S{} := S{i}.T > 1.0; END_TRANSITION", (i + 1) % n);
    }
    for i in 1..n {
        let _ = writeln!(src, "ACTION A{i}\n    X.Y := {i};\nEND_ACTION");
    }
    src
}

//! `linc eval EXPR`: evaluate one expression and print its value.

use linc_driver::Reporter;
use std::path::Path;

pub fn run(expr: &str, db: Option<&Path>, now: Option<&str>, seed: Option<u64>, r: &mut Reporter) -> u8 {
    match linc_driver::eval::evaluate(expr, db, now, seed, r) {
        Ok(v) => {
            crate::out::line(&linc_runtime::text::format_value(&v));
            0
        }
        Err(status) => status,
    }
}

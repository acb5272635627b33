//! `linc eval EXPR`: evaluate one expression and print its value.

use crate::report::Reporter;
use std::path::Path;

pub fn run(expr: &str, db: Option<&Path>, now: Option<i64>, seed: Option<u64>, r: &Reporter) -> u8 {
    match linc_driver::eval::evaluate(expr, db, now, seed) {
        Ok((v, warnings)) => {
            let status = r.report(&warnings);
            crate::out::line(&linc_driver::eval::text(&v));
            status
        }
        Err(p) => r.report(&p),
    }
}

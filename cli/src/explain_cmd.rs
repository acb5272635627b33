//! `linc explain CODE`: print a code's explanation page.

use crate::report::{usage, Reporter};
use linc_compiler::diag::codes::{lookup, CODES};
use linc_compiler::diag::escape;

pub fn run(code: Option<&str>, list: bool, r: &Reporter) -> u8 {
    match code {
        Some(c) if !list => match lookup(c) {
            Some(entry) => {
                crate::out::print(entry.explanation());
                if !entry.explanation().ends_with('\n') {
                    crate::out::line("");
                }
                0
            }
            None => usage(r, format!("`{}` is not a linc diagnostic code (see `linc explain --list`)", escape(c))),
        },
        _ => {
            for c in CODES {
                crate::out::line(&format!("{}  {}", c, c.title()));
            }
            0
        }
    }
}

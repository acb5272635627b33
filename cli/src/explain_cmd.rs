//! `linc explain CODE`: print a code's explanation page.

use linc_compiler::diag::codes::{lookup, CODES};
use linc_compiler::diag::render;

pub fn run(code: Option<&str>, list: bool, r: &mut linc_driver::Reporter) -> u8 {
    match code {
        Some(c) if !list => match lookup(c) {
            Some(entry) => {
                crate::out::print(entry.explanation());
                if !entry.explanation().ends_with('\n') {
                    crate::out::line("");
                }
                0
            }
            None => crate::report::usage(
                r,
                format_args!("`{}` is not a linc diagnostic code (see `linc explain --list`)", render::escape(c)),
            ),
        },
        _ => {
            for c in CODES {
                crate::out::line(&format!("{}  {}", c, c.title()));
            }
            0
        }
    }
}

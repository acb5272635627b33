//! `linc check`: the driver checks; this prints trees and resources and
//! renders the diagnostics, with a count of them in the `human` format.

use crate::report::Reporter;
use linc_compiler::diag::Format;
use linc_driver::check::{CheckRequest, Shown};
use linc_format::Code;

pub fn run(req: &CheckRequest, r: &Reporter) -> u8 {
    let checked = match linc_driver::check::check(req) {
        Ok(c) => c,
        Err(p) => return r.report(&p),
    };
    for shown in &checked.shown {
        match shown {
            Shown::Tree(t) => crate::out::print(t),
            Shown::Resources(used) => crate::sfc_cmd::print_resources(used, r.format()),
        }
    }
    let status = r.report(&checked.problems);
    let (errors, warnings) = (checked.errors, checked.warnings);
    if r.format() == Format::Human && (errors > 0 || warnings > 0) {
        r.note(Code::I0001, format!("linc: {errors} error{}, {warnings} warning{}", plural(errors), plural(warnings)));
    }
    status
}

fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

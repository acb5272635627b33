//! `linc disasm OUT.sto`: the driver's listing of an object file, written
//! to standard output as it is made.

use crate::report::Reporter;
use std::io::Write;
use std::path::Path;

pub fn run(path: &Path, r: &Reporter) -> u8 {
    match linc_driver::disasm::load(path) {
        Ok(obj) => {
            // A closed pipe (`| head`) ends the listing; nothing to report.
            let mut out = crate::out::Stream::new();
            let _ = linc_driver::disasm::listing(obj.object(), &mut out).and_then(|()| out.flush());
            0
        }
        Err(p) => r.report(&p),
    }
}

//! `linc compile FILE... -o OUT.sto`: the driver compiles and writes.

use crate::report::Reporter;
use std::path::{Path, PathBuf};

pub fn run(files: &[PathBuf], out: &Path, db: Option<&Path>, map: Option<&Path>, r: &Reporter) -> u8 {
    r.done(linc_driver::build::compile_to(files, out, db, map))
}

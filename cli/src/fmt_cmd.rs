//! `linc fmt [FILE|DIR…] [--check]`.

use crate::out;
use crate::report::{usage, Reporter};
use linc_compiler::diag::Problems;
use std::path::{Path, PathBuf};

/// Formats the files in place, or with `check` lists those that would
/// change. Exit status: 0 all formatted; 1 a file would change (`--check`)
/// or does not parse; 2 a file could not be read or written.
pub fn run(files: &[PathBuf], check: bool, r: &Reporter) -> u8 {
    let targets = linc_driver::fmt::targets(files, Path::new("."));
    if targets.is_empty() && files.is_empty() {
        return usage(r, "name the files to format: no strategy database in this directory names a file");
    }
    let mut status = 0u8;
    for path in &targets {
        match linc_driver::fmt::format_file(path) {
            Ok(None) => {}
            Ok(Some(_)) if check => {
                out::line(&path.display().to_string());
                status = status.max(1);
            }
            Ok(Some(f)) => {
                let (before, after) = (f.original.as_bytes(), f.formatted.as_bytes());
                if let Err(e) = linc_driver::files::replace_input(path, before, after) {
                    status = status.max(r.report(&Problems::from(e)));
                }
            }
            Err(p) => status = status.max(r.report(&p)),
        }
    }
    status
}

//! Turning source files into an object: shared by `compile`, `run` and `eval`.

use crate::check_cmd::io_error;
use linc_compiler::check::Context;
use linc_compiler::lower::{self, Lines, Unit};
use linc_compiler::render::{self, Format, SourceFiles};
use linc_compiler::{hir, Diagnostic};
use linc_runtime::{Database, ObjectFile};
use std::path::PathBuf;

/// Why a build failed (everything already printed); carries the exit status.
pub struct Failed(pub u8);

/// Checks and lowers `paths` into one object. Diagnostics are printed; any
/// error gives `Failed(errors_status)` (or 2 for I/O problems).
pub fn compile(
    paths: &[PathBuf],
    db: Option<&Database>,
    format: Format,
    errors_status: u8,
) -> Result<ObjectFile, Failed> {
    let builtin;
    let (db, resolve_blocks) = match db {
        Some(d) => (d, true),
        None => {
            builtin = Database::builtin();
            (&builtin, false)
        }
    };
    let ctx = Context { db, resolve_blocks, steps: None };
    let mut files = SourceFiles::new();
    let mut checked: Vec<(usize, hir::Program, String, Lines)> = Vec::new();
    let mut failed = false;
    for path in paths {
        let text = crate::files::read_input_text(path).map_err(|e| {
            io_error(path, &e, format);
            Failed(2)
        })?;
        let name = path.display().to_string();
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("action").to_string();
        let lines = Lines::new(&text);
        let report = linc_compiler::check_source(&text, &stem, ctx);
        let id = files.add(name.clone(), text);
        for d in &report.diagnostics {
            print!("{}", render::render(&files, id, d, format));
        }
        match report.program {
            Some(p) if !report.has_errors() => checked.push((id, p, name, lines)),
            _ => failed = true,
        }
    }
    if failed {
        return Err(Failed(errors_status));
    }
    // Action names are unique across the object (§10.2.1).
    let mut seen: Vec<(String, usize, linc_compiler::Span)> = Vec::new();
    for (id, p, _, _) in &checked {
        for a in &p.actions {
            if let Some((_, fid, _)) = seen.iter().find(|(n, _, _)| n.eq_ignore_ascii_case(&a.name)) {
                let d = Diagnostic::error("E0117", format!("action `{}` is defined twice", a.name), a.span.to(a.span))
                    .label(format!(
                        "also defined in {}",
                        files.get(*fid).map(|f| f.name().clone()).unwrap_or_default()
                    ));
                print!("{}", render::render(&files, *id, &d, format));
                failed = true;
            }
            seen.push((a.name.clone(), *id, a.span));
        }
    }
    if failed {
        return Err(Failed(errors_status));
    }
    let units: Vec<Unit> = checked.iter().map(|(_, p, name, lines)| Unit { program: p, file: name, lines }).collect();
    lower::lower_units(&units).map_err(|errors| {
        // Lowering errors belong to the file whose action failed; with one
        // unit that is exact, with several the first file is named.
        let id = checked.first().map(|c| c.0).unwrap_or(0);
        for e in errors {
            print!("{}", render::render(&files, id, &e.to_diagnostic(), format));
        }
        Failed(errors_status)
    })
}

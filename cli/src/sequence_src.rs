//! `.sfc` files on the command line: read, checked (and lowered) by the
//! compiler's sequence front end, diagnostics printed through the renderer.

use linc_compiler::diag::render::SourceFiles;
use linc_compiler::sfc;
use linc_compiler::sfc::{resources, resources::Instrument};
use linc_compiler::Context;
use linc_driver::Reporter;
use linc_runtime::ObjectFile;
use std::path::Path;

/// What checking one `.sfc` file gave.
pub struct Checked {
    pub errors: usize,
    pub warnings: usize,
    pub object: Option<ObjectFile>,
}

/// What a sequence is checked with beyond its database.
#[derive(Default)]
pub struct Extra<'a> {
    /// The map when `ctx.db` holds its aliases: unknown names are then
    /// generic names the map lacks (E0250).
    pub map: Option<&'a crate::sfc_cmd::Bound>,
    /// Unmapped generic names are warnings (W0250).
    pub allow_unmapped: bool,
    /// Print the resources used against this instrument's limits.
    pub resources: Option<Instrument>,
}

/// Reads, checks and (when `lower`) compiles one sequence, with a map and
/// resources; reports its diagnostics (and prints its tree when `tree`).
/// `Err` is an I/O failure, reported.
pub fn check_with(
    path: &Path,
    ctx: Context,
    extra: &Extra,
    (lower, tree): (bool, bool),
    r: &mut Reporter,
) -> Result<Checked, ()> {
    let bytes = linc_driver::files::read_input(path).map_err(|e| r.unreadable(path, &e))?;
    let name = path.display().to_string();
    let (text, invalid) = linc_compiler::diag::files::decode(bytes);
    let mut files = SourceFiles::new();
    let id = files.add_decoded(name.clone(), text.clone(), invalid.clone());
    let mut diagnostics = Vec::new();
    diagnostics.extend(linc_compiler::session::SessionError::not_utf8(&invalid).map(|e| e.to_diagnostic()));
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("sequence");
    let (more, object) = if lower && invalid.is_empty() {
        match extra.map {
            Some(b) => sfc::compile_generic(&text, (stem, &name), ctx, &b.map),
            None => sfc::compile_sequence(&text, stem, &name, ctx),
        }
    } else {
        let report = match extra.map {
            Some(b) => sfc::check_generic(&text, ctx, &b.map, extra.allow_unmapped),
            None => sfc::check_sequence(&text, ctx),
        };
        let mut d = report.diagnostics;
        if let Some(t) = &report.tree {
            if tree {
                crate::out::print(&sfc::pretty::sequence(t));
            }
            if let Some(i) = extra.resources {
                let uses = resources::count(t, i);
                crate::sfc_cmd::print_resources(&name, &uses, i.name(), r.format());
                d.extend(resources::over_limit(&uses, i));
            }
        }
        (d, None)
    };
    diagnostics.extend(more);
    let errors = diagnostics.iter().filter(|d| d.is_error()).count();
    for d in &diagnostics {
        r.emit(&files, &d.clone().in_file(id));
    }
    Ok(Checked { errors, warnings: diagnostics.len() - errors, object })
}

//! Sequences on the command line: a `.sfc` file checked (and lowered) by
//! the compiler's sequence front end with a map of generic names and its
//! resources (`linc check`, `linc compile --map`), and generic sequences
//! (guide §9.1) — `specialise` and `generalise` through a map file,
//! `map-template` listing generic names. The rewriting is the compiler's
//! (`linc_compiler::sfc::generic`); this reads and writes the files.

use linc_compiler::diag::{Diagnostic, Problems, SourceFiles};
use linc_compiler::sfc::generic::{self, Map};
use linc_compiler::sfc::{self, resources, resources::Instrument};
use linc_compiler::Context;
use linc_runtime::{Database, ObjectFile};
use std::path::Path;

/// A map bound to a database: the database with the map's aliases, the map
/// file's name for messages, and the map file's errors.
pub struct Bound {
    pub db: Database,
    pub map: generic::Named,
    pub problems: Problems,
}

/// Reads `path` as a map and binds it to `db`; its errors are found in it
/// (an unreadable map is a refused request).
pub fn load_map(path: &Path, db: &Database, resolve_blocks: bool) -> Result<Bound, Problems> {
    let (map, text, errors) = read_map(path)?;
    let (bound, more) = generic::bind(&map, db, resolve_blocks);
    let file = path.display().to_string();
    let mut files = SourceFiles::new();
    let id = files.add(file.clone(), text);
    let all: Vec<Diagnostic> = errors.iter().chain(&more).map(|e| e.to_diagnostic().in_file(id)).collect();
    Ok(Bound { db: bound, map: generic::Named { map, file }, problems: Problems::of(files, all) })
}

fn read_map(path: &Path) -> Result<(Map, String, Vec<generic::MapError>), Problems> {
    let text = crate::files::read_input_text(path).map_err(|e| Problems::unreadable(path, &e))?;
    let (map, errors) = generic::parse_map(&text);
    Ok((map, text, errors))
}

/// What a sequence is checked with beyond its database.
#[derive(Default)]
pub struct Extra<'a> {
    /// The map when `ctx.db` holds its aliases: unknown names are then
    /// generic names the map lacks (E0250).
    pub map: Option<&'a Bound>,
    /// Unmapped generic names are warnings (W0250).
    pub allow_unmapped: bool,
    /// Count the resources used against this instrument's limits.
    pub resources: Option<Instrument>,
    /// Keep the tree, printed (`--tree`).
    pub tree: bool,
    /// Lower it to an object.
    pub lower: bool,
}

/// What checking one `.sfc` file gave.
pub struct Sequence {
    pub problems: Problems,
    pub object: Option<ObjectFile>,
    /// The tree printed, when asked for.
    pub tree: Option<String>,
    /// The resources used, when asked for.
    pub resources: Option<Resources>,
}

/// What a sequence uses, against one instrument's limits (`--resources`).
pub struct Resources {
    pub file: String,
    pub instrument: &'static str,
    pub uses: Vec<resources::Use>,
}

/// Reads, checks and (when `extra.lower`) compiles one sequence, with a map
/// and resources. An unreadable file is a refused request.
pub fn check(path: &Path, ctx: Context, extra: &Extra) -> Result<Sequence, Problems> {
    let bytes = crate::files::read_input(path).map_err(|e| Problems::unreadable(path, &e))?;
    let name = path.display().to_string();
    let (text, invalid) = linc_compiler::diag::decode(bytes);
    let mut files = SourceFiles::new();
    let id = files.add_decoded(name.clone(), text.clone(), invalid.clone());
    let mut diagnostics = Vec::new();
    diagnostics.extend(linc_compiler::session::SessionError::not_utf8(&invalid).map(|e| e.to_diagnostic()));
    let stem = crate::source::stem(path, "sequence");
    let (mut tree, mut used) = (None, None);
    let (more, object) = if extra.lower && invalid.is_empty() {
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
            if extra.tree {
                tree = Some(sfc::pretty::sequence(t));
            }
            if let Some(i) = extra.resources {
                let uses = resources::count(t, i);
                d.extend(resources::over_limit(&uses, i));
                used = Some(Resources { file: name.clone(), instrument: i.name(), uses });
            }
        }
        (d, None)
    };
    diagnostics.extend(more);
    let problems = Problems::of(files, diagnostics.into_iter().map(|d| d.in_file(id)).collect());
    Ok(Sequence { problems, object, tree, resources: used })
}

/// Reads and parses a sequence for rewriting. A sequence that does not
/// parse is not rewritten (its references can't all be found).
fn parse(path: &Path) -> Result<(String, sfc::ast::Sequence), Problems> {
    let text = crate::files::read_input_text(path).map_err(|e| Problems::unreadable(path, &e))?;
    let (seq, diagnostics) = sfc::parser::parse(&text);
    let diagnostics = generic::allow_long_names(diagnostics, &text);
    let errors: Vec<Diagnostic> = diagnostics.into_iter().filter(Diagnostic::is_error).collect();
    if errors.is_empty() {
        return Ok((text, seq));
    }
    let mut files = SourceFiles::new();
    let id = files.add(path.display().to_string(), text);
    Err(Problems::of(files, errors.into_iter().map(|d| d.in_file(id)).collect()))
}

/// Which way a rewrite goes.
#[derive(Clone, Copy)]
pub enum Direction {
    Specialise,
    Generalise,
}

/// `linc sfc specialise|generalise FILE --map MAP -o OUT`.
pub fn rewrite(dir: Direction, file: &Path, map_path: &Path, out: &Path) -> Result<(), Problems> {
    crate::files::check_output(out, &[file, map_path])?;
    let (map, text, errors) = read_map(map_path)?;
    if !errors.is_empty() {
        let mut files = SourceFiles::new();
        let id = files.add(map_path.display().to_string(), text);
        return Err(Problems::of(files, errors.iter().map(|e| e.to_diagnostic().in_file(id)).collect()));
    }
    let (src, seq) = parse(file)?;
    let written = match dir {
        Direction::Specialise => generic::specialise(&src, &seq, &map),
        Direction::Generalise => generic::generalise(&src, &seq, &map),
    };
    Ok(crate::files::write_atomic(out, written.as_bytes())?)
}

/// `linc sfc map-template FILE [--db DB]`: a map with every generic name
/// and an empty target.
pub fn map_template(file: &Path, db: Option<&Path>) -> Result<String, Problems> {
    let db = crate::database::load_opt(db)?.map_or_else(Database::builtin, |d| d.db);
    let (_, seq) = parse(file)?;
    Ok(generic::map_template(&generic::generic_names(&seq, &db)))
}

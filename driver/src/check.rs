//! `linc check`: files checked in one compile session (names shared across
//! the action and ladder files of one run), a sequence with a map or its
//! resources through the sequence front end; what each file printed (its
//! tree, its resources) and every diagnostic returned in file order.

use crate::sfc::{Bound, Extra, Resources};
use linc_compiler::diag::{Diagnostic, Problems};
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_compiler::sfc::resources::Instrument;
use linc_compiler::Context;
use std::path::PathBuf;

/// What to check, and how.
#[derive(Clone, Debug, Default)]
pub struct CheckRequest {
    pub files: Vec<PathBuf>,
    pub db: Option<PathBuf>,
    /// Print the syntax tree of each file.
    pub tree: bool,
    /// Each file is one transition expression.
    pub transition: bool,
    /// Actions are sequence actions, where step variables exist.
    pub sequence: bool,
    /// A map file for generic sequences.
    pub map: Option<PathBuf>,
    pub allow_unmapped: bool,
    /// The resources of each sequence against this instrument's limits.
    pub resources: Option<Instrument>,
}

/// What a file gave for standard output, in file order.
pub enum Shown {
    Tree(String),
    Resources(Resources),
}

/// What checking gave: what to show, the diagnostics (an unreadable file
/// makes them a refused request; the other files are checked all the
/// same), and how many errors and warnings the files had.
pub struct Checked {
    pub shown: Vec<Shown>,
    pub problems: Problems,
    pub errors: usize,
    pub warnings: usize,
}

/// Checks every file. A database that does not load is a refused request
/// and nothing is checked.
pub fn check(req: &CheckRequest) -> Result<Checked, Problems> {
    let db = crate::database::load_opt(req.db.as_deref())?.map(|d| d.db);
    let plain = Context::of(db.as_ref());
    let (db, resolve_blocks) = (plain.db, plain.resolve_blocks);
    let any_step: &[String] = &[];
    let steps = (req.sequence || req.transition).then_some(any_step);
    let mut session = Session::new(Context { steps, ..plain });
    let (mut shown, mut errors, mut warnings) = (Vec::new(), 0, 0);
    // In file order: diagnostics of the session's files, or problems of
    // their own (a map, a sequence, a file that could not be read).
    let mut chunks: Vec<Result<Vec<Diagnostic>, Problems>> = Vec::new();
    let bound: Option<Bound> = match &req.map {
        Some(m) => {
            let mut b = crate::sfc::load_map(m, db, resolve_blocks)?;
            errors += b.problems.errors();
            chunks.push(Err(std::mem::take(&mut b.problems)));
            Some(b)
        }
        None => None,
    };
    let extra = Extra {
        map: bound.as_ref(),
        allow_unmapped: req.allow_unmapped,
        resources: req.resources,
        tree: req.tree,
        lower: false,
    };
    let input = if req.transition { Input::Transition } else { Input::Actions };
    // A sequence checked with a map, its resources or its tree goes through
    // the sequence front end's own options; every other file, whatever its
    // kind, through the session.
    let sequence_options = bound.is_some() || req.allow_unmapped || req.resources.is_some() || req.tree;
    for path in &req.files {
        if sequence_options && crate::source::is_sequence(path) {
            let seq_db = bound.as_ref().map_or(db, |b| &b.db);
            let ctx = Context { db: seq_db, ..plain };
            match crate::sfc::check(path, ctx, &extra) {
                Ok(c) => {
                    shown.extend(c.tree.map(Shown::Tree));
                    shown.extend(c.resources.map(Shown::Resources));
                    errors += c.problems.errors();
                    warnings += c.problems.warnings();
                    chunks.push(Err(c.problems));
                }
                Err(p) => chunks.push(Err(p)),
            }
            continue;
        }
        let bytes = match crate::files::read_input(path) {
            Ok(b) => b,
            Err(e) => {
                chunks.push(Err(Problems::unreadable(path, &e)));
                continue;
            }
        };
        let id = session.add(path.display().to_string(), bytes);
        let checked = session.check(id, CheckOptions { input, tree: req.tree });
        shown.extend(checked.tree.as_ref().map(|t| Shown::Tree(t.pretty())));
        errors += checked.diagnostics.iter().filter(|d| d.is_error()).count();
        warnings += checked.diagnostics.iter().filter(|d| !d.is_error()).count();
        chunks.push(Ok(checked.diagnostics));
    }
    // The session's files first, so its diagnostics' file ids stand; the
    // others' files are moved after them.
    let mut problems = Problems::of(session.into_files(), Vec::new());
    for chunk in chunks {
        match chunk {
            Ok(ds) => ds.into_iter().for_each(|d| problems.push(d)),
            Err(p) => problems.append(p),
        }
    }
    Ok(Checked { shown, problems, errors, warnings })
}

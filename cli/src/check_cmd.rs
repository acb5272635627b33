//! `linc check`: check files in one session, printing diagnostics.

use linc_compiler::diag::render::{Format, SourceFiles};
use linc_compiler::session::{CheckOptions, Input, Session};
use linc_compiler::sfc::resources::Instrument;
use linc_compiler::Context;
use linc_driver::Reporter;
use std::path::PathBuf;

pub struct Options {
    pub files: Vec<PathBuf>,
    pub db: Option<PathBuf>,
    pub tree: bool,
    pub transition: bool,
    pub sequence: bool,
    /// A map file for generic sequences (`.sfc` files only).
    pub map: Option<PathBuf>,
    pub allow_unmapped: bool,
    /// Print each sequence's resources against this instrument's limits.
    pub resources: Option<Instrument>,
}

pub fn run(o: &Options, r: &mut Reporter) -> u8 {
    let mut dbfiles = SourceFiles::new();
    let db = match linc_driver::database::load(o.db.as_deref(), &mut dbfiles, r) {
        Ok(db) => db,
        Err(status) => return status,
    };
    let plain = Context::of(db.as_ref());
    let (db, resolve_blocks) = (plain.db, plain.resolve_blocks);
    let any_step: &[String] = &[];
    let steps = (o.sequence || o.transition).then_some(any_step);
    let mut session = Session::new(Context { steps, ..plain });
    let (mut errors, mut warnings, mut status) = (0usize, 0usize, 0u8);
    let bound = match &o.map {
        Some(m) => match crate::sfc_cmd::load_map(m, db, resolve_blocks, r) {
            Ok(b) => {
                errors += b.errors;
                Some(b)
            }
            Err(status) => return status,
        },
        None => None,
    };
    let extra =
        crate::sequence_src::Extra { map: bound.as_ref(), allow_unmapped: o.allow_unmapped, resources: o.resources };
    let input = if o.transition { Input::Transition } else { Input::Actions };
    // A sequence checked with a map, its resources or its tree goes through
    // the sequence front end's own options; every other file, whatever its
    // kind, through the session.
    let sequence_options = bound.is_some() || o.allow_unmapped || o.resources.is_some() || o.tree;
    for path in &o.files {
        if sequence_options && linc_driver::source::is_sequence(path) {
            let seq_db = bound.as_ref().map_or(db, |b| &b.db);
            let ctx = Context { db: seq_db, resolve_blocks, steps: None };
            match crate::sequence_src::check_with(path, ctx, &extra, (false, o.tree), r) {
                Ok(c) => {
                    errors += c.errors;
                    warnings += c.warnings;
                }
                Err(()) => status = 2,
            }
            continue;
        }
        let bytes = match linc_driver::files::read_input(path) {
            Ok(b) => b,
            Err(e) => {
                r.unreadable(path, &e);
                status = 2;
                continue;
            }
        };
        let id = session.add(path.display().to_string(), bytes);
        let checked = session.check(id, CheckOptions { input, tree: o.tree });
        if let Some(t) = &checked.tree {
            crate::out::print(&t.pretty());
        }
        for d in &checked.diagnostics {
            if d.is_error() {
                errors += 1;
            } else {
                warnings += 1;
            }
            r.emit(session.files(), d);
        }
    }
    if r.format() == Format::Human && (errors > 0 || warnings > 0) {
        eprintln!("linc: {errors} error{}, {warnings} warning{}", plural(errors), plural(warnings));
    }
    if status == 0 && errors > 0 {
        status = 1;
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

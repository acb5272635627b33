//! `linc ladder …`: tools for ladder files (`.ld`, docs/ladder.md).
//!
//! `to-st` prints the ST a ladder file compiles as (ADR 0009): what runs
//! is exactly that ST, so it is the way to review what a rung does.

use clap::Subcommand;
use linc_compiler::diag::render::SourceFiles;
use linc_compiler::ladder;
use linc_compiler::Context;
use linc_driver::database::load as load_db;
use linc_driver::Reporter;
use std::path::{Path, PathBuf};

#[derive(Subcommand)]
pub enum LadderCommand {
    /// Draw each rung as a diagram between the rails.
    Show {
        file: PathBuf,
        /// Run the file's actions first (--db, --set, --cycles) and draw powered elements with `==` wires.
        #[arg(long)]
        values: bool,
        #[arg(long)]
        db: Option<PathBuf>,
        /// Set a field before the run: BLOCK.FIELD=VALUE (repeatable).
        #[arg(long)]
        set: Vec<String>,
        /// Runs of every action before drawing.
        #[arg(long, default_value_t = 1)]
        cycles: u32,
    },
    /// Print the ST a ladder file compiles as (a jump becomes an IF around the rungs it skips).
    ToSt {
        file: PathBuf,
        /// The database that types contacts and coils (without it, names are not checked).
        #[arg(long)]
        db: Option<PathBuf>,
    },
}

pub fn run(command: LadderCommand, r: &mut Reporter) -> u8 {
    match command {
        LadderCommand::Show { file, values, db, set, cycles } => {
            if !values {
                return show(&file, &|_| None, r);
            }
            let Some(db) = db else {
                return crate::report::usage(r, "--values runs the ladder: give --db DB.json");
            };
            match linc_driver::ladder::after_run(&file, &db, &set, cycles, r) {
                Ok(known) => show(&file, &|span| known.get(&(span.start, span.end)).copied(), r),
                Err(status) => status,
            }
        }
        LadderCommand::ToSt { file, db } => to_st(&file, db.as_deref(), r),
    }
}

/// Prints the ST, or the ladder's own errors (exit 1).
fn to_st(file: &Path, db: Option<&Path>, r: &mut Reporter) -> u8 {
    let mut files = SourceFiles::new();
    let loaded = match load_db(db, &mut files, r) {
        Ok(d) => d,
        Err(status) => return status,
    };
    let ctx = Context::of(loaded.as_ref());
    let bytes = match linc_driver::files::read_input(file) {
        Ok(b) => b,
        Err(e) => {
            r.unreadable(file, &e);
            return 2;
        }
    };
    let name = file.display().to_string();
    let (text, invalid) = linc_compiler::diag::files::decode(bytes);
    let id = files.add_decoded(name, text.clone(), invalid.clone());
    if let Some(e) = linc_compiler::session::SessionError::not_utf8(&invalid) {
        r.emit(&files, &e.to_diagnostic().in_file(id));
        return 1;
    }
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("ladder");
    match ladder::to_st(&text, stem, ctx) {
        Ok(st) => {
            crate::out::print(&st);
            0
        }
        Err(diagnostics) => {
            r.emit_all(&files, &diagnostics.into_iter().map(|d| d.in_file(id)).collect::<Vec<_>>());
            1
        }
    }
}

/// Prints the diagram, or the file's syntax errors (exit 1).
fn show(file: &Path, values: ladder::pretty::draw::Values, r: &mut Reporter) -> u8 {
    let bytes = match linc_driver::files::read_input(file) {
        Ok(b) => b,
        Err(e) => {
            r.unreadable(file, &e);
            return 2;
        }
    };
    let (text, _) = linc_compiler::diag::files::decode(bytes);
    let stem = file.file_stem().and_then(|s| s.to_str()).unwrap_or("ladder");
    let mut out = crate::out::Stream::new();
    let drawn = ladder::draw_to(&text, stem, values, &mut |s| out.text(s));
    let _ = std::io::Write::flush(&mut out);
    drop(out);
    match drawn {
        Ok(()) => 0,
        Err(diagnostics) => {
            let mut files = SourceFiles::new();
            let id = files.add(file.display().to_string(), text);
            r.emit_all(&files, &diagnostics.into_iter().map(|d| d.in_file(id)).collect::<Vec<_>>());
            1
        }
    }
}

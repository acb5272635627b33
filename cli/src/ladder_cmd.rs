//! `linc ladder …`: tools for ladder files (`.ld`, docs/ladder.md).
//!
//! `to-st` prints the ST a ladder file compiles as (ADR 0009): what runs
//! is exactly that ST, so it is the way to review what a rung does.

use crate::report::{usage, Reporter};
use clap::Subcommand;
use linc_compiler::diag::Problems;
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

pub fn run(command: LadderCommand, r: &Reporter) -> u8 {
    match command {
        LadderCommand::Show { file, values, db, set, cycles } => {
            if !values {
                return show(&file, (&|_| None, None), Problems::new(), r);
            }
            let Some(db) = db else {
                return usage(r, "--values runs the ladder: give --db DB.json");
            };
            match linc_driver::ladder::after_run(&file, &db, &set, cycles) {
                Ok((after, ran)) => {
                    let values = |span: linc_compiler::diag::Span| after.truths.get(&(span.start, span.end)).copied();
                    show(&file, (&values, after.lines_ran.as_deref()), ran, r)
                }
                Err(p) => r.report(&p),
            }
        }
        LadderCommand::ToSt { file, db } => match linc_driver::ladder::to_st(&file, db.as_deref()) {
            Ok(st) => {
                crate::out::print(&st);
                0
            }
            Err(p) => r.report(&p),
        },
    }
}

/// Prints the diagram after what the run found (`ran`), or the file's
/// syntax errors (exit 1).
fn show(
    file: &Path,
    (values, lines): (linc_driver::ladder::Values, Option<&[u32]>),
    ran: Problems,
    r: &Reporter,
) -> u8 {
    let status = r.report(&ran);
    let mut out = crate::out::Stream::new();
    let drawn = linc_driver::ladder::show(file, values, lines, &mut |s| out.text(s));
    let _ = std::io::Write::flush(&mut out);
    drop(out);
    match drawn {
        Ok(()) => status,
        Err(p) => r.report(&p),
    }
}

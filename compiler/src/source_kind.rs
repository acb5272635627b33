//! What kind of source a file is, decided in one place for every command
//! (`check`, `compile`, `run`, the console, scenarios): action files (ST)
//! and ladder files are checked together, names shared across them; a
//! sequence or an FST table is a unit of its own; an object file is not a
//! source at all. The session ([`crate::session::Session`]) checks and
//! compiles each kind by this.

use crate::diag::Diagnostic;
use crate::st::check::Context;
use linc_format::{Code, ObjectFile};
use std::path::Path;

/// The kind of a source file, by its extension (and an object's magic
/// number, whatever its name).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SourceKind {
    /// Structured Text actions (`.stx`, `.st`, and anything not below).
    Actions,
    /// A ladder file (`.ld`).
    Ladder,
    /// A sequence (`.sfc`).
    Sequence,
    /// An FST table (`.csv`, as ROCLINK 800 exports it).
    FstTable,
    /// A compiled object (by name `.sto`; by contents its magic number).
    Object,
}

impl SourceKind {
    /// The kind a file's name says, before it is read: a command loads a
    /// `.sto` file as an object (the loader refuses one that is not).
    pub fn of_name(name: &str) -> SourceKind {
        let ext = Path::new(name).extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        match ext.as_str() {
            "ld" => SourceKind::Ladder,
            "sfc" => SourceKind::Sequence,
            "csv" => SourceKind::FstTable,
            "sto" => SourceKind::Object,
            _ => SourceKind::Actions,
        }
    }

    /// The kind of a file given to a compile session, by its name and
    /// contents: an object is known by its magic number whatever its name,
    /// and a `.sto` file without it is text like any other (read as ST).
    pub fn of(name: &str, contents: &[u8]) -> SourceKind {
        if contents.starts_with(linc_format::object::MAGIC) {
            return SourceKind::Object;
        }
        match SourceKind::of_name(name) {
            SourceKind::Object => SourceKind::Actions,
            kind => kind,
        }
    }

    /// A sequence or a table is compiled into an object of its own.
    pub fn stands_alone(self) -> bool {
        matches!(self, SourceKind::Sequence | SourceKind::FstTable)
    }
}

/// The stem a unit of its own is named after (`batch.sfc` → `batch`).
fn stem<'n>(name: &'n str, otherwise: &'static str) -> &'n str {
    Path::new(name).file_stem().and_then(|s| s.to_str()).unwrap_or(otherwise)
}

/// The points an FST table is checked against: the database, when the
/// session has one (a table without one is checked for its form only).
fn points<'d>(ctx: &Context<'d>) -> Option<&'d linc_format::Database> {
    ctx.resolve_blocks.then_some(ctx.db)
}

/// Reads a sequence or an FST table by its own front end, once: its
/// diagnostics (unlocated: the caller puts them in the file) and, when
/// `lower` and it is clean, its object (a table only with its points).
pub(crate) fn read_alone(
    kind: SourceKind,
    (name, text): (&str, &str),
    ctx: Context,
    lower: bool,
) -> (Vec<Diagnostic>, Option<ObjectFile>) {
    let ctx = Context { steps: None, ..ctx };
    match kind {
        SourceKind::Sequence if lower => crate::sfc::compile_sequence(text, stem(name, "sequence"), name, ctx),
        SourceKind::Sequence => (crate::sfc::check_sequence(text, ctx).diagnostics, None),
        _ => crate::fst::compile(text, stem(name, "fst"), name, points(&ctx)),
    }
}

/// E0025: an FST table compiles against the points it names.
pub(crate) fn needs_points(name: &str) -> Diagnostic {
    Diagnostic::command(Code::E0025, format!("compiling the FST table `{name}` needs its point database"))
        .help("pass the database that defines its points with --db")
}

/// E0024: a sequence or an FST table is compiled on its own.
pub(crate) fn not_alone(kind: SourceKind, name: &str) -> Diagnostic {
    let what = if kind == SourceKind::Sequence { "a sequence" } else { "an FST table" };
    Diagnostic::command(Code::E0024, format!("`{name}` is {what}: compile it on its own, not with other files"))
        .help("each sequence and each FST table is an object of its own; compile the other files separately")
}

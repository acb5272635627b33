//! What kind of source a file is, decided in one place for every command
//! (`check`, `compile`, `run`, the console, scenarios): action files (ST)
//! and ladder files are checked together, names shared across them; a
//! sequence or an FST table is a unit of its own; an object file is not a
//! source at all. The session ([`crate::session::Session`]) checks and
//! compiles each kind by this.

use crate::check::Context;
use crate::diagnostic::Diagnostic;
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
    /// A compiled object (`.sto`, or any file starting with its magic).
    Object,
}

impl SourceKind {
    /// The kind of the file `name` whose contents start with `head`.
    pub fn of(name: &str, head: &[u8]) -> SourceKind {
        if head.starts_with(linc_format::object::MAGIC) {
            return SourceKind::Object;
        }
        let ext = Path::new(name).extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        match ext.as_str() {
            "ld" => SourceKind::Ladder,
            "sfc" => SourceKind::Sequence,
            "csv" => SourceKind::FstTable,
            "sto" => SourceKind::Object,
            _ => SourceKind::Actions,
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

/// Checks a sequence or an FST table (unlocated diagnostics: the caller
/// puts them in the file).
pub(crate) fn check_alone(kind: SourceKind, name: &str, text: &str, ctx: Context) -> Vec<Diagnostic> {
    match kind {
        SourceKind::Sequence => crate::sfc::check_sequence(text, Context { steps: None, ..ctx }).diagnostics,
        _ => crate::fst::compile(text, stem(name, "fst"), name, points(&ctx)).0,
    }
}

/// Compiles a sequence or an FST table into its object; `Err` holds the
/// diagnostics (unlocated) when it has errors.
pub(crate) fn compile_alone(
    kind: SourceKind,
    name: &str,
    text: &str,
    ctx: Context,
) -> Result<ObjectFile, Vec<Diagnostic>> {
    let (diagnostics, object) = match kind {
        SourceKind::Sequence => crate::sfc::compile_sequence(text, stem(name, "sequence"), name, ctx),
        _ => match points(&ctx) {
            Some(db) => crate::fst::compile(text, stem(name, "fst"), name, Some(db)),
            None => (vec![needs_points(name)], None),
        },
    };
    object.ok_or(diagnostics)
}

/// E0025: an FST table compiles against the points it names.
fn needs_points(name: &str) -> Diagnostic {
    Diagnostic::command(Code::E0025, format!("compiling the FST table `{name}` needs its point database"))
        .help("pass the database that defines its points with --db")
}

/// E0024: a sequence or an FST table is compiled on its own.
pub(crate) fn not_alone(kind: SourceKind, name: &str) -> Diagnostic {
    let what = if kind == SourceKind::Sequence { "a sequence" } else { "an FST table" };
    Diagnostic::command(Code::E0024, format!("`{name}` is {what}: compile it on its own, not with other files"))
        .help("each sequence and each FST table is an object of its own; compile the other files separately")
}

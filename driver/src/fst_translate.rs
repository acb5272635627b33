//! `linc fst to-st` and `to-sfc`: an FST table translated to the ST action
//! of one cycle, or to a sequence (`docs/fst-translation.md`). The translation
//! itself is the compiler's (`linc_compiler::fst::translate`); this reads
//! the files, finds the FST block that would run the table and its
//! steps-per-cycle limit, and reports what stops the translation.

use crate::{source, Reporter};
use linc_compiler::fst;
use linc_compiler::{Diagnostic, FileId};
use linc_format::Code;
use linc_runtime::store::Store;
use std::path::Path;

/// An action name from a file's stem: letters, digits and `_`, starting
/// with a letter, at most 8 characters (an ST identifier).
pub fn action_name(path: &Path) -> String {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    let mut name: String = stem.chars().filter(|c| c.is_ascii_alphanumeric() || *c == '_').take(8).collect();
    if !name.starts_with(|c: char| c.is_ascii_alphabetic()) {
        name = format!("T{}", name.chars().take(7).collect::<String>());
    }
    name
}

/// A table read and checked against its database, with the FST block that
/// would run it and that block's steps-per-cycle limit.
struct Prepared {
    table: fst::Table,
    checked: fst::Checked,
    block: String,
    steps: u32,
    files: linc_compiler::diag::render::SourceFiles,
    id: linc_compiler::FileId,
}

/// Reads, checks and finds the block; problems are reported to `r`.
fn prepare(path: &Path, db: &Path, block: Option<&str>, r: &mut Reporter) -> Result<Prepared, u8> {
    let mut dbfiles = linc_compiler::diag::render::SourceFiles::new();
    let db = crate::database::load(Some(db), &mut dbfiles, r)?.unwrap_or_default();
    let (text, files, id) = match source::read(path, r)? {
        (Some(t), files, id) => (t, files, id),
        (None, ..) => return Err(1),
    };
    let (table, mut diagnostics) = fst::reader::read(&text);
    let (checked, more) = fst::check::check(&table, Some(&db));
    diagnostics.extend(more);
    let checked = match checked {
        Some(c) if !diagnostics.iter().any(Diagnostic::is_error) => c,
        _ => {
            r.emit_all(&files, &diagnostics.iter().map(|d| d.clone().in_file(id)).collect::<Vec<_>>());
            return Err(1);
        }
    };
    let b = crate::single::find_block(&db, block, crate::single::Kind::Fst).map_err(|d| {
        r.emit_own(*d);
        2u8
    })?;
    let name = db.blocks[b].name.clone();
    let store = Store::new(db);
    let int = |field: &str| linc_engines::strategy::register(&store, b, field);
    // BRK slows the table from the start; the table writes IP (step 0's
    // offset, 0) after each cycle, and IP is read-only to ST.
    for (field, why) in
        [("BRK", "the table runs one command a period"), ("IP", "the table sets it to 0, which ST cannot")]
    {
        if int(field) != 0 {
            let why = format!("block `{name}` has {field} {}: {why}", int(field));
            r.emit(&dbfiles, &in_database(&dbfiles, &name, field, why));
            return Err(1);
        }
    }
    // BRK is 0 here, so this is STEPS or the default.
    let steps = linc_engines::strategy::steps_per_cycle(0, int("STEPS"));
    Ok(Prepared { table, checked, block: name, steps, files, id })
}

/// E0430 for a block's `field`, at its value in the database file (or at
/// the block's name, when the value is the template's), the one file
/// `files` holds.
fn in_database(files: &linc_compiler::diag::render::SourceFiles, block: &str, field: &str, why: String) -> Diagnostic {
    let root = files.get(0).and_then(|f| linc_format::db::tree::parse(&crate::database::without_bom(f.text())).ok());
    let written = |path: &[&str]| linc_format::db::tree::member_at(root.as_ref()?, path);
    let (span, label) = if let Some(m) = written(&["blocks", block, "values", field]) {
        (m.value.span, "the table cannot start from this")
    } else if let Some(m) = written(&["blocks", block]) {
        (m.key_span, "this block")
    } else {
        return Diagnostic::command(Code::E0430, why);
    };
    Diagnostic::error(Code::E0430, why, linc_compiler::Span::new(span.0, span.1)).label(label).in_file(FileId(0))
}

impl Prepared {
    fn refused(&self, r: &mut Reporter, ds: &[Diagnostic]) -> u8 {
        r.emit_all(&self.files, &ds.iter().map(|d| d.clone().in_file(self.id)).collect::<Vec<_>>());
        1
    }
}

/// The ST translation of `path` against the database `db` for the FST
/// block `block` (the one FST block when there is one). Problems are
/// reported to `r`; `Err` is the exit status.
pub fn to_st(path: &Path, db: &Path, block: Option<&str>, r: &mut Reporter) -> Result<String, u8> {
    let p = prepare(path, db, block, r)?;
    let action = action_name(path);
    let target = fst::translate::Target { block: &p.block, steps_per_cycle: p.steps, action: &action };
    fst::translate::to_st(&p.table, &p.checked, &target).map_err(|ds| p.refused(r, &ds))
}

/// The sequence translation of `path` (`linc fst to-sfc`), with `exit`
/// (`BLOCK.FIELD`) the field a step that leaves in several ways records
/// its way in.
pub fn to_sfc(path: &Path, db: &Path, block: Option<&str>, exit: Option<&str>, r: &mut Reporter) -> Result<String, u8> {
    let p = prepare(path, db, block, r)?;
    let exit = exit.map(|f| format!("[{f}]"));
    let target = fst::translate::SfcTarget { block: &p.block, steps_per_cycle: p.steps, exit: exit.as_deref() };
    fst::translate::to_sfc(&p.table, &p.checked, &target).map_err(|ds| p.refused(r, &ds))
}

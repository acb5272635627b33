//! FST tables as the `linc fst` commands read them: `list`, the table as
//! the FST Editor shows it; `to-st` and `to-sfc`, the table translated to
//! the ST action of one cycle, or to a sequence
//! (`docs/fst-translation.md`). The translation itself is the compiler's
//! (`linc_compiler::fst::translate`); this reads the files, finds the FST
//! block that would run the table and its steps-per-cycle limit, and
//! returns what stops the translation.

use crate::source;
use linc_compiler::diag::{Diagnostic, FileId, Problems, SourceFiles};
use linc_compiler::fst;
use linc_format::Code;
use linc_runtime::store::Store;
use std::path::Path;

/// `linc fst list TABLE.csv [--db DB]`: the table aligned as the FST
/// Editor shows it, with each step's instruction offset (IP) when the
/// database lets it compile, and the table's warnings.
pub fn list(path: &Path, db: Option<&Path>) -> Result<(String, Problems), Problems> {
    let db = crate::database::load_opt(db)?;
    let source = source::read(path)?;
    let (table, mut diagnostics) = fst::reader::read(&source.text);
    let stem = source::stem(path, "fst");
    let (more, object) = fst::compile(&source.text, stem, &path.display().to_string(), db.as_ref().map(|d| &d.db));
    if db.is_some() {
        diagnostics = more;
    }
    let failed = diagnostics.iter().any(Diagnostic::is_error);
    let problems = source.problems(diagnostics);
    if failed {
        return Err(problems);
    }
    let offsets = object.as_ref().and_then(fst::offsets);
    Ok((fst::list::listing(&table, offsets.as_deref()), problems))
}

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
    source: source::Source,
}

/// Reads, checks and finds the block.
fn prepare(path: &Path, db: &Path, block: Option<&str>) -> Result<Prepared, Problems> {
    let db = crate::database::load(db)?;
    let source = source::read(path)?;
    let (table, mut diagnostics) = fst::reader::read(&source.text);
    let (checked, more) = fst::check::check(&table, Some(&db.db));
    diagnostics.extend(more);
    let checked = match checked {
        Some(c) if !diagnostics.iter().any(Diagnostic::is_error) => c,
        _ => return Err(source.problems(diagnostics)),
    };
    let b = crate::single::find_block(&db.db, block, crate::single::Kind::Fst)?;
    let name = db.db.blocks[b].name.clone();
    let store = Store::new(db.db.clone());
    let int = |field: &str| linc_engines::strategy::register(&store, b, field);
    // BRK slows the table from the start; the table writes IP (step 0's
    // offset, 0) after each cycle, and IP is read-only to ST.
    for (field, why) in
        [("BRK", "the table runs one command a period"), ("IP", "the table sets it to 0, which ST cannot")]
    {
        if int(field) != 0 {
            let why = format!("block `{name}` has {field} {}: {why}", int(field));
            return Err(in_database(&db, &name, field, why));
        }
    }
    // BRK is 0 here, so this is STEPS or the default.
    let steps = linc_engines::strategy::steps_per_cycle(0, int("STEPS"));
    Ok(Prepared { table, checked, block: name, steps, source })
}

/// E0430 for a block's `field`, at its value in the database file (or at
/// the block's name, when the value is the template's).
fn in_database(db: &crate::database::DbFile, block: &str, field: &str, why: String) -> Problems {
    let root = linc_format::db::tree::parse(&crate::database::without_bom(&db.text)).ok();
    let written = |path: &[&str]| linc_format::db::tree::member_at(root.as_ref()?, path);
    let (span, label) = if let Some(m) = written(&["blocks", block, "values", field]) {
        (m.value.span, "the table cannot start from this")
    } else if let Some(m) = written(&["blocks", block]) {
        (m.key_span, "this block")
    } else {
        return Problems::finding(Diagnostic::command(Code::E0430, why));
    };
    let d = Diagnostic::error(Code::E0430, why, linc_compiler::diag::Span::new(span.0, span.1)).label(label);
    let mut files = SourceFiles::new();
    files.add(db.name.clone(), db.text.clone());
    Problems::of(files, vec![d.in_file(FileId(0))])
}

/// The ST translation of `path` against the database `db` for the FST
/// block `block` (the one FST block when there is one).
pub fn to_st(path: &Path, db: &Path, block: Option<&str>) -> Result<String, Problems> {
    let p = prepare(path, db, block)?;
    let action = action_name(path);
    let target = fst::translate::Target { block: &p.block, steps_per_cycle: p.steps, action: &action };
    fst::translate::to_st(&p.table, &p.checked, &target).map_err(|ds| p.source.problems(ds))
}

/// The sequence translation of `path` (`linc fst to-sfc`), with `exit`
/// (`BLOCK.FIELD`) the field a step that leaves in several ways records
/// its way in.
pub fn to_sfc(path: &Path, db: &Path, block: Option<&str>, exit: Option<&str>) -> Result<String, Problems> {
    let p = prepare(path, db, block)?;
    let exit = match exit {
        None => None,
        Some(f) => {
            let db = crate::database::load(db)?;
            let field = fst::check::field_param(&db.db, f.trim_matches(|c| c == '[' || c == ']'));
            Some(field.map_err(|why| Problems::usage(Code::E0434, format!("--exit {f}: {why}")))?)
        }
    };
    let target = fst::translate::SfcTarget { block: &p.block, steps_per_cycle: p.steps, exit: exit.as_ref() };
    fst::translate::to_sfc(&p.table, &p.checked, &target).map_err(|ds| p.source.problems(ds))
}

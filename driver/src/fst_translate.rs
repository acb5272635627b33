//! `linc fst to-st`: an FST table translated to the ST action that does
//! what one cycle of it does (`docs/fst-translation.md`). The translation
//! itself is the compiler's (`linc_compiler::fst::translate`); this reads
//! the files, finds the FST block that would run the table and its
//! steps-per-cycle limit, and reports what stops the translation.

use crate::{source, Reporter};
use linc_compiler::fst;
use linc_compiler::Diagnostic;
use linc_format::Code;
use linc_runtime::store::{Cell, Store};
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

/// The ST translation of `path` against the database `db` for the FST
/// block `block` (the one FST block when there is one). Problems are
/// reported to `r`; `Err` is the exit status.
pub fn to_st(path: &Path, db: &Path, block: Option<&str>, r: &mut Reporter) -> Result<String, u8> {
    let mut dbfiles = linc_compiler::render::SourceFiles::new();
    let db = crate::database::load(Some(db), &mut dbfiles, r)?.unwrap_or_default();
    let (text, files, id) = match source::read(path, r)? {
        (Some(t), files, id) => (t, files, id),
        (None, ..) => return Err(1),
    };
    let (table, mut diagnostics) = fst::reader::read(&text);
    let (checked, more) = fst::check::check(&table, Some(&db));
    diagnostics.extend(more);
    let emit = |r: &mut Reporter, ds: &[Diagnostic]| {
        r.emit_all(&files, &ds.iter().map(|d| d.clone().in_file(id)).collect::<Vec<_>>());
    };
    let checked = match checked {
        Some(c) if !diagnostics.iter().any(Diagnostic::is_error) => c,
        _ => {
            emit(r, &diagnostics);
            return Err(1);
        }
    };
    let b = crate::single::find_block(&db, block, crate::single::Kind::Fst).map_err(|d| {
        r.emit_own(*d);
        2u8
    })?;
    let store = Store::new(db.clone());
    let int = |field: &str| match store.cell_of(b, field).and_then(|c| store.cells.get(c as usize)) {
        Some(Cell::Int(i)) => *i,
        Some(Cell::Bits { v, .. }) => i32::from(*v),
        Some(Cell::Real(x)) => *x as i32,
        _ => 0,
    };
    let name = db.blocks[b].name.clone();
    if int("BRK") != 0 {
        let why = format!("block `{name}` has BRK {}: the table runs one command a period", int("BRK"));
        r.emit_own(Diagnostic::command(Code::E0430, why));
        return Err(1);
    }
    // The table writes IP (step 0's offset, 0) after each cycle; IP is
    // read-only to ST, so an action leaves it as the database has it.
    if int("IP") != 0 {
        let why = format!("block `{name}` has IP {}: the table sets it to 0, which an ST action cannot", int("IP"));
        r.emit_own(Diagnostic::command(Code::E0430, why));
        return Err(1);
    }
    let steps = match int("STEPS") {
        n if n > 0 => n as u32,
        _ => linc_engines::strategy::DEFAULT_STEPS,
    };
    let action = action_name(path);
    let target = fst::translate::Target { block: &name, steps_per_cycle: steps, action: &action };
    fst::translate::to_st(&table, &checked, &target).map_err(|ds| {
        emit(r, &ds);
        1
    })
}

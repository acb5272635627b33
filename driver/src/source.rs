//! What kind of file a path names, and reading a source: the one place a
//! source's bytes are read and decoded outside a compile session (UTF-8, a
//! byte order mark kept in the text but ignored by the renderer, each byte
//! that is not UTF-8 reported once as a located E0017).

use crate::Reporter;
use linc_compiler::diag::render::SourceFiles;
use linc_compiler::source_kind::SourceKind;
use linc_compiler::FileId;
use std::path::Path;

/// The kind of source a path names, by its name (the compiler decides).
pub fn kind(path: &Path) -> SourceKind {
    SourceKind::of_name(&path.to_string_lossy())
}

/// Whether a path names a sequence source (`.sfc`).
pub fn is_sequence(path: &Path) -> bool {
    kind(path) == SourceKind::Sequence
}

/// Whether a path names an FST table (`.csv`, as ROCLINK 800 exports it).
pub fn is_fst(path: &Path) -> bool {
    kind(path) == SourceKind::FstTable
}

/// Whether a path names a compiled object (`.sto`).
pub fn is_object(path: &Path) -> bool {
    kind(path) == SourceKind::Object
}

/// Reads `path` as a source: its text (`None` when it is not UTF-8, which
/// is reported at the first bad byte), the file map holding it for
/// diagnostics, and its id there. `Err` is the exit status of an
/// unreadable file (2), already reported.
pub fn read(path: &Path, r: &mut Reporter) -> Result<(Option<String>, SourceFiles, FileId), u8> {
    let bytes = crate::files::read_input(path).map_err(|e| {
        r.unreadable(path, &e);
        2u8
    })?;
    let (text, invalid) = linc_compiler::diag::files::decode(bytes);
    let mut files = SourceFiles::new();
    let id = files.add_decoded(path.display().to_string(), text.clone(), invalid.clone());
    match linc_compiler::session::SessionError::not_utf8(&invalid) {
        Some(e) => {
            r.emit(&files, &e.to_diagnostic().in_file(id));
            Ok((None, files, id))
        }
        None => Ok((Some(text), files, id)),
    }
}

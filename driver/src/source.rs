//! What kind of file a path names, and reading a source: the one place a
//! source's bytes are read and decoded outside a compile session (UTF-8, a
//! byte order mark kept in the text but ignored by the renderer, each byte
//! that is not UTF-8 reported once as a located E0017).

use linc_compiler::diag::{Diagnostic, FileId, Problems, SourceFiles};
use linc_compiler::source_kind::SourceKind;
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

/// A source file read and decoded.
pub struct Source {
    /// Its name as given.
    pub name: String,
    pub text: String,
    files: SourceFiles,
}

/// The stem of a file's name, or `default`: the name of a file's only
/// action when it has no `ACTION` header.
pub fn stem<'a>(path: &'a Path, default: &'a str) -> &'a str {
    path.file_stem().and_then(|s| s.to_str()).unwrap_or(default)
}

impl Source {
    /// `ds`, which point into this source, with it.
    pub fn problems(self, ds: Vec<Diagnostic>) -> Problems {
        let located = ds.into_iter().map(|d| d.in_file(FileId(0))).collect();
        Problems::of(self.files, located)
    }

    /// [`Source::problems`] without giving the source up.
    pub fn problems_of(&self, ds: &[Diagnostic]) -> Problems {
        let mut files = SourceFiles::new();
        files.add(self.name.clone(), self.text.clone());
        Problems::of(files, ds.iter().map(|d| d.clone().in_file(FileId(0))).collect())
    }
}

/// Reads `path` as a source. An unreadable file is a refused request; a
/// file that is not UTF-8 is an error found in it (E0017 at its first bad
/// byte).
pub fn read(path: &Path) -> Result<Source, Problems> {
    let bytes = crate::files::read_input(path).map_err(|e| Problems::unreadable(path, &e))?;
    let (text, invalid) = linc_compiler::diag::decode(bytes);
    let name = path.display().to_string();
    let mut files = SourceFiles::new();
    files.add_decoded(name.clone(), text.clone(), invalid.clone());
    let source = Source { name, text, files };
    match linc_compiler::session::SessionError::not_utf8(&invalid) {
        Some(e) => Err(source.problems(vec![e.to_diagnostic()])),
        None => Ok(source),
    }
}

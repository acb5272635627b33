//! What a request of linc ran into, as data: the diagnostics, the source
//! files they point into, and whether the request itself was refused.
//!
//! Every library function of linc that can fail returns
//! `Result<T, Problems>` (and a `Problems` of warnings or findings beside
//! what it made when it succeeds); nothing below the command line prints.
//! The command line renders a `Problems` once, in the format asked for
//! ([`Problems::render`]), and a language server or an HTTP API reads the
//! same diagnostics as data.

use super::files::SourceFiles;
use super::render::{render, Format};
use super::span::{FileId, Span};
use super::{Diagnostic, Severity};
use linc_format::Code;

/// Diagnostics with the files they point into.
#[derive(Debug, Default)]
pub struct Problems {
    files: SourceFiles,
    list: Vec<Diagnostic>,
    /// The request could not be carried out (a refused option, a file that
    /// can't be read, a database or program that does not load), as
    /// opposed to finding errors in what it was asked to check or run.
    refused: bool,
}

impl Problems {
    pub fn new() -> Problems {
        Problems::default()
    }

    /// A refused request: one error about the request itself, which points
    /// into no file (E0903 for an option, E0904 for a `--block` …).
    pub fn usage(code: Code, message: impl Into<String>) -> Problems {
        Problems::refusal(Diagnostic::command(code, message))
    }

    /// A refused request, for a diagnostic that points into no file.
    pub fn refusal(d: Diagnostic) -> Problems {
        let mut p = Problems::new();
        p.push(d);
        p.refused = true;
        p
    }

    /// An error found (not a refused request) that points into no file: a
    /// trace line that is not a record, a console command refused.
    pub fn finding(d: Diagnostic) -> Problems {
        let mut p = Problems::new();
        p.push(d);
        p
    }

    /// A refused request about a whole file (an unreadable input, a damaged
    /// object): shown against the file's name, without a snippet.
    pub fn whole_file(file: &str, code: Code, message: impl Into<String>) -> Problems {
        let mut p = Problems::new();
        p.push_whole_file(file, code, message);
        p.refused = true;
        p
    }

    /// `path` could not be read (E0900).
    pub fn unreadable(path: &std::path::Path, e: &std::io::Error) -> Problems {
        let name = path.display().to_string();
        Problems::whole_file(&name, Code::E0900, format!("can't read `{name}`: {e}"))
    }

    /// Diagnostics found in `files`, taken with them.
    pub fn of(files: SourceFiles, list: Vec<Diagnostic>) -> Problems {
        Problems { files, list, refused: false }
    }

    /// Marks the whole as a refused request.
    pub fn refused(mut self) -> Problems {
        self.refused = true;
        self
    }

    /// Whether the request was refused rather than finding errors.
    pub fn is_refused(&self) -> bool {
        self.refused
    }

    /// Adds a file that diagnostics pushed later may point into.
    pub fn add_file(&mut self, name: impl Into<String>, text: String) -> FileId {
        self.files.add(name.into(), text)
    }

    /// Adds a diagnostic that points into no file or into a file added
    /// with [`Problems::add_file`].
    pub fn push(&mut self, d: Diagnostic) {
        self.list.push(d);
    }

    /// Adds an error about a whole file, shown against its name.
    pub fn push_whole_file(&mut self, file: &str, code: Code, message: impl Into<String>) {
        let id = self.add_file(file, String::new());
        self.push(Diagnostic::error(code, message, Span::new(0, 0)).in_file(id));
    }

    /// Takes `other`'s diagnostics and files after these ones (its file
    /// ids are moved past this one's files); refused if either was.
    pub fn append(&mut self, other: Problems) {
        let shift = self.files.len() as u32;
        let moved = |id: FileId| if id == FileId::NONE { id } else { FileId(id.0 + shift) };
        self.files.append(other.files);
        self.list.extend(other.list.into_iter().map(|mut d| {
            d.file = moved(d.file);
            for l in &mut d.secondary {
                l.file = l.file.map(moved);
            }
            d
        }));
        self.refused |= other.refused;
    }

    /// Adds the diagnostics `list`, found in `files`.
    pub fn extend(&mut self, files: SourceFiles, list: Vec<Diagnostic>) {
        self.append(Problems::of(files, list));
    }

    pub fn diagnostics(&self) -> &[Diagnostic] {
        &self.list
    }

    pub fn files(&self) -> &SourceFiles {
        &self.files
    }

    /// How many errors (not warnings or notes).
    pub fn errors(&self) -> usize {
        self.list.iter().filter(|d| d.is_error()).count()
    }

    /// How many warnings.
    pub fn warnings(&self) -> usize {
        self.list.iter().filter(|d| d.severity == Severity::Warning).count()
    }

    pub fn has_errors(&self) -> bool {
        self.list.iter().any(Diagnostic::is_error)
    }

    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Every diagnostic rendered in `format`, in order.
    pub fn render(&self, format: Format) -> String {
        self.list.iter().map(|d| render(&self.files, d, format)).collect()
    }
}

impl std::fmt::Display for Problems {
    /// The problems in the short format, one a line (for tests and logs).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.render(Format::Short))
    }
}

impl From<Diagnostic> for Problems {
    /// A diagnostic that points into no file, as a refused request.
    fn from(d: Diagnostic) -> Problems {
        Problems::refusal(d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn appended_problems_keep_pointing_into_their_own_files() {
        let mut a = Problems::new();
        let f = a.add_file("a.st", "x := 1;\n".into());
        a.push(Diagnostic::error(Code::E0100, "in a", Span::new(0, 1)).in_file(f));
        let mut files = SourceFiles::new();
        files.add("b.st".into(), "y := 2;\nz := 3;\n".into());
        let b = Problems::of(files, vec![Diagnostic::warning(Code::W0001, "in b", Span::new(8, 9)).in_file(FileId(0))]);
        a.append(b);
        a.push(Diagnostic::command(Code::E0903, "no file"));
        assert_eq!(
            a.render(Format::Short),
            "a.st:1:1: error[E0100]: in a\nb.st:2:1: warning[W0001]: in b\nerror[E0903]: no file\n"
        );
        assert_eq!((a.errors(), a.warnings(), a.is_refused()), (2, 1, false));
        a.append(Problems::usage(Code::E0903, "bad"));
        assert!(a.is_refused());
    }
}

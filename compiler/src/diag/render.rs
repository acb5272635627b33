//! The one place diagnostics are turned into text.
//!
//! Three formats: `human` (codespan-reporting with source snippets, labels
//! and help notes), `short` (`FILE:LINE:COL: error[E0001]: message`, one line
//! each, for editors and grep) and `json` (one object per diagnostic per
//! line, for tools). Each diagnostic is shown against its own file.
//!
//! Source text never reaches the terminal raw: `human` shows each source line
//! through a view in which control characters and invisible direction marks
//! are escaped (`\u{1b}`), bytes that were not UTF-8 are shown as `\xB0`, a
//! leading byte order mark is dropped and very long lines are cut to windows
//! around the labels; messages and file names are escaped the same way in
//! `human` and `short`. `json` escapes through JSON itself.

pub use super::files::SourceFiles;
use crate::diag::files::{SourceFile, BOM, SUBSTITUTE};
use crate::diag::span::{FileId, Span};
use crate::diag::{Diagnostic, Severity};
use codespan_reporting::diagnostic as cs;
use codespan_reporting::files::{Error as FilesError, Files, Location};
use codespan_reporting::term;
use std::borrow::Cow;
use std::fmt::Write;
use std::ops::Range;

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Human,
    Short,
    Json,
}

/// Renders one diagnostic against the file it names.
pub fn render(files: &SourceFiles, d: &Diagnostic, format: Format) -> String {
    match format {
        Format::Human => human(files, d),
        Format::Short => short(files, d),
        Format::Json => json(files, d),
    }
}

/// Whether a character must not be written to a terminal as it is: control
/// characters (but tab), and marks that reorder or hide text.
fn needs_escape(c: char) -> bool {
    (c.is_control() && c != '\t')
        || matches!(c, '\u{200E}' | '\u{200F}' | '\u{061C}' | '\u{202A}'..='\u{202E}' | '\u{2066}'..='\u{2069}')
        || matches!(c, '\u{2028}' | '\u{2029}' | BOM)
}

/// [`escape`] for text of several lines (a listing, a drawing, a reply):
/// line ends stay line ends, every other control character is escaped.
pub fn escape_text(s: &str) -> Cow<'_, str> {
    if !s.chars().any(|c| c != '\n' && needs_escape(c)) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for (i, line) in s.split('\n').enumerate() {
        if i > 0 {
            out.push('\n');
        }
        out.push_str(&escape(line));
    }
    Cow::Owned(out)
}

/// `s` with every character that must not reach a terminal written as `\u{..}`.
pub fn escape(s: &str) -> Cow<'_, str> {
    if !s.chars().any(needs_escape) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        if needs_escape(c) {
            let _ = write!(out, "\\u{{{:x}}}", c as u32);
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

fn file_name(files: &SourceFiles, id: FileId) -> &str {
    files.file(id).map(SourceFile::name).unwrap_or("<unknown>")
}

/// `(line, column)`, both 1-based, of byte `at` of file `id`.
pub fn line_col(files: &SourceFiles, id: FileId, at: usize) -> (usize, usize) {
    files.file(id).map(|f| f.line_col(at)).unwrap_or((1, 1))
}

fn severity_word(s: Severity) -> &'static str {
    match s {
        Severity::Error => "error",
        Severity::Warning => "warning",
        Severity::Note => "note",
    }
}

fn short(files: &SourceFiles, d: &Diagnostic) -> String {
    if d.severity == Severity::Note {
        return format!("{}\n", escape(&d.message));
    }
    if d.file == FileId::NONE {
        return format!("{}[{}]: {}\n", severity_word(d.severity), d.code, escape(&d.message));
    }
    let (line, col) = line_col(files, d.file, d.span.start);
    let name = escape(file_name(files, d.file));
    format!("{name}:{line}:{col}: {}[{}]: {}\n", severity_word(d.severity), d.code, escape(&d.message))
}

fn json(files: &SourceFiles, d: &Diagnostic) -> String {
    let (line, column) = line_col(files, d.file, d.span.start);
    let (end_line, end_column) = line_col(files, d.file, d.span.end);
    let labels: Vec<serde_json::Value> = d
        .secondary
        .iter()
        .map(|l| {
            let file = l.file.unwrap_or(d.file);
            let (line, column) = line_col(files, file, l.span.start);
            serde_json::json!({
                "file": file_name(files, file),
                "line": line,
                "column": column,
                "start": l.span.start,
                "end": l.span.end,
                "message": l.text,
            })
        })
        .collect();
    let located = d.file != FileId::NONE;
    let v = serde_json::json!({
        "file": located.then(|| file_name(files, d.file)),
        "line": located.then_some(line),
        "column": located.then_some(column),
        "end_line": located.then_some(end_line),
        "end_column": located.then_some(end_column),
        "start": located.then_some(d.span.start),
        "end": located.then_some(d.span.end),
        "severity": severity_word(d.severity),
        "code": d.code,
        "message": d.message,
        "label": d.label,
        "labels": labels,
        "help": d.help,
    });
    format!("{v}\n")
}

fn human(files: &SourceFiles, d: &Diagnostic) -> String {
    if d.severity == Severity::Note {
        return short(files, d);
    }
    // A file with no text (an object file given as source) has no snippet.
    let empty = d.file == FileId::NONE || files.file(d.file).is_some_and(|f| f.text().is_empty());
    let mut labels = if empty { Vec::new() } else { vec![(d.file, d.span, d.label.as_str(), true)] };
    labels.extend(d.secondary.iter().map(|l| (l.file.unwrap_or(d.file), l.span, l.text.as_str(), false)));
    let (view, ranges) = View::build(files, &labels);
    let cs_labels: Vec<cs::Label<usize>> = labels
        .iter()
        .zip(ranges)
        .filter_map(|((_, _, text, primary), at)| {
            let (file, range) = at?;
            let label = if *primary { cs::Label::primary(file, range) } else { cs::Label::secondary(file, range) };
            Some(label.with_message(escape(text)))
        })
        .collect();
    let base = match d.severity {
        Severity::Error => cs::Diagnostic::error(),
        Severity::Warning => cs::Diagnostic::warning(),
        Severity::Note => cs::Diagnostic::note(),
    };
    // Without a snippet, a note still names the file the error belongs to
    // (a diagnostic about the command itself has none).
    let whole_file = (empty && d.file != FileId::NONE).then(|| format!("in {}", escape(file_name(files, d.file))));
    let notes = whole_file.into_iter().chain(d.help.iter().map(|h| format!("help: {}", escape(h)))).collect();
    let diag = base.with_code(d.code).with_message(escape(&d.message)).with_labels(cs_labels).with_notes(notes);
    let config = term::Config::default();
    term::emit_into_string(&config, &view, &diag).unwrap_or_else(|_| short(files, d))
}

/// Lines codespan prints after the first and before the last line of a
/// label over several lines (its `start_context_lines`, `end_context_lines`).
const MULTI_START: usize = 3;
const MULTI_END: usize = 1;

/// Lines longer than this (in bytes) are shown in windows around labels.
const LONG_LINE: usize = 240;
/// How much of a long line is kept on each side of a labelled position.
const CONTEXT: usize = 60;

/// The lines of one file that one diagnostic shows, made safe to print.
struct FileView {
    name: String,
    text: String,
    /// Sorted by line: the real 0-based line and its bytes in `text`
    /// (terminator included, as codespan expects).
    lines: Vec<(usize, Range<usize>)>,
    /// Real locations of the view offsets where labels start.
    locations: Vec<(usize, Location)>,
}

/// What codespan renders from: only the lines a diagnostic needs.
struct View {
    files: Vec<FileView>,
}

type LabelAt<'a> = (FileId, Span, &'a str, bool);

/// Where a label landed: the view file and the range in it.
type Placed = Option<(usize, Range<usize>)>;

impl View {
    /// Builds the view of `labels` and returns, per label, its view file
    /// and range (`None` for a label in an unknown file).
    fn build(files: &SourceFiles, labels: &[LabelAt]) -> (View, Vec<Placed>) {
        let mut ids: Vec<FileId> = Vec::new();
        for l in labels {
            if files.file(l.0).is_some() && !ids.contains(&l.0) {
                ids.push(l.0);
            }
        }
        let mut view = View { files: Vec::new() };
        let mut out = vec![None; labels.len()];
        for id in ids {
            let Some(f) = files.file(id) else { continue };
            let mine: Vec<usize> = (0..labels.len()).filter(|&i| labels[i].0 == id).collect();
            let spans: Vec<Range<usize>> = mine
                .iter()
                .map(|&i| {
                    let s = f.clamp(labels[i].1.start);
                    s..f.clamp(labels[i].1.end).max(s)
                })
                .collect();
            let (fv, ranges) = file_view(f, &spans);
            let k = view.files.len();
            view.files.push(fv);
            for (i, r) in mine.into_iter().zip(ranges) {
                out[i] = Some((k, r));
            }
        }
        (view, out)
    }

    fn file(&self, id: usize) -> Result<&FileView, FilesError> {
        self.files.get(id).ok_or(FilesError::FileMissing)
    }
}

/// The view of one file for label ranges `spans` (original offsets), and
/// the ranges mapped into the view.
fn file_view(f: &SourceFile, spans: &[Range<usize>]) -> (FileView, Vec<Range<usize>>) {
    // The lines codespan prints: those a label starts or ends on, the first
    // lines inside a label over several lines and the one before its end,
    // and the line between two printed lines that are one apart (printed
    // rather than a break). Other lines inside a label are never printed:
    // they read as empty, so a label over a whole file costs a few lines.
    let mut wanted: Vec<usize> = Vec::new();
    for s in spans {
        let (first, last) = (f.line_index(s.start), f.line_index(s.end));
        if last - first <= MULTI_START + MULTI_END + 1 {
            wanted.extend(first..=last);
        } else {
            wanted.extend(first..=first + MULTI_START);
            wanted.extend(last - MULTI_END..=last);
        }
    }
    wanted.sort_unstable();
    wanted.dedup();
    let gaps: Vec<usize> = wanted.windows(2).filter(|w| w[1] == w[0] + 2).map(|w| w[0] + 1).collect();
    wanted.extend(gaps);
    wanted.sort_unstable();
    let mut points: Vec<usize> = spans.iter().flat_map(|s| [s.start, s.end]).collect();
    points.sort_unstable();
    points.dedup();
    let mut mapped: Vec<(usize, usize)> = Vec::with_capacity(points.len());
    let mut fv =
        FileView { name: escape(f.name()).into_owned(), text: String::new(), lines: Vec::new(), locations: Vec::new() };
    for line in wanted {
        let range = f.line_range(line);
        let start = fv.text.len();
        let here: Vec<usize> = points.iter().copied().filter(|&p| f.line_index(p) == line).collect();
        let (shown, at) = display_line(f, range, &here);
        fv.text.push_str(&shown);
        fv.text.push('\n');
        fv.lines.push((line, start..fv.text.len()));
        mapped.extend(here.into_iter().zip(at.into_iter().map(|a| start + a)));
    }
    let find = |p: usize| mapped.iter().find(|m| m.0 == p).map(|m| m.1).unwrap_or(0);
    let ranges: Vec<Range<usize>> = spans.iter().map(|s| find(s.start)..find(s.end).max(find(s.start))).collect();
    for (s, r) in spans.iter().zip(&ranges) {
        let (line_number, column_number) = f.line_col(s.start);
        fv.locations.push((r.start, Location { line_number, column_number }));
    }
    (fv, ranges)
}

/// One line made safe to print, cut to windows around `points` if long;
/// returns the text and where each point (sorted, on this line) lands in it.
fn display_line(f: &SourceFile, line: Range<usize>, points: &[usize]) -> (String, Vec<usize>) {
    let text = f.text();
    let kept: Vec<Range<usize>> = if line.len() <= LONG_LINE {
        vec![line.clone()]
    } else {
        let mut windows: Vec<Range<usize>> = Vec::new();
        let centres: Vec<usize> = if points.is_empty() { vec![line.start + CONTEXT] } else { points.to_vec() };
        for p in centres {
            let s = f.clamp(p.saturating_sub(CONTEXT).max(line.start));
            let e = f.clamp((p + CONTEXT).min(line.end)).max(s);
            match windows.last_mut() {
                Some(w) if s <= w.end => w.end = w.end.max(e),
                _ => windows.push(s..e),
            }
        }
        windows
    };
    let mut out = String::new();
    let mut at = Vec::with_capacity(points.len());
    let mut next = 0;
    let mut prev_end = line.start;
    for r in &kept {
        if r.start > prev_end {
            out.push('…');
        }
        for (i, c) in text[r.clone()].char_indices() {
            let pos = r.start + i;
            while next < points.len() && points[next] <= pos {
                at.push(out.len());
                next += 1;
            }
            push_shown(&mut out, f, pos, c);
        }
        while next < points.len() && points[next] <= r.end {
            at.push(out.len());
            next += 1;
        }
        prev_end = r.end;
    }
    if prev_end < line.end {
        out.push('…');
    }
    while next < points.len() {
        at.push(out.len());
        next += 1;
    }
    (out, at)
}

fn push_shown(out: &mut String, f: &SourceFile, pos: usize, c: char) {
    if c == BOM && pos == 0 {
        return;
    }
    if c == SUBSTITUTE {
        if let Some(b) = f.invalid_byte_at(pos) {
            let _ = write!(out, "\\x{b:02X}");
            return;
        }
    }
    if needs_escape(c) {
        let _ = write!(out, "\\u{{{:x}}}", c as u32);
    } else {
        out.push(c);
    }
}

impl<'a> Files<'a> for View {
    type FileId = usize;
    type Name = &'a str;
    type Source = &'a str;

    fn name(&'a self, id: usize) -> Result<&'a str, FilesError> {
        Ok(&self.file(id)?.name)
    }

    fn source(&'a self, id: usize) -> Result<&'a str, FilesError> {
        Ok(&self.file(id)?.text)
    }

    fn line_index(&'a self, id: usize, byte_index: usize) -> Result<usize, FilesError> {
        let f = self.file(id)?;
        let k = f.lines.partition_point(|l| l.1.start <= byte_index).saturating_sub(1);
        f.lines.get(k).map(|l| l.0).ok_or(FilesError::IndexTooLarge { given: byte_index, max: f.text.len() })
    }

    fn line_range(&'a self, id: usize, line_index: usize) -> Result<Range<usize>, FilesError> {
        let f = self.file(id)?;
        let last = f.lines.last().map(|l| l.0).unwrap_or(0);
        match f.lines.binary_search_by_key(&line_index, |l| l.0) {
            Ok(k) => Ok(f.lines[k].1.clone()),
            // A line inside a long label, which is not printed.
            Err(_) if line_index < last => Ok(f.text.len()..f.text.len()),
            Err(_) => Err(FilesError::LineTooLarge { given: line_index, max: last }),
        }
    }

    fn location(&'a self, id: usize, byte_index: usize) -> Result<Location, FilesError> {
        let f = self.file(id)?;
        if let Some((_, l)) = f.locations.iter().find(|(at, _)| *at == byte_index) {
            return Ok(*l);
        }
        let line = self.line_index(id, byte_index)?;
        let start = self.line_range(id, line)?.start;
        let column_number = f.text.get(start..byte_index).map(|s| s.chars().count()).unwrap_or(0) + 1;
        Ok(Location { line_number: line + 1, column_number })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn one(src: &str, span: Span, format: Format) -> String {
        let mut files = SourceFiles::new();
        let id = files.add("a.st".into(), src.into());
        render(
            &files,
            &Diagnostic::error(linc_format::Code::E0001, "bad \u{1b}[31m", span).in_file(id).label("here"),
            format,
        )
    }

    #[test]
    fn control_characters_are_escaped_in_snippets_and_messages() {
        let out = one("x := '\u{1b}[31m';\n", Span::new(6, 7), Format::Human);
        assert!(!out.contains('\u{1b}'), "{out}");
        assert!(out.contains("x := '\\u{1b}[31m';"), "{out}");
        assert!(out.contains("bad \\u{1b}[31m"), "{out}");
        let short = one("x := '\u{1b}';\n", Span::new(6, 7), Format::Short);
        assert_eq!(short, "a.st:1:7: error[E0001]: bad \\u{1b}[31m\n");
    }

    #[test]
    fn long_lines_are_cut_around_the_label() {
        let src = format!("x := {};\n", "1+".repeat(100_000) + "1");
        let at = src.len() / 2;
        let out = one(&src, Span::new(at, at + 1), Format::Human);
        assert!(out.len() < 1_000, "{}", out.len());
        assert!(out.contains(&format!("a.st:1:{}", at + 1)), "{out}");
        assert!(out.contains("…+1+1"), "{out}");
    }
    #[test]
    fn a_label_over_many_lines_shows_its_ends() {
        let src: String = (1..=10_000).map(|i| format!("line {i}\n")).collect();
        let out = one(&src, Span::new(0, src.len() - 1), Format::Human);
        assert!(out.len() < 1_000, "{out}");
        assert!(out.contains("line 1\n") && out.contains("line 4\n") && out.contains("line 10000"), "{out}");
        assert!(!out.contains("line 5000"), "{out}");
    }
}

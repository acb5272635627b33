//! `linc fmt`: one canonical layout for every language linc reads
//! (docs/style.md). A formatter only moves blanks and line breaks, writes
//! keywords in capitals and aligns; every comment stays where it was, and
//! the compiled object is the same before and after except for source
//! positions (tested over the examples, the conformance cases and
//! generated programs). A text with a syntax error is not formatted: its
//! errors come back instead, as `linc check` reports them.

mod fst;
mod ladder;
mod out;
mod printer;
mod sfc;
mod tokens;

use crate::diag::Diagnostic;
use crate::source_kind::SourceKind;

/// Formats `src`, a file of the given kind; the syntax errors that stop it.
/// A file whose first comment says `linc-fmt: skip` (an example of
/// mistakes, a table laid out by hand) is left as it is.
pub fn format(kind: SourceKind, src: &str) -> Result<String, Vec<Diagnostic>> {
    if skipped(src) {
        return Ok(src.to_string());
    }
    let errors = syntax_errors(kind, src);
    if !errors.is_empty() {
        return Err(errors);
    }
    Ok(match kind {
        SourceKind::Actions => st(src),
        SourceKind::Sequence => sfc::format(src),
        SourceKind::Ladder => ladder::format(src),
        SourceKind::FstTable => fst::format(src),
        SourceKind::Object => src.to_string(),
    })
}

fn skipped(src: &str) -> bool {
    let text = src.trim_start_matches(crate::diag::files::BOM).trim_start();
    text.starts_with("(*") && text.find("*)").is_some_and(|end| text[..end].contains("linc-fmt: skip"))
}

fn st(src: &str) -> String {
    let lexed = tokens::tokens(src);
    let mut p = printer::Printer::new(src, &lexed);
    p.brk = true;
    p.statements(&|_| false);
    p.gap(lexed.tail, true);
    p.out.finish()
}

/// The errors of reading `src` (lexing and parsing, not checking).
fn syntax_errors(kind: SourceKind, src: &str) -> Vec<Diagnostic> {
    let mut diags = match kind {
        SourceKind::Actions => {
            // Read and dropped an item at a time: a large file is never held as a tree.
            let (_, e) = crate::st::parser::parse_actions(src, &mut |_| {});
            e.lex.iter().map(|e| e.to_diagnostic()).chain(e.syntax.iter().map(|e| e.to_diagnostic())).collect()
        }
        // A generic sequence's names may have up to 16 characters (guide
        // §9.1); whether they do is its map's business, which `fmt` never
        // reads: the layout does not depend on it.
        SourceKind::Sequence => crate::sfc::generic::allow_long_names(crate::sfc::parser::parse(src).1, src),
        SourceKind::Ladder => crate::ladder::parser::parse(src, "fmt").1,
        SourceKind::FstTable => crate::fst::reader::read(src).1,
        SourceKind::Object => Vec::new(),
    };
    diags.retain(Diagnostic::is_error);
    diags
}

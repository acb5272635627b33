//! The formatter's view of a text: the ST lexer's raw tokens, each with the
//! comments and line breaks in the gap before it. The compiler's lexer
//! skips comments; the formatter must keep every one in place, so it reads
//! the gaps itself (a gap holds only blanks and `(* … *)`, which do not nest).

use crate::st::token::Raw;
use logos::Logos;

/// A comment in a gap.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Comment {
    pub start: usize,
    pub end: usize,
    /// A line break (or the start of the text) comes before it in the gap:
    /// it stands on its own line.
    pub own_line: bool,
    /// Two or more line breaks come before it: a blank line.
    pub blank_before: bool,
}

/// What stands between two tokens besides blanks. Its comments are a range
/// of [`Lexed::comments`], so that a token stays small: a text is held as
/// tokens while it is formatted.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct Gap {
    pub comments: (u32, u32),
    /// A line break between the last comment (or the previous token) and
    /// the token.
    pub newline: bool,
    /// Two or more of them: a blank line.
    pub blank: bool,
    /// Nothing at all between the previous token and this one.
    pub adjacent: bool,
}

/// A raw token (`None`: text the ST lexer does not know, such as a rung's
/// `|`) and its gap.
#[derive(Clone, Debug)]
pub(crate) struct Token {
    pub raw: Option<Raw>,
    pub start: usize,
    pub end: usize,
    pub gap: Gap,
}

/// A text as tokens, the comments between them, and the gap after the last.
pub(crate) struct Lexed {
    pub toks: Vec<Token>,
    pub comments: Vec<Comment>,
    pub tail: Gap,
}

/// Every token of `src` and the gap after the last one.
pub(crate) fn tokens(src: &str) -> Lexed {
    let mut lexer = Raw::lexer(src);
    let first = if src.starts_with(crate::diag::files::BOM) { crate::diag::files::BOM.len_utf8() } else { 0 };
    lexer.bump(first);
    let (mut toks, mut comments) = (Vec::new(), Vec::new());
    let mut prev = first;
    while let Some(r) = lexer.next() {
        let span = lexer.span();
        let gap = gap(src, prev, span.start, toks.is_empty(), &mut comments);
        toks.push(Token { raw: r.ok(), start: span.start, end: span.end, gap });
        prev = span.end;
    }
    let tail = gap(src, prev, src.len(), toks.is_empty(), &mut comments);
    Lexed { toks, comments, tail }
}

/// Reads the gap `src[from..to]`, adding its comments to `comments`.
fn gap(src: &str, from: usize, to: usize, at_start: bool, comments: &mut Vec<Comment>) -> Gap {
    let b = src.as_bytes();
    let mut g = Gap { adjacent: from == to, ..Gap::default() };
    let first = comments.len() as u32;
    let mut breaks = usize::from(at_start);
    let mut i = from;
    while i < to {
        if b[i] == b'\n' {
            breaks += 1;
            i += 1;
        } else if b[i] == b'(' && b.get(i + 1) == Some(&b'*') {
            let end = src[i + 2..to].find("*)").map(|k| i + 2 + k + 2).unwrap_or(to);
            comments.push(Comment { start: i, end, own_line: breaks > 0, blank_before: breaks > 1 });
            breaks = 0;
            i = end;
        } else {
            i += 1;
        }
    }
    g.comments = (first, comments.len() as u32);
    // A token at the very start is on its own line, but no blank comes before it.
    g.newline = breaks > 0;
    g.blank = breaks > 1 && !(at_start && first == comments.len() as u32);
    g
}

/// The 0-based column (in characters) of byte `at` in `src`.
pub(crate) fn column(src: &str, at: usize) -> usize {
    let line_start = src[..at].rfind('\n').map(|i| i + 1).unwrap_or(0);
    src[line_start..at].chars().count()
}

//! The layout of ladder rungs (`.ld`, and the rungs of a sequence's
//! ladder actions and transitions): one rung a line, labels in a column of
//! their own, the `->` of every rung of an action in one column, like the
//! rails of the diagram. The ST lexer does not know rungs (`|`, `->`, a
//! contact holding a bracketed name), so they are scanned here by hand.

use super::out::{Out, INDENT};
use super::printer::Printer;
use super::tokens::{column, tokens};

/// The column where conditions start when no label is longer.
const CONDITION_COLUMN: usize = 8;

enum Piece {
    /// A comment on its own line: text, column it stood at, blank line before.
    Comment(String, usize, bool),
    Header(String),
    /// `END_ACTION`, the comments before its `;` and whether it has one.
    End(String, bool),
    Rung(Rung),
}

#[derive(Default)]
struct Rung {
    label: Option<String>,
    cond: String,
    output: String,
    blank_before: bool,
    /// Comments after the `;` on the rung's line.
    trailing: Vec<String>,
}

struct Scan<'a> {
    s: &'a str,
    b: &'a [u8],
    pos: usize,
}

/// A `.ld` file.
pub(crate) fn format(src: &str) -> String {
    let start = if src.starts_with(crate::diag::files::BOM) { crate::diag::files::BOM.len_utf8() } else { 0 };
    let mut sc = Scan { s: src, b: src.as_bytes(), pos: start };
    let mut out = Out::default();
    let mut pieces = Vec::new();
    let mut first = true;
    loop {
        let more = sc.pieces(&mut pieces, first);
        first = false;
        let (mut group, mut indent) = (Vec::new(), 0);
        for p in pieces.drain(..) {
            match p {
                Piece::Header(h) => {
                    write_group(&mut out, &mut group, indent);
                    out.indent = 0;
                    out.newline();
                    out.put(&h, false);
                    indent = INDENT.len();
                }
                Piece::End(comments, semi) => {
                    write_group(&mut out, &mut group, indent);
                    indent = 0;
                    out.newline();
                    out.indent = 0;
                    out.put("END_ACTION", false);
                    out.put(&comments, false);
                    out.put(if semi { ";" } else { "" }, false);
                }
                other => group.push(other),
            }
        }
        write_group(&mut out, &mut group, indent);
        if !more {
            break;
        }
    }
    out.finish()
}

/// The rungs of a sequence's ladder action, each line indented `indent`
/// columns.
pub(crate) fn rungs(body: &str, indent: usize) -> String {
    let mut sc = Scan { s: body, b: body.as_bytes(), pos: 0 };
    let mut pieces = Vec::new();
    sc.pieces(&mut pieces, false);
    let mut out = Out::default();
    write_group(&mut out, &mut pieces, indent);
    out.newline();
    out.buf
}

/// A transition's rung without an output: `condition;`.
pub(crate) fn condition_rung(text: &str) -> String {
    let mut sc = Scan { s: text, b: text.as_bytes(), pos: 0 };
    let cond = sc.condition(b";");
    let mut rest = String::new();
    sc.pos = (sc.pos + 1).min(text.len());
    for c in sc.comments().0 {
        rest.push(' ');
        rest.push_str(&text[c.0..c.1]);
    }
    format!("{cond};{rest}")
}

/// Writes a run of rungs and comment lines, aligned.
fn write_group(out: &mut Out, group: &mut Vec<Piece>, indent: usize) {
    let rungs = group.iter().filter_map(|p| if let Piece::Rung(r) = p { Some(r) } else { None });
    let label = rungs.clone().filter_map(|r| r.label.as_ref()).map(|l| l.chars().count() + 2).max().unwrap_or(0);
    let cond_col = label.max(CONDITION_COLUMN);
    let widest = rungs.map(|r| r.cond.chars().count()).max().unwrap_or(0);
    let arrow_col = cond_col + widest + usize::from(widest > 0);
    for p in group.drain(..) {
        match p {
            Piece::Comment(text, was, blank) => {
                if blank {
                    out.blank();
                } else {
                    out.newline();
                }
                out.indent = indent;
                out.comment(&text, || was, false);
                out.newline();
            }
            Piece::Rung(r) => {
                if r.blank_before {
                    out.blank();
                } else {
                    out.newline();
                }
                let mut line = r.label.map(|l| format!("{l}:")).unwrap_or_default();
                pad(&mut line, cond_col);
                line.push_str(&r.cond);
                pad(&mut line, arrow_col);
                line.push_str("-> ");
                line.push_str(&r.output);
                line.push(';');
                for c in &r.trailing {
                    line.push(' ');
                    line.push_str(c);
                }
                out.indent = indent;
                out.put(&line, false);
            }
            Piece::Header(_) | Piece::End(..) => {}
        }
    }
}

fn pad(line: &mut String, col: usize) {
    let n = line.chars().count();
    line.extend(std::iter::repeat_n(' ', col.saturating_sub(n)));
}

/// ST text (an assignment, a contact's expression) laid out on one line.
fn st_inline(text: &str) -> String {
    let lexed = tokens(text);
    if lexed.toks.iter().any(|t| t.raw.is_none()) {
        return text.trim().to_string();
    }
    let mut p = Printer::new(text, &lexed);
    p.inline(lexed.toks.len());
    p.gap(lexed.tail, false);
    p.out.buf.trim().to_string()
}

impl Scan<'_> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.pos).copied()
    }

    fn at_word(&self, w: &str) -> bool {
        let end = self.pos + w.len();
        self.s.get(self.pos..end).is_some_and(|t| t.eq_ignore_ascii_case(w))
            && !self.b.get(end).is_some_and(|&c| c.is_ascii_alphanumeric() || c == b'_')
    }

    /// Skips blanks and comments: the comments (start, end, own line,
    /// blank before) and the line breaks after the last one.
    fn comments(&mut self) -> (Vec<(usize, usize, bool, bool)>, usize) {
        let mut found = Vec::new();
        let mut breaks = 0;
        while let Some(c) = self.peek() {
            if c == b'\n' {
                breaks += 1;
                self.pos += 1;
            } else if c.is_ascii_whitespace() {
                self.pos += 1;
            } else if self.s[self.pos..].starts_with("(*") {
                let end = self.s[self.pos + 2..].find("*)").map(|k| self.pos + 4 + k).unwrap_or(self.s.len());
                found.push((self.pos, end, breaks > 0, breaks > 1));
                breaks = 0;
                self.pos = end;
            } else {
                break;
            }
        }
        (found, breaks)
    }

    /// Reads pieces up to the end or up to an `ACTION` header after the
    /// first piece; true if a header stopped it.
    fn pieces(&mut self, pieces: &mut Vec<Piece>, at_start: bool) -> bool {
        let mut first = at_start;
        loop {
            let (comments, breaks) = self.comments();
            for (a, b, own, blank) in comments {
                let own = own || (first && pieces.is_empty());
                if own || !matches!(pieces.last(), Some(Piece::Rung(_))) {
                    let text = &self.s[a..b];
                    let was = if text.contains('\n') { column(self.s, a) } else { 0 };
                    pieces.push(Piece::Comment(text.to_string(), was, blank));
                } else if let Some(Piece::Rung(r)) = pieces.last_mut() {
                    r.trailing.push(self.s[a..b].to_string());
                }
                first = false;
            }
            if self.pos >= self.b.len() {
                return false;
            }
            if self.at_word("ACTION") && !pieces.is_empty() {
                return true;
            }
            if self.at_word("ACTION") {
                pieces.push(Piece::Header(self.header()));
            } else if self.at_word("END_ACTION") {
                self.pos += "END_ACTION".len();
                let save = self.pos;
                let mut before_semi = String::new();
                self.comments_into(&mut before_semi);
                let semi = self.peek() == Some(b';');
                self.pos = if semi { self.pos + 1 } else { save };
                if !semi {
                    before_semi.clear();
                }
                pieces.push(Piece::End(before_semi, semi));
                return self.pos < self.b.len();
            } else {
                let mut r = self.rung();
                r.blank_before = breaks > 1;
                pieces.push(Piece::Rung(r));
            }
            first = false;
        }
    }

    fn ident(&mut self) -> &str {
        let start = self.pos;
        while self.peek().is_some_and(|c| c.is_ascii_alphanumeric() || c == b'_') {
            self.pos += 1;
        }
        &self.s[start..self.pos]
    }

    /// Skips blanks and comments, writing each comment with a space
    /// before it: comments inside a header or between a label and its
    /// `:` stay where they were, on the one line.
    fn comments_into(&mut self, out: &mut String) {
        for (a, b, _, _) in self.comments().0 {
            out.push(' ');
            out.push_str(&self.s[a..b]);
        }
    }

    /// `ACTION name : TYPE`, with any comments between its words.
    fn header(&mut self) -> String {
        self.pos += "ACTION".len();
        let mut h = "ACTION".to_string();
        self.comments_into(&mut h);
        h.push(' ');
        h.push_str(self.ident());
        let save = self.pos;
        let mut before_colon = String::new();
        self.comments_into(&mut before_colon);
        if self.peek() == Some(b':') {
            self.pos += 1;
            h.push_str(&before_colon);
            h.push_str(" :");
            self.comments_into(&mut h);
            h.push(' ');
            h.push_str(self.ident());
        } else {
            // Comments on later lines are the body's (read as pieces).
            self.pos = save;
        }
        for c in self.trailing() {
            h.push(' ');
            h.push_str(&c);
        }
        h
    }

    fn rung(&mut self) -> Rung {
        let mut r = Rung::default();
        let save = self.pos;
        let mut word = self.ident().to_string();
        let named = !word.is_empty();
        self.comments_into(&mut word);
        if named && self.peek() == Some(b':') && self.b.get(self.pos + 1) != Some(&b'=') {
            // Comments after the `:` are read with the condition.
            self.pos += 1;
            r.label = Some(word);
        } else {
            self.pos = save;
        }
        r.cond = self.condition(b"-");
        self.pos = (self.pos + 2).min(self.s.len());
        let start = self.pos;
        self.skip_to(b';');
        r.output = output(&self.s[start..self.pos]);
        self.pos = (self.pos + 1).min(self.s.len());
        r.trailing = self.trailing();
        r
    }

    /// The comments after the cursor on its line (after a rung's `;`, an
    /// action's header), which stay on that line.
    fn trailing(&mut self) -> Vec<String> {
        let save = self.pos;
        let line_end = self.s[self.pos..].find('\n').map(|k| self.pos + k).unwrap_or(self.s.len());
        let (cs, _) = self.comments();
        self.pos = save;
        let mut found = Vec::new();
        for (a, b, _, _) in cs.into_iter().filter(|c| c.1 <= line_end) {
            found.push(self.s[a..b].to_string());
            self.pos = b;
        }
        found
    }

    /// A condition up to `->` (`stop` is `-`) or `;`, laid out.
    fn condition(&mut self, stop: &[u8]) -> String {
        let mut out = String::new();
        let mut prev = b' ';
        loop {
            let (cs, _) = self.comments();
            for (a, b, _, _) in cs {
                join(&mut out, prev, b'*');
                out.push_str(&self.s[a..b]);
                prev = b'*';
            }
            let Some(c) = self.peek() else { break };
            if stop.contains(&c) && (c != b'-' || self.b.get(self.pos + 1) == Some(&b'>')) {
                break;
            }
            match c {
                b'[' => {
                    let start = self.pos;
                    self.skip_bracket();
                    join(&mut out, prev, b'[');
                    out.push_str(&contact(&self.s[start + 1..self.pos - 1]));
                    prev = b']';
                }
                b'(' | b')' | b'|' | b',' => {
                    join(&mut out, prev, c);
                    out.push(c as char);
                    self.pos += 1;
                    prev = c;
                }
                _ if c.is_ascii_alphabetic() => {
                    let w = self.ident().to_ascii_uppercase();
                    join(&mut out, prev, b'a');
                    out.push_str(&w);
                    prev = b'a';
                }
                _ => {
                    // Not a rung element (the parser refuses such a file).
                    out.push(c as char);
                    self.pos += 1;
                }
            }
        }
        out
    }

    /// Moves past a `[…]` contact, whose expression may hold bracketed
    /// names and strings.
    fn skip_bracket(&mut self) {
        let mut depth = 0usize;
        while let Some(c) = self.peek() {
            match c {
                b'(' if self.b.get(self.pos + 1) == Some(&b'*') => {
                    self.comments();
                    continue;
                }
                b'[' => depth += 1,
                b']' => {
                    depth -= 1;
                    if depth == 0 {
                        self.pos += 1;
                        return;
                    }
                }
                b'\'' | b'"' => {
                    self.skip_string(c);
                    continue;
                }
                _ => {}
            }
            self.pos += 1;
        }
    }

    fn skip_string(&mut self, quote: u8) {
        self.pos += 1;
        while let Some(c) = self.peek() {
            self.pos += 1;
            if c == b'$' {
                self.pos += 1;
            } else if c == quote || c == b'\n' {
                return;
            }
        }
    }

    /// Moves to the `;` that ends an output, outside brackets, strings and
    /// comments.
    fn skip_to(&mut self, end: u8) {
        let mut depth = 0usize;
        while let Some(c) = self.peek() {
            match c {
                b'(' if self.b.get(self.pos + 1) == Some(&b'*') => {
                    self.comments();
                    continue;
                }
                b'(' | b'[' | b'{' => depth += 1,
                b')' | b']' | b'}' => depth = depth.saturating_sub(1),
                b'\'' | b'"' => {
                    self.skip_string(c);
                    continue;
                }
                _ if c == end && depth == 0 => return,
                _ => {}
            }
            self.pos += 1;
        }
    }
}

/// The space between two condition elements: none inside brackets, before
/// `)` and `,`, or between a box's name and its `(`.
fn join(out: &mut String, prev: u8, next: u8) {
    if out.is_empty() || prev == b'(' || next == b')' || next == b',' || (prev == b'a' && next == b'(') {
        return;
    }
    out.push(' ');
}

/// A contact `[…]` from the text between its brackets: comments before a
/// negating `/` stay before it.
fn contact(inner: &str) -> String {
    let mut t = inner.trim();
    let mut lead = String::new();
    while let Some(k) = t.strip_prefix("(*").and_then(|r| r.find("*)")) {
        lead.push_str(&t[..k + 4]);
        lead.push(' ');
        t = t[k + 4..].trim_start();
    }
    match t.strip_prefix('/') {
        Some(rest) => format!("[{lead}/{}]", st_inline(rest)),
        None => format!("[{}]", st_inline(inner.trim())),
    }
}

/// A coil, a jump or an assignment.
fn output(text: &str) -> String {
    let t = text.trim();
    if t.starts_with('(') && t.ends_with(')') && !t.contains("(*") {
        let inner = t[1..t.len() - 1].trim();
        if let Some(rest) = inner.strip_prefix('/') {
            return format!("(/{})", rest.trim());
        }
        let b = inner.as_bytes();
        if b.len() > 1 && matches!(b[0], b'S' | b'R' | b's' | b'r') && b[1].is_ascii_whitespace() {
            return format!("({} {})", (b[0] as char).to_ascii_uppercase(), inner[1..].trim());
        }
        return format!("({inner})");
    }
    let b = t.as_bytes();
    if b.len() > 4 && t[..4].eq_ignore_ascii_case("JUMP") && b[4].is_ascii_whitespace() {
        return format!("JUMP {}", t[4..].trim());
    }
    st_inline(t)
}

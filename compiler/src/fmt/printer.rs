//! The token printer shared by every language: ST statements and
//! expressions with the guide's layout, and the comments between tokens.

use super::out::{Out, INDENT};
use super::tokens::{column, Comment, Gap, Lexed, Token};
use crate::st::token::Raw;

pub(crate) struct Printer<'a> {
    pub src: &'a str,
    pub toks: &'a [Token],
    comments: &'a [Comment],
    pub pos: usize,
    pub out: Out,
    /// Columns every line of this part starts at (a nested chart's).
    pub base: usize,
    /// Statement nesting inside the part.
    pub level: usize,
    /// The token written last, and whether it was a sign.
    prev: Option<Raw>,
    prev_sign: bool,
    /// Bracket depth: a `;` inside brackets does not end a statement.
    depth: usize,
    /// The next token starts a line.
    pub brk: bool,
    /// A statement has begun and not ended: its further lines are indented
    /// once more.
    in_stmt: bool,
}

impl<'a> Printer<'a> {
    pub fn new(src: &'a str, lexed: &'a Lexed) -> Printer<'a> {
        Printer {
            src,
            toks: &lexed.toks,
            comments: &lexed.comments,
            pos: 0,
            out: Out::default(),
            base: 0,
            level: 0,
            prev: None,
            prev_sign: false,
            depth: 0,
            brk: false,
            in_stmt: false,
        }
    }

    pub fn raw(&self, i: usize) -> Option<Raw> {
        self.toks.get(i).and_then(|t| t.raw)
    }

    pub fn text(&self, i: usize) -> &'a str {
        self.toks.get(i).map(|t| &self.src[t.start..t.end]).unwrap_or("")
    }

    /// The token at `i` is the name `word` (a contextual keyword), any case.
    pub fn word_at(&self, i: usize, word: &str) -> bool {
        self.raw(i) == Some(Raw::Name) && self.text(i).eq_ignore_ascii_case(word)
    }

    fn set_indent(&mut self) {
        self.out.indent = self.base + INDENT.len() * (self.level + usize::from(self.in_stmt));
    }

    /// Starts a new line for what comes next (at a statement boundary).
    pub fn line(&mut self) {
        self.brk = true;
        self.in_stmt = false;
        self.prev = None;
    }

    /// Writes the comments before token `i` (or the text's tail gap) and
    /// the line breaks the layout wants before it.
    pub fn gap(&mut self, gap: Gap, starts_line: bool) {
        self.set_indent();
        let comments = &self.comments[gap.comments.0 as usize..gap.comments.1 as usize];
        let (n, src) = (comments.len(), self.src);
        for (k, c) in comments.iter().enumerate() {
            let text = &self.src[c.start..c.end];
            let newline_after = comments.get(k + 1).map(|d| d.own_line).unwrap_or(gap.newline);
            if c.own_line {
                if c.blank_before {
                    self.out.blank();
                } else {
                    self.out.newline();
                }
                self.set_indent();
                self.out.comment(text, || column(src, c.start), false);
                if newline_after {
                    self.out.newline();
                }
            } else {
                self.out.comment(text, || column(src, c.start), true);
                if newline_after && k + 1 < n {
                    self.out.newline();
                }
            }
        }
        // A comment that starts a line and has code after it on that line
        // (`(*SET POINT*) TIC.SL := 5;`) keeps the code beside it.
        let glued = comments.last().is_some_and(|c| c.own_line) && !gap.newline;
        if (starts_line || self.brk) && !glued {
            if gap.blank {
                self.out.blank();
            } else {
                self.out.newline();
            }
        }
        if glued {
            self.out.put("", true);
        }
        self.brk = false;
        self.set_indent();
    }

    /// The token's text as written out: keywords in capitals (§12), the
    /// `T#` of a time constant too, everything else as written.
    pub fn spelled(&self, i: usize) -> String {
        let text = self.text(i);
        match self.raw(i) {
            Some(r) if is_keyword(r) => text.to_ascii_uppercase(),
            Some(Raw::Time) => format!("T{}", &text[1..]),
            _ => text.to_string(),
        }
    }

    /// Writes token `i` (after its gap) with the spacing of ST.
    pub fn emit(&mut self, i: usize, starts_line: bool) {
        self.emit_spaced(i, starts_line, None);
    }

    /// [`Printer::emit`] with the space before the token decided by the
    /// caller (`Some`), where the chart structure differs from ST.
    pub fn emit_spaced(&mut self, i: usize, starts_line: bool, space: Option<bool>) {
        let t = &self.toks[i];
        self.gap(t.gap, starts_line);
        let raw = t.raw;
        let space = space.unwrap_or_else(|| self.space_before(raw, t.gap.adjacent));
        let text = self.spelled(i);
        self.out.put(&text, space);
        self.prev_sign = matches!(raw, Some(Raw::Minus | Raw::Plus)) && !self.prev.is_some_and(ends_operand);
        self.prev = raw;
        self.in_stmt = true;
        match raw {
            Some(Raw::LParen | Raw::LBrace) => self.depth += 1,
            Some(Raw::RParen | Raw::RBrace) => self.depth = self.depth.saturating_sub(1),
            _ => {}
        }
        self.pos = i + 1;
    }

    /// Writes `text` (not a token of the part: a rung, a separator) with a
    /// space before it.
    pub fn put(&mut self, text: &str) {
        self.set_indent();
        self.out.put(text, true);
        self.prev = Some(Raw::Name);
        self.in_stmt = true;
    }

    fn space_before(&self, cur: Option<Raw>, adjacent: bool) -> bool {
        let Some(prev) = self.prev else { return true };
        let Some(cur) = cur else { return !adjacent };
        if matches!(cur, Raw::Semi | Raw::Comma | Raw::RParen | Raw::RBrace | Raw::LBrace) {
            return false;
        }
        if matches!(prev, Raw::LParen | Raw::LBrace) || self.prev_sign {
            return false;
        }
        match cur {
            Raw::LParen => prev != Raw::Name,
            // `f[e]` and `F{n}.Bit0` mean what they mean because they touch.
            Raw::Bracketed | Raw::DotName | Raw::Dot if ends_operand(prev) => !adjacent,
            _ => true,
        }
    }

    /// Formats ST statements until `stop` says the token at `pos` ends
    /// them (or the tokens end). `ACTION` headers are laid out here too.
    pub fn statements(&mut self, stop: &dyn Fn(&Printer) -> bool) {
        while self.pos < self.toks.len() && !stop(self) {
            self.statement_token();
        }
    }

    fn statement_token(&mut self) {
        let i = self.pos;
        let raw = self.raw(i);
        let closes = matches!(
            raw,
            Some(Raw::Elsif | Raw::Else | Raw::EndIf | Raw::EndFor | Raw::EndWhile | Raw::Until | Raw::EndAction)
        );
        if closes || raw == Some(Raw::EndRepeat) {
            // Comments on their own lines before a closing keyword belong to
            // the block it closes, and keep its indentation.
            let gap = self.toks[i].gap;
            self.line();
            self.gap(gap, true);
            if closes {
                self.level = self.level.saturating_sub(1);
            }
            self.line();
            self.emit_without_gap(i);
            self.after_closer(raw);
            return;
        }
        if raw == Some(Raw::Action) && self.prev != Some(Raw::Colon) {
            self.line();
            self.emit(i, true);
            self.action_rest();
            return;
        }
        let starts = self.brk;
        self.emit(i, starts);
        match raw {
            Some(Raw::Then | Raw::Do | Raw::Else | Raw::Repeat) => {
                self.level += 1;
                self.line();
            }
            Some(Raw::Semi) if self.depth == 0 => self.line(),
            Some(Raw::EndAction) if self.raw(self.pos) != Some(Raw::Semi) => self.line(),
            _ => {}
        }
    }

    fn after_closer(&mut self, raw: Option<Raw>) {
        match raw {
            Some(Raw::Else) => {
                self.level += 1;
                self.line();
            }
            Some(Raw::EndAction) if self.raw(self.pos) != Some(Raw::Semi) => self.line(),
            _ => {}
        }
    }

    /// After `ACTION`: its name, `: TYPE`, and the body's indentation.
    fn action_rest(&mut self) {
        if self.pos < self.toks.len() {
            self.emit(self.pos, false);
        }
        if self.raw(self.pos) == Some(Raw::Colon) {
            self.emit(self.pos, false);
            if self.pos < self.toks.len() {
                self.emit(self.pos, false);
            }
        }
        self.level += 1;
        self.line();
    }

    /// Writes tokens up to (not including) index `end` on the current line,
    /// with expression spacing.
    pub fn inline(&mut self, end: usize) {
        while self.pos < end.min(self.toks.len()) {
            self.emit(self.pos, false);
        }
    }
}

/// The ST keywords, written in capitals.
fn is_keyword(r: Raw) -> bool {
    use Raw::*;
    matches!(
        r,
        If | Then
            | Elsif
            | Else
            | EndIf
            | For
            | To
            | By
            | Do
            | EndFor
            | While
            | EndWhile
            | Repeat
            | Until
            | EndRepeat
            | Exit
            | Action
            | EndAction
            | And
            | Or
            | Xor
            | Not
            | Mod
            | True
            | False
    )
}

/// After these an operator is expected (so a `-` after them is binary).
fn ends_operand(r: Raw) -> bool {
    use Raw::*;
    matches!(r, Name | DotName | Bracketed | Int | Based | Real | Time | Str | RParen | RBrace | True | False)
}

impl Printer<'_> {
    /// Writes token `i` in capitals (a contextual keyword: `STEP`, `FROM`).
    pub fn emit_upper(&mut self, i: usize, starts_line: bool) {
        let t = &self.toks[i];
        self.gap(t.gap, starts_line);
        let space = self.space_before(t.raw, t.gap.adjacent);
        let text = self.text(i).to_ascii_uppercase();
        self.out.put(&text, space);
        self.prev = t.raw;
        self.prev_sign = false;
        self.in_stmt = true;
        self.pos = i + 1;
    }

    /// Writes token `i` without the comments before it (they were part of
    /// a piece another formatter wrote).
    pub fn emit_without_gap(&mut self, i: usize) {
        self.brk = false;
        self.set_indent();
        let text = self.spelled(i);
        self.out.put(&text, false);
        self.prev = self.raw(i);
        self.in_stmt = true;
        self.pos = i + 1;
    }

    /// The indentation, in columns, of a new line at the current level.
    pub fn indent_cols(&self) -> usize {
        self.base + INDENT.len() * self.level
    }
}

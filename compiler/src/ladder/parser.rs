//! Reads a `.ld` text into a [`File`].
//!
//! The rung structure is read here, by hand, character by character: the
//! ST lexer would read `[Dig_1a.In]` as one bracketed name, and `|` and
//! `->` are not ST. What stands between a contact's brackets, inside a coil
//! and after `->` in a variable output is ST, handed as a slice of the text
//! to the ST parser; what it finds is moved to its place in the file. After
//! a mistake, reading resumes after the `;` that ends the rung, so one
//! mistake gives one error.

use super::ast::{Action, BoxOp, CoilKind, Cond, File, Output, Rung};
use crate::diag::span::Span;
use crate::diag::{Diagnostic, MAX_ERRORS};
use crate::sfc::shift;
use crate::st::ast::{Expr, Ident, Stmt};
use crate::st::errors::SyntaxError;
use crate::st::parser::{parse_expr, parse_file, ParseErrors};
use linc_format::Code;

/// How deeply branches and boxes may nest (the stack is not unbounded).
const MAX_DEPTH: usize = 32;

/// The most elements (contacts, function boxes and outputs) one action may
/// hold. Each costs about a kilobyte while the action is checked (its tree,
/// its ST, the checked program), so the limit bounds the memory of any
/// ladder file: a 48 MB series needed more than 4 GB without it. The
/// LINtools editor draws at most 48 rungs of 8 elements.
pub const MAX_ELEMENTS: usize = 10_000;

/// Parses a ladder file; `stem` names its action when it has no headers.
/// Every diagnostic of reading comes back, in the file's coordinates.
pub fn parse(src: &str, stem: &str) -> (File, Vec<Diagnostic>) {
    let mut actions = Vec::new();
    let diags = parse_each(src, stem, &mut |a| actions.push(a));
    (File { actions }, diags)
}

/// Parses a ladder file, handing each action to `each` as soon as it is
/// read, so that only one action is held at a time. Returns every
/// diagnostic of reading, in the file's coordinates.
pub fn parse_each(src: &str, stem: &str, each: &mut dyn FnMut(Action)) -> Vec<Diagnostic> {
    let mut p = Parser { src, b: src.as_bytes(), pos: 0, diags: Vec::new(), depth: 0, elements: 0 };
    // Rungs before any header are the file's one action, unless a header
    // follows; then they (and any after an action) are E0309.
    let (mut loose, mut first_loose, mut headers) = (Vec::new(), None, false);
    loop {
        p.ws();
        if p.pos >= p.b.len() {
            break;
        }
        if p.at_word("ACTION") {
            headers = true;
            loose = Vec::new();
            each(p.action());
        } else if p.at_word("END_ACTION") {
            p.error("a rung or `ACTION`");
            p.pos += "END_ACTION".len();
        } else if let Some(r) = p.rung() {
            first_loose.get_or_insert(r.span);
            if !headers {
                loose.push(r);
            }
        }
    }
    if !headers {
        let name = Ident { text: stem.into(), span: Span::new(0, 0) };
        each(Action { name, block_type: None, rungs: loose, header: None, span: Span::new(0, src.len()) });
    } else if let Some(span) = first_loose {
        let d = Diagnostic::error(Code::E0309, "rung outside an action", span)
            .label("this file has ACTION headers, so every rung must be inside one")
            .help("move the rung between `ACTION name` and `END_ACTION`, or remove the headers");
        p.push(d);
    }
    p.diags
}

/// An error already reported; the caller recovers.
struct Reported;

type R<T> = Result<T, Reported>;

struct Parser<'s> {
    src: &'s str,
    b: &'s [u8],
    pos: usize,
    diags: Vec<Diagnostic>,
    depth: usize,
    /// Elements read in the current action; past [`MAX_ELEMENTS`] the rest
    /// of the action is skipped.
    elements: usize,
}

/// Whether `text` is an ST keyword, which cannot name an action or a block
/// type in ST (so its ST, `linc ladder to-st`, would not read back).
fn keyword(text: &str) -> bool {
    !matches!(crate::st::lexer::Lexer::new(text).next(), Some((_, crate::st::lexer::Tok::Name(_), _)))
}

fn is_ident(c: u8) -> bool {
    c.is_ascii_alphanumeric() || c == b'_'
}

impl Parser<'_> {
    fn peek(&self) -> Option<u8> {
        self.b.get(self.pos).copied()
    }

    fn peek_at(&self, i: usize) -> Option<u8> {
        self.b.get(self.pos + i).copied()
    }

    fn push(&mut self, d: Diagnostic) {
        if self.diags.len() < MAX_ERRORS {
            self.diags.push(d);
        }
    }

    /// Skips blanks and `(* … *)` comments.
    fn ws(&mut self) {
        loop {
            while self.peek().is_some_and(|c| c.is_ascii_whitespace()) {
                self.pos += 1;
            }
            if !(self.peek() == Some(b'(') && self.peek_at(1) == Some(b'*')) {
                return;
            }
            let start = self.pos;
            match self.src[start + 2..].find("*)") {
                Some(i) => self.pos = start + 2 + i + 2,
                None => {
                    self.pos = self.b.len();
                    let d = Diagnostic::error(Code::E0003, "comment is not closed", Span::new(start, start + 2))
                        .label("this comment has no `*)`");
                    self.push(d);
                }
            }
        }
    }

    fn at_word(&self, w: &str) -> bool {
        let end = self.pos + w.len();
        self.b.len() >= end
            && self.b[self.pos..end].eq_ignore_ascii_case(w.as_bytes())
            && !self.b.get(end).is_some_and(|&c| is_ident(c) || c == b'.')
    }

    fn at(&self, s: &str) -> bool {
        self.b[self.pos.min(self.b.len())..].starts_with(s.as_bytes())
    }

    /// The span of the character (or end of file) at the cursor.
    fn here(&self) -> Span {
        let at = self.pos.min(self.src.len());
        let len = self.src[at..].chars().next().map_or(0, char::len_utf8);
        Span::new(at, at + len)
    }

    fn error(&mut self, expected: &str) -> Reported {
        let span = self.here();
        let d = match self.src[self.pos.min(self.src.len())..].chars().next() {
            None => Diagnostic::error(Code::E0300, format!("unexpected end of file, expected {expected}"), span)
                .label(format!("expected {expected}")),
            Some(c) => Diagnostic::error(Code::E0300, format!("unexpected `{c}`, expected {expected}"), span)
                .label(format!("expected {expected}")),
        };
        self.push(d);
        Reported
    }

    fn ident(&mut self) -> Option<Ident> {
        let start = self.pos;
        while self.peek().is_some_and(is_ident) {
            self.pos += 1;
        }
        (self.pos > start).then(|| Ident { text: self.src[start..self.pos].into(), span: Span::new(start, self.pos) })
    }

    /// Moves past the end of a broken rung: its `;`, or the `END_ACTION` or
    /// `ACTION` that follows it. Strings and comments are skipped whole.
    fn recover(&mut self) {
        while let Some(c) = self.peek() {
            match c {
                b';' => {
                    self.pos += 1;
                    return;
                }
                b'\'' | b'"' => self.skip_string(c),
                b'(' if self.peek_at(1) == Some(b'*') => self.ws(),
                _ if (self.pos == 0 || !is_ident(self.b[self.pos - 1]))
                    && (self.at_word("END_ACTION") || self.at_word("ACTION")) =>
                {
                    return
                }
                _ => self.pos += 1,
            }
        }
    }

    fn skip_string(&mut self, quote: u8) {
        self.pos += 1;
        while let Some(c) = self.peek() {
            self.pos += 1;
            if c == b'$' {
                // `$` escapes the next character; a `$` at the very end escapes nothing.
                self.pos = (self.pos + 1).min(self.b.len());
            } else if c == quote {
                return;
            }
        }
    }

    /// The end of the ST text that starts at the cursor: the first `closer`
    /// (one of `;`, `)`, `]`) not inside brackets, parentheses or a string.
    fn st_end(&self, closer: u8) -> Option<usize> {
        let (mut i, mut depth) = (self.pos, 0usize);
        while let Some(&c) = self.b.get(i) {
            match c {
                b'\'' | b'"' => {
                    i += 1;
                    while let Some(&d) = self.b.get(i) {
                        i += if d == b'$' { 2 } else { 1 };
                        if d == c {
                            break;
                        }
                    }
                    continue;
                }
                b'(' if self.b.get(i + 1) == Some(&b'*') => {
                    i = i + 2 + self.src[i + 2..].find("*)")? + 2;
                    continue;
                }
                _ if c == closer && depth == 0 => return Some(i),
                b'[' | b'(' | b'{' => depth += 1,
                b']' | b')' | b'}' if depth > 0 => depth -= 1,
                b';' => return None,
                _ => {}
            }
            i += 1;
        }
        None
    }

    /// Counts one element at `span`; the first over [`MAX_ELEMENTS`] is
    /// reported (E0313) and stops the rung.
    fn element(&mut self, span: Span) -> R<()> {
        self.elements += 1;
        if self.elements == MAX_ELEMENTS + 1 {
            let d = Diagnostic::error(Code::E0313, format!("more than {MAX_ELEMENTS} elements in one action"), span)
                .label(format!("element {}", MAX_ELEMENTS + 1))
                .help("split the rungs into several actions; the rest of this action is skipped");
            self.push(d);
        }
        if self.elements > MAX_ELEMENTS {
            return Err(Reported);
        }
        Ok(())
    }

    /// Places the ST parser's errors for the slice starting at `at`.
    fn slice_errors(&mut self, errors: ParseErrors, at: usize) {
        let lex = errors.lex.iter().map(|e| e.to_diagnostic());
        let syntax = errors.syntax.iter().map(|e| e.to_diagnostic());
        for mut d in lex.chain(syntax).collect::<Vec<_>>() {
            shift::diagnostic(&mut d, at);
            self.push(d);
        }
    }

    /// An ST expression in `a..b`, placed in the file.
    fn st_expr(&mut self, a: usize, b: usize) -> Option<Expr> {
        let (expr, errors) = parse_expr(&self.src[a..b]);
        let failed = !errors.lex.is_empty() || !errors.syntax.is_empty();
        self.slice_errors(errors, a);
        let mut e = expr?;
        shift::expr(&mut e, a);
        (!failed).then_some(e)
    }
}

impl Parser<'_> {
    /// `ACTION name [: BLOCKTYPE] rungs END_ACTION [;]`.
    fn action(&mut self) -> Action {
        let l = self.pos;
        self.pos += "ACTION".len();
        self.ws();
        let name = match self.ident() {
            Some(n) => n,
            None => {
                self.error("an action name");
                Ident { text: crate::st::ast::Name::default(), span: self.here() }
            }
        };
        if name.text.chars().count() > 8 || name.text.starts_with(|c: char| c.is_ascii_digit()) || keyword(&name.text) {
            self.push(SyntaxError::BadActionName { span: name.span, name: name.text.to_string() }.to_diagnostic());
        }
        self.ws();
        let mut block_type = None;
        if self.peek() == Some(b':') {
            self.pos += 1;
            self.ws();
            let at = self.pos;
            block_type = self.ident();
            match &block_type {
                None => {
                    self.error("a block type after `:`");
                }
                // ACTION is a keyword and a block type (as in ST).
                Some(t) if keyword(&t.text) && !t.text.eq_ignore_ascii_case("ACTION") => {
                    self.pos = at;
                    self.error("a block type after `:`");
                    self.pos = t.span.end;
                    block_type = None;
                }
                Some(_) => {}
            }
        }
        let header = Span::new(l, self.pos);
        let mut rungs = Vec::new();
        self.elements = 0;
        loop {
            self.ws();
            if self.at_word("END_ACTION") {
                self.pos += "END_ACTION".len();
                self.ws();
                if self.peek() == Some(b';') {
                    self.pos += 1;
                }
                break;
            }
            if self.pos >= self.b.len() || self.at_word("ACTION") {
                self.error("`END_ACTION`");
                break;
            }
            if let Some(r) = self.rung() {
                rungs.push(r);
            }
        }
        self.elements = 0;
        Action { name, block_type, rungs, header: Some(header), span: Span::new(l, self.pos) }
    }

    /// One rung; `None` when it did not parse (reported, skipped).
    fn rung(&mut self) -> Option<Rung> {
        if self.elements > MAX_ELEMENTS {
            // Over the limit (reported): skipped unread.
            self.recover();
            return None;
        }
        let start = self.pos;
        match self.rung_body(start) {
            Ok(r) => Some(r),
            Err(Reported) => {
                self.recover();
                None
            }
        }
    }

    fn rung_body(&mut self, start: usize) -> R<Rung> {
        let label = self.label();
        self.ws();
        let cond = if self.at("->") { None } else { Some(self.series().inspect_err(|_| self.st_hint(start))?) };
        self.ws();
        if !self.at("->") {
            let r = self.error("a contact, a branch or `->`");
            self.st_hint(start);
            return Err(r);
        }
        self.pos += 2;
        self.ws();
        let output = self.output()?;
        let end = self.pos;
        self.ws();
        if self.peek() != Some(b';') {
            let d = Diagnostic::error(Code::E0300, "expected `;` after the rung's output", Span::new(end, end))
                .label("`;` expected here")
                .help("every rung ends with `;`, the last one too");
            self.push(d);
            return Err(Reported);
        }
        self.pos += 1;
        Ok(Rung { label, cond, output, span: Span::new(start, self.pos) })
    }

    /// When the broken rung starting at `start` reads like an ST statement
    /// (a `:=` and no `->` before its `;`), says how to write it in ladder.
    fn st_hint(&mut self, start: usize) {
        let rest = &self.src[start..];
        let rung = &rest[..rest.find(';').unwrap_or(rest.len())];
        if rung.contains(":=") && !rung.contains("->") {
            if let Some(d) = self.diags.last_mut() {
                d.help.push(
                    "a ladder action holds rungs, not ST statements: write a variable output as `-> target := value;` \
                     (ST actions go in a .st or .stx file)"
                        .into(),
                );
            }
        }
    }

    /// `name:` (not `:=`) at the start of a rung.
    fn label(&mut self) -> Option<Ident> {
        let save = self.pos;
        let id = self.ident()?;
        self.ws();
        if self.peek() == Some(b':') && self.peek_at(1) != Some(b'=') {
            self.pos += 1;
            return Some(id);
        }
        self.pos = save;
        None
    }

    /// Elements in series, up to `->`, `|`, `,` or `)`.
    fn series(&mut self) -> R<Cond> {
        let mut terms = Vec::new();
        loop {
            self.ws();
            let boxed = [("AND", BoxOp::And), ("OR", BoxOp::Or), ("XOR", BoxOp::Xor), ("NOT", BoxOp::Not)]
                .into_iter()
                .find(|(w, _)| self.at_word(w));
            match self.peek() {
                Some(b'[') => terms.push(self.contact()?),
                Some(b'(') => terms.push(self.nested(|p| p.parallel())?),
                _ if boxed.is_some() => terms.push(self.nested(|p| p.function_box(boxed.map_or(BoxOp::And, |b| b.1)))?),
                _ => break,
            }
        }
        match terms.len() {
            0 => Err(self.error("a contact `[x]`, a branch `( … | … )` or a function box")),
            1 => Ok(terms.pop().unwrap_or(Cond::Series(Vec::new()))),
            _ => Ok(Cond::Series(terms)),
        }
    }

    fn nested(&mut self, f: impl FnOnce(&mut Self) -> R<Cond>) -> R<Cond> {
        if self.depth >= MAX_DEPTH {
            let span = self.here();
            self.push(
                Diagnostic::error(Code::E0300, "branches nested too deeply", span)
                    .label(format!("more than {MAX_DEPTH} branches or boxes inside each other")),
            );
            return Err(Reported);
        }
        self.depth += 1;
        let r = f(self);
        self.depth -= 1;
        r
    }

    /// `[x]` or `[/x]`.
    fn contact(&mut self) -> R<Cond> {
        let open = self.pos;
        self.element(Span::new(open, open + 1))?;
        self.pos += 1;
        let Some(close) = self.st_end(b']') else {
            let d = Diagnostic::error(Code::E0301, "contact is not closed", Span::new(open, open + 1))
                .label("this `[` has no `]` before the end of the rung");
            self.push(d);
            return Err(Reported);
        };
        // Blanks and comments (closed before `close`: `st_end` skipped
        // them whole) may come before the `/` as anywhere else.
        loop {
            while self.pos < close && self.peek().is_some_and(|c| c.is_ascii_whitespace()) {
                self.pos += 1;
            }
            match self.src[self.pos..close].strip_prefix("(*").and_then(|r| r.find("*)")) {
                Some(k) => self.pos += 2 + k + 2,
                None => break,
            }
        }
        let negated = self.peek() == Some(b'/') && self.pos < close;
        if negated {
            self.pos += 1;
        }
        let (a, span) = (self.pos, Span::new(open, close + 1));
        self.pos = close + 1;
        if self.src[a..close].trim().is_empty() {
            self.push(
                Diagnostic::error(Code::E0311, "empty contact", span)
                    .label("a contact needs a variable or a condition"),
            );
            return Err(Reported);
        }
        let expr = self.st_expr(a, close).ok_or(Reported)?;
        Ok(Cond::Contact { negated, expr, span })
    }

    /// `( a | b | … )`.
    fn parallel(&mut self) -> R<Cond> {
        let open = self.pos;
        self.pos += 1;
        let mut branches = vec![self.series()?];
        loop {
            self.ws();
            match self.peek() {
                Some(b'|') => {
                    self.pos += 1;
                    branches.push(self.series()?);
                }
                Some(b')') => break,
                _ => return Err(self.error("`|` or `)`")),
            }
        }
        self.pos += 1;
        Ok(Cond::Parallel(branches, Span::new(open, self.pos)))
    }

    /// `AND(…)`, `OR(…)`, `XOR(…)`, `NOT(…)`.
    fn function_box(&mut self, op: BoxOp) -> R<Cond> {
        let start = self.pos;
        self.element(Span::new(start, start + op.name().len()))?;
        self.pos += op.name().len();
        self.ws();
        if self.peek() != Some(b'(') {
            return Err(self.error("`(` after the function box"));
        }
        self.pos += 1;
        let mut args = vec![self.series()?];
        loop {
            self.ws();
            match self.peek() {
                Some(b',') => {
                    self.pos += 1;
                    args.push(self.series()?);
                }
                Some(b')') => break,
                _ => return Err(self.error("`,` or `)`")),
            }
        }
        self.pos += 1;
        let span = Span::new(start, self.pos);
        let ok = if op == BoxOp::Not { args.len() == 1 } else { args.len() >= 2 };
        if !ok {
            let want = if op == BoxOp::Not { "exactly one input" } else { "two or more inputs" };
            let d = Diagnostic::error(Code::E0310, format!("{} box with {} input(s)", op.name(), args.len()), span)
                .label(format!("{} takes {want}", op.name()));
            self.push(d);
        }
        Ok(Cond::Box { op, args, span })
    }

    /// A coil, a jump or a variable output.
    fn output(&mut self) -> R<Output> {
        let start = self.pos;
        self.element(self.here())?;
        if self.peek() == Some(b'(') {
            return self.coil();
        }
        if self.at_word("JUMP") {
            self.pos += 4;
            self.ws();
            let Some(label) = self.ident() else { return Err(self.error("a label after JUMP")) };
            return Ok(Output::Jump { span: Span::new(start, label.span.end), label });
        }
        let Some(semi) = self.st_end(b';') else {
            return Err(self.error("a coil `(x)`, `JUMP label` or `target := value` ended by `;`"));
        };
        let (file, errors) = parse_file(&self.src[start..=semi], "rung");
        let failed = !errors.lex.is_empty() || !errors.syntax.is_empty();
        self.slice_errors(errors, start);
        self.pos = semi;
        let mut stmts = file.and_then(|f| f.actions.into_iter().next()).map(|a| a.body).unwrap_or_default();
        if failed {
            return Err(Reported);
        }
        match (stmts.len(), stmts.pop()) {
            (1, Some(s @ Stmt::Assign { .. })) => {
                let mut a = crate::st::ast::Action {
                    name: Ident { text: crate::st::ast::Name::default(), span: Span::default() },
                    block_type: None,
                    body: vec![s],
                    header: None,
                    span: Span::default(),
                };
                shift::action(&mut a, start);
                Ok(Output::Assign(a.body.remove(0)))
            }
            _ => {
                self.pos = start;
                Err(self.error("a coil `(x)`, `JUMP label` or one assignment `target := value`"))
            }
        }
    }

    /// `(x)`, `(/x)`, `(S x)`, `(R x)`.
    fn coil(&mut self) -> R<Output> {
        let open = self.pos;
        self.pos += 1;
        self.ws();
        let kind = match (self.peek(), self.peek_at(1)) {
            (Some(b'/'), _) => CoilKind::Negated,
            (Some(b'S' | b's'), Some(c)) if c.is_ascii_whitespace() => CoilKind::Set,
            (Some(b'R' | b'r'), Some(c)) if c.is_ascii_whitespace() => CoilKind::Reset,
            _ => CoilKind::Normal,
        };
        if kind != CoilKind::Normal {
            self.pos += 1;
        }
        let a = self.pos;
        let Some(close) = self.st_end(b')') else {
            return Err(self.error("a coil's variable and `)`"));
        };
        self.pos = close + 1;
        let span = Span::new(open, self.pos);
        if self.src[a..close].trim().is_empty() {
            self.push(
                Diagnostic::error(Code::E0308, "coil without a variable", span).label("a coil writes a variable"),
            );
            return Err(Reported);
        }
        let target = self.st_expr(a, close).ok_or(Reported)?;
        Ok(Output::Coil { kind, target, span })
    }
}

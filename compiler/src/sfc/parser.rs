//! Reads a `.sfc` text into a [`Sequence`].
//!
//! The chart structure is read here, by hand, from the ST lexer's tokens:
//! `STEP`, `TRANSITION`, `FROM`, `PRIORITY`, `CHART` and the qualifiers are
//! contextual words (plain names to the ST lexer), so a database field
//! called `S` or `D` still works in ST code. The ST inside (action bodies
//! and transition conditions) is handed, as a slice of the text, to the ST
//! parser, and what it finds is moved to its place in the file. After a
//! mistake, reading resumes after the `END_STEP`, `END_TRANSITION` or
//! `END_ACTION` that closes it, so one mistake gives one error.

use super::ast::{Action, ActionBody, Assoc, Chart, Sequence, Step, Transition};
use super::errors::SfcError;
use super::shift;
use crate::diag::span::Span;
use crate::diag::{Diagnostic, MAX_ERRORS};
use crate::st::ast::{Action as StAction, Ident};
use crate::st::errors::SyntaxError;
use crate::st::lexer::{Lexer, Spanned, Tok};
use crate::st::parser::{parse_expr, parse_file, ParseErrors};
use linc_format::Code;
use std::cell::RefCell;
use std::collections::VecDeque;

/// Parses a sequence; every diagnostic of lexing and parsing comes back,
/// placed in the file (not yet sorted or deduplicated).
pub fn parse(src: &str) -> (Sequence, Vec<Diagnostic>) {
    let window = Window { lexer: Lexer::new(src), held: VecDeque::new(), first: 0 };
    let mut p = Parser { src, toks: RefCell::new(window), pos: 0, diags: Vec::new(), ladder: Vec::new() };
    let mut sequence = Sequence { chart: Chart::default(), actions: Vec::new() };
    p.items(&mut sequence.chart, Some(&mut sequence.actions));
    fit(&mut sequence.chart);
    let mut lexer = p.toks.into_inner().lexer;
    lexer.by_ref().for_each(drop);
    let lex_errors = lexer.errors.into_parts().0;
    // The ST lexer does not know rungs (`|`, `->`): the ladder front end
    // reads the bodies of ladder actions and reports their errors itself.
    let in_ladder = |at: usize| p.ladder.iter().any(|&(l, r)| (l..r).contains(&at));
    let mut diags: Vec<Diagnostic> =
        lex_errors.iter().map(|e| e.to_diagnostic()).filter(|d| !in_ladder(d.span.start)).collect();
    diags.append(&mut p.diags);
    (sequence, diags)
}

/// Gives back the room a chart's lists grew beyond their items, before the
/// checks add their tables to the tree.
fn fit(chart: &mut Chart) {
    chart.steps.shrink_to_fit();
    chart.transitions.shrink_to_fit();
}

/// The words that start an item; reading resumes at them after an error.
const STARTERS: [&str; 3] = ["STEP", "INITIAL_STEP", "TRANSITION"];

/// The tokens from the start of the item being read on, lexed as the
/// parser reaches them: the whole file's tokens (40 bytes each, about 10
/// times the text) are never held at once (issue 30).
struct Window<'s> {
    lexer: Lexer<'s>,
    held: VecDeque<Spanned<'s>>,
    /// The index in the file's tokens of `held[0]`.
    first: usize,
}

struct Parser<'s> {
    src: &'s str,
    /// Interior mutability lets the read-only helpers (`tok`, `here`, …)
    /// lex ahead.
    toks: RefCell<Window<'s>>,
    pos: usize,
    diags: Vec<Diagnostic>,
    /// Byte ranges of ladder action bodies.
    ladder: Vec<(usize, usize)>,
}

/// An error already reported; the caller recovers.
struct Reported;

type R<T> = Result<T, Reported>;

impl<'s> Parser<'s> {
    /// The token at index `i` of the file, lexing up to it.
    fn at(&self, i: usize) -> Option<Spanned<'s>> {
        let mut w = self.toks.borrow_mut();
        let k = i.checked_sub(w.first).expect("a token the parser let go of");
        while w.held.len() <= k {
            let t = w.lexer.next()?;
            w.held.push_back(t);
        }
        w.held.get(k).copied()
    }

    /// A token already read.
    fn nth(&self, i: usize) -> Spanned<'s> {
        self.at(i).expect("a token read before")
    }

    /// Lets go of the tokens before the last one read: an item looks back
    /// only within itself, and its end is where the last token read ends.
    fn forget_read(&mut self) {
        let w = self.toks.get_mut();
        let keep = self.pos.saturating_sub(1);
        while w.first < keep && w.held.pop_front().is_some() {
            w.first += 1;
        }
    }

    fn tok(&self) -> Option<Tok<'s>> {
        self.at(self.pos).map(|t| t.1)
    }

    fn here(&self) -> Span {
        match self.at(self.pos) {
            Some(t) => Span::new(t.0, t.2),
            None => Span::new(self.src.len(), self.src.len()),
        }
    }

    fn word_at(&self, i: usize, word: &str) -> bool {
        matches!(self.at(i), Some((_, Tok::Name(n), _)) if n.eq_ignore_ascii_case(word))
    }

    fn word(&self, word: &str) -> bool {
        self.word_at(self.pos, word)
    }

    /// At a word that starts an item, or at `ACTION`/`END_ACTION`.
    fn at_starter(&self) -> bool {
        STARTERS.iter().any(|w| self.word(w)) || matches!(self.tok(), Some(Tok::Action | Tok::EndAction))
    }

    fn push(&mut self, d: Diagnostic) {
        if self.diags.len() < MAX_ERRORS {
            self.diags.push(d);
        }
    }

    fn error(&mut self, expected: &'static str) -> Reported {
        let span = self.here();
        let e = match self.tok() {
            None => SfcError::UnexpectedEof { span, expected },
            Some(t) => SfcError::Unexpected { span, found: t.describe(), expected },
        };
        self.push(e.to_diagnostic());
        Reported
    }

    fn expect(&mut self, tok: Tok<'static>, expected: &'static str) -> R<Span> {
        if self.tok() == Some(tok) {
            self.pos += 1;
            return Ok(Span::new(self.nth(self.pos - 1).0, self.nth(self.pos - 1).2));
        }
        Err(self.error(expected))
    }

    fn expect_word(&mut self, word: &str, expected: &'static str) -> R<()> {
        if self.word(word) {
            self.pos += 1;
            return Ok(());
        }
        Err(self.error(expected))
    }

    fn name(&mut self, expected: &'static str) -> R<Ident> {
        match self.at(self.pos) {
            Some((l, Tok::Name(n), r)) => {
                self.pos += 1;
                Ok(Ident { text: n.trim().into(), span: Span::new(l, r) })
            }
            _ => Err(self.error(expected)),
        }
    }

    fn semi(&mut self) {
        if self.tok() == Some(Tok::Semi) {
            self.pos += 1;
        }
    }

    /// Skips to just after the `end` word (and its `;`), or to the next item.
    fn recover(&mut self, end: &str) {
        while self.tok().is_some() {
            if self.word(end) {
                self.pos += 1;
                self.semi();
                return;
            }
            if self.at_starter() {
                return;
            }
            self.pos += 1;
        }
    }

    /// Reads steps, transitions and (at the top, where `actions` is given)
    /// actions; a nested chart stops at its `END_ACTION`.
    fn items(&mut self, chart: &mut Chart, mut actions: Option<&mut Vec<Action>>) {
        while let Some(t) = self.tok() {
            self.forget_read();
            if self.word("STEP") || self.word("INITIAL_STEP") {
                self.step(chart);
            } else if self.word("TRANSITION") {
                self.transition(chart);
            } else if matches!(t, Tok::Action | Tok::EndAction) && actions.is_none() {
                return;
            } else if let (Tok::Action, Some(list)) = (t, actions.as_deref_mut()) {
                let a = self.action();
                list.push(a);
            } else {
                let expected = if actions.is_some() {
                    "`STEP`, `INITIAL_STEP`, `TRANSITION` or `ACTION`"
                } else {
                    "`STEP`, `INITIAL_STEP`, `TRANSITION` or `END_ACTION`"
                };
                self.error(expected);
                self.pos += 1;
                while self.tok().is_some() && !self.at_starter() {
                    self.pos += 1;
                }
            }
        }
    }

    fn step(&mut self, chart: &mut Chart) {
        let l = self.here().start;
        let initial = self.word("INITIAL_STEP");
        self.pos += 1;
        let Ok(name) = self.name("a step name") else {
            return self.recover("END_STEP");
        };
        self.check_name(&name, "a step name has no dots");
        let mut step = Step { name, initial, assocs: Vec::new(), span: Span::new(l, l) };
        if self.step_body(&mut step).is_err() {
            self.recover("END_STEP");
        }
        step.span = Span::new(l, self.prev_end());
        // A step has few associations: a Vec's first growth makes room for
        // four (512 bytes, more than the step's text).
        step.assocs.shrink_to_fit();
        chart.steps.push(step);
    }

    fn prev_end(&self) -> usize {
        self.pos.checked_sub(1).and_then(|i| self.at(i)).map(|t| t.2).unwrap_or(0)
    }

    /// The associations of a step. A missing `:` is reported and reading
    /// goes on; a broken association is skipped to its `;`, so the ones
    /// after it still count (and their actions are not reported unused).
    fn step_body(&mut self, step: &mut Step) -> R<()> {
        if self.expect(Tok::Colon, "`:` after the step name").is_err() && self.tok() == Some(Tok::Colon) {
            self.pos += 1;
        }
        while !self.word("END_STEP") {
            if self.tok().is_none() || self.at_starter() {
                return Err(self.error("an action association or `END_STEP`"));
            }
            match self.assoc() {
                Ok(a) => step.assocs.push(a),
                Err(Reported) => self.skip_assoc(),
            }
        }
        self.pos += 1;
        self.semi();
        Ok(())
    }

    /// Skips past the `;` that ends a broken association, stopping before
    /// `END_STEP` or the next item.
    fn skip_assoc(&mut self) {
        while self.tok().is_some() && !self.word("END_STEP") && !self.at_starter() {
            self.pos += 1;
            if self.nth(self.pos - 1).1 == Tok::Semi {
                return;
            }
        }
    }

    /// `Action(Q);` or `Action(Q, T#…);`.
    fn assoc(&mut self) -> R<Assoc> {
        let action = self.name("an action name")?;
        self.expect(Tok::LParen, "`(` and a qualifier after the action name")?;
        let qualifier = self.name("a qualifier: P, N, L, D, E, F, S or R")?;
        let mut time = None;
        if self.tok() == Some(Tok::Comma) {
            self.pos += 1;
            match self.at(self.pos) {
                Some((l, Tok::Time(t), r)) => {
                    self.pos += 1;
                    time = Some((t, Span::new(l, r)));
                }
                _ => return Err(self.error("a time constant such as T#10s")),
            }
        }
        let r = self.expect(Tok::RParen, "`)`")?;
        // A missing `;` is reported; the association is whole and kept.
        let _ = self.expect(Tok::Semi, "`;` after the association");
        Ok(Assoc { span: Span::new(action.span.start, r.end), action, qualifier, time })
    }

    /// Step and transition names follow the identifier rules (§12.8).
    fn check_name(&mut self, name: &Ident, dotted: &'static str) {
        let (span, text) = (name.span, name.text.clone());
        let e = if text.contains('.') {
            SyntaxError::InvalidName { span, name: text.to_string(), why: dotted }
        } else if text.starts_with(|c: char| c.is_ascii_digit()) {
            SyntaxError::InvalidName { span, name: text.to_string(), why: "starts with a digit" }
        } else if text.chars().count() > 8 {
            SyntaxError::NameTooLong { span, name: text.to_string() }
        } else {
            return;
        };
        self.push(e.to_diagnostic());
    }
}

impl Parser<'_> {
    fn transition(&mut self, chart: &mut Chart) {
        let l = self.here().start;
        self.pos += 1;
        let mut t = Transition {
            name: None,
            priority: None,
            from: Vec::new(),
            to: Vec::new(),
            cond: None,
            ladder: None,
            span: Span::new(l, l),
        };
        if self.transition_body(&mut t).is_err() {
            chart.broken = true;
            self.recover("END_TRANSITION");
        }
        t.span = Span::new(l, self.prev_end());
        chart.transitions.push(t);
    }

    fn transition_body(&mut self, t: &mut Transition) -> R<()> {
        if matches!(self.tok(), Some(Tok::Name(_))) && !self.word("FROM") {
            let n = self.name("a transition name")?;
            self.check_name(&n, "a transition name has no dots");
            t.name = Some(Box::new(n));
        }
        if self.tok() == Some(Tok::LParen) {
            self.pos += 1;
            self.expect_word("PRIORITY", "`PRIORITY`")?;
            self.expect(Tok::Assign, "`:=` after PRIORITY")?;
            match self.at(self.pos) {
                Some((l, Tok::Int(n), r)) => {
                    self.pos += 1;
                    t.priority = Some(Box::new((n, Span::new(l, r))));
                }
                _ => return Err(self.error("a priority number")),
            }
            self.expect(Tok::RParen, "`)`")?;
        }
        self.expect_word("FROM", "`FROM` and the steps the transition leaves")?;
        t.from = self.steps()?;
        self.expect(Tok::To, "`TO` and the steps the transition leads to")?;
        t.to = self.steps()?;
        if self.tok() == Some(Tok::Colon) && self.word_at(self.pos + 1, "LADDER") {
            self.pos += 2;
            return self.ladder_condition(t);
        }
        self.expect(Tok::Assign, "`:=` and the transition condition")?;
        self.condition(t)
    }

    /// `… : LADDER <contacts>; END_TRANSITION` (§20.5.7): one rung without
    /// an output, read by the ladder front end and desugared into the ST
    /// condition it stands for.
    fn ladder_condition(&mut self, t: &mut Transition) -> R<()> {
        let a = self.at(self.pos).map_or(self.src.len(), |tok| tok.0);
        while self.tok().is_some() && self.tok() != Some(Tok::Semi) && !self.word("END_TRANSITION") {
            self.pos += 1;
        }
        let b = self.at(self.pos).map_or(self.src.len(), |tok| tok.0);
        if self.tok() != Some(Tok::Semi) {
            return Err(self.error("`;` after the ladder condition"));
        }
        self.pos += 1;
        self.ladder.push((a, b));
        t.ladder = Some(Box::new(Span::new(a, b)));
        let (cond, diagnostics) = crate::ladder::desugar_condition(&self.src[a..b]);
        for mut d in diagnostics {
            shift::diagnostic(&mut d, a);
            self.push(d);
        }
        t.cond = cond.map(|mut e| {
            shift::expr(&mut e, a);
            e
        });
        self.expect_word("END_TRANSITION", "`END_TRANSITION`")?;
        self.semi();
        Ok(())
    }

    /// A step name or `(a, b, …)`.
    fn steps(&mut self) -> R<Vec<Ident>> {
        if self.tok() != Some(Tok::LParen) {
            return Ok(vec![self.name("a step name or `(` and a list of steps")?]);
        }
        self.pos += 1;
        let mut list = vec![self.name("a step name")?];
        while self.tok() == Some(Tok::Comma) {
            self.pos += 1;
            list.push(self.name("a step name")?);
        }
        self.expect(Tok::RParen, "`,` or `)`")?;
        Ok(list)
    }

    /// The condition runs to the `;` before `END_TRANSITION`; the ST parser
    /// reads it.
    fn condition(&mut self, t: &mut Transition) -> R<()> {
        let first = self.pos;
        while self.tok().is_some() && !self.word("END_TRANSITION") && !self.at_starter() {
            self.pos += 1;
        }
        let end = self.pos;
        let has_semi = end > first && self.nth(end - 1).1 == Tok::Semi;
        let last = if has_semi { end - 1 } else { end };
        if last == first {
            self.pos = first;
            return Err(self.error("a transition condition"));
        }
        let (a, b) = (self.nth(first).0, self.nth(last - 1).2);
        let (expr, errors) = parse_expr(&self.src[a..b]);
        self.slice_errors(errors, a, b, last);
        t.cond = expr.map(|mut e| {
            shift::expr(&mut e, a);
            e
        });
        if !has_semi {
            return Err(self.error("`;` after the condition"));
        }
        self.expect_word("END_TRANSITION", "`END_TRANSITION`")?;
        self.semi();
        Ok(())
    }

    /// Places the ST parser's errors for the slice starting at `at` in the
    /// file. The slice's end is not the file's: "unexpected end of file"
    /// there becomes "unexpected" the token that follows the slice, `next`.
    fn slice_errors(&mut self, errors: ParseErrors, at: usize, end: usize, next: usize) {
        let lex = errors.lex.iter().map(|e| e.to_diagnostic());
        let syntax = errors.syntax.iter().map(|e| e.to_diagnostic());
        for mut d in lex.chain(syntax).collect::<Vec<_>>() {
            shift::diagnostic(&mut d, at);
            if let (Some((l, t, r)), Code::E0011, true) = (self.at(next), d.code, d.span.start >= end) {
                d.code = Code::E0010;
                d.message = format!("unexpected {}", t.describe());
                d.span = Span::new(l, r);
            }
            self.push(d);
        }
    }

    fn action(&mut self) -> Action {
        let l = self.here().start;
        let is_chart = matches!(self.at(self.pos + 2), Some((_, Tok::Colon, _))) && self.word_at(self.pos + 3, "CHART");
        if is_chart {
            return self.chart_action(l);
        }
        let is_ladder =
            matches!(self.at(self.pos + 2), Some((_, Tok::Colon, _))) && self.word_at(self.pos + 3, "LADDER");
        if is_ladder {
            return self.ladder_action(l);
        }
        self.st_action(l)
    }

    /// `ACTION name : LADDER rungs END_ACTION` (§10.2.2): the rungs are read
    /// by the ladder front end and desugared into ST (ADR 0009), so the
    /// action checks and compiles like an ST action. Contacts and coils are
    /// typed by the ST checker here (its codes, not the ladder's).
    fn ladder_action(&mut self, l: usize) -> Action {
        let name = match self.at(self.pos + 1) {
            Some((nl, Tok::Name(n), nr)) => Ident { text: n.trim().into(), span: Span::new(nl, nr) },
            _ => Ident { text: crate::st::ast::Name::default(), span: self.here() },
        };
        let body_start = self.at(self.pos + 3).map_or(l, |t| t.2);
        self.pos += 4;
        while self.tok().is_some() && !matches!(self.tok(), Some(Tok::EndAction | Tok::Action)) {
            self.pos += 1;
        }
        let body_end = if self.tok().is_some() { self.here().start } else { self.src.len() };
        if self.expect(Tok::EndAction, "`END_ACTION`").is_ok() {
            self.semi();
        }
        self.ladder.push((body_start, body_end));
        let (st, diagnostics) = crate::ladder::desugar_body(&self.src[body_start..body_end], &name.text);
        for mut d in diagnostics {
            shift::diagnostic(&mut d, body_start);
            self.push(d);
        }
        let mut st = st;
        shift::action(&mut st, body_start);
        st.name = name.clone();
        Action { name, body: ActionBody::St(st), span: Span::new(l, self.prev_end()) }
    }

    /// `ACTION name : CHART steps and transitions END_ACTION`.
    fn chart_action(&mut self, l: usize) -> Action {
        self.pos += 1;
        let name = match self.at(self.pos) {
            Some((nl, Tok::Name(n), nr)) => Ident { text: n.trim().into(), span: Span::new(nl, nr) },
            _ => {
                self.error("an action name");
                Ident { text: crate::st::ast::Name::default(), span: self.here() }
            }
        };
        if name.text.contains('.')
            || name.text.chars().count() > 8
            || name.text.starts_with(|c: char| c.is_ascii_digit())
        {
            self.push(SyntaxError::BadActionName { span: name.span, name: name.text.to_string() }.to_diagnostic());
        }
        self.pos += 3;
        let mut chart = Chart::default();
        self.items(&mut chart, None);
        fit(&mut chart);
        if self.expect(Tok::EndAction, "`END_ACTION`").is_ok() {
            self.semi();
        }
        Action { name, body: ActionBody::Chart(chart), span: Span::new(l, self.prev_end()) }
    }

    /// `ACTION name … END_ACTION`, read by the ST parser; it runs to its
    /// `END_ACTION`, or up to the next `ACTION` if that is missing.
    fn st_action(&mut self, l: usize) -> Action {
        let first = self.pos;
        self.pos += 1;
        while self.tok().is_some() && !matches!(self.tok(), Some(Tok::EndAction | Tok::Action)) {
            self.pos += 1;
        }
        if self.tok() == Some(Tok::EndAction) {
            self.pos += 1;
            self.semi();
        }
        let end = self.prev_end();
        let stem = match self.at(first + 1) {
            Some((_, Tok::Name(n), _)) => n.trim().to_string(),
            _ => String::new(),
        };
        let (file, errors) = parse_file(&self.src[l..end], &stem);
        self.slice_errors(errors, l, end, self.pos);
        let mut st = match file.and_then(|f| f.actions.into_iter().next()) {
            Some(a) => a,
            None => StAction {
                name: Ident { text: stem.into(), span: Span::new(0, 0) },
                block_type: None,
                body: Vec::new(),
                header: None,
                span: Span::new(0, end - l),
            },
        };
        shift::action(&mut st, l);
        Action { name: st.name.clone(), body: ActionBody::St(st), span: Span::new(l, end) }
    }
}

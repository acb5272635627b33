//! Keeps the parser's stack bounded whatever the input.
//!
//! The LR parser holds one stack entry (about 100 bytes) for every token of
//! a construct that is still open: each unclosed bracket, each prefix
//! operator waiting for its operand, each IF waiting for its END_IF. The
//! depth limits of [`crate::st::parse_support`] are checked when a construct
//! closes, which is too late: 100 MB of `(` held 7.5 GB before the parser
//! saw the end, and unclosed IFs made error recovery quadratic. This filter
//! sits between the lexer and the parser and counts what is open. The first
//! token over a limit is reported (E0021 or E0022), and the construct it
//! opens is skipped up to its end and handed on as one placeholder token,
//! which the grammar turns into a part that is already reported. The parser
//! then never holds more than the limits allow, so memory is bounded by the
//! limits, not by the input.
//!
//! Counting tokens agrees with the parser's nesting for text whose brackets
//! and statements are balanced; for unbalanced text it can only count more,
//! so the bound holds either way.

use crate::diag::span::Span;
use crate::diag::Capped;
use crate::st::errors::SyntaxError;
use crate::st::lexer::{Spanned, Tok};
use crate::st::parse_support::{MAX_EXPR_DEPTH, MAX_NESTING};
use std::collections::VecDeque;

/// The filter, as an iterator over the lexer's tokens.
pub struct DepthGuard<'s, I: Iterator<Item = Spanned<'s>>> {
    inner: I,
    /// Tokens decided but not yet handed out (at most three).
    queue: VecDeque<Spanned<'s>>,
    pub errors: Capped<SyntaxError>,
    /// Brackets `(` and `{` open since the last `;` (no bracket spans a
    /// `;`, and the parser drops open brackets when it recovers there).
    brackets: u16,
    /// The END keywords of the IF, FOR, WHILE and REPEAT statements still
    /// open, innermost last (at most [`MAX_NESTING`]). An END keyword of
    /// another kind closes nothing, as in the parser, which skips it.
    statements: Vec<Tok<'static>>,
    /// Prefix operators (`-`, `NOT`) in a row.
    run: u16,
    /// Whether the last token handed out ends an operand (then `-` is binary).
    after_operand: bool,
}

impl<'s, I: Iterator<Item = Spanned<'s>>> DepthGuard<'s, I> {
    pub fn new(inner: I) -> Self {
        DepthGuard {
            inner,
            queue: VecDeque::new(),
            errors: Capped::default(),
            brackets: 0,
            statements: Vec::new(),
            run: 0,
            after_operand: false,
        }
    }

    /// Decides what `t` becomes: nearly always `t` itself, handed back to
    /// go on at once; over a limit, the tokens that replace it are queued
    /// and `None` comes back.
    fn admit(&mut self, t: Spanned<'s>) -> Option<Spanned<'s>> {
        let prefix = matches!(t.1, Tok::Not) || (matches!(t.1, Tok::Minus) && !self.after_operand);
        self.run = if prefix { self.run.saturating_add(1) } else { 0 };
        match t.1 {
            Tok::LParen | Tok::LBrace => {
                self.brackets += 1;
                if self.brackets > MAX_EXPR_DEPTH {
                    self.errors.push(SyntaxError::ExprTooDeep { span: Span::new(t.0, t.2) });
                    let at = t.2;
                    self.queue.push_back(t);
                    self.skip_brackets(at);
                    return None;
                }
            }
            Tok::RParen | Tok::RBrace => self.brackets = self.brackets.saturating_sub(1),
            Tok::Semi => self.brackets = 0,
            Tok::If | Tok::For | Tok::While | Tok::Repeat => {
                if self.statements.len() >= usize::from(MAX_NESTING) {
                    let keyword = crate::st::lexer::keyword_text(&t.1);
                    self.errors.push(SyntaxError::NestedTooDeep { span: Span::new(t.0, t.2), keyword });
                    self.skip_statement(t.0);
                    return None;
                }
                self.statements.push(end_of(&t.1));
            }
            Tok::EndIf | Tok::EndFor | Tok::EndWhile | Tok::EndRepeat if self.closes_last(&t.1) => {
                self.statements.pop();
            }
            _ if prefix && self.run > MAX_EXPR_DEPTH => {
                self.errors.push(SyntaxError::ExprTooDeep { span: Span::new(t.0, t.2) });
                self.skip_prefixes(t);
                return None;
            }
            _ => {}
        }
        Some(t)
    }

    /// Whether the END keyword `t` closes the statement opened last. The
    /// keywords carry nothing, so their kinds are compared, not the tokens
    /// (the tokens' equality is a call for every token that reaches it).
    fn closes_last(&self, t: &Tok) -> bool {
        self.statements.last().is_some_and(|open| std::mem::discriminant(open) == std::mem::discriminant(t))
    }

    /// Skips what is inside an over-deep bracket: up to its closing bracket
    /// (handed on), a `;` (handed on: the bracket is unclosed) or the end.
    fn skip_brackets(&mut self, at: usize) {
        let (mut open, mut span) = (1u64, Span::new(at, at));
        let stop = loop {
            let Some(t) = self.inner.next() else { break None };
            match t.1 {
                Tok::LParen | Tok::LBrace => open += 1,
                Tok::RParen | Tok::RBrace => open -= 1,
                Tok::Semi => break Some(t),
                _ => {}
            }
            if open == 0 {
                break Some(t);
            }
            span = span.to(Span::new(t.0, t.2));
        };
        self.queue.push_back((span.start, Tok::Skipped, span.end));
        match stop {
            Some(t) if matches!(t.1, Tok::Semi) => {
                self.brackets = 0;
                self.queue.push_back(t);
            }
            Some(t) => {
                self.brackets -= 1;
                self.queue.push_back(t);
            }
            None => {}
        }
    }

    /// Skips an over-deep statement from its keyword (at `start`) through
    /// its END keyword, or to the end of the text.
    fn skip_statement(&mut self, start: usize) {
        let (mut open, mut end) = (1u64, start);
        for t in self.inner.by_ref() {
            end = t.2;
            match t.1 {
                Tok::If | Tok::For | Tok::While | Tok::Repeat => open += 1,
                Tok::EndIf | Tok::EndFor | Tok::EndWhile | Tok::EndRepeat => open -= 1,
                _ => {}
            }
            if open == 0 {
                break;
            }
        }
        self.queue.push_back((start, Tok::SkippedStatement, end));
    }

    /// Replaces the over-long run of prefix operators from `t` on by one
    /// placeholder operator; the operand that follows is kept.
    fn skip_prefixes(&mut self, t: Spanned<'s>) {
        let mut end = t.2;
        let next = loop {
            match self.inner.next() {
                Some(n) if matches!(n.1, Tok::Not | Tok::Minus) => end = n.2,
                other => break other,
            }
        };
        self.queue.push_back((t.0, Tok::SkippedPrefix, end));
        self.run = 0;
        if let Some(n) = next {
            self.after_operand = false;
            if let Some(n) = self.admit(n) {
                self.queue.push_back(n);
            }
        }
    }
}

/// The keyword that ends a statement opened by `t`.
fn end_of(t: &Tok) -> Tok<'static> {
    match t {
        Tok::If => Tok::EndIf,
        Tok::For => Tok::EndFor,
        Tok::While => Tok::EndWhile,
        _ => Tok::EndRepeat,
    }
}

impl<'s, I: Iterator<Item = Spanned<'s>>> Iterator for DepthGuard<'s, I> {
    type Item = Spanned<'s>;

    fn next(&mut self) -> Option<Spanned<'s>> {
        let t = match self.queue.pop_front() {
            Some(t) => t,
            None => {
                let t = self.inner.next()?;
                match self.admit(t) {
                    Some(t) => t,
                    None => self.queue.pop_front()?,
                }
            }
        };
        self.after_operand = t.1.ends_operand() || matches!(t.1, Tok::Skipped);
        Some(t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::st::lexer::Lexer;

    fn guarded(src: &str) -> (Vec<Tok<'_>>, Vec<&'static str>) {
        let mut g = DepthGuard::new(Lexer::new(src));
        let toks = g.by_ref().map(|t| t.1).collect();
        let codes = g.errors.into_parts().0.iter().map(|e| e.to_diagnostic().code.as_str()).collect();
        (toks, codes)
    }

    #[test]
    fn within_the_limits_every_token_passes() {
        let e = MAX_EXPR_DEPTH as usize;
        let src = format!("X := {}1{} - {}2;", "(".repeat(e), ")".repeat(e), "- NOT ".repeat(e / 2));
        let (toks, codes) = guarded(&src);
        assert_eq!(toks.len(), Lexer::new(&src).count());
        assert!(codes.is_empty());
    }

    #[test]
    fn an_over_deep_bracket_keeps_its_brackets_around_one_placeholder() {
        let src = format!("X := {}1{};Y := 2;", "(".repeat(300), ")".repeat(300));
        let (toks, codes) = guarded(&src);
        assert_eq!(codes, ["E0022"]);
        let skipped = toks.iter().position(|t| *t == Tok::Skipped).expect("placeholder");
        assert_eq!(skipped, 2 + MAX_EXPR_DEPTH as usize + 1);
        assert_eq!(toks.iter().filter(|t| **t == Tok::RParen).count(), MAX_EXPR_DEPTH as usize + 1);
        assert_eq!(toks[toks.len() - 4..], [Tok::Name("Y"), Tok::Assign, Tok::Int(2), Tok::Semi]);
    }

    #[test]
    fn an_over_long_prefix_run_becomes_one_placeholder_operator() {
        let src = format!("X := {}1;", "- ".repeat(1000));
        let (toks, codes) = guarded(&src);
        assert_eq!(codes, ["E0022"]);
        assert_eq!(toks.iter().filter(|t| **t == Tok::Minus).count(), MAX_EXPR_DEPTH as usize);
        assert_eq!(toks[toks.len() - 3..], [Tok::SkippedPrefix, Tok::Int(1), Tok::Semi]);
    }

    #[test]
    fn an_over_deep_statement_is_skipped_through_its_end() {
        let n = MAX_NESTING as usize + 50;
        let src = format!("{}X := 1;{}Y := 2;", "WHILE 1 DO ".repeat(n), "END_WHILE; ".repeat(n));
        let (toks, codes) = guarded(&src);
        assert_eq!(codes, ["E0021"]);
        assert_eq!(toks.iter().filter(|t| **t == Tok::While).count(), MAX_NESTING as usize);
        assert_eq!(toks.iter().filter(|t| **t == Tok::EndWhile).count(), MAX_NESTING as usize);
        assert_eq!(toks.iter().filter(|t| **t == Tok::SkippedStatement).count(), 1);
    }

    #[test]
    fn an_end_keyword_of_another_kind_closes_nothing() {
        // The parser skips the stray END_WHILE and stays inside the IF.
        let n = MAX_NESTING as usize + 1;
        let (_, codes) = guarded(&"IF 1 THEN END_WHILE; ".repeat(n));
        assert_eq!(codes, ["E0021"]);
    }
}

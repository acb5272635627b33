//! Turns source text into the parser's tokens, enforcing the space rules.
//!
//! logos recognises raw tokens ([`Raw`]); this pass "cooks" them: it decodes
//! numbers and time constants, reports illegal spaces inside names, operators
//! and constants (§12.2.2) and then repairs them so that parsing goes on with
//! one error instead of many, and turns `name[expr]` directly after a name
//! into an offset (the guide's FOR example writes `f[PIC_004.PV]`).

use crate::diag::span::Span;
use crate::diag::Capped;
use crate::st::errors::LexError;
use crate::st::token::Raw;
use logos::Logos;
use std::collections::VecDeque;

/// A token as the grammar sees it. `Copy`: it is handed through three
/// layers (cooking, the depth guard, the parser) for every token.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Tok<'s> {
    If,
    Then,
    Elsif,
    Else,
    EndIf,
    For,
    To,
    By,
    Do,
    EndFor,
    While,
    EndWhile,
    Repeat,
    Until,
    EndRepeat,
    Exit,
    Action,
    EndAction,
    And,
    Or,
    Xor,
    Not,
    Mod,
    True,
    False,
    Assign,
    Colon,
    Semi,
    Comma,
    LParen,
    RParen,
    LBrace,
    RBrace,
    Plus,
    Minus,
    Power,
    Star,
    Slash,
    Eq,
    Ne,
    Lt,
    Gt,
    Le,
    Ge,
    /// Dotted name text as written (it may contain illegal spaces already
    /// reported, which the parser trims).
    Name(&'s str),
    /// The segment after `}.` or `].`, without the dot.
    DotName(&'s str),
    /// The text between `[` and `]`.
    Bracketed(&'s str),
    /// Unclipped magnitude; the parser clips to 32 bits after applying a sign.
    Int(i64),
    Real(f64),
    /// Seconds.
    Time(f64),
    /// The text between the quotes, `$`-sequences as written.
    Str(&'s str),
    /// Injected first token selecting what the parser reads.
    StartFile,
    StartExpr,
    /// Placeholders from [`crate::st::depth_guard`] for a part over a depth
    /// limit, already reported: the inside of a bracket, a run of prefix
    /// operators, a statement.
    Skipped,
    SkippedPrefix,
    SkippedStatement,
}

impl Tok<'_> {
    /// How the token reads in a diagnostic.
    pub fn describe(&self) -> String {
        match self {
            Tok::Name(n) => format!("name `{}`", n.trim()),
            Tok::DotName(n) => format!("`.{n}`"),
            Tok::Bracketed(n) => format!("name `[{n}]`"),
            Tok::Int(i) => format!("number `{i}`"),
            Tok::Real(r) => format!("number `{r}`"),
            Tok::Time(_) => "time constant".to_string(),
            Tok::Str(_) => "string constant".to_string(),
            Tok::StartFile | Tok::StartExpr => "start of input".to_string(),
            Tok::Skipped | Tok::SkippedPrefix => "an expression nested too deep".to_string(),
            Tok::SkippedStatement => "statements nested too deep".to_string(),
            other => format!("`{}`", keyword_text(other)),
        }
    }

    /// True for tokens after which an operator is expected.
    #[inline]
    pub(crate) fn ends_operand(&self) -> bool {
        matches!(
            self,
            Tok::Name(_)
                | Tok::DotName(_)
                | Tok::Bracketed(_)
                | Tok::Int(_)
                | Tok::Real(_)
                | Tok::Time(_)
                | Tok::Str(_)
                | Tok::RParen
                | Tok::RBrace
                | Tok::True
                | Tok::False
        )
    }
}

/// The spelling of a keyword or punctuation token.
pub fn keyword_text(t: &Tok) -> &'static str {
    match t {
        Tok::If => "IF",
        Tok::Then => "THEN",
        Tok::Elsif => "ELSIF",
        Tok::Else => "ELSE",
        Tok::EndIf => "END_IF",
        Tok::For => "FOR",
        Tok::To => "TO",
        Tok::By => "BY",
        Tok::Do => "DO",
        Tok::EndFor => "END_FOR",
        Tok::While => "WHILE",
        Tok::EndWhile => "END_WHILE",
        Tok::Repeat => "REPEAT",
        Tok::Until => "UNTIL",
        Tok::EndRepeat => "END_REPEAT",
        Tok::Exit => "EXIT",
        Tok::Action => "ACTION",
        Tok::EndAction => "END_ACTION",
        Tok::And => "AND",
        Tok::Or => "OR",
        Tok::Xor => "XOR",
        Tok::Not => "NOT",
        Tok::Mod => "MOD",
        Tok::True => "TRUE",
        Tok::False => "FALSE",
        Tok::Assign => ":=",
        Tok::Colon => ":",
        Tok::Semi => ";",
        Tok::Comma => ",",
        Tok::LParen => "(",
        Tok::RParen => ")",
        Tok::LBrace => "{",
        Tok::RBrace => "}",
        Tok::Plus => "+",
        Tok::Minus => "-",
        Tok::Power => "**",
        Tok::Star => "*",
        Tok::Slash => "/",
        Tok::Eq => "=",
        Tok::Ne => "<>",
        Tok::Lt => "<",
        Tok::Gt => ">",
        Tok::Le => "<=",
        Tok::Ge => ">=",
        _ => "",
    }
}

/// A token with its byte range, in the triple form lalrpop consumes.
pub type Spanned<'s> = (usize, Tok<'s>, usize);

/// Lexes `src` completely, returning tokens and every lexical error.
pub fn lex(src: &str) -> (Vec<Spanned<'_>>, Vec<LexError>) {
    let mut lexer = Lexer::new(src);
    let tokens = lexer.by_ref().collect();
    (tokens, lexer.errors.into_parts().0)
}

/// The cooking lexer, as an iterator the parser pulls from: tokens are never
/// all held at once. The last token made stays queued until the next raw
/// token is seen, because an illegal space may join the two.
pub struct Lexer<'s> {
    src: &'s str,
    raw: logos::Lexer<'s, Raw>,
    pending: Option<(Raw, std::ops::Range<usize>)>,
    queue: VecDeque<Spanned<'s>>,
    done: bool,
    /// The token handed out last, for [`glued_word_operator`].
    last: Option<Tok<'s>>,
    pub errors: Capped<LexError>,
    /// Names that start with a word operator and follow an operand (`A ANDB`),
    /// by start offset: if the parser stops there, the error says why.
    pub glued: Vec<(usize, &'static str)>,
}

impl<'s> Lexer<'s> {
    pub fn new(src: &'s str) -> Lexer<'s> {
        Lexer::starting_at(src, 0)
    }

    /// A lexer that starts at byte `start` of `src` (a token's start), with
    /// offsets still those of the whole text.
    pub fn starting_at(src: &'s str, start: usize) -> Lexer<'s> {
        let mut raw = Raw::lexer(src);
        // A byte order mark is not part of the text (it stays in the file,
        // so offsets are those of the file).
        if start == 0 && src.starts_with(crate::diag::files::BOM) {
            raw.bump(crate::diag::files::BOM.len_utf8());
        } else if start > 0 {
            raw.bump(start);
        }
        Lexer {
            src,
            raw,
            pending: None,
            queue: VecDeque::new(),
            done: false,
            last: None,
            errors: Capped::default(),
            glued: Vec::new(),
        }
    }
}

impl<'s> Iterator for Lexer<'s> {
    type Item = Spanned<'s>;

    fn next(&mut self) -> Option<Spanned<'s>> {
        while self.queue.len() < 2 && !self.done {
            let mut cook = Cook { src: self.src, out: &mut self.queue, errors: &mut self.errors };
            if !cook.step(&mut self.raw, &mut self.pending) {
                self.done = true;
            }
        }
        let t = self.queue.pop_front()?;
        if let Some(op) = glued_word_operator(self.last.as_ref(), &t.1) {
            self.glued.push((t.0, op));
        }
        self.last = Some(t.1);
        Some(t)
    }
}

/// One cooking step's view of the lexer state.
struct Cook<'s, 'q> {
    src: &'s str,
    out: &'q mut VecDeque<Spanned<'s>>,
    errors: &'q mut Capped<LexError>,
}

impl<'s> Cook<'s, '_> {
    /// Cooks one raw token (or a pending one); false at the end of input.
    fn step(&mut self, raw: &mut logos::Lexer<'s, Raw>, pending: &mut Option<(Raw, std::ops::Range<usize>)>) -> bool {
        let src = self.src;
        let (tok, range) = match pending.take() {
            Some(p) => p,
            None => match raw.next() {
                None => return false,
                Some(Ok(t)) => (t, raw.span()),
                Some(Err(())) => {
                    self.unexpected(raw.span());
                    return true;
                }
            },
        };
        let (s, e) = (range.start, range.end);
        let text = &src[s..e];
        let prev_adjacent = self.out.back().map(|p| p.2 == s).unwrap_or(false);
        if let Some(t) = simple(tok) {
            self.keyword(tok, t, s, e);
            return true;
        }
        match tok {
            Raw::Name | Raw::BadName => self.out.push_back((s, Tok::Name(text), e)),
            Raw::Int => {
                let v = text.bytes().fold(0i64, |a, b| (a * 10 + i64::from(b - b'0')).min(1 << 40));
                self.out.push_back((s, Tok::Int(v), e));
            }
            Raw::Based => self.out.push_back((s, Tok::Int(based(text)), e)),
            Raw::BadBased => {
                self.errors.push(LexError::BadNumber { span: Span::new(s, e), text: text.to_string() });
                self.out.push_back((s, Tok::Int(0), e));
            }
            Raw::Real => self.real(text.parse().unwrap_or(0.0), s, e),
            Raw::Time => {
                let secs = time_seconds(&text[2..]);
                if secs > MAX_TIME_SECONDS {
                    self.errors.push(LexError::TimeOutOfRange { span: Span::new(s, e), text: text.to_string() });
                }
                self.out.push_back((s, Tok::Time(secs), e));
            }
            Raw::BadTime => {
                self.errors.push(LexError::BadTime { span: Span::new(s, e), text: text.to_string() });
                self.out.push_back((s, Tok::Time(0.0), e));
            }
            Raw::Str => self.out.push_back((s, Tok::Str(&text[1..text.len() - 1]), e)),
            Raw::UnclosedStr => {
                self.errors.push(LexError::UnclosedString { span: Span::new(s, e) });
                self.out.push_back((s, Tok::Str(&text[1..]), e));
            }
            Raw::CurlyStr => {
                let ch = text.chars().next().unwrap_or('"');
                self.errors.push(LexError::UnexpectedChar { span: Span::new(s, s + ch.len_utf8()), ch });
                let close = text.chars().last().map(char::len_utf8).unwrap_or(0);
                self.out.push_back((s, Tok::Str(&text[ch.len_utf8()..text.len() - close]), e));
            }
            Raw::UnclosedComment => {
                self.errors.push(LexError::UnclosedComment { span: Span::new(s, e) });
                return false;
            }
            Raw::Bracketed if prev_adjacent && ends_name(self.out.back()) => {
                // `f[e]` right after a name: an offset written with brackets.
                // The inside holds no `]`, so this goes one level deep at most.
                self.out.push_back((s, Tok::LBrace, s + 1));
                let mut inner = Raw::lexer(&src[..e - 1]);
                inner.bump(s + 1);
                let mut inner_pending = None;
                while self.step(&mut inner, &mut inner_pending) {}
                self.out.push_back((e - 1, Tok::RBrace, e));
            }
            Raw::Bracketed => self.out.push_back((s, Tok::Bracketed(&text[1..text.len() - 1]), e)),
            Raw::UnclosedBracket => {
                self.errors.push(LexError::UnclosedBracket { span: Span::new(s, e) });
                self.out.push_back((s, Tok::Bracketed(&text[1..]), e));
            }
            Raw::DotName => self.dot_name(text, s, e),
            Raw::Dot => self.dot(raw, pending, s, e),
            _ => {}
        }
        true
    }

    /// A keyword or operator; the second half of a two-character operator
    /// split by a space (`: =`) is joined to the first, and reported.
    fn keyword(&mut self, tok: Raw, t: Tok<'static>, s: usize, e: usize) {
        if let Some(prev) = self.out.back_mut() {
            // The pair is tested first: it is cheap and nearly always fails,
            // while the blank test reads the gap before every keyword.
            let joined = split_operator(&prev.1, tok);
            if let Some(joined) = joined.filter(|_| prev.2 < s && self.src[prev.2..s].trim().is_empty()) {
                self.errors.push(LexError::IllegalSpace {
                    span: Span::new(prev.2, s),
                    what: "an operator",
                    fixed: keyword_text(&joined),
                });
                prev.1 = joined;
                prev.2 = e;
                return;
            }
        }
        self.out.push_back((s, t, e));
    }

    /// A character that starts no token; a run of them is one error.
    fn unexpected(&mut self, span: std::ops::Range<usize>) {
        if let Some(LexError::UnexpectedChar { span: last, .. }) = self.errors.last_mut() {
            if last.end == span.start {
                last.end = span.end;
                return;
            }
        }
        let ch = self.src[span.start..].chars().next().unwrap_or('?');
        self.errors.push(LexError::UnexpectedChar { span: Span::new(span.start, span.end), ch });
    }

    /// A REAL constant, which must fit a 32-bit REAL.
    fn real(&mut self, x: f64, s: usize, e: usize) {
        if !(x as f32).is_finite() {
            self.errors.push(LexError::RealOutOfRange { span: Span::new(s, e), text: self.src[s..e].to_string() });
        }
        self.out.push_back((s, Tok::Real(x), e));
    }

    /// `.Name` after `}` or `]` continues a name; after a name it is an
    /// illegal space inside it.
    fn dot_name(&mut self, text: &'s str, s: usize, e: usize) {
        match self.out.back().map(|p| (p.0, p.1, p.2)) {
            Some((_, Tok::RBrace | Tok::Bracketed(_), pe)) => {
                if pe != s {
                    self.errors.push(LexError::IllegalSpace {
                        span: Span::new(pe, s),
                        what: "a database name",
                        fixed: "",
                    });
                }
                self.out.push_back((s, Tok::DotName(&text[1..]), e));
            }
            Some((ps, Tok::Name(_), pe)) => {
                self.errors.push(LexError::IllegalSpace { span: Span::new(pe, s), what: "a database name", fixed: "" });
                self.out.pop_back();
                self.out.push_back((ps, Tok::Name(&self.src[ps..e]), e));
            }
            _ => self.errors.push(LexError::StrayDot { span: Span::new(s, e) }),
        }
    }

    /// A lone `.`: `A. B` and `3. 5` are names and constants with an illegal
    /// space; anything else is a stray dot.
    fn dot(
        &mut self,
        raw: &mut logos::Lexer<'s, Raw>,
        pending: &mut Option<(Raw, std::ops::Range<usize>)>,
        s: usize,
        e: usize,
    ) {
        let src = self.src;
        let next = raw.next();
        let next_span = raw.span();
        let next_tok = match next {
            Some(Ok(t)) => Some(t),
            _ => None,
        };
        let joined = match (self.out.back(), next_tok) {
            (Some((ps, Tok::Name(_), pe)), Some(Raw::Name | Raw::Int | Raw::BadName)) if *pe == s => {
                Some((*ps, Tok::Name(&src[*ps..next_span.end])))
            }
            (Some((ps, Tok::Int(_), pe)), Some(Raw::Int)) if *pe == s => {
                let digits: String = src[*ps..next_span.end].chars().filter(|c| !c.is_whitespace()).collect();
                Some((*ps, Tok::Real(digits.parse().unwrap_or(0.0))))
            }
            _ => None,
        };
        match joined {
            Some((start, tok)) => {
                let what = if matches!(tok, Tok::Real(_)) { "a constant" } else { "a database name" };
                self.errors.push(LexError::IllegalSpace { span: Span::new(e, next_span.start), what, fixed: "" });
                self.out.pop_back();
                match tok {
                    Tok::Real(x) => self.real(x, start, next_span.end),
                    tok => self.out.push_back((start, tok, next_span.end)),
                }
            }
            None => {
                self.errors.push(LexError::StrayDot { span: Span::new(s, e) });
                if let Some(t) = next_tok {
                    *pending = Some((t, next_span));
                } else if let Some(Err(())) = next {
                    self.unexpected(next_span);
                }
            }
        }
    }
}

fn simple(raw: Raw) -> Option<Tok<'static>> {
    Some(match raw {
        Raw::If => Tok::If,
        Raw::Then => Tok::Then,
        Raw::Elsif => Tok::Elsif,
        Raw::Else => Tok::Else,
        Raw::EndIf => Tok::EndIf,
        Raw::For => Tok::For,
        Raw::To => Tok::To,
        Raw::By => Tok::By,
        Raw::Do => Tok::Do,
        Raw::EndFor => Tok::EndFor,
        Raw::While => Tok::While,
        Raw::EndWhile => Tok::EndWhile,
        Raw::Repeat => Tok::Repeat,
        Raw::Until => Tok::Until,
        Raw::EndRepeat => Tok::EndRepeat,
        Raw::Exit => Tok::Exit,
        Raw::Action => Tok::Action,
        Raw::EndAction => Tok::EndAction,
        Raw::And => Tok::And,
        Raw::Or => Tok::Or,
        Raw::Xor => Tok::Xor,
        Raw::Not => Tok::Not,
        Raw::Mod => Tok::Mod,
        Raw::True => Tok::True,
        Raw::False => Tok::False,
        Raw::Assign => Tok::Assign,
        Raw::Colon => Tok::Colon,
        Raw::Semi => Tok::Semi,
        Raw::Comma => Tok::Comma,
        Raw::LParen => Tok::LParen,
        Raw::RParen => Tok::RParen,
        Raw::LBrace => Tok::LBrace,
        Raw::RBrace => Tok::RBrace,
        Raw::Plus => Tok::Plus,
        Raw::Minus => Tok::Minus,
        Raw::Power => Tok::Power,
        Raw::Star => Tok::Star,
        Raw::Slash => Tok::Slash,
        Raw::Eq => Tok::Eq,
        Raw::Ne => Tok::Ne,
        Raw::Lt => Tok::Lt,
        Raw::Gt => Tok::Gt,
        Raw::Le => Tok::Le,
        Raw::Ge => Tok::Ge,
        _ => return None,
    })
}

/// Two-character operators that a space may have split: `: =`, `* *`, ...
fn split_operator(first: &Tok, second: Raw) -> Option<Tok<'static>> {
    Some(match (first, second) {
        (Tok::Colon, Raw::Eq) => Tok::Assign,
        (Tok::Star, Raw::Star) => Tok::Power,
        (Tok::Lt, Raw::Eq) => Tok::Le,
        (Tok::Lt, Raw::Gt) => Tok::Ne,
        (Tok::Gt, Raw::Eq) => Tok::Ge,
        _ => return None,
    })
}

/// The longest time constant, in seconds: the largest INT, so that a time
/// means the same stored in an INT field (a suppression time) as in a REAL.
pub const MAX_TIME_SECONDS: f64 = 2_147_483_647.0;

/// Whether the last token can carry an offset (`name`, `}` or `[name]`).
fn ends_name(last: Option<&Spanned>) -> bool {
    matches!(last, Some((_, Tok::Name(_) | Tok::DotName(_) | Tok::RBrace | Tok::Bracketed(_), _)))
}

/// Value of `16#FF`, `8#17` or `2#1010`, saturating well above 32 bits.
fn based(text: &str) -> i64 {
    let (radix, digits) = match text.split_once('#') {
        Some((r, d)) => (r.parse::<u32>().unwrap_or(10), d),
        None => (10, text),
    };
    digits
        .chars()
        .filter(|c| *c != '_')
        .filter_map(|c| c.to_digit(radix))
        .fold(0i64, |a, d| (a * i64::from(radix) + i64::from(d)).min(1 << 40))
}

/// Seconds in the body of a time constant such as `1d12.2h`.
pub fn time_seconds(body: &str) -> f64 {
    let mut total = 0.0;
    let mut number = String::new();
    let mut after_unit = false;
    for c in body.chars() {
        if after_unit && (c == '.' || c == '_') {
            after_unit = false;
            continue;
        }
        after_unit = false;
        let unit = match c.to_ascii_lowercase() {
            'd' => 86_400.0,
            'h' => 3_600.0,
            'm' => 60.0,
            's' => 1.0,
            _ => {
                number.push(c);
                continue;
            }
        };
        total += number.parse::<f64>().unwrap_or(0.0) * unit;
        number.clear();
        after_unit = true;
    }
    total
}

/// Checks that `tokens` sees no word operator glued to an operand.
///
/// `A ANDB` lexes as the two names `A` and `ANDB`; the parser then fails at
/// `ANDB`. This helper recognises that case so the error can say why.
#[inline]
pub fn glued_word_operator(prev: Option<&Tok>, tok: &Tok) -> Option<&'static str> {
    let Tok::Name(text) = tok else { return None };
    if !prev.map(Tok::ends_operand).unwrap_or(false) {
        return None;
    }
    ["AND", "XOR", "OR", "MOD", "NOT"]
        .into_iter()
        .find(|op| text.len() > op.len() && text.get(..op.len()).is_some_and(|p| p.eq_ignore_ascii_case(op)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn toks(src: &str) -> Vec<Tok<'_>> {
        lex(src).0.into_iter().map(|t| t.1).collect()
    }

    #[test]
    fn numbers_and_times() {
        assert_eq!(
            toks("16#FF 16#00ff 2#1100 45 3.6"),
            [Tok::Int(255), Tok::Int(255), Tok::Int(12), Tok::Int(45), Tok::Real(3.6)]
        );
        assert_eq!(
            toks("T#3s t#4m13.0S T#5.6h T#1d12.2h T#1d.12.2h T#1h_30m"),
            [
                Tok::Time(3.0),
                Tok::Time(253.0),
                Tok::Time(20160.0),
                Tok::Time(130320.0),
                Tok::Time(130320.0),
                Tok::Time(5400.0)
            ]
        );
    }

    #[test]
    fn illegal_spaces_are_reported_and_repaired() {
        let (t, e) = lex("HEAT_PID. SL:=REC1. A3;");
        assert_eq!(e.len(), 2);
        assert_eq!(t.iter().map(|t| t.1).collect::<Vec<_>>()[1], Tok::Assign);
        let (t, e) = lex("a : = 3. 5");
        assert_eq!(e.len(), 2);
        assert_eq!(t[1].1, Tok::Assign);
        assert_eq!(t[2].1, Tok::Real(3.5));
    }

    #[test]
    fn bracket_after_name_is_an_offset() {
        assert_eq!(toks("f[PIC_004.PV]"), [Tok::Name("f"), Tok::LBrace, Tok::Name("PIC_004.PV"), Tok::RBrace]);
        assert_eq!(toks("[6366.MN]"), [Tok::Bracketed("6366.MN")]);
    }

    #[test]
    fn comments_are_spaces() {
        assert_eq!(toks("(*ADJUST*) a(*x*):=1;(* y *)"), [Tok::Name("a"), Tok::Assign, Tok::Int(1), Tok::Semi]);
        assert_eq!(lex("a (* never closed").1.len(), 1);
    }

    #[test]
    fn strings_keep_dollar_sequences() {
        assert_eq!(toks(r#"'a$'b' "a$62c""#), [Tok::Str("a$'b"), Tok::Str("a$62c")]);
        assert_eq!(lex("'open").1.len(), 1);
    }
}

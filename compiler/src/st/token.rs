//! Raw tokens of LIN Structured Text, recognised by logos.
//!
//! The raw token set deliberately includes "near misses" (a name that starts
//! with a digit, a based integer with bad digits, a lone `.`) so that the
//! cooking pass in [`crate::st::lexer`] can report them precisely instead of
//! letting the parser stumble over them.

use logos::Logos;

/// A token as logos sees it. Keywords ignore case (§12).
#[derive(Logos, Clone, Copy, Debug, PartialEq)]
#[logos(skip r"[ \t\r\n\x0C]+")]
pub enum Raw {
    #[token("IF", ignore(case))]
    If,
    #[token("THEN", ignore(case))]
    Then,
    #[token("ELSIF", ignore(case))]
    Elsif,
    #[token("ELSE", ignore(case))]
    Else,
    #[token("END_IF", ignore(case))]
    EndIf,
    #[token("FOR", ignore(case))]
    For,
    #[token("TO", ignore(case))]
    To,
    #[token("BY", ignore(case))]
    By,
    #[token("DO", ignore(case))]
    Do,
    #[token("END_FOR", ignore(case))]
    EndFor,
    #[token("WHILE", ignore(case))]
    While,
    #[token("END_WHILE", ignore(case))]
    EndWhile,
    #[token("REPEAT", ignore(case))]
    Repeat,
    #[token("UNTIL", ignore(case))]
    Until,
    #[token("END_REPEAT", ignore(case))]
    EndRepeat,
    #[token("EXIT", ignore(case))]
    Exit,
    #[token("ACTION", ignore(case))]
    Action,
    #[token("END_ACTION", ignore(case))]
    EndAction,
    #[token("AND", ignore(case))]
    And,
    #[token("OR", ignore(case))]
    Or,
    #[token("XOR", ignore(case))]
    Xor,
    #[token("NOT", ignore(case))]
    Not,
    #[token("MOD", ignore(case))]
    Mod,
    #[token("TRUE", ignore(case))]
    True,
    #[token("FALSE", ignore(case))]
    False,

    #[token(":=")]
    Assign,
    #[token(":")]
    Colon,
    #[token(";")]
    Semi,
    #[token(",")]
    Comma,
    #[token("(")]
    LParen,
    #[token(")")]
    RParen,
    #[token("{")]
    LBrace,
    #[token("}")]
    RBrace,
    #[token("+")]
    Plus,
    #[token("-")]
    Minus,
    #[token("**")]
    Power,
    #[token("*")]
    Star,
    #[token("/")]
    Slash,
    #[token("=")]
    Eq,
    #[token("<>")]
    Ne,
    #[token("<")]
    Lt,
    #[token(">")]
    Gt,
    #[token("<=")]
    Le,
    #[token(">=")]
    Ge,

    /// A possibly dotted name: `PIC_004.PV`, `Dig_A.Out.Bit3`. Segments that
    /// start with a digit are lexed here and rejected with a located error.
    #[regex(r"[A-Za-z_][A-Za-z0-9_]*(\.[A-Za-z0-9_]+)*")]
    Name,
    /// A dotted continuation after an offset: the `.Bit0` of `F{n}.Bit0`.
    #[regex(r"\.[A-Za-z0-9_]+")]
    DotName,
    #[token(".")]
    Dot,
    /// `[any text]`: a name that is not a valid identifier (§12.8.2).
    #[regex(r"\[[^\]\n]*\]")]
    Bracketed,
    #[regex(r"\[[^\]\n]*", priority = 0)]
    UnclosedBracket,

    #[regex(r"[0-9]+", priority = 10)]
    Int,
    #[regex(r"(16#[0-9A-Fa-f][0-9A-Fa-f_]*|8#[0-7][0-7_]*|2#[01][01_]*)", priority = 10)]
    Based,
    #[regex(r"[0-9]+#[0-9A-Za-z_]*", priority = 1)]
    BadBased,
    /// `3.6`, `1.5E3`; also `1E3` (an exponent without a point, decision 20).
    #[regex(r"[0-9]+\.[0-9]+([eE][+-]?[0-9]+)?|[0-9]+[eE][+-]?[0-9]+", priority = 10)]
    Real,
    /// `T#4m13.0s`; units d h m s in either case (§12.9).
    /// A `.` or `_` may follow a unit (`T#1d.12.2h`, §18.3).
    #[regex(r"[tT]#([0-9]+(\.[0-9]+)?[dDhHmMsS][._]?)*[0-9]+(\.[0-9]+)?[dDhHmMsS]", priority = 10)]
    Time,
    #[regex(r"[tT]#[0-9A-Za-z_.]*", priority = 1)]
    BadTime,
    /// Something that starts like a number and goes on like a name: `1A`,
    /// `6366.MN`.
    #[regex(r"[0-9][A-Za-z0-9_]*(\.[A-Za-z0-9_]+)+|[0-9]+[A-Za-z_][A-Za-z0-9_]*", priority = 1)]
    BadName,
    #[regex(r"'([^'$\n]|\$[^\n])*'")]
    #[regex(r#""([^"$\n]|\$[^\n])*""#)]
    Str,
    #[regex(r"'([^'$\n]|\$[^\n])*\$?", priority = 0)]
    #[regex(r#""([^"$\n]|\$[^\n])*\$?"#, priority = 0)]
    UnclosedStr,
    /// `(*` starts a comment, skipped to its `*)` by [`comment`]; without
    /// one it is this token, an unclosed comment.
    #[token("(*", comment)]
    UnclosedComment,
    /// A string in typographic quotes, as text copied from a manual has.
    #[regex("\u{201C}[^\u{201D}\n]*\u{201D}")]
    #[regex("\u{2018}[^\u{2019}\n]*\u{2019}")]
    CurlyStr,
}

/// Skips a comment `(* … *)` by finding its end. A regular expression did
/// this before (`\(\*([^*]|\*+[^*)])*\*+\)`, which also ends at the first
/// `*)`), but logos's matcher for it recursed once per star in a debug
/// build: a long comment full of `*` overflowed the stack.
fn comment(lex: &mut logos::Lexer<'_, Raw>) -> logos::FilterResult<(), ()> {
    match lex.remainder().find("*)") {
        Some(at) => {
            lex.bump(at + 2);
            logos::FilterResult::Skip
        }
        None => logos::FilterResult::Emit(()),
    }
}

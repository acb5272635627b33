//! A JSON reader that keeps where everything is.
//!
//! `serde_json` forgets byte positions and, with `preserve_order`, silently
//! keeps only the last of two equal keys. The loader needs both: every error
//! points at the key or value that caused it, and a repeated key is an error
//! (E0807) rather than a value that quietly disappears. The grammar is RFC
//! 8259; nesting is limited so that hostile input cannot exhaust the stack.

use super::json::{code, DbError};

/// A byte range in the database text.
pub type Span = (usize, usize);

/// Deepest nesting accepted (the contract itself needs six levels).
const MAX_DEPTH: usize = 128;

/// One JSON value and where it is.
#[derive(Clone, Debug, PartialEq)]
pub struct Node {
    pub v: Json,
    pub span: Span,
}

/// One key of an object, with its position, and its value.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    pub key: String,
    pub key_span: Span,
    pub value: Node,
}

/// JSON values. Numbers are `f64`; a number too large for it is infinite
/// here and rejected where a value is checked.
#[derive(Clone, Debug, PartialEq)]
pub enum Json {
    Null,
    Bool(bool),
    Num(f64),
    Str(String),
    Arr(Vec<Node>),
    /// Members in text order; keys are unique.
    Obj(Vec<Member>),
}

impl Node {
    pub fn as_str(&self) -> Option<&str> {
        match &self.v {
            Json::Str(s) => Some(s),
            _ => None,
        }
    }

    pub fn as_object(&self) -> Option<&[Member]> {
        match &self.v {
            Json::Obj(m) => Some(m),
            _ => None,
        }
    }

    /// The whole number this is, if it is one from `lo` to `hi`.
    pub fn whole(&self, lo: f64, hi: f64) -> Option<i64> {
        match self.v {
            Json::Num(x) if x.fract() == 0.0 && (lo..=hi).contains(&x) => Some(x as i64),
            _ => None,
        }
    }

    /// What kind of value this is, for messages.
    pub fn kind(&self) -> &'static str {
        match self.v {
            Json::Null => "null",
            Json::Bool(_) => "a boolean",
            Json::Num(_) => "a number",
            Json::Str(_) => "a string",
            Json::Arr(_) => "an array",
            Json::Obj(_) => "an object",
        }
    }
}

/// The member called `key` of an object's members.
pub fn get<'a>(members: &'a [Member], key: &str) -> Option<&'a Member> {
    members.iter().find(|m| m.key == key)
}

/// The member at the end of `path` (keys from the root object down), if
/// it is written: a complaint about a value can point at it.
pub fn member_at<'a>(root: &'a Node, path: &[&str]) -> Option<&'a Member> {
    let (last, parents) = path.split_last()?;
    let mut node = root;
    for key in parents {
        node = &get(node.as_object()?, key)?.value;
    }
    get(node.as_object()?, last)
}

/// Parses a whole JSON text: a database.
pub fn parse(text: &str) -> Result<Node, DbError> {
    parse_named(text, "the database")
}

/// Parses a whole JSON text; `what` names it in messages ("the map file"),
/// since other files than a database are JSON too.
pub fn parse_named(text: &str, what: &'static str) -> Result<Node, DbError> {
    let mut p = Parser { text, bytes: text.as_bytes(), at: 0, what };
    let node = p.value(0)?;
    p.skip_ws();
    if p.at < p.bytes.len() {
        return Err(p.syntax("unexpected text after the end of the value"));
    }
    Ok(node)
}

struct Parser<'a> {
    text: &'a str,
    bytes: &'a [u8],
    at: usize,
    /// The file as messages name it.
    what: &'static str,
}

impl Parser<'_> {
    fn syntax(&self, what: &str) -> DbError {
        let end = if self.at < self.bytes.len() { self.at + utf8_len(self.bytes[self.at]) } else { self.at };
        DbError {
            code: code::NOT_JSON,
            message: format!("{} is not valid JSON: {what}", self.what),
            span: Some((self.at, end)),
        }
    }

    fn skip_ws(&mut self) {
        while matches!(self.bytes.get(self.at), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.at += 1;
        }
    }

    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.at).copied()
    }

    fn value(&mut self, depth: usize) -> Result<Node, DbError> {
        self.skip_ws();
        let start = self.at;
        let v = match self.peek() {
            None => return Err(self.syntax("the text ends where a value should be")),
            Some(b'{' | b'[') if depth >= MAX_DEPTH => {
                return Err(self.syntax(&format!("nested more than {MAX_DEPTH} levels deep")))
            }
            Some(b'{') => self.object(depth)?,
            Some(b'[') => self.array(depth)?,
            Some(b'"') => Json::Str(self.string()?),
            Some(b'-' | b'0'..=b'9') => Json::Num(self.number()?),
            Some(_) => self.literal()?,
        };
        Ok(Node { v, span: (start, self.at) })
    }

    fn literal(&mut self) -> Result<Json, DbError> {
        for (word, v) in [("true", Json::Bool(true)), ("false", Json::Bool(false)), ("null", Json::Null)] {
            if self.bytes[self.at..].starts_with(word.as_bytes()) {
                self.at += word.len();
                return Ok(v);
            }
        }
        Err(self.syntax("expected a value"))
    }

    fn object(&mut self, depth: usize) -> Result<Json, DbError> {
        self.at += 1;
        let mut members: Vec<Member> = Vec::new();
        let mut seen = std::collections::HashSet::new();
        self.skip_ws();
        if self.peek() == Some(b'}') {
            self.at += 1;
            return Ok(Json::Obj(members));
        }
        loop {
            self.skip_ws();
            if self.peek() != Some(b'"') {
                return Err(self.syntax("expected a key in double quotes"));
            }
            let start = self.at;
            let key = self.string()?;
            let key_span = (start, self.at);
            if !seen.insert(key.clone()) {
                return Err(DbError {
                    code: code::DUPLICATE_KEY,
                    message: format!(
                        "key `{key}` appears twice in one JSON object (JSON readers would silently keep only one)"
                    ),
                    span: Some(key_span),
                });
            }
            self.skip_ws();
            if self.peek() != Some(b':') {
                return Err(self.syntax("expected `:` after an object key"));
            }
            self.at += 1;
            let value = self.value(depth + 1)?;
            members.push(Member { key, key_span, value });
            self.skip_ws();
            match self.peek() {
                Some(b',') => self.at += 1,
                Some(b'}') => {
                    self.at += 1;
                    return Ok(Json::Obj(members));
                }
                _ => return Err(self.syntax("expected `,` or `}` in an object")),
            }
        }
    }

    fn array(&mut self, depth: usize) -> Result<Json, DbError> {
        self.at += 1;
        let mut items = Vec::new();
        self.skip_ws();
        if self.peek() == Some(b']') {
            self.at += 1;
            return Ok(Json::Arr(items));
        }
        loop {
            items.push(self.value(depth + 1)?);
            self.skip_ws();
            match self.peek() {
                Some(b',') => self.at += 1,
                Some(b']') => {
                    self.at += 1;
                    return Ok(Json::Arr(items));
                }
                _ => return Err(self.syntax("expected `,` or `]` in an array")),
            }
        }
    }

    /// A number by the JSON grammar: `-? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?`.
    fn number(&mut self) -> Result<f64, DbError> {
        let start = self.at;
        if self.peek() == Some(b'-') {
            self.at += 1;
        }
        match self.peek() {
            Some(b'0') => self.at += 1,
            Some(b'1'..=b'9') => self.digits(),
            _ => return Err(self.syntax("expected a digit")),
        }
        if self.peek() == Some(b'.') {
            self.at += 1;
            if !matches!(self.peek(), Some(b'0'..=b'9')) {
                return Err(self.syntax("expected a digit after the decimal point"));
            }
            self.digits();
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            self.at += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.at += 1;
            }
            if !matches!(self.peek(), Some(b'0'..=b'9')) {
                return Err(self.syntax("expected a digit in the exponent"));
            }
            self.digits();
        }
        // The grammar above is a subset of what `f64::from_str` reads, and
        // huge exponents give infinity rather than an error.
        self.text[start..self.at].parse().map_err(|_| self.syntax("number out of range"))
    }

    fn digits(&mut self) {
        while matches!(self.peek(), Some(b'0'..=b'9')) {
            self.at += 1;
        }
    }

    fn string(&mut self) -> Result<String, DbError> {
        self.at += 1;
        let mut out = String::new();
        loop {
            let run = self.at;
            while matches!(self.peek(), Some(c) if c != b'"' && c != b'\\' && c >= 0x20) {
                self.at += 1;
            }
            out.push_str(&self.text[run..self.at]);
            match self.peek() {
                Some(b'"') => {
                    self.at += 1;
                    return Ok(out);
                }
                Some(b'\\') => {
                    self.at += 1;
                    let c = self.escape()?;
                    out.push(c);
                }
                Some(_) => return Err(self.syntax("control character inside a string (write it as an escape)")),
                None => return Err(self.syntax("the text ends inside a string")),
            }
        }
    }

    /// The character an escape after `\` stands for.
    fn escape(&mut self) -> Result<char, DbError> {
        let c = match self.peek() {
            Some(b'"') => '"',
            Some(b'\\') => '\\',
            Some(b'/') => '/',
            Some(b'b') => '\u{8}',
            Some(b'f') => '\u{c}',
            Some(b'n') => '\n',
            Some(b'r') => '\r',
            Some(b't') => '\t',
            Some(b'u') => return self.unicode(),
            _ => return Err(self.syntax("unknown escape in a string")),
        };
        self.at += 1;
        Ok(c)
    }

    /// `uXXXX`, or a surrogate pair `uD83D\uDE00`.
    fn unicode(&mut self) -> Result<char, DbError> {
        self.at += 1;
        let hi = self.hex4()?;
        let code = if (0xD800..0xDC00).contains(&hi) {
            if !self.bytes[self.at..].starts_with(b"\\u") {
                return Err(self.syntax("a lone surrogate in a \\u escape"));
            }
            self.at += 2;
            let lo = self.hex4()?;
            if !(0xDC00..0xE000).contains(&lo) {
                return Err(self.syntax("a lone surrogate in a \\u escape"));
            }
            0x10000 + ((hi - 0xD800) << 10) + (lo - 0xDC00)
        } else {
            hi
        };
        char::from_u32(code).ok_or_else(|| self.syntax("a lone surrogate in a \\u escape"))
    }

    fn hex4(&mut self) -> Result<u32, DbError> {
        let digits = self.bytes.get(self.at..self.at + 4).ok_or_else(|| self.syntax("expected four hex digits"))?;
        let mut v = 0;
        for &d in digits {
            let d = char::from(d).to_digit(16).ok_or_else(|| self.syntax("expected four hex digits"))?;
            v = v * 16 + d;
        }
        self.at += 4;
        Ok(v)
    }
}

/// Length of the UTF-8 character that starts with `b` (so error spans end
/// on a character boundary).
fn utf8_len(b: u8) -> usize {
    match b {
        0xF0.. => 4,
        0xE0.. => 3,
        0xC0.. => 2,
        _ => 1,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> (&'static str, Option<Span>) {
        let e = parse(text).expect_err(text);
        (e.code.as_str(), e.span)
    }

    /// A path names a member only if every key on it is written.
    #[test]
    fn the_member_at_a_path() {
        let n = parse(r#"{"blocks": {"F": {"values": {"BRK": 3}}}}"#).expect("parses");
        let at = |path: &[&str]| member_at(&n, path).map(|m| (m.key.clone(), m.value.span));
        assert_eq!(at(&["blocks", "F", "values", "BRK"]), Some(("BRK".into(), (36, 37))));
        assert_eq!(at(&["blocks", "F", "values"]), Some(("values".into(), (28, 38))));
        assert_eq!(at(&["blocks", "F", "values", "IP"]), None);
        assert_eq!(at(&["blocks", "G", "values", "BRK"]), None);
        assert_eq!(at(&["blocks", "F", "values", "BRK", "x"]), None);
        assert_eq!(at(&[]), None);
    }

    #[test]
    fn values_and_spans() {
        let n = parse(r#" {"a": [1, -2.5e1, true, null], "b\u00e9\n": "x\"\ud83d\ude00"} "#).expect("parses");
        assert_eq!(n.span, (1, 63));
        let m = n.as_object().expect("object");
        assert_eq!(m[0].key, "a");
        assert_eq!(m[0].key_span, (2, 5));
        let Json::Arr(items) = &m[0].value.v else { panic!("array") };
        assert_eq!(items.iter().map(|i| i.v.clone()).collect::<Vec<_>>()[..2], [Json::Num(1.0), Json::Num(-25.0)]);
        assert_eq!(items[1].span, (11, 17));
        assert_eq!(m[1].key, "bé\n");
        assert_eq!(m[1].value.as_str(), Some("x\"\u{1F600}"));
    }

    #[test]
    fn syntax_errors_are_located() {
        assert_eq!(err("{ \"blocks\": "), ("E0800", Some((12, 12))));
        assert_eq!(err("{\"a\" 1}"), ("E0800", Some((5, 6))));
        assert_eq!(err("[01]"), ("E0800", Some((2, 3))));
        assert_eq!(err("[1.]"), ("E0800", Some((3, 4))));
        assert_eq!(err("\"a\u{1}\""), ("E0800", Some((2, 3))));
        assert_eq!(err("\"\\ud800x\""), ("E0800", Some((7, 8))));
        assert_eq!(err("[tru]"), ("E0800", Some((1, 2))));
        assert_eq!(err("{} x"), ("E0800", Some((3, 4))));
        assert_eq!(err("[é"), ("E0800", Some((1, 3))));
    }

    #[test]
    fn huge_numbers_are_infinite_not_errors() {
        assert_eq!(parse("1e400").map(|n| n.v), Ok(Json::Num(f64::INFINITY)));
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let deep = "[".repeat(100_000);
        assert_eq!(err(&deep), ("E0800", Some((128, 129))));
        assert!(parse(&format!("{}{}", "[".repeat(128), "]".repeat(128))).is_ok());
    }

    #[test]
    fn repeated_keys_are_located_at_the_second() {
        assert_eq!(err(r#"{"v": {"A0": 1, "A0": 2}}"#), ("E0807", Some((16, 20))));
        // Equal after unescaping is equal.
        assert_eq!(err(r#"{"A": 1, "\u0041": 2}"#), ("E0807", Some((9, 17))));
        // Keys that differ only in case are different JSON keys.
        assert!(parse(r#"{"a": 1, "A": 2}"#).is_ok());
    }
}

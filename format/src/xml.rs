//! Text escaped for XML 1.0 (text and attribute values), as the JUnit
//! report and the SVG pictures write it.

/// What becomes of tab and newline, which XML may hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Whitespace {
    /// Kept as they are (a report's multi-line text).
    Keep,
    /// One line: a tab becomes a space, a newline is replaced like any
    /// other control character (a picture's `<text>` is one line).
    OneLine,
}

/// `&`, `<`, `>`, `"` and `'` escaped; characters XML 1.0 cannot hold
/// (control characters, U+FFFE, U+FFFF) replaced by U+FFFD.
pub fn escape(text: &str, ws: Whitespace) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' if ws == Whitespace::Keep => out.push(c),
            '\t' => out.push(' '),
            c if (c as u32) < 0x20 || c == '\u{fffe}' || c == '\u{ffff}' => out.push('\u{fffd}'),
            c => out.push(c),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_is_escaped_and_what_xml_cannot_hold_replaced() {
        assert_eq!(escape("a<b & 'c'\"", Whitespace::Keep), "a&lt;b &amp; &apos;c&apos;&quot;");
        assert_eq!(escape("x\ty\nz\u{1}\u{ffff}", Whitespace::Keep), "x\ty\nz\u{fffd}\u{fffd}");
        assert_eq!(escape("x\ty\nz\u{1}", Whitespace::OneLine), "x y\u{fffd}z\u{fffd}");
    }
}

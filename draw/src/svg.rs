//! Writing SVG: escaped text, a fixed number format (so that the same input
//! gives the same bytes) and one style sheet with a light and a dark look.

use crate::geom::{Rect, P};
use std::fmt::Write;

/// The width a character is taken to have at the style's 12 px monospace
/// font, so this is what the layout can count on, and a line's height.
pub const CHAR_W: f64 = 7.2;
pub const LINE_H: f64 = 16.0;

/// The width `text` takes in the style's font.
pub fn text_width(text: &str) -> f64 {
    text.chars().count() as f64 * CHAR_W
}

/// The style of every picture. Colours follow the user's scheme; a
/// `class="dark"` or `class="light"` on the root forces one.
const STYLE: &str = "
svg { --fg: #1b1f24; --bg: #ffffff; --box: #f6f8fa; --wire: #57606a; --on: #1a7f37; --onbg: #dafbe1; --cur: #bf8700; --curbg: #fff8c5; --dim: #6e7781; --p0: #ddf4ff; --p1: #fbefff; }
svg.dark { --fg: #e6edf3; --bg: #0d1117; --box: #161b22; --wire: #8b949e; --on: #3fb950; --onbg: #12361c; --cur: #d29922; --curbg: #3b2e00; --dim: #8b949e; --p0: #0c2d6b; --p1: #3c1e70; }
@media (prefers-color-scheme: dark) { svg:not(.light) { --fg: #e6edf3; --bg: #0d1117; --box: #161b22; --wire: #8b949e; --on: #3fb950; --onbg: #12361c; --cur: #d29922; --curbg: #3b2e00; --dim: #8b949e; --p0: #0c2d6b; --p1: #3c1e70; } }
.bg { fill: var(--bg); }
text { font-family: ui-monospace, 'DejaVu Sans Mono', Menlo, Consolas, monospace; font-size: 12px; fill: var(--fg); white-space: pre; }
text.dim { fill: var(--dim); }
text.value { fill: var(--fg); }
text.value.true { fill: var(--on); font-weight: bold; }
text.value.false { fill: var(--dim); }
.rung.skipped { opacity: 0.55; }
.rung.skipped .wire, .rung.skipped .contact, .rung.skipped .coil, .rung.skipped .box { stroke-dasharray: 4 3; }
.rung.skipped text { fill: var(--dim); }
.box { fill: var(--box); stroke: var(--fg); stroke-width: 1.2; }
.wire { stroke: var(--wire); stroke-width: 1.2; fill: none; }
.bar { stroke: var(--fg); stroke-width: 3; }
.rail { stroke: var(--fg); stroke-width: 3; }
.arrow { fill: var(--wire); }
.line { fill: none; stroke-width: 1.6; }
.line.c0 { stroke: #0969da; } .line.c1 { stroke: #cf222e; } .line.c2 { stroke: #1a7f37; }
.line.c3 { stroke: #8250df; } .line.c4 { stroke: #bf8700; } .line.c5 { stroke: #1b7c83; }
.piece .box { stroke: none; } .piece.p0 .box { fill: var(--p0); } .piece.p1 .box { fill: var(--p1); }
.piece.on .box { fill: var(--onbg); } .piece.off .box { fill: none; }
.step.active .box { fill: var(--onbg); stroke: var(--on); stroke-width: 2.4; }
.wire.on { stroke: var(--on); stroke-width: 2.4; }
.coil { fill: none; stroke: var(--fg); stroke-width: 1.4; }
.contact { stroke: var(--fg); stroke-width: 2; }
.on .contact, .on.contact, .on .coil { stroke: var(--on); }
.fst-step.current .box { fill: var(--curbg); stroke: var(--cur); stroke-width: 2.4; }
.held .box { stroke-dasharray: 4 2; }
.frame { fill: none; stroke: var(--dim); stroke-dasharray: 3 3; }
text.name { font-weight: bold; }
.double { stroke: var(--wire); stroke-width: 1.2; }
";

/// An SVG document being written.
pub struct Svg {
    body: String,
}

/// A number as SVG gets it: at most two decimals, no trailing zeros.
pub fn num(v: f64) -> String {
    let r = (v * 100.0).round() / 100.0;
    let r = if r == 0.0 { 0.0 } else { r };
    let s = format!("{r:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

/// `text` escaped for XML text and attribute values, on one line.
pub fn escape(text: &str) -> String {
    linc_format::xml::escape(text, linc_format::xml::Whitespace::OneLine)
}

/// An id made of the characters XML names allow: others become `_`.
pub fn id(prefix: &str, name: &str) -> String {
    let mut out = String::from(prefix);
    for c in name.chars() {
        out.push(if c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.') { c } else { '_' });
    }
    out
}

impl Svg {
    pub fn new() -> Svg {
        Svg { body: String::new() }
    }

    pub fn open(&mut self, id: Option<&str>, class: &str) {
        match id {
            Some(i) => {
                let _ = write!(self.body, "<g id=\"{}\" class=\"{}\">", escape(i), escape(class));
            }
            None => {
                let _ = write!(self.body, "<g class=\"{}\">", escape(class));
            }
        }
    }

    /// Appends elements written elsewhere (a nested picture).
    pub fn raw(&mut self, s: &str) {
        self.body.push_str(s);
    }

    /// The elements written so far, for nesting in another picture.
    pub fn into_body(self) -> String {
        self.body
    }

    pub fn close(&mut self) {
        self.body.push_str("</g>\n");
    }

    /// A path (`d` as SVG writes it).
    pub fn path(&mut self, d: &str, class: &str) {
        let _ = write!(self.body, "<path class=\"{class}\" d=\"{d}\"/>");
    }

    /// A tooltip for the enclosing group (full text where a label is short).
    pub fn title(&mut self, text: &str) {
        let _ = write!(self.body, "<title>{}</title>", escape(text));
    }

    pub fn rect(&mut self, r: Rect, class: &str) {
        let _ = write!(
            self.body,
            "<rect class=\"{class}\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/>",
            num(r.x),
            num(r.y),
            num(r.w),
            num(r.h)
        );
    }

    pub fn line(&mut self, a: P, b: P, class: &str) {
        let _ = write!(
            self.body,
            "<line class=\"{class}\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>",
            num(a.x),
            num(a.y),
            num(b.x),
            num(b.y)
        );
    }

    pub fn polyline(&mut self, points: &[P], class: &str, extra: &str) {
        self.body.push_str("<polyline class=\"");
        self.body.push_str(class);
        self.body.push_str("\" points=\"");
        for (i, q) in points.iter().enumerate() {
            if i > 0 {
                self.body.push(' ');
            }
            let _ = write!(self.body, "{},{}", num(q.x), num(q.y));
        }
        let _ = write!(self.body, "\"{extra}/>");
    }

    /// An arrow head pointing down (`dy` 1) or up (-1), its tip at `tip`;
    /// or right/left with `dx`.
    pub fn arrow(&mut self, tip: P, dx: f64, dy: f64) {
        let (bx, by) = (tip.x - dx * 7.0, tip.y - dy * 7.0);
        let (px, py) = (dy * 4.0, dx * 4.0);
        let _ = write!(
            self.body,
            "<polygon class=\"arrow\" points=\"{},{} {},{} {},{}\"/>",
            num(tip.x),
            num(tip.y),
            num(bx + px),
            num(by + py),
            num(bx - px),
            num(by - py)
        );
    }

    /// Text whose first line's baseline is `y`; `anchor` is start, middle or end.
    pub fn text(&mut self, x: f64, y: f64, text: &str, class: &str, anchor: &str) {
        let _ = write!(self.body, "<text x=\"{}\" y=\"{}\"", num(x), num(y));
        if !class.is_empty() {
            let _ = write!(self.body, " class=\"{class}\"");
        }
        if anchor != "start" {
            let _ = write!(self.body, " text-anchor=\"{anchor}\"");
        }
        let _ = write!(self.body, ">{}</text>", escape(text));
    }

    /// The document: `kind` is a class on the root (sfc, ld, fst, trend).
    pub fn finish(self, kind: &str, w: f64, h: f64) -> String {
        let (w, h) = (num(w.ceil()), num(h.ceil()));
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"linc {kind}\" width=\"{w}\" height=\"{h}\" \
             viewBox=\"0 0 {w} {h}\">\n<style>{STYLE}</style>\n<rect class=\"bg\" x=\"0\" y=\"0\" width=\"{w}\" \
             height=\"{h}\"/>\n{}</svg>\n",
            self.body
        )
    }
}

impl Default for Svg {
    fn default() -> Self {
        Self::new()
    }
}

/// Splits `text` into lines of at most `width` characters at spaces (a
/// longer word is cut), at most `max_lines` of them (the last ends in `…`).
pub fn wrap(text: &str, width: usize, max_lines: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for word in text.split_whitespace() {
        let mut word: String = word.to_string();
        loop {
            let n = cur.chars().count();
            let wn = word.chars().count();
            if n > 0 && n + 1 + wn <= width {
                cur.push(' ');
                cur.push_str(&word);
                break;
            }
            if n > 0 {
                lines.push(std::mem::take(&mut cur));
            }
            if wn <= width {
                cur = word;
                break;
            }
            let head: String = word.chars().take(width).collect();
            word = word.chars().skip(width).collect();
            lines.push(head);
        }
        if lines.len() > max_lines {
            break;
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    if lines.len() > max_lines {
        lines.truncate(max_lines);
        if let Some(last) = lines.last_mut() {
            let keep: String = last.chars().take(width.saturating_sub(1)).collect();
            *last = keep + "…";
        }
    }
    lines
}

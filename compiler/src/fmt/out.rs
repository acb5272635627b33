//! The formatter's output: lines, indentation, and comments moved with
//! their continuation lines.

/// One level of indentation.
pub(crate) const INDENT: &str = "    ";

#[derive(Default)]
pub(crate) struct Out {
    pub buf: String,
    /// Columns of indentation a new line gets.
    pub indent: usize,
}

impl Out {
    /// Nothing but indentation on the current line yet.
    pub fn at_line_start(&self) -> bool {
        self.buf.is_empty() || self.buf.ends_with('\n')
    }

    /// Ends the current line (if it has anything on it).
    pub fn newline(&mut self) {
        if !self.at_line_start() {
            let kept = self.buf.trim_end_matches(' ').len();
            self.buf.truncate(kept);
            self.buf.push('\n');
        }
    }

    /// Ends the line and leaves one blank line (never at the start).
    pub fn blank(&mut self) {
        self.newline();
        if !self.buf.is_empty() && !self.buf.ends_with("\n\n") {
            self.buf.push('\n');
        }
    }

    /// Writes `text`, after the indentation on a new line, or after one
    /// space when `space` says so.
    pub fn put(&mut self, text: &str, space: bool) {
        if self.at_line_start() {
            self.buf.extend(std::iter::repeat_n(' ', self.indent));
        } else if space && !self.buf.ends_with(' ') {
            self.buf.push(' ');
        }
        self.buf.push_str(text);
    }

    /// The current column (in characters).
    pub fn column(&self) -> usize {
        let line = self.buf.rfind('\n').map(|i| i + 1).unwrap_or(0);
        self.buf[line..].chars().count()
    }

    /// Writes a comment that stood at column `was`: its continuation lines
    /// move by as many columns as its first line does, so a comment's own
    /// layout survives re-indentation (and a second run moves nothing).
    /// `was` is asked only for a comment over several lines: finding a
    /// column scans back to the line's start, which for every comment of
    /// a very long line would be quadratic.
    pub fn comment(&mut self, text: &str, was: impl FnOnce() -> usize, space: bool) {
        self.put("", space);
        if !text.contains('\n') {
            self.buf.push_str(text.trim_end_matches('\r'));
            return;
        }
        let (now, was) = (self.column(), was());
        let mut lines = text.split('\n');
        self.buf.push_str(lines.next().unwrap_or("").trim_end_matches('\r'));
        for line in lines {
            let line = line.trim_end();
            self.buf.push('\n');
            if line.trim().is_empty() {
                continue;
            }
            if now >= was {
                self.buf.extend(std::iter::repeat_n(' ', now - was));
                self.buf.push_str(line);
            } else {
                let lead = line.len() - line.trim_start_matches(' ').len();
                self.buf.push_str(&line[lead.min(was - now)..]);
            }
        }
    }

    /// The finished text: one line break at the end, none doubled.
    pub fn finish(mut self) -> String {
        self.newline();
        while self.buf.ends_with("\n\n") {
            self.buf.pop();
        }
        self.buf
    }
}

//! Standard output: what a command was asked for. Everything printed there
//! goes through here, escaped as the renderer escapes diagnostics — a block
//! name, a string value, a listing or a drawing can hold an escape sequence
//! (from a database, an object or a source), and none may reach the
//! terminal raw. Line ends stay line ends.

use linc_compiler::diag::{escape_text, Problems};
use std::io::Write;

/// Prints `text` as it is (escaped).
pub fn print(text: &str) {
    // A closed standard output ends the process by SIGPIPE (see main); any
    // other failure to write is no reason to panic.
    let _ = std::io::stdout().lock().write_all(escape_text(text).as_bytes());
}

/// Prints `text` and a line end (escaped).
pub fn line(text: &str) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(escape_text(text).as_bytes());
    let _ = out.write_all(b"\n");
}

/// What a command made (`make`: the text and its problems), printed, or
/// written atomically to `out` (`-o`), which is checked against the
/// command's `inputs` before anything is made. The exit status.
pub fn print_or_write(
    out: Option<&std::path::Path>,
    inputs: &[&std::path::Path],
    r: &crate::report::Reporter,
    make: impl FnOnce() -> Result<(String, Problems), Problems>,
) -> u8 {
    let made = out
        .map_or(Ok(()), |out| linc_driver::files::check_output(out, inputs).map_err(Problems::from))
        .and_then(|()| make());
    let (text, mut problems) = match made {
        Ok(made) => made,
        Err(p) => return r.report(&p),
    };
    match out {
        Some(out) => {
            if let Err(e) = linc_driver::files::write_atomic(out, text.as_bytes()) {
                problems.append(e.into());
            }
        }
        None => print(&text),
    }
    r.report(&problems)
}

/// Standard output written as it is made (a listing or a drawing can be
/// many times its input), escaped like [`fn@print`] and buffered.
pub struct Stream {
    out: std::io::BufWriter<std::io::StdoutLock<'static>>,
}

impl Stream {
    pub fn new() -> Self {
        Stream { out: std::io::BufWriter::new(std::io::stdout().lock()) }
    }

    /// Writes `text` escaped; a closed standard output is no error here.
    pub fn text(&mut self, text: &str) {
        let _ = self.out.write_all(escape_text(text).as_bytes());
    }
}

impl Write for Stream {
    /// Text formatted into the stream is escaped; bytes that are not UTF-8
    /// are written as the replacement character.
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let text = String::from_utf8_lossy(buf);
        self.out.write_all(escape_text(&text).as_bytes())?;
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

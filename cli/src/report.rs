//! The one place a command's problems are printed.
//!
//! Every error, warning and note of every stage — compile diagnostics, a
//! database that does not load, a refused object, a runtime fault, a
//! strategy that can't start, a damaged state file, a refused option —
//! comes back from the driver as [`Problems`] and is rendered here, in the
//! format asked for (`--message-format human|short|json`), on standard
//! error; standard output carries only what the command was asked for
//! (values, listings, traces, reports, the console's replies). The exit
//! status follows from the problems: 2 when the request was refused, 1
//! when errors were found, 0 otherwise.

use linc_compiler::diag::{Diagnostic, Format, Problems};
use linc_format::Code;
use std::io::Write;

/// Renders problems in one format to standard error.
#[derive(Clone, Copy)]
pub struct Reporter {
    format: Format,
}

impl Reporter {
    pub fn new(format: Format) -> Reporter {
        Reporter { format }
    }

    pub fn format(&self) -> Format {
        self.format
    }

    /// Prints `p` and gives the exit status it means.
    pub fn report(&self, p: &Problems) -> u8 {
        // A closed standard error is no reason to stop or panic.
        let _ = std::io::stderr().lock().write_all(p.render(self.format).as_bytes());
        status(p)
    }

    /// [`Reporter::report`] for what a command made (its warnings, or its
    /// findings) or what stopped it.
    pub fn done(&self, result: Result<Problems, Problems>) -> u8 {
        match result {
            Ok(p) | Err(p) => self.report(&p),
        }
    }

    /// A note about the command (a summary line), as every other problem
    /// is printed; in `json` an object with its code.
    pub fn note(&self, code: Code, message: impl Into<String>) {
        self.report(&Problems::finding(Diagnostic::note(code, message)));
    }

    /// `p` rendered, for a transcript that keeps replies and refusals in
    /// order on standard output (the console's).
    pub fn text(&self, p: &Problems) -> String {
        p.render(self.format)
    }
}

/// The exit status `p` means: 2 a refused request, 1 errors found, else 0.
pub fn status(p: &Problems) -> u8 {
    if p.is_refused() {
        2
    } else {
        u8::from(p.has_errors())
    }
}

/// A refused option or argument (E0903), printed; exit status 2.
pub fn usage(r: &Reporter, message: impl Into<String>) -> u8 {
    r.report(&Problems::usage(Code::E0903, message))
}

//! Usage problems of the command line, through the one reporter.

use linc_driver::Reporter;

/// Reports a refused option or argument (E0903) and gives exit status 2.
pub fn usage(r: &mut Reporter, msg: impl std::fmt::Display) -> u8 {
    r.command("E0903", msg.to_string());
    2
}

/// Reports a diagnostic about the command (E0903, E0904 …) and gives exit
/// status 2.
pub fn refused(r: &mut Reporter, d: linc_compiler::Diagnostic) -> u8 {
    r.emit_own(d);
    2
}

//! Errors in the files the comms commands read (a host's word table and
//! command list, a Modbus map), as plain data: a code, a message and where
//! in the file. The driver renders them with the other diagnostics.

use linc_format::Code;

/// A byte range in a file's text.
pub type Span = (usize, usize);

#[derive(Clone, Debug, PartialEq)]
pub struct FileError {
    pub code: Code,
    pub message: String,
    pub span: Option<Span>,
}

impl FileError {
    pub fn at(code: Code, message: impl Into<String>, span: Span) -> FileError {
        FileError { code, message: message.into(), span: Some(span) }
    }
}

impl std::fmt::Display for FileError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "error[{}]: {}", self.code.as_str(), self.message)
    }
}

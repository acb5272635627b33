//! TEMPORARY stub of the console (being written on branch console).
use crate::strategy::Strategy;

#[derive(Clone, Debug, PartialEq)]
pub struct ConsoleError {
    pub code: &'static str,
    pub message: String,
}

pub struct Console {
    pub strategy: Strategy,
}

impl Console {
    pub fn new(strategy: Strategy) -> Console {
        Console { strategy }
    }
    pub fn execute(&mut self, line: &str) -> Vec<Result<String, ConsoleError>> {
        vec![Err(ConsoleError { code: "C0001", message: format!("stub: {line}") })]
    }
    pub fn take_failures(&mut self) -> Vec<crate::RuntimeError> {
        Vec::new()
    }
}

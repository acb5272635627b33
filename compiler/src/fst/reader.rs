//! (stub: being written on branch fst-front)
use super::Table;
use crate::diagnostic::Diagnostic;
pub fn read(_text: &str) -> (Table, Vec<Diagnostic>) {
    (Table::default(), Vec::new())
}

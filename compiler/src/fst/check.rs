//! (stub: being written on branch fst-front)
use super::{Checked, Table};
use crate::diagnostic::Diagnostic;
use linc_runtime::Database;
pub fn check(_table: &Table, _db: Option<&Database>) -> (Option<Checked>, Vec<Diagnostic>) {
    (None, Vec::new())
}

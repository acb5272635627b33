//! Case-insensitive name lookup without allocating: names ignore case
//! (§12.8), and the checker looks up a block and a field for every
//! reference it reads, so a lookup that built an upper-case `String` and
//! hashed it with SipHash was a fifth of `linc check`'s time. Keys are
//! stored in upper case; a name is upper-cased into a stack buffer for the
//! lookup, and hashed with foldhash (fast, and seeded per process, so a
//! hostile database cannot choose colliding names ahead of time).

use std::collections::HashMap;

/// The longest name upper-cased on the stack; longer ones allocate.
const STACK: usize = 64;

#[derive(Clone, Debug, Default)]
pub struct NameMap(HashMap<Box<[u8]>, usize, foldhash::fast::RandomState>);

impl PartialEq for NameMap {
    fn eq(&self, other: &Self) -> bool {
        self.0 == other.0
    }
}

impl NameMap {
    pub fn get(&self, name: &str) -> Option<usize> {
        upper(name, |key| self.0.get(key).copied())
    }

    pub fn contains(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    pub fn insert(&mut self, name: &str, index: usize) {
        self.0.insert(name.to_ascii_uppercase().into_bytes().into_boxed_slice(), index);
    }
}

impl FromIterator<(String, usize)> for NameMap {
    fn from_iter<I: IntoIterator<Item = (String, usize)>>(iter: I) -> Self {
        let mut m = NameMap::default();
        for (name, i) in iter {
            m.insert(&name, i);
        }
        m
    }
}

/// Calls `f` with the bytes of `name` in ASCII upper case.
fn upper<R>(name: &str, f: impl FnOnce(&[u8]) -> R) -> R {
    let n = name.len();
    if n > STACK {
        return f(name.to_ascii_uppercase().as_bytes());
    }
    let mut buf = [0u8; STACK];
    buf[..n].copy_from_slice(name.as_bytes());
    buf[..n].make_ascii_uppercase();
    f(&buf[..n])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookups_ignore_ascii_case_at_any_length() {
        let long = "x".repeat(100);
        let m: NameMap =
            [("Tic_100".to_string(), 1), (long.clone(), 2), ("Größe".to_string(), 3)].into_iter().collect();
        assert_eq!(m.get("TIC_100"), Some(1));
        assert_eq!(m.get("tic_100"), Some(1));
        assert_eq!(m.get(&long.to_ascii_uppercase()), Some(2));
        assert_eq!(m.get("GRößE"), Some(3));
        assert_eq!(m.get("TIC_10"), None);
    }
}

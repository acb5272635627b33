//! Case-insensitive name lookup without allocating: names ignore case
//! (§12.8), and the checker looks up a block and a field for every
//! reference it reads, so a lookup that built an upper-case `String` and
//! hashed it with SipHash was a fifth of `linc check`'s time. Keys are
//! stored in upper case; a name is upper-cased into a stack buffer for the
//! lookup, and hashed with foldhash (fast, and seeded per process, so a
//! hostile database cannot choose colliding names ahead of time).
//!
//! Names of at most eight bytes (every LIN block and field name, §12.8) are
//! kept apart, packed into an integer with their length: a lookup then
//! upper-cases into a register and hashes and compares one integer, which
//! took the checker's lookups from about 120 instructions to about 70
//! (6% of the checking thread's work on the check benchmark).

use std::collections::HashMap;

/// The longest name upper-cased on the stack; longer ones allocate.
const STACK: usize = 64;

#[derive(Clone, Debug, Default)]
pub struct NameMap {
    /// Names of at most [`SHORT`] bytes, by [`packed`] key.
    short: HashMap<u128, usize, foldhash::fast::RandomState>,
    long: HashMap<Box<[u8]>, usize, foldhash::fast::RandomState>,
}

impl PartialEq for NameMap {
    fn eq(&self, other: &Self) -> bool {
        self.short == other.short && self.long == other.long
    }
}

/// The longest name kept in the packed map.
const SHORT: usize = 8;

/// A name of at most [`SHORT`] bytes in ASCII upper case, its bytes in the
/// low half and its length above them (so that a name ending in NUL bytes
/// differs from the shorter one).
fn packed(name: &[u8]) -> u128 {
    let mut key = 0u64;
    for (i, b) in name.iter().enumerate() {
        key |= u64::from(b.to_ascii_uppercase()) << (8 * i);
    }
    u128::from(key) | (name.len() as u128) << 64
}

impl NameMap {
    pub fn get(&self, name: &str) -> Option<usize> {
        if name.len() <= SHORT {
            return self.short.get(&packed(name.as_bytes())).copied();
        }
        upper(name, |key| self.long.get(key).copied())
    }

    pub fn contains(&self, name: &str) -> bool {
        self.get(name).is_some()
    }

    pub fn insert(&mut self, name: &str, index: usize) {
        if name.len() <= SHORT {
            self.short.insert(packed(name.as_bytes()), index);
        } else {
            self.long.insert(name.to_ascii_uppercase().into_bytes().into_boxed_slice(), index);
        }
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

    #[test]
    fn short_and_long_names_of_every_length_are_told_apart() {
        // Lengths around the packed keys' limit, names that differ only in
        // trailing NUL bytes or in bytes outside ASCII, and every case.
        let names: Vec<String> = (1..=12)
            .flat_map(|n| [format!("{:a<n$}", "b"), format!("{:\0<n$}", "b"), "é".repeat(n / 2).to_string()])
            .filter(|s| !s.is_empty())
            .collect();
        let mut m = NameMap::default();
        let mut seen: Vec<String> = Vec::new();
        for name in &names {
            if !seen.iter().any(|s| s.eq_ignore_ascii_case(name)) {
                m.insert(name, seen.len());
                seen.push(name.clone());
            }
        }
        for (i, name) in seen.iter().enumerate() {
            assert_eq!(m.get(name), Some(i), "{name:?}");
            assert_eq!(m.get(&name.to_ascii_lowercase()), Some(i), "{name:?}");
            assert_eq!(m.get(&name.to_ascii_uppercase()), Some(i), "{name:?}");
            assert_eq!(
                m.get(&format!("{name}x")).is_some(),
                seen.iter().any(|s| s.eq_ignore_ascii_case(&format!("{name}x")))
            );
        }
        assert_eq!(m.get(""), None);
        assert_eq!(m.get("\0"), None);
    }
}

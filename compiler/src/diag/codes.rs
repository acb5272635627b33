//! The registry of diagnostic codes lives beneath every stage, in
//! [`linc_format::code`]: a code is a [`Code`], so an error can only carry
//! a registered code with its page. This module re-exports it for the CLI
//! (`linc explain`) and checks that every registered code is used.

pub use linc_format::code::Code;

/// Every code, in order.
pub static CODES: &[Code] = Code::ALL;

/// Looks a code up, ignoring case (`e0001` works too).
pub fn lookup(code: &str) -> Option<Code> {
    Code::lookup(code)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every `.rs` file of the crates that emit codes, found by walking
    /// their source folders (a new file needs no entry in a list).
    fn sources() -> Vec<(std::path::PathBuf, String)> {
        fn walk(dir: &std::path::Path, out: &mut Vec<(std::path::PathBuf, String)>) {
            for entry in std::fs::read_dir(dir).expect("source folder").flatten() {
                let p = entry.path();
                if p.is_dir() {
                    walk(&p, out);
                } else if p.extension().is_some_and(|e| e == "rs") {
                    out.push((p.clone(), std::fs::read_to_string(&p).expect("source")));
                }
            }
        }
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
        let mut out = Vec::new();
        for krate in ["stdlib", "format", "runtime", "engines", "compiler", "driver", "draw", "comms", "serve", "cli"] {
            walk(&root.join(krate).join("src"), &mut out);
        }
        out
    }

    /// The codes named as `Code::E0104` in `src`.
    fn named(src: &str) -> Vec<&str> {
        src.match_indices("Code::")
            .filter_map(|(i, _)| src.get(i + 6..i + 11))
            .filter(|c| c.as_bytes()[0].is_ascii_uppercase() && c[1..].bytes().all(|b| b.is_ascii_digit()))
            .collect()
    }

    /// Every registered code is emitted by some stage's code (tests may
    /// name codes that no stage emits), and no stage carries a code as a
    /// bare string literal any more.
    #[test]
    fn every_registered_code_is_emitted() {
        let mut used = std::collections::HashSet::new();
        for (path, src) in sources() {
            let name = path.to_string_lossy();
            if name.ends_with("format/src/code.rs") || name.ends_with("tests.rs") {
                continue;
            }
            let code = src.split("#[cfg(test)]").next().unwrap_or_default();
            used.extend(named(code).into_iter().map(str::to_string));
            let b = code.as_bytes();
            let literal = (0..b.len().saturating_sub(6)).find(|&i| {
                b[i] == b'"'
                    && b"ECRW".contains(&b[i + 1])
                    && b[i + 2..i + 6].iter().all(u8::is_ascii_digit)
                    && b[i + 6] == b'"'
            });
            assert!(literal.is_none(), "{} writes a code as a string: use `Code::…`", path.display());
        }
        let unused: Vec<&str> = CODES.iter().map(|c| c.as_str()).filter(|c| !used.contains(*c)).collect();
        assert!(unused.is_empty(), "registered but never emitted: {unused:?}");
    }
}

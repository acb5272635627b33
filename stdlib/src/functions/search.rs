//! FIND (§12.6.2) and DELIMIT.
//!
//! Occurrences never overlap. With a positive N they are counted from the
//! left, each search starting after the previous occurrence; with a
//! negative N from the right, each search ending before the previous
//! occurrence. So FIND('AAAAA', 'AA', -1) = 4 and, for DELIMIT, the
//! delimiters are found from the right when N < 0:
//! DELIMIT('ABC>>>DEF>>>G', '>>', -2) = 'DEF>' (the guide's only example of
//! overlapping delimiters counts from the left: N = 2 gives '>DEF').

/// The first occurrence of `needle` (non-empty) in `hay` at or after
/// `from`.
fn find_from(hay: &[u8], needle: &[u8], from: usize) -> Option<usize> {
    if needle.is_empty() {
        return None;
    }
    let tail = hay.get(from..)?;
    tail.windows(needle.len()).position(|w| w == needle).map(|p| p + from)
}

/// The last occurrence of `needle` (non-empty) lying wholly before `end`.
fn rfind_before(hay: &[u8], needle: &[u8], end: usize) -> Option<usize> {
    if needle.is_empty() {
        return None;
    }
    let head = hay.get(..end)?;
    head.windows(needle.len()).rposition(|w| w == needle)
}

/// FIND(s1, s2, N): the 1-based position of the Nth occurrence of `s2` in
/// `s1` (N defaults to 1).
///
/// 0 when N = 0, `s1` is null or there is no Nth occurrence. When `s2` is
/// null: 1 for N > 0, LEN(s1)+1 for N < 0. The guide does not order these
/// rules; linc checks N = 0 first, then a null `s1` (so FIND('', '') = 0).
pub fn find(s1: &[u8], s2: &[u8], n: i32) -> i32 {
    if n == 0 || s1.is_empty() {
        return 0;
    }
    let position = |p: usize| i32::try_from(p + 1).unwrap_or(i32::MAX);
    if s2.is_empty() {
        return if n > 0 { 1 } else { position(s1.len()) };
    }
    let wanted = n.unsigned_abs();
    let mut found = 0;
    if n > 0 {
        let mut from = 0;
        while let Some(p) = find_from(s1, s2, from) {
            found += 1;
            if found == wanted {
                return position(p);
            }
            from = p + s2.len();
        }
    } else {
        let mut end = s1.len();
        while let Some(p) = rfind_before(s1, s2, end) {
            found += 1;
            if found == wanted {
                return position(p);
            }
            end = p;
        }
    }
    0
}

/// DELIMIT(s1, s2, N): the Nth field of `s1` separated by `s2`, the start
/// and end of `s1` counting as delimiters; counted from the right when
/// N < 0. Null when `s1` or `s2` is null, N = 0, or `s1` has fewer than
/// |N|-1 delimiters.
pub fn delimit(s1: &[u8], s2: &[u8], n: i32) -> Vec<u8> {
    if s1.is_empty() || s2.is_empty() || n == 0 {
        return Vec::new();
    }
    let skip = n.unsigned_abs() - 1;
    let field = if n > 0 {
        let mut start = 0;
        for _ in 0..skip {
            match find_from(s1, s2, start) {
                Some(p) => start = p + s2.len(),
                None => return Vec::new(),
            }
        }
        let end = find_from(s1, s2, start).unwrap_or(s1.len());
        s1.get(start..end)
    } else {
        let mut end = s1.len();
        for _ in 0..skip {
            match rfind_before(s1, s2, end) {
                Some(p) => end = p,
                None => return Vec::new(),
            }
        }
        let start = rfind_before(s1, s2, end).map_or(0, |p| p + s2.len());
        s1.get(start..end)
    };
    field.map_or_else(Vec::new, <[u8]>::to_vec)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn find_edges() {
        assert_eq!(find(b"ABC", b"ABCD", 1), 0);
        assert_eq!(find(b"ABC", b"ABCD", -1), 0);
        assert_eq!(find(b"", b"", 1), 0);
        assert_eq!(find(b"", b"", -1), 0);
        assert_eq!(find(b"ABC", b"", 5), 1);
        assert_eq!(find(b"ABC", b"", i32::MIN), 4);
        assert_eq!(find(b"AAAAA", b"A", i32::MAX), 0);
        assert_eq!(find(b"AAAAA", b"A", i32::MIN), 0);
        assert_eq!(find(b"AAAAA", b"AA", 2), 3);
        assert_eq!(find(b"AAAAA", b"AA", 3), 0);
        assert_eq!(find(b"AAAAA", b"AA", -2), 2);
        assert_eq!(find(b"AAAAA", b"AA", -3), 0);
    }

    #[test]
    fn delimit_edges() {
        assert_eq!(delimit(b"a+b+c", b"+", -1), b"c");
        assert_eq!(delimit(b"a+b+c", b"+", -3), b"a");
        assert_eq!(delimit(b"a+b+c", b"+", -4), b"");
        assert_eq!(delimit(b"a+b+c", b"+", 4), b"");
        assert_eq!(delimit(b"a+b+c", b"+", i32::MIN), b"");
        assert_eq!(delimit(b"a+b+c", b"+", i32::MAX), b"");
        assert_eq!(delimit(b"+", b"+", 1), b"");
        assert_eq!(delimit(b"+", b"+", 2), b"");
        assert_eq!(delimit(b"a+", b"+", -1), b"");
        assert_eq!(delimit(b"ABC>>>DEF>>>G", b">>", -1), b"G");
        assert_eq!(delimit(b"ABC>>>DEF>>>G", b">>", -2), b"DEF>");
        assert_eq!(delimit(b"ABC>>>DEF>>>G", b">>", -3), b"ABC>");
        assert_eq!(delimit(b"ABC>>>DEF>>>G", b">>", 3), b">G");
    }
}

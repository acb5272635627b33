//! String basics (§12.6): byte sequences with 1-based positions. FIND and
//! DELIMIT are in [`super::search`].
//!
//! The "null sequence" is the empty byte sequence. Where the guide is
//! silent, a length or field width that is zero or negative gives the null
//! sequence (for LEFT, RIGHT, MID, DELETE, REPLACE, STRING and SPACE, and
//! for a negative JUSTIFY_* width); in particular DELETE and REPLACE with
//! L = 0 give the null sequence rather than the unchanged input.

use super::{clip_len, span, MAX_LEN};
use std::cmp::Ordering;
use std::ops::Range;

/// A length argument as a byte count, or `None` if it is zero or negative.
#[inline]
fn count(l: i32) -> Option<usize> {
    usize::try_from(l).ok().filter(|&l| l > 0)
}

/// EQUAL: strict byte equality (no case folding).
pub fn equal(a: &[u8], b: &[u8]) -> bool {
    a == b
}

/// LEN: the number of bytes (saturating at the INT maximum).
pub fn len(s: &[u8]) -> i32 {
    i32::try_from(s.len()).unwrap_or(i32::MAX)
}

/// LEFT(s, L): the first L bytes; null if `s` has fewer than L bytes or
/// L <= 0.
pub fn left(s: &[u8], l: i32) -> Vec<u8> {
    count(l).and_then(|l| s.get(..l)).map_or_else(Vec::new, <[u8]>::to_vec)
}

/// RIGHT(s, L): the last L bytes; null if `s` has fewer than L bytes or
/// L <= 0.
pub fn right(s: &[u8], l: i32) -> Vec<u8> {
    count(l).and_then(|l| s.len().checked_sub(l)).and_then(|start| s.get(start..)).map_or_else(Vec::new, <[u8]>::to_vec)
}

/// MID(s, L, P): L bytes from position P; null if `s` has fewer than
/// L+P-1 bytes, P <= 0, P > LEN(s) or L <= 0.
pub fn mid(s: &[u8], l: i32, p: i32) -> Vec<u8> {
    count(l).and_then(|l| span(s.len(), p, l)).and_then(|r| s.get(r)).map_or_else(Vec::new, <[u8]>::to_vec)
}

/// The bytes of a string of `len` bytes that LEFT(s, L) keeps, as a range
/// (empty for the null sequence): what the VM's string stack keeps in
/// place instead of building a new value.
#[inline]
pub fn left_range(len: usize, l: i32) -> Range<usize> {
    count(l).filter(|&l| l <= len).map_or(0..0, |l| 0..l)
}

/// The bytes RIGHT(s, L) keeps of a string of `len` bytes.
#[inline]
pub fn right_range(len: usize, l: i32) -> Range<usize> {
    count(l).and_then(|l| len.checked_sub(l)).map_or(0..0, |start| start..len)
}

/// The bytes MID(s, L, P) keeps of a string of `len` bytes.
#[inline]
pub fn mid_range(len: usize, l: i32, p: i32) -> Range<usize> {
    count(l).and_then(|l| span(len, p, l)).unwrap_or(0..0)
}

/// CONCAT: `a` followed by `b`.
pub fn concat(a: &[u8], b: &[u8]) -> Vec<u8> {
    [a, b].concat()
}

/// INSERT(s1, s2, P): `s2` inserted before position P of `s1`; null if
/// P <= 0 or P > LEN(s1)+1.
pub fn insert(s1: &[u8], s2: &[u8], p: i32) -> Vec<u8> {
    match span(s1.len(), p, 0) {
        Some(at) => {
            [s1.get(..at.start), Some(s2), s1.get(at.start..)].into_iter().flatten().flatten().copied().collect()
        }
        None => Vec::new(),
    }
}

/// DELETE(s, L, P): `s` without the L bytes from position P; null if `s`
/// has fewer than L+P-1 bytes, P <= 0 or L <= 0.
pub fn delete(s: &[u8], l: i32, p: i32) -> Vec<u8> {
    replace(s, &[], l, p)
}

/// REPLACE(s1, s2, L, P): `s1` with its L bytes from position P replaced by
/// `s2` (of any length); null if `s1` has fewer than L+P-1 bytes, P <= 0 or
/// L <= 0.
pub fn replace(s1: &[u8], s2: &[u8], l: i32, p: i32) -> Vec<u8> {
    match count(l).and_then(|l| span(s1.len(), p, l)) {
        Some(r) => [s1.get(..r.start), Some(s2), s1.get(r.end..)].into_iter().flatten().flatten().copied().collect(),
        None => Vec::new(),
    }
}

/// The field width as a byte count clipped to [`MAX_LEN`], or `None` if
/// negative.
fn field_width(w: i32) -> Option<usize> {
    usize::try_from(w).ok().map(|w| w.min(MAX_LEN))
}

/// JUSTIFY_LEFT / JUSTIFY_RIGHT / JUSTIFY_CENTRE with `left_share(pad)` of
/// the padding on the left. Null if `s` is longer than the width or the
/// width is negative; a width above 1020 is clipped to 1020.
fn justify(s: &[u8], w: i32, left_share: fn(usize) -> usize) -> Vec<u8> {
    let Some(pad) = field_width(w).and_then(|w| w.checked_sub(s.len())) else {
        return Vec::new();
    };
    let before = left_share(pad);
    let mut out = vec![b' '; before];
    out.extend_from_slice(s);
    out.resize(s.len() + pad, b' ');
    out
}

/// JUSTIFY_LEFT(s, W): `s` padded with spaces on the right to W bytes.
pub fn justify_left(s: &[u8], w: i32) -> Vec<u8> {
    justify(s, w, |_| 0)
}

/// JUSTIFY_RIGHT(s, W): `s` padded with spaces on the left to W bytes.
pub fn justify_right(s: &[u8], w: i32) -> Vec<u8> {
    justify(s, w, |pad| pad)
}

/// JUSTIFY_CENTRE(s, W): `s` centred in W bytes; when it cannot be centred
/// exactly it is biased to the left (the extra space goes on the right).
pub fn justify_centre(s: &[u8], w: i32) -> Vec<u8> {
    justify(s, w, |pad| pad / 2)
}

/// LTRIM: without leading spaces (byte 16#20 only).
pub fn ltrim(s: &[u8]) -> Vec<u8> {
    let start = s.iter().take_while(|&&c| c == b' ').count();
    s.get(start..).unwrap_or(&[]).to_vec()
}

/// RTRIM: without trailing spaces (byte 16#20 only).
pub fn rtrim(s: &[u8]) -> Vec<u8> {
    let end = s.len() - s.iter().rev().take_while(|&&c| c == b' ').count();
    s.get(..end).unwrap_or(&[]).to_vec()
}

/// TRIM: without leading or trailing spaces.
pub fn trim(s: &[u8]) -> Vec<u8> {
    rtrim(&ltrim(s))
}

/// UCASE: ASCII a–z to A–Z; other bytes unchanged.
pub fn ucase(s: &[u8]) -> Vec<u8> {
    s.to_ascii_uppercase()
}

/// LCASE: ASCII A–Z to a–z; other bytes unchanged.
pub fn lcase(s: &[u8]) -> Vec<u8> {
    s.to_ascii_lowercase()
}

/// STRING(L, s): the first byte of `s` repeated L times, L clipped to 1020.
/// Null if L <= 0 or `s` is null.
pub fn string(l: i32, s: &[u8]) -> Vec<u8> {
    match (clip_len(l), s.first()) {
        (Some(l), Some(&c)) => vec![c; l],
        _ => Vec::new(),
    }
}

/// SPACE(L): L spaces, L clipped to 1020; null if L <= 0.
pub fn space(l: i32) -> Vec<u8> {
    clip_len(l).map_or_else(Vec::new, |l| vec![b' '; l])
}

/// STRCOMP: -1, 0 or 1 by unsigned byte-wise comparison, a prefix sorting
/// first ('aa' < 'ab', 'aa' < 'aaa').
pub fn strcomp(a: &[u8], b: &[u8]) -> i32 {
    match a.cmp(b) {
        Ordering::Less => -1,
        Ordering::Equal => 0,
        Ordering::Greater => 1,
    }
}

/// PURGE(s1, s2): `s1` without every byte that appears in `s2`.
pub fn purge(s1: &[u8], s2: &[u8]) -> Vec<u8> {
    s1.iter().copied().filter(|c| !s2.contains(c)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn extreme_positions_and_lengths_are_null() {
        let s = b"ABCDE";
        for (l, p) in [(i32::MAX, 1), (1, i32::MAX), (i32::MAX, i32::MAX), (i32::MIN, 1), (1, i32::MIN), (-1, -1)] {
            assert_eq!(mid(s, l, p), b"", "MID {l} {p}");
            assert_eq!(delete(s, l, p), b"", "DELETE {l} {p}");
            assert_eq!(replace(s, b"x", l, p), b"", "REPLACE {l} {p}");
        }
        for p in [i32::MIN, -1, 0, 7, i32::MAX] {
            assert_eq!(insert(s, b"x", p), b"", "INSERT {p}");
        }
        for l in [i32::MIN, -1, 0, 6, i32::MAX] {
            assert_eq!(left(s, l), b"");
            assert_eq!(right(s, l), b"");
        }
    }

    #[test]
    fn justify_widths() {
        assert_eq!(justify_left(b"ab", i32::MIN), b"");
        assert_eq!(justify_right(b"", 0), b"");
        assert_eq!(justify_centre(b"ab", i32::MAX).len(), MAX_LEN);
        assert_eq!(justify_left(&[b'a'; 1100], i32::MAX), b"");
    }

    #[test]
    fn strings_and_spaces_clip() {
        assert_eq!(string(i32::MAX, b"xy").len(), MAX_LEN);
        assert_eq!(string(3, b""), b"");
        assert_eq!(string(i32::MIN, b"x"), b"");
        assert_eq!(space(i32::MAX).len(), MAX_LEN);
        assert_eq!(space(-3), b"");
        assert_eq!(space(0), b"");
    }

    #[test]
    fn trims_and_cases() {
        assert_eq!(trim(b"   "), b"");
        assert_eq!(trim(b""), b"");
        assert_eq!(ltrim(b"\t a"), b"\t a");
        assert_eq!(ucase(b"a\xe9z"), b"A\xe9Z");
        assert_eq!(lcase(b"A\xc9Z"), b"a\xc9z");
        assert_eq!(strcomp(b"\xff", b"a"), 1);
        assert_eq!(strcomp(b"", b""), 0);
    }
}

//! The VM's string stack: every value end to end in one byte buffer.
//!
//! A stack of separate buffers cost a buffer's bookkeeping per value (find
//! a spare, hand it back) and a copy per CONCAT. Here pushing copies once
//! into memory kept from run to run, LEFT, RIGHT and MID move the bytes they
//! keep to the value's start, and CONCAT of the two top values, which lie
//! side by side, only forgets the boundary between them: the string
//! building of a LIN action allocates nothing once the buffer has grown.

use linc_stdlib::call::InPlace;

/// What the buffer keeps between runs at most: more is given back when a
/// run starts, so one run's huge strings do not stay allocated.
const KEEP: usize = 1 << 20;

#[derive(Debug, Default)]
pub(crate) struct StrStack {
    bytes: Vec<u8>,
    /// Where each value starts in `bytes`, bottom first; the top one ends
    /// where `bytes` does.
    starts: Vec<usize>,
}

impl StrStack {
    /// How many values the stack holds.
    pub fn len(&self) -> usize {
        self.starts.len()
    }

    /// Where the top value starts.
    #[inline]
    fn start(&self) -> usize {
        self.starts.last().copied().unwrap_or(0)
    }

    #[inline]
    pub fn push(&mut self, s: &[u8]) {
        self.starts.push(self.bytes.len());
        append(&mut self.bytes, s);
    }

    /// Appends `s` to the top value (on an empty stack, makes it one).
    #[cfg(feature = "jit")]
    #[inline]
    pub fn extend_top(&mut self, s: &[u8]) {
        if self.starts.is_empty() {
            self.starts.push(0);
        }
        append(&mut self.bytes, s);
    }

    /// The top value (the null string on an empty stack).
    #[inline]
    pub fn top(&self) -> &[u8] {
        self.bytes.get(self.start()..).unwrap_or_default()
    }

    /// The two top values, the lower first (null strings where the stack
    /// holds fewer).
    pub fn top_two(&self) -> (&[u8], &[u8]) {
        let mid = self.start();
        let low = match self.starts.len() {
            0 | 1 => mid,
            n => self.starts[n - 2],
        };
        (&self.bytes[low..mid], &self.bytes[mid..])
    }

    /// Removes the top value (none on an empty stack).
    #[inline]
    pub fn drop_top(&mut self) {
        if let Some(start) = self.starts.pop() {
            self.bytes.truncate(start);
        }
    }

    /// Removes the top value into `out` (cleared first).
    pub fn pop_into(&mut self, out: &mut Vec<u8>) {
        out.clear();
        out.extend_from_slice(self.top());
        self.drop_top();
    }

    /// Makes sure the stack holds at least `n` values, adding null strings
    /// below the others: an instruction short of operands reads nulls, as
    /// popping an empty stack does.
    #[inline]
    pub fn at_least(&mut self, n: usize) {
        while self.starts.len() < n {
            self.starts.insert(0, 0);
        }
    }

    /// CONCAT of the two top values (a lone value stays as it is); the
    /// length of the result.
    #[inline]
    pub fn join(&mut self) -> usize {
        if self.starts.len() >= 2 {
            self.starts.pop();
        }
        self.bytes.len() - self.start()
    }

    /// The top value cut by LEFT, RIGHT or MID in place; its new length.
    #[inline]
    pub fn cut(&mut self, how: InPlace, ints: [i32; 2]) -> usize {
        let start = self.start();
        let keep = how.keep(self.bytes.len() - start, ints);
        let len = keep.len();
        if keep.start > 0 {
            self.bytes.copy_within(start + keep.start..start + keep.end, start);
        }
        self.bytes.truncate(start + len);
        len
    }

    /// Empties the stack at the start of a run, keeping its memory up to
    /// [`KEEP`] bytes.
    pub fn clear(&mut self) {
        self.bytes.clear();
        self.starts.clear();
        self.bytes.shrink_to(KEEP);
    }

    /// Room for `n` values without growing the list of their starts.
    pub fn reserve(&mut self, n: usize) {
        self.starts.reserve(n);
    }
}

/// Appends `s` to `v`. The strings of LIN actions are mostly short: up to
/// 16 bytes are moved as two overlapping words, not by a call of `memcpy`
/// (which took a fifth of a string-building loop's instructions).
#[inline]
pub(crate) fn append(v: &mut Vec<u8>, s: &[u8]) {
    let n = s.len();
    if n > 16 {
        v.extend_from_slice(s);
        return;
    }
    v.reserve(16);
    let len = v.len();
    // SAFETY: `reserve` made room for 16 more bytes after `len`, and every
    // write below ends within `n` <= 16 bytes of it; every read is within
    // `s` (the two reads of a size overlap when `n` is not a power of two).
    // The bytes written past `len + n` are beyond the new length.
    unsafe {
        let (src, dst) = (s.as_ptr(), v.as_mut_ptr().add(len));
        if n >= 8 {
            let (a, b) = (src.cast::<u64>().read_unaligned(), src.add(n - 8).cast::<u64>().read_unaligned());
            dst.cast::<u64>().write_unaligned(a);
            dst.add(n - 8).cast::<u64>().write_unaligned(b);
        } else if n >= 4 {
            let (a, b) = (src.cast::<u32>().read_unaligned(), src.add(n - 4).cast::<u32>().read_unaligned());
            dst.cast::<u32>().write_unaligned(a);
            dst.add(n - 4).cast::<u32>().write_unaligned(b);
        } else if n >= 2 {
            let (a, b) = (src.cast::<u16>().read_unaligned(), src.add(n - 2).cast::<u16>().read_unaligned());
            dst.cast::<u16>().write_unaligned(a);
            dst.add(n - 2).cast::<u16>().write_unaligned(b);
        } else if n == 1 {
            *dst = *src;
        }
        v.set_len(len + n);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stack(values: &[&str]) -> StrStack {
        let mut s = StrStack::default();
        for v in values {
            s.push(v.as_bytes());
        }
        s
    }

    #[test]
    fn values_lie_end_to_end() {
        let mut s = stack(&["ab", "", "cde"]);
        assert_eq!(s.len(), 3);
        assert_eq!(s.top(), b"cde");
        assert_eq!(s.top_two(), (&b""[..], &b"cde"[..]));
        s.drop_top();
        assert_eq!(s.top_two(), (&b"ab"[..], &b""[..]));
        let mut out = b"junk".to_vec();
        s.pop_into(&mut out);
        assert_eq!(out, b"");
        s.pop_into(&mut out);
        assert_eq!((out.as_slice(), s.len(), s.top()), (&b"ab"[..], 0, &b""[..]));
        // Popping an empty stack gives the null string.
        s.pop_into(&mut out);
        assert_eq!((out.as_slice(), s.len()), (&b""[..], 0));
    }

    #[test]
    fn join_and_cut_work_on_the_top() {
        let mut s = stack(&["x", "abc", "def"]);
        assert_eq!(s.join(), 6);
        assert_eq!(s.top_two(), (&b"x"[..], &b"abcdef"[..]));
        assert_eq!(s.cut(InPlace::Right, [4, 0]), 4);
        assert_eq!(s.top(), b"cdef");
        assert_eq!(s.cut(InPlace::Mid, [2, 2]), 2);
        assert_eq!(s.top(), b"de");
        assert_eq!(s.cut(InPlace::Left, [3, 0]), 0, "LEFT of more than the length is null");
        s.push(b"yz");
        assert_eq!(s.join(), 2, "a null string joined to yz");
        assert_eq!(s.top_two(), (&b"x"[..], &b"yz"[..]));
        // Short of operands, the missing ones are nulls below.
        let mut one = stack(&["q"]);
        one.at_least(2);
        assert_eq!(one.top_two(), (&b""[..], &b"q"[..]));
        assert_eq!(one.join(), 1);
        assert_eq!((one.len(), one.top()), (1, &b"q"[..]));
    }

    #[test]
    fn append_copies_every_length() {
        let source: Vec<u8> = (0..40u8).collect();
        for n in 0..=40 {
            for before in [0, 1, 7, 15] {
                let mut v: Vec<u8> = vec![200; before];
                append(&mut v, &source[..n]);
                let mut want = vec![200; before];
                want.extend_from_slice(&source[..n]);
                assert_eq!(v, want, "{n} bytes after {before}");
            }
        }
    }

    #[test]
    fn clear_keeps_a_bounded_buffer() {
        let mut s = stack(&["abc"]);
        s.push(&vec![b'z'; 3 * KEEP]);
        s.clear();
        assert_eq!((s.len(), s.top()), (0, &b""[..]));
        assert!(s.bytes.capacity() <= KEEP);
    }
}

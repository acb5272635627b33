//! Implementations of the function table (§12.6), one module per category.
//!
//! Every function here is total: it accepts any argument values (negative
//! lengths, huge positions, empty sequences, `i32::MIN`, NaN) and never
//! panics, indexes out of bounds or allocates more than [`MAX_LEN`] bytes
//! beyond the size of its inputs. [`crate::call::call`] dispatches to them.

pub mod bits;
pub mod checksum;
pub mod convert;
pub mod datetime;
pub mod extract;
pub mod format;
pub mod numeric;
pub mod scan;
pub mod search;
pub mod select;
pub(crate) mod spec;
pub mod strings;

use crate::Value;

/// The longest sequence a length or width argument can ask for: STRING and
/// SPACE clip their length to 1020 (§12.6), and linc clips the field width
/// of JUSTIFY_* and FORMAT the same way.
pub const MAX_LEN: usize = 1020;

/// Total, typed access to an argument list: a missing argument or one of the
/// wrong kind reads as 0, FALSE, 0.0 or the null sequence.
#[derive(Clone, Copy, Debug)]
pub struct Args<'a>(pub &'a [Value]);

impl<'a> Args<'a> {
    pub fn len(&self) -> usize {
        self.0.len()
    }

    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// The argument itself, if given.
    pub fn get(&self, i: usize) -> Option<&'a Value> {
        self.0.get(i)
    }

    /// An INT parameter (a REAL rounds half away from zero, saturating).
    pub fn int(&self, i: usize) -> i32 {
        self.0.get(i).map_or(0, Value::as_int)
    }

    /// An ANY_NUM parameter read as a REAL.
    pub fn real(&self, i: usize) -> f32 {
        self.0.get(i).map_or(0.0, Value::as_real)
    }

    /// A BOOL parameter (non-zero is TRUE).
    pub fn boolean(&self, i: usize) -> bool {
        self.0.get(i).is_some_and(Value::as_bool)
    }

    /// A byte-sequence parameter (anything else is the null sequence).
    pub fn bytes(&self, i: usize) -> &'a [u8] {
        self.0.get(i).map_or(&[], Value::as_bytes)
    }
}

/// A length argument as a count of bytes: `None` when it is zero or
/// negative, otherwise clipped to [`MAX_LEN`].
pub(crate) fn clip_len(l: i32) -> Option<usize> {
    let l = usize::try_from(l).ok().filter(|&l| l > 0)?;
    Some(l.min(MAX_LEN))
}

/// The byte range `[p-1, p-1+n)` of a sequence of `len` bytes for a 1-based
/// position `p`, or `None` unless `p >= 1` and the range lies inside.
#[inline]
pub(crate) fn span(len: usize, p: i32, n: usize) -> Option<std::ops::Range<usize>> {
    let start = usize::try_from(p).ok()?.checked_sub(1)?;
    let end = start.checked_add(n)?;
    (end <= len).then_some(start..end)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn args_are_total() {
        let v = [Value::Bytes(b"ab".to_vec()), Value::Real(2.5)];
        let a = Args(&v);
        assert_eq!(a.int(0), 0);
        assert_eq!(a.int(1), 3);
        assert_eq!(a.int(7), 0);
        assert_eq!(a.bytes(0), b"ab");
        assert_eq!(a.bytes(1), b"");
        assert_eq!(a.bytes(9), b"");
        assert!(!a.boolean(9));
        assert_eq!(a.real(9), 0.0);
    }

    #[test]
    fn lengths_and_spans() {
        assert_eq!(clip_len(0), None);
        assert_eq!(clip_len(-5), None);
        assert_eq!(clip_len(i32::MIN), None);
        assert_eq!(clip_len(7), Some(7));
        assert_eq!(clip_len(i32::MAX), Some(MAX_LEN));
        assert_eq!(span(5, 1, 5), Some(0..5));
        assert_eq!(span(5, 2, 5), None);
        assert_eq!(span(5, 0, 1), None);
        assert_eq!(span(5, i32::MIN, 1), None);
        assert_eq!(span(5, i32::MAX, 1), None);
        assert_eq!(span(0, 1, 0), Some(0..0));
    }
}

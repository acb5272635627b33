//! The encoding of object-file tables, described once.
//!
//! Every table of a `.sto` file is a record declared with [`records!`]: the
//! field list gives the struct, its encoder and its bounds-checked decoder,
//! in field order (the wasmi way, as the instruction set does in `isa.rs`).
//! Adding a field to a record changes all three together.

use crate::errors::LoadError;
use crate::isa::Op;

/// A bounds-checked cursor; every read names the table it is in.
pub struct Reader<'a> {
    pub data: &'a [u8],
    pub at: usize,
}

impl<'a> Reader<'a> {
    pub fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8], LoadError> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.data.len());
        let end = end.ok_or_else(|| LoadError::Truncated { what: what.to_string() })?;
        let s = &self.data[self.at..end];
        self.at = end;
        Ok(s)
    }

    fn array<const N: usize>(&mut self, what: &str) -> Result<[u8; N], LoadError> {
        let b = self.bytes(N, what)?;
        let mut out = [0u8; N];
        out.copy_from_slice(b);
        Ok(out)
    }

    /// An element count of a table of `T`: it cannot exceed the bytes left
    /// divided by the fewest bytes a `T` takes, nor `T`'s own limit, so a
    /// damaged or hostile count can't make the table allocate more than a
    /// fixed multiple of the file.
    pub fn count<T: Wire>(&mut self, what: &str) -> Result<usize, LoadError> {
        let n = u32::get(self, what)? as usize;
        if n > (self.data.len() - self.at) / T::MIN.max(1) {
            return Err(LoadError::Truncated { what: what.to_string() });
        }
        if n > T::MAX_COUNT {
            let max = T::MAX_COUNT;
            return Err(LoadError::Malformed { what: format!("{what}: {n} entries, more than the {max} it may have") });
        }
        Ok(n)
    }
}

/// A value with a fixed place in the object encoding.
pub trait Wire: Sized {
    /// The fewest bytes an encoded value takes.
    const MIN: usize;
    /// The most values a table of them may hold (what the instructions can
    /// name: a `u16` operand names at most 65,536).
    const MAX_COUNT: usize = u32::MAX as usize;
    fn put(&self, out: &mut Vec<u8>);
    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError>;
}

macro_rules! wire_int {
    ($($t:ty),*) => {$(
        impl Wire for $t {
            const MIN: usize = std::mem::size_of::<$t>();
            fn put(&self, out: &mut Vec<u8>) {
                out.extend_from_slice(&self.to_le_bytes());
            }
            fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
                Ok(<$t>::from_le_bytes(r.array(what)?))
            }
        }
    )*};
}
wire_int!(u8, u16, u32, u64);

/// Names: a `u16` byte length and UTF-8. Longer text can't be encoded; the
/// compiler and the database loader refuse such names before they get here,
/// so `put` cutting at a character boundary is a last resort, not a path.
/// The one table of names, an FST table's step listing, is named by the
/// `u16` of `Step`.
impl Wire for String {
    const MIN: usize = 2;
    const MAX_COUNT: usize = 1 << 16;
    fn put(&self, out: &mut Vec<u8>) {
        let mut n = self.len().min(usize::from(u16::MAX));
        while !self.is_char_boundary(n) {
            n -= 1;
        }
        (n as u16).put(out);
        out.extend_from_slice(&self.as_bytes()[..n]);
    }
    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
        let n = usize::from(u16::get(r, what)?);
        let b = r.bytes(n, what)?;
        String::from_utf8(b.to_vec()).map_err(|_| LoadError::Malformed { what: format!("{what}: text is not UTF-8") })
    }
}

/// A byte string of the constant pool: `u32` length and bytes.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Bytes(pub Vec<u8>);

impl Wire for Bytes {
    const MIN: usize = 4;
    fn put(&self, out: &mut Vec<u8>) {
        (self.0.len() as u32).put(out);
        out.extend_from_slice(&self.0);
    }
    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
        let n = u32::get(r, what)? as usize;
        Ok(Bytes(r.bytes(n, what)?.to_vec()))
    }
}

/// A table: `u32` count, then the elements.
impl<T: Wire> Wire for Vec<T> {
    const MIN: usize = 4;
    fn put(&self, out: &mut Vec<u8>) {
        (self.len() as u32).put(out);
        for e in self {
            e.put(out);
        }
    }
    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
        // Exactly as many as the count, which `count` bounds by the bytes
        // left: a table never grows (a doubling would hold 1.5 times).
        let n = r.count::<T>(what)?;
        let mut v = Vec::with_capacity(n);
        for _ in 0..n {
            v.push(T::get(r, what)?);
        }
        Ok(v)
    }
}

/// Code: a `u32` byte length and the encoded instructions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Code(pub Vec<Op>);

impl std::ops::Deref for Code {
    type Target = [Op];
    fn deref(&self) -> &[Op] {
        &self.0
    }
}

impl Wire for Code {
    const MIN: usize = 4;
    fn put(&self, out: &mut Vec<u8>) {
        let mut code = Vec::new();
        for op in &self.0 {
            op.encode(&mut code);
        }
        (code.len() as u32).put(out);
        out.extend_from_slice(&code);
    }
    fn get(r: &mut Reader, what: &str) -> Result<Self, LoadError> {
        let n = u32::get(r, what)? as usize;
        let code = r.bytes(n, what)?;
        // Counted first, so that the instructions take exactly their room.
        let (mut count, mut at) = (0, 0);
        while at < code.len() && Op::decode(code, &mut at).is_some() {
            count += 1;
        }
        let mut ops = Vec::with_capacity(count);
        let mut at = 0;
        while at < code.len() {
            let start = at;
            let op = Op::decode(code, &mut at)
                .ok_or(LoadError::BadInstruction { at: r.at - code.len() + start, opcode: code[start] })?;
            ops.push(op);
        }
        Ok(Code(ops))
    }
}

/// Declares records: the struct and its [`Wire`] encoding, fields in order;
/// `at most N` limits a table of them to N.
#[macro_export]
macro_rules! records {
    ($( $(#[$m:meta])* $name:ident $what:literal $(at most $max:literal)? { $( $(#[$fm:meta])* $field:ident : $ty:ty ),* $(,)? } )*) => {$(
        $(#[$m])*
        #[derive(Clone, Debug, Default, PartialEq)]
        pub struct $name { $( $(#[$fm])* pub $field: $ty, )* }

        impl $crate::wire::Wire for $name {
            const MIN: usize = 0 $( + <$ty as $crate::wire::Wire>::MIN )*;
            $( const MAX_COUNT: usize = $max; )?
            fn put(&self, out: &mut Vec<u8>) {
                $( $crate::wire::Wire::put(&self.$field, out); )*
            }
            fn get(r: &mut $crate::wire::Reader, _what: &str) -> Result<Self, $crate::errors::LoadError> {
                Ok($name { $( $field: <$ty as $crate::wire::Wire>::get(r, $what)?, )* })
            }
        }
    )*};
}

#[cfg(test)]
mod tests {
    use super::*;

    records! {
        /// A record for the test.
        Sample "sample" { a: u8, b: u16, name: String, list: Vec<u32>, code: Code }
    }

    #[test]
    fn records_round_trip_and_every_cut_fails() {
        let s = Sample {
            a: 7,
            b: 300,
            name: "Fill".into(),
            list: vec![1, 2, 3],
            code: Code(vec![Op::PushI { v: 1 }, Op::Ret {}]),
        };
        let mut out = Vec::new();
        s.put(&mut out);
        let mut r = Reader { data: &out, at: 0 };
        assert_eq!(Sample::get(&mut r, "x"), Ok(s));
        assert_eq!(r.at, out.len());
        for cut in 0..out.len() {
            let mut r = Reader { data: &out[..cut], at: 0 };
            assert!(Sample::get(&mut r, "x").is_err(), "cut at {cut}");
        }
    }

    #[test]
    fn long_names_are_cut_at_a_character_boundary() {
        let long = "é".repeat(40_000);
        let mut out = Vec::new();
        long.put(&mut out);
        let mut r = Reader { data: &out, at: 0 };
        let back = String::get(&mut r, "x").expect("decodes");
        assert!(back.len() <= usize::from(u16::MAX) && long.starts_with(&back));
    }
}

//! The limits of the object format, checked while checking, so that
//! `linc check` rejects exactly what `linc compile` would (E0132).
//!
//! Each limit is reported once per action, at the first thing over it.

use super::errors::CheckError;
use super::Checker;
use crate::diag::span::Span;
use std::collections::HashSet;
use std::hash::{BuildHasherDefault, Hasher};

/// Arguments of one call: the call instruction types each in 2 bits of a
/// 32-bit word.
pub const MAX_CALL_ARGS: usize = linc_format::isa::MAX_CALL_ARGS;

/// FOR loops in one action: each keeps its limit in a local, numbered by
/// one byte with the last number reserved.
pub const MAX_FOR_LOOPS: u32 = 254;

/// Different database references in one object file: symbols are numbered
/// by 16 bits.
pub const MAX_REFERENCES: usize = 1 << 16;

/// A database reference as the object file's symbol table tells them apart:
/// block (0 for the action's own block, else its index + 1), field index in
/// the template, sub-part (see `Resolved`) and storage class.
pub type SymbolKey = (u32, u32, u32, u8);

/// A fast hasher for small integer keys and short names (FNV-1a).
#[derive(Default)]
pub struct Fnv(u64);

impl Hasher for Fnv {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        let mut h = if self.0 == 0 { 0xcbf2_9ce4_8422_2325 } else { self.0 };
        for b in bytes {
            h = (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3);
        }
        self.0 = h;
    }
}

/// A `HashSet`/`HashMap` hasher for keys that are not attacker-chosen in a
/// way that matters (a slow input is still linear).
pub type FastHash = BuildHasherDefault<Fnv>;

/// What spans the files of one object: the database references seen.
#[derive(Debug, Default)]
pub struct Limits {
    symbols: HashSet<SymbolKey, FastHash>,
}

/// Which limits one action has already reported.
#[derive(Debug, Default)]
pub(super) struct ActionLimits {
    for_loops: u32,
    reported_for: bool,
    reported_args: bool,
    reported_refs: bool,
}

impl Checker<'_> {
    /// Counts one FOR loop of the current action.
    pub(super) fn count_for_loop(&mut self, span: Span) {
        let a = &mut self.action_limits;
        a.for_loops += 1;
        if a.for_loops > MAX_FOR_LOOPS && !a.reported_for {
            a.reported_for = true;
            self.errors.push(CheckError::TooMany {
                span,
                what: "FOR loops in one action",
                limit: "an action has at most 254 FOR loops; move some loops into another action",
            });
        }
    }

    /// Reports a call with more than [`MAX_CALL_ARGS`] arguments.
    pub(super) fn count_call_args(&mut self, n: usize, span: Span) {
        if n > MAX_CALL_ARGS && !self.action_limits.reported_args {
            self.action_limits.reported_args = true;
            self.errors.push(CheckError::TooMany {
                span,
                what: "arguments in one call",
                limit: "a call has at most 16 arguments; split the call, e.g. MAX(MAX(a, b, ...), MAX(p, q, ...))",
            });
        }
    }

    /// Counts a database reference into the object's symbol table.
    pub(super) fn count_reference(&mut self, key: SymbolKey, span: Span) {
        if self.limits.symbols.len() < MAX_REFERENCES {
            self.limits.symbols.insert(key);
            return;
        }
        if !self.limits.symbols.contains(&key) && !self.action_limits.reported_refs {
            self.action_limits.reported_refs = true;
            self.errors.push(CheckError::TooMany {
                span,
                what: "database references in one object file",
                limit: "the actions compiled into one object use at most 65536 different fields and alarms; compile fewer files together",
            });
        }
    }
}

//! The compiling tier left out (built without the `jit` feature): nothing
//! compiles, and every block runs on the interpreter, which is the
//! reference anyway (`--tier compiled` then reports 0 blocks compiled).

use super::{Buffers, JitRun, Mode, Services};
use crate::link::Linked;
use crate::store::Store;

/// Compiled code, of which there is none without the feature.
pub struct Compiled {
    never: std::convert::Infallible,
}

impl Compiled {
    pub(crate) fn run(
        &self,
        _store: &mut Store,
        _retained: &mut [u32],
        _budget: u64,
        _buf: Buffers<'_>,
        _services: Services<'_, '_>,
    ) -> JitRun {
        match self.never {}
    }
}

/// A block ready to translate, of which there is none either.
pub(crate) struct Prepared {
    never: std::convert::Infallible,
}

impl Prepared {
    pub(super) fn compile(self) -> Option<Compiled> {
        match self.never {}
    }
}

pub(super) fn prepare(_: &Linked, _: &Store, _: (usize, usize), _: Mode) -> Option<Prepared> {
    None
}

pub(super) fn compile_as(_: &Linked, _: &Store, _: (usize, usize), _: Mode) -> Option<Compiled> {
    None
}

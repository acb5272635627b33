//! Which statements of an action ran in its last execution, for a picture
//! that must show what ran: a ladder rung skipped by a taken jump did not
//! run, whatever its contacts read now (docs/pictures.md).
//!
//! It is recorded, not worked out from the values afterwards: a rung after
//! the label may change what the jump read, so only the run knows. The
//! runtime's coverage counters (ADR 0020) already count each statement a
//! program starts, on the interpreter and compiled code alike; a watched
//! action's counts are read before and after each of its executions, and
//! the lines whose statements were counted in between are kept. Only the
//! watched actions pay for it (their object counts coverage from then on).

use super::Strategy;

/// What a watched action's last execution ran.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LinesRan {
    /// Source lines (1-based) on which a statement started.
    pub lines: Vec<u32>,
    /// How many times the action has executed since it was watched (0: it
    /// has not, and `lines` is empty).
    pub executions: u64,
}

/// A watched member's record.
#[derive(Clone, Debug, Default)]
pub(super) struct Watch {
    /// Each statement start's line and count, as they stood before the
    /// current execution.
    before: Vec<(u32, u64)>,
    last: LinesRan,
}

impl Strategy {
    /// From now on, keeps which statements of the action `block` runs (an
    /// ACTION-type block's action; not a sequence or an FST table) ran in
    /// its last execution. `false` when the block runs no such action.
    /// Call it before the run starts: counting begins with the next
    /// execution.
    pub fn watch_runs(&mut self, block: usize) -> bool {
        let Some(m) = self.members.iter().position(|m| m.block == block && m.seq.is_none() && m.fst.is_none()) else {
            return false;
        };
        self.objects[self.members[m].object].enable_coverage();
        self.members[m].watch.get_or_insert_with(Box::default);
        true
    }

    /// What the watched action `block` ran in its last execution (`None`
    /// when it is not watched).
    pub fn lines_ran(&self, block: usize) -> Option<&LinesRan> {
        self.members.iter().find(|m| m.block == block).and_then(|m| m.watch.as_deref()).map(|w| &w.last)
    }

    /// The count of every statement start of member `m`'s unit, with its
    /// line.
    fn statement_counts(&self, m: usize) -> Vec<(u32, u64)> {
        let member = &self.members[m];
        linc_runtime::cover::statement_counts(&self.objects[member.object], member.program)
    }

    /// Before member `m` executes: its counts as they stand, if watched.
    pub(super) fn watch_before(&mut self, m: usize) {
        if self.members[m].watch.is_none() {
            return;
        }
        let counts = self.statement_counts(m);
        if let Some(w) = self.members[m].watch.as_mut() {
            w.before = counts;
        }
    }

    /// After member `m` executed (to the end or to a fault): the lines
    /// whose statements were counted since [`Self::watch_before`].
    pub(super) fn watch_after(&mut self, m: usize) {
        if self.members[m].watch.is_none() {
            return;
        }
        let after = self.statement_counts(m);
        let Some(w) = self.members[m].watch.as_mut() else { return };
        let lines = linc_runtime::cover::lines_between(&w.before, &after);
        w.last = LinesRan { lines, executions: w.last.executions + 1 };
    }
}

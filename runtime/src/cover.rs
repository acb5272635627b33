//! Coverage counters (ADR 0020): what a run executed, counted per code
//! block instruction, per sequence step entered and per transition fired,
//! for `linc test --coverage`.
//!
//! The counters belong to a [`crate::Linked`] object and are shared by its
//! clones; the interpreter and compiled code add to the same ones. A linked
//! object runs on one thread at a time, so a count is a plain load and
//! store (no locked instruction): atomics only make sharing the table safe.
//! The counts of one unit add up whichever block ran it, so two programs of
//! one unit (two ACTION blocks naming it) count into the same place.

use crate::object::{ObjectFile, Unit};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// One count.
#[derive(Debug, Default)]
#[repr(transparent)]
pub struct Counter(AtomicU64);

impl Counter {
    /// Adds one (a plain add: see the module's comment).
    #[inline]
    pub fn bump(&self) {
        self.0.store(self.0.load(Relaxed).wrapping_add(1), Relaxed);
    }

    /// Takes one back (a compiled run that stopped at an instruction it
    /// had counted, which the interpreter then counts again).
    pub(crate) fn unbump(&self) {
        self.0.store(self.0.load(Relaxed).wrapping_sub(1), Relaxed);
    }

    pub fn get(&self) -> u64 {
        self.0.load(Relaxed)
    }

    /// Where compiled code adds to it (an `AtomicU64` is a `u64` in memory).
    #[cfg_attr(not(feature = "jit"), allow(dead_code))]
    pub(crate) fn as_ptr(&self) -> *mut u64 {
        self.0.as_ptr()
    }
}

fn counters(n: usize) -> Box<[Counter]> {
    (0..n).map(|_| Counter::default()).collect()
}

/// One code block's counts, by instruction index.
#[derive(Debug)]
pub struct BlockCounters {
    /// Times each instruction ran. The interpreter counts every one;
    /// compiled code counts the [`Self::is_point`] ones, which are all a
    /// report reads.
    pub(crate) hits: Box<[Counter]>,
    /// Times each conditional jump jumped.
    pub(crate) taken: Box<[Counter]>,
    /// The instructions a report reads: statement starts (the line table)
    /// and conditional jumps.
    points: Box<[bool]>,
}

impl BlockCounters {
    fn new(ops: &[crate::isa::Op], lines: &[crate::object::LineEntry]) -> BlockCounters {
        BlockCounters { hits: counters(ops.len()), taken: counters(ops.len()), points: points(ops, lines) }
    }

    /// Where compiled code adds: the first hit and taken counters.
    #[cfg_attr(not(feature = "jit"), allow(dead_code))]
    pub(crate) fn bases(&self) -> (*mut u64, *mut u64) {
        let base = |c: &[Counter]| c.first().map_or(std::ptr::null_mut(), Counter::as_ptr);
        (base(&self.hits), base(&self.taken))
    }

    /// The instructions a report reads, by index: what compiled code counts.
    #[cfg_attr(not(feature = "jit"), allow(dead_code))]
    pub(crate) fn points(&self) -> &[bool] {
        &self.points
    }

    /// Whether a report reads instruction `pc`'s counts.
    pub fn is_point(&self, pc: usize) -> bool {
        self.points.get(pc).copied().unwrap_or(false)
    }
}

/// The instructions of a block a report reads: its statement starts (the
/// line table) and its decisions.
pub fn points(ops: &[crate::isa::Op], lines: &[crate::object::LineEntry]) -> Box<[bool]> {
    let mut points: Box<[bool]> = ops.iter().map(is_decision).collect();
    for l in lines {
        if let Some(p) = points.get_mut(l.op as usize) {
            *p = true;
        }
    }
    points
}

/// Whether an instruction is a decision: a jump that depends on a value.
pub fn is_decision(op: &crate::isa::Op) -> bool {
    matches!(op, crate::isa::Op::JumpIfFalse { .. } | crate::isa::Op::JumpIfTrue { .. })
}

/// One unit's counts.
#[derive(Debug)]
struct UnitCounters {
    blocks: Vec<BlockCounters>,
    /// Steps of every chart of a sequence, charts in order.
    steps: Box<[Counter]>,
    transitions: Box<[Counter]>,
    /// Step and transition names (unique in a sequence) to their index.
    step_index: HashMap<String, usize>,
    transition_index: HashMap<String, usize>,
}

impl UnitCounters {
    fn new(u: &Unit) -> UnitCounters {
        let blocks = u.blocks.iter().map(|b| BlockCounters::new(&b.ops.0, &b.lines)).collect();
        let step_names = u.charts.iter().flat_map(|c| c.steps.iter().map(|s| s.name.clone()));
        let step_index: HashMap<String, usize> = step_names.enumerate().map(|(i, n)| (n, i)).collect();
        let transition_names = u.charts.iter().flat_map(|c| c.transitions.iter().map(|t| t.name.clone()));
        let transition_index: HashMap<String, usize> = transition_names.enumerate().map(|(i, n)| (n, i)).collect();
        let steps = counters(u.charts.iter().map(|c| c.steps.len()).sum());
        let transitions = counters(u.charts.iter().map(|c| c.transitions.len()).sum());
        UnitCounters { blocks, steps, transitions, step_index, transition_index }
    }
}

/// The counters of every unit of an object.
#[derive(Debug)]
pub struct Counters {
    units: Vec<UnitCounters>,
}

impl Counters {
    pub fn new(object: &ObjectFile) -> Counters {
        Counters { units: object.units.iter().map(UnitCounters::new).collect() }
    }

    pub(crate) fn block(&self, unit: usize, block: usize) -> Option<&BlockCounters> {
        self.units.get(unit)?.blocks.get(block)
    }

    /// A sequence's step `name` was entered.
    pub fn entered(&self, unit: usize, name: &str) {
        if let Some(u) = self.units.get(unit) {
            if let Some(&i) = u.step_index.get(name) {
                u.steps[i].bump();
            }
        }
    }

    /// A sequence's transition `name` fired.
    pub fn fired(&self, unit: usize, name: &str) {
        if let Some(u) = self.units.get(unit) {
            if let Some(&i) = u.transition_index.get(name) {
                u.transitions[i].bump();
            }
        }
    }

    /// Times instruction `pc` of block `block` of unit `unit` ran so far
    /// (0 for one that does not exist): a single count, for a caller that
    /// watches a few statements scan by scan without copying every count.
    pub fn hits(&self, unit: usize, block: usize, pc: usize) -> u64 {
        self.block(unit, block).and_then(|b| b.hits.get(pc)).map_or(0, Counter::get)
    }

    /// The counts as they stand.
    pub fn counts(&self) -> Counts {
        let read = |c: &[Counter]| c.iter().map(Counter::get).collect();
        let units = self.units.iter().map(|u| UnitCounts {
            blocks: u.blocks.iter().map(|b| BlockCounts { hits: read(&b.hits), taken: read(&b.taken) }).collect(),
            steps: read(&u.steps),
            transitions: read(&u.transitions),
        });
        Counts { units: units.collect() }
    }
}

/// The count of each statement start of `program`'s unit in `linked`,
/// with its source line: what a picture compares before and after an
/// execution to tell which lines ran (empty when coverage is off).
pub fn statement_counts(linked: &crate::Linked, program: usize) -> Vec<(u32, u64)> {
    let (Some(counters), Some(p)) = (linked.coverage(), linked.program(program)) else { return Vec::new() };
    let Some(unit) = linked.object().units.get(p.unit) else { return Vec::new() };
    let mut out = Vec::new();
    for (b, block) in unit.blocks.iter().enumerate() {
        for l in &block.lines {
            out.push((l.line, counters.hits(p.unit, b, l.op as usize)));
        }
    }
    out
}

/// The lines (sorted, once each) whose statements were counted between
/// two [`statement_counts`] of the same program.
pub fn lines_between(before: &[(u32, u64)], after: &[(u32, u64)]) -> Vec<u32> {
    let mut lines: Vec<u32> =
        after.iter().enumerate().filter(|(i, a)| a.1 > before.get(*i).map_or(0, |b| b.1)).map(|(_, a)| a.0).collect();
    lines.sort_unstable();
    lines.dedup();
    lines
}

/// Counts as plain numbers, laid out as the object's units (what a report
/// is made from).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Counts {
    pub units: Vec<UnitCounts>,
}

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct UnitCounts {
    pub blocks: Vec<BlockCounts>,
    /// Times each step was entered, charts in order.
    pub steps: Vec<u64>,
    /// Times each transition fired, charts in order.
    pub transitions: Vec<u64>,
}

/// A block's counts by instruction: `hits` is meaningful at statement
/// starts and conditional jumps, `taken` at conditional jumps.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct BlockCounts {
    pub hits: Vec<u64>,
    pub taken: Vec<u64>,
}

#[cfg(test)]
mod tests {
    use super::lines_between;

    #[test]
    fn the_lines_between_two_counts_are_those_counted_in_between_once_each() {
        let before = [(3, 1), (4, 1), (4, 0), (7, 2), (9, 0)];
        let after = [(3, 2), (4, 1), (4, 1), (7, 2), (9, 0)];
        assert_eq!(lines_between(&before, &after), [3, 4]);
        assert!(lines_between(&after, &after).is_empty(), "nothing ran");
        // A first count (coverage just enabled) counts from nothing.
        assert_eq!(lines_between(&[], &[(5, 1), (2, 1), (5, 3)]), [2, 5]);
    }
}

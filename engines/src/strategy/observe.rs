//! What a scenario test reads from a running strategy without changing it:
//! its fastest task, its sequences' step variables (`docs/testing.md`), and
//! how much of its code the compiling tier runs.

use super::Strategy;
use crate::Linked;

impl Strategy {
    /// Code blocks of the strategy's programs: how many the compiling tier
    /// has compiled so far (for a traced run or not) and how many there are.
    pub fn compiled_blocks(&self) -> (usize, usize) {
        self.objects.iter().map(Linked::compiled_blocks).fold((0, 0), |(c, a), (c2, a2)| (c + c2, a + a2))
    }

    /// Counts what runs from now on, for coverage reports (ADR 0020).
    pub fn enable_coverage(&mut self) {
        self.objects.iter_mut().for_each(Linked::enable_coverage);
    }

    /// Each object with the coverage counted so far (none when coverage
    /// is off).
    pub fn coverage(&self) -> Vec<(&linc_runtime::ObjectFile, linc_runtime::cover::Counts)> {
        let counted = self.objects.iter().filter_map(|l| l.coverage().map(|c| (l.object(), c.counts())));
        counted.collect()
    }

    /// The period of the fastest task, µs: one scan of the strategy.
    pub fn scan_us(&self) -> u64 {
        self.tasks.iter().map(|t| t.period_us).min().unwrap_or(100_000).max(1)
    }

    /// Every step of every sequence the strategy runs, sequence by sequence
    /// (database order) and in each in slot order: the names an expectation
    /// may use as `Step.X` and `Step.T`.
    pub fn step_names(&self) -> Vec<String> {
        let mut out = Vec::new();
        for m in self.members.iter().filter(|m| m.seq.is_some()) {
            let Some(unit) = self.objects[m.object].unit(m.program) else { continue };
            let mut steps: Vec<(u16, &str)> =
                unit.charts.iter().flat_map(|c| c.steps.iter().map(|s| (s.slot, s.name.as_str()))).collect();
            steps.sort_unstable();
            steps.dedup_by_key(|s| s.0);
            out.extend(steps.into_iter().map(|(_, n)| n.to_string()));
        }
        out
    }

    /// The step variables of [`Strategy::step_names`], in the same order:
    /// `.X` at `2 × i`, `.T` (seconds, REAL bits) at `2 × i + 1`.
    pub fn step_slots(&self, out: &mut Vec<u32>) {
        out.clear();
        for m in self.members.iter().filter(|m| m.seq.is_some()) {
            out.extend_from_slice(&m.act.retained);
        }
    }
}

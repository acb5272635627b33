//! The "unsafe" chart check: a transition that can activate a step that is
//! still active. That is what a transition leaving one branch of a
//! simultaneous divergence, or a divergence whose branches never converge,
//! leads to once the chart comes round again: the abandoned branch is still
//! active when the divergence fires again.
//!
//! The chart is played as a token game from its initial steps, each enabled
//! transition fired on its own (conditions may be anything), over the
//! distinct sets of active steps. The search is bounded (in sets held and in
//! work done), so a huge chart is checked only as far as the bounds allow and
//! can never exhaust memory or time; what it reports is always real.

use std::collections::{HashSet, VecDeque};

/// Words of active-step sets held at most (8 MB).
const MAX_WORDS: usize = 1 << 20;
/// Transitions examined at most.
const MAX_WORK: usize = 5_000_000;

/// A transition by step indices (its unknown steps left out).
pub struct Edge {
    pub from: Vec<usize>,
    pub to: Vec<usize>,
}

/// The first transition found that can activate an active step, by the
/// shortest run of firings (breadth first): the transition's index and the
/// step's. Only the first is reported, as one abandoned branch usually makes
/// several transitions unsafe.
pub fn unsafe_edge(steps: usize, initial: &[usize], edges: &[Edge]) -> Option<(usize, usize)> {
    let words = steps.div_ceil(64).max(1);
    let max_sets = (MAX_WORDS / words).max(1);
    let mut start = vec![0u64; words];
    for &s in initial {
        start[s / 64] |= 1 << (s % 64);
    }
    // The transitions leaving each step: a set of active steps looks only
    // at those, not at every transition of the chart (which made a chart of
    // n steps in a ring cost n × n).
    let leaving = Leaving::new(steps, edges);
    let has = |m: &[u64], s: usize| m[s / 64] & (1 << (s % 64)) != 0;
    let mut seen: HashSet<Vec<u64>> = HashSet::from([start.clone()]);
    let mut todo = VecDeque::from([start]);
    let mut work = 0usize;
    let mut enabled = Vec::new();
    while let Some(m) = todo.pop_front() {
        // In index order, as the search examined them before.
        enabled.clear();
        enabled.extend(active(&m).flat_map(|s| leaving.of(s).iter().copied()));
        enabled.sort_unstable();
        enabled.dedup();
        for &ti in &enabled {
            let e = &edges[ti];
            work += 1;
            if work > MAX_WORK {
                return None;
            }
            if !e.from.iter().all(|&s| has(&m, s)) {
                continue;
            }
            let mut next = m.clone();
            for &s in &e.from {
                next[s / 64] &= !(1 << (s % 64));
            }
            if let Some(&twice) = e.to.iter().find(|&&s| has(&next, s)) {
                return Some((ti, twice));
            }
            for &s in &e.to {
                next[s / 64] |= 1 << (s % 64);
            }
            if seen.len() < max_sets && seen.insert(next.clone()) {
                todo.push_back(next);
            }
        }
    }
    None
}

/// The transitions leaving each step, in order, each once (`FROM (A, A)`
/// leaves A once), in one list: a list per step took 56 bytes a step.
struct Leaving {
    /// Step `s`'s transitions are `list[start[s]..start[s + 1]]`.
    start: Vec<usize>,
    list: Vec<usize>,
}

impl Leaving {
    fn new(steps: usize, edges: &[Edge]) -> Leaving {
        // Each (step, transition) once: the transition last counted for each
        // step tells a repeat.
        let mut last = vec![usize::MAX; steps];
        let mut start = vec![0usize; steps + 1];
        for (ti, e) in edges.iter().enumerate() {
            for &s in &e.from {
                if std::mem::replace(&mut last[s], ti) != ti {
                    start[s + 1] += 1;
                }
            }
        }
        for s in 0..steps {
            start[s + 1] += start[s];
        }
        last.fill(usize::MAX);
        let mut next = start.clone();
        let mut list = vec![0; start[steps]];
        for (ti, e) in edges.iter().enumerate() {
            for &s in &e.from {
                if std::mem::replace(&mut last[s], ti) != ti {
                    list[next[s]] = ti;
                    next[s] += 1;
                }
            }
        }
        Leaving { start, list }
    }

    fn of(&self, s: usize) -> &[usize] {
        self.start.get(s..s + 2).map_or(&[], |r| &self.list[r[0]..r[1]])
    }
}

/// The steps of a set, in order.
fn active(m: &[u64]) -> impl Iterator<Item = usize> + '_ {
    m.iter().enumerate().flat_map(|(w, &word)| {
        let mut bits = word;
        std::iter::from_fn(move || {
            if bits == 0 {
                return None;
            }
            let b = bits.trailing_zeros() as usize;
            bits &= bits - 1;
            Some(w * 64 + b)
        })
    })
}

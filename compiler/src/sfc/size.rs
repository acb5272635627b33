//! What a sequence becomes in its object, counted before it is lowered, so
//! that every limit the loader enforces on a sequence unit is a located
//! check error and a sequence that checks clean also loads (issue 16):
//!
//! - charts nest at most [`MAX_DEPTH`] deep (the verifier's
//!   `MAX_CHART_DEPTH`, E0213);
//! - the steps, nested charts included, have two retained slots each in a
//!   `u16` count: at most [`MAX_STEPS`] (E0214);
//! - lowering writes a chart for each use of a chart action, a code block
//!   for each transition of each such chart and one for each ST action:
//!   charts and blocks are named by a `u16`: at most 65,535 of each
//!   (E0215). Counting expands nothing: each chart action's share is
//!   computed once.

use super::ast::{ActionBody, Chart, Sequence};
use super::errors::SfcError;
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use std::collections::HashMap;

/// Deepest nesting of chart actions below the root chart.
pub const MAX_DEPTH: usize = linc_format::MAX_CHART_DEPTH;

/// Most steps of a sequence: `.X` and `.T` of each are retained slots,
/// counted in a `u16`.
pub use super::lower::MAX_STEPS;

/// Most charts and most code blocks of a sequence's unit (the lowering's
/// numbering stops at the same number).
pub const MAX_TABLE: usize = super::lower::MAX_BLOCKS;

/// What one use of a chart adds to the object.
#[derive(Clone, Copy, Default)]
struct Share {
    charts: usize,
    /// Condition blocks of its transitions and of its nested charts'.
    blocks: usize,
}

struct Sizer<'s> {
    seq: &'s Sequence,
    by_name: HashMap<String, usize>,
    shares: HashMap<usize, Share>,
    /// Levels of charts of one use of a chart action, itself included.
    levels: HashMap<usize, usize>,
}

/// Checks the sizes of a sequence whose chart actions do not run themselves.
pub fn check(seq: &Sequence, out: &mut Vec<Diagnostic>) {
    steps(seq, out);
    let mut by_name = HashMap::new();
    for (i, a) in seq.actions.iter().enumerate().rev() {
        by_name.insert(a.name.text.as_str().to_ascii_uppercase(), i);
    }
    let mut s = Sizer { seq, by_name, shares: HashMap::new(), levels: HashMap::new() };
    match s.below(&seq.chart, 0) {
        Ok(_) => s.tables(out),
        Err(d) => out.push(*d),
    }
}

/// E0214 at the first step past [`MAX_STEPS`].
fn steps(seq: &Sequence, out: &mut Vec<Diagnostic>) {
    let charts = std::iter::once(&seq.chart).chain(seq.actions.iter().filter_map(|a| match &a.body {
        ActionBody::Chart(c) => Some(c),
        ActionBody::St(_) => None,
    }));
    if let Some(s) = charts.flat_map(|c| &c.steps).nth(MAX_STEPS) {
        out.push(SfcError::TooManySteps { span: s.name.span, limit: MAX_STEPS }.into());
    }
}

impl<'s> Sizer<'s> {
    /// The chart actions `c`'s steps name, each once, with the association
    /// that names it first (lowering's order).
    fn children(&self, c: &Chart) -> Vec<(usize, Span)> {
        let mut seen = Vec::new();
        for a in c.steps.iter().flat_map(|s| &s.assocs) {
            if let Some(&g) = self.by_name.get(a.action.text.as_str().to_ascii_uppercase().as_str()) {
                if !seen.iter().any(|&(h, _)| h == g) {
                    seen.push((g, a.span));
                }
            }
        }
        seen
    }

    fn chart_of(&self, g: usize) -> Option<&'s Chart> {
        let seq: &'s Sequence = self.seq;
        match &seq.actions[g].body {
            ActionBody::Chart(c) => Some(c),
            ActionBody::St(_) => None,
        }
    }

    /// How many levels of charts are below `c`, which is `depth` below the
    /// root; E0213 at the association that puts a chart deeper than
    /// [`MAX_DEPTH`]. The walk stops one level past the limit, and each
    /// chart action's levels are counted once.
    fn below(&mut self, c: &Chart, depth: usize) -> Result<usize, Box<Diagnostic>> {
        let mut most = 0;
        for (g, span) in self.children(c) {
            let Some(child) = self.chart_of(g) else { continue };
            let too_deep = |levels: usize| {
                let action = self.seq.actions[g].name.text.clone();
                Box::new(Diagnostic::from(SfcError::ChartsTooDeep {
                    span,
                    action: action.to_string(),
                    depth: depth + levels,
                    limit: MAX_DEPTH,
                }))
            };
            if depth + 1 > MAX_DEPTH {
                return Err(too_deep(1));
            }
            let levels = match self.levels.get(&g) {
                Some(&l) => l,
                None => {
                    let l = 1 + self.below(child, depth + 1)?;
                    self.levels.insert(g, l);
                    l
                }
            };
            if depth + levels > MAX_DEPTH {
                return Err(too_deep(levels));
            }
            most = most.max(levels);
        }
        Ok(most)
    }

    /// What one use of chart action `g` adds (its depth is within the limit,
    /// so the recursion is too).
    fn share(&mut self, g: usize) -> Share {
        if let Some(&s) = self.shares.get(&g) {
            return s;
        }
        let mut s = Share::default();
        if let Some(c) = self.chart_of(g) {
            s = self.chart_share(c);
        }
        self.shares.insert(g, s);
        s
    }

    fn chart_share(&mut self, c: &Chart) -> Share {
        let mut s = Share { charts: 1, blocks: conditions(c) };
        for (g, _) in self.children(c) {
            let child = self.share(g);
            s.charts = s.charts.saturating_add(child.charts);
            s.blocks = s.blocks.saturating_add(child.blocks);
        }
        s
    }

    /// E0215 where the charts or code blocks of the object pass 65,535: at
    /// the root's association whose chart action takes them over, or at the
    /// root's transition that does.
    fn tables(&mut self, out: &mut Vec<Diagnostic>) {
        let (mut charts, mut blocks) = (1usize, self.st_actions());
        let mut over = |what: &'static str, n: usize, span: Span| {
            out.push(SfcError::TooLarge { span, what, count: n, limit: MAX_TABLE }.into());
        };
        for (g, span) in self.children(&self.seq.chart) {
            let s = self.share(g);
            charts = charts.saturating_add(s.charts);
            blocks = blocks.saturating_add(s.blocks);
            if charts > MAX_TABLE {
                return over("charts", charts, span);
            }
            if blocks > MAX_TABLE {
                return over("code blocks", blocks, span);
            }
        }
        for t in self.seq.chart.transitions.iter().filter(|t| t.cond.is_some()) {
            blocks += 1;
            if blocks > MAX_TABLE {
                return over("code blocks", blocks, Span::new(t.span.start, t.span.start + "TRANSITION".len()));
            }
        }
    }

    /// The ST actions some chart of the object runs: one code block each.
    fn st_actions(&self) -> usize {
        let mut seen = vec![false; self.seq.actions.len()];
        let mut todo = vec![&self.seq.chart];
        let mut n = 0;
        while let Some(c) = todo.pop() {
            for (g, _) in self.children(c) {
                if std::mem::replace(&mut seen[g], true) {
                    continue;
                }
                match &self.seq.actions[g].body {
                    ActionBody::Chart(child) => todo.push(child),
                    ActionBody::St(_) => n += 1,
                }
            }
        }
        n
    }
}

/// Transitions of `c` with a condition: a code block each.
fn conditions(c: &Chart) -> usize {
    c.transitions.iter().filter(|t| t.cond.is_some()).count()
}

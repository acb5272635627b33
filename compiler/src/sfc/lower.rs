//! Lowering of a checked sequence into one sequence unit: chart tables
//! (ROOT first, then a chart for each use of a chart action, so charts nest
//! as a tree), a condition block per transition, a code block per ST action.
//! Steps get retained slots in the order the checker lists them (ROOT's
//! steps, then each chart action's), where `Step.X` and `Step.T` are read.

use super::ast::{Action, ActionBody, Chart, Sequence};
use crate::diag::span::Span;
use crate::st::check::{Checker, Context, Limits};
use crate::st::lower::sequence::SequenceBuilder;
use crate::st::lower::{Lines, LowerError};
use linc_format::object::{ActionRec, AssocRec, ChartRec, ObjectFile, StepRec, TransitionRec};
use std::collections::HashMap;

/// Every step name, in slot order.
fn step_names(seq: &Sequence) -> Vec<String> {
    let charts = std::iter::once(&seq.chart).chain(seq.actions.iter().filter_map(|a| match &a.body {
        ActionBody::Chart(c) => Some(c),
        ActionBody::St(_) => None,
    }));
    charts.flat_map(|c| c.steps.iter().map(|s| s.name.text.to_string())).collect()
}

/// Most steps a sequence may have: each has two retained slots (`.X` and
/// `.T`), and slot numbers are 16-bit.
pub const MAX_STEPS: usize = 32_767;

/// Most code blocks (transition conditions and ST actions) in one sequence
/// unit: block numbers are 16-bit.
pub const MAX_BLOCKS: usize = 65_535;

struct Lowering<'a, 's> {
    seq: &'s Sequence,
    /// Action by upper-case name, the first of equal names.
    actions: HashMap<String, usize>,
    checker: Checker<'a>,
    b: SequenceBuilder,
    slots: HashMap<String, u16>,
    /// Code block of each ST action, once lowered.
    code: HashMap<usize, u16>,
    charts: Vec<ChartRec>,
    /// Chart actions being expanded (to refuse one that uses itself).
    open: Vec<usize>,
}

/// Lowers a sequence that checked clean. `name` names its unit.
pub fn lower(seq: &Sequence, name: &str, file: &str, src: &str, ctx: Context) -> Result<ObjectFile, Vec<LowerError>> {
    let steps = step_names(seq);
    let ctx = Context { steps: Some(&steps), ..ctx };
    let slots = steps.iter().enumerate().map(|(i, s)| (s.to_ascii_uppercase(), i as u16)).collect();
    let mut actions = HashMap::with_capacity(seq.actions.len());
    for (i, a) in seq.actions.iter().enumerate() {
        actions.entry(a.name.text.as_str().to_ascii_uppercase()).or_insert(i);
    }
    let mut l = Lowering {
        seq,
        actions,
        checker: Checker::new(ctx, Limits::default()),
        b: SequenceBuilder::new(file, Lines::new(src), &steps),
        slots,
        code: HashMap::new(),
        charts: Vec::new(),
        open: Vec::new(),
    };
    l.chart(&seq.chart).map_err(|e| vec![e])?;
    let Lowering { b, charts, .. } = l;
    b.finish(name, charts)
}

impl Lowering<'_, '_> {
    fn action_index(&self, name: &str) -> Option<usize> {
        self.actions.get(&name.to_ascii_uppercase()).copied()
    }

    /// Adds chart `c` and the charts it uses; returns its index.
    fn chart(&mut self, c: &Chart) -> Result<u16, LowerError> {
        let me = self.charts.len();
        self.charts.push(ChartRec::default());
        // Each transition names its steps: looked up, not searched for
        // (a search through the chart's steps made lowering quadratic).
        let mut by_name = HashMap::with_capacity(c.steps.len());
        for (i, s) in c.steps.iter().enumerate() {
            by_name.entry(s.name.text.as_str().to_ascii_uppercase()).or_insert(i);
        }
        let index = |name: &str| by_name.get(&name.to_ascii_uppercase()).copied();
        let (mut actions, mut local): (Vec<ActionRec>, HashMap<usize, u16>) = (Vec::new(), HashMap::new());
        let mut steps = Vec::with_capacity(c.steps.len());
        for s in &c.steps {
            let mut assocs = Vec::with_capacity(s.assocs.len());
            for a in &s.assocs {
                let g = self.action_index(&a.action.text).ok_or_else(|| LowerError::ChartAction {
                    span: a.span,
                    name: a.action.text.to_string(),
                    why: "is not an action of the sequence",
                })?;
                let at = match local.get(&g) {
                    Some(&at) => at,
                    None => {
                        actions.push(self.action(g, a.span)?);
                        local.insert(g, (actions.len() - 1) as u16);
                        (actions.len() - 1) as u16
                    }
                };
                let qualifier = a.qualifier.text.bytes().next().unwrap_or(b'N').to_ascii_uppercase();
                let time_us = a.time.map_or(0, |(t, _)| (t.max(0.0) * 1e6).round() as u64);
                assocs.push(AssocRec { action: at, qualifier, time_us });
            }
            let slot = self.slots.get(s.name.text.as_str().to_ascii_uppercase().as_str()).copied().unwrap_or(0);
            let (name, initial, line) = (s.name.text.to_string(), u8::from(s.initial), self.b.line_of(s.span));
            steps.push(StepRec { name, initial, slot, assocs, line });
        }
        let mut transitions = Vec::with_capacity(c.transitions.len());
        for t in &c.transitions {
            let ids = |v: &[crate::st::ast::Ident]| v.iter().filter_map(|n| index(&n.text)).map(|i| i as u16).collect();
            let name = t.display_name();
            let cond = t.cond.as_ref().map(|e| self.checker.transition(e));
            let block = cond.map_or(0, |h| self.b.condition(&name, &h));
            let priority =
                t.priority.as_deref().map_or(u32::MAX, |&(p, _)| u32::try_from(p.max(0)).unwrap_or(u32::MAX - 1));
            let line = self.b.line_of(t.span);
            transitions.push(TransitionRec { name, from: ids(&t.from), to: ids(&t.to), priority, block, line });
        }
        self.charts[me] = ChartRec { steps, transitions, actions };
        u16::try_from(me).map_err(|_| LowerError::TooMany { span: Span::default(), what: "charts" })
    }

    /// The table entry of action `g`: its code block, or its chart.
    fn action(&mut self, g: usize, used_at: Span) -> Result<ActionRec, LowerError> {
        let a: &Action = &self.seq.actions[g];
        let name = a.name.text.clone();
        match &a.body {
            ActionBody::St(st) => {
                let index = match self.code.get(&g) {
                    Some(&i) => i,
                    None => {
                        let h = self.checker.action(st);
                        let i = self.b.action(&name, &h.body, used_at);
                        self.code.insert(g, i);
                        i
                    }
                };
                Ok(ActionRec { name: name.to_string(), kind: 0, index })
            }
            ActionBody::Chart(c) => {
                if self.open.contains(&g) {
                    return Err(LowerError::ChartAction { span: used_at, name: name.to_string(), why: "uses itself" });
                }
                self.open.push(g);
                let index = self.chart(c);
                self.open.pop();
                Ok(ActionRec { name: name.to_string(), kind: 1, index: index? })
            }
        }
    }
}

//! The checks of a sequence: its charts (initial steps, step names,
//! transitions, reachability), its associations (actions and qualifiers,
//! §20.5.5) and the ST inside, which the ST checker reads with the
//! sequence's step names in scope (`Step.X`, `Step.T`).

use super::ast::{Action, ActionBody, Assoc, Chart, Sequence, Step};
use super::errors::SfcError;
use super::safety::{unsafe_edge, Edge};
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use crate::st::ast::Ident;
use crate::st::check::{Checker, Context, Limits};
use linc_format::Code;
use std::collections::HashMap;

/// A chart with what the diagnostics call it.
struct Named<'a> {
    chart: &'a Chart,
    what: String,
    at: Span,
}

/// Checks a parsed sequence; returns its diagnostics, unsorted.
pub fn check(seq: &Sequence, ctx: Context) -> Vec<Diagnostic> {
    let mut charts = vec![Named { chart: &seq.chart, what: "the sequence's chart".into(), at: first_span(&seq.chart) }];
    for a in &seq.actions {
        if let ActionBody::Chart(c) = &a.body {
            charts.push(Named { chart: c, what: format!("chart action `{}`", a.name.text), at: a.name.span });
        }
    }
    let mut out = Vec::new();
    let steps = step_names(&charts, &mut out);
    // Which chart has a step is asked only about unknown steps: the map is
    // made at the first.
    let mut home = None;
    for c in &charts {
        chart(c, &charts, &mut home, &mut out);
    }
    drop(home);
    transition_names(&charts, &mut out);
    actions(seq, &charts, &mut out);
    let before = out.len();
    chart_cycles(seq, &mut out);
    if out[before..].iter().all(|d| d.code != Code::E0212) {
        super::size::check(seq, &mut out);
    }
    let names: Vec<String> = steps.into_iter().map(|s| s.text.to_string()).collect();
    let ctx = Context { steps: Some(&names), ..ctx };
    let mut checker = Checker::new(ctx, Limits::default()).reporting_only();
    for a in &seq.actions {
        if let ActionBody::St(st) = &a.body {
            checker.action(st);
        }
    }
    for c in &charts {
        for t in c.chart.transitions.iter().filter_map(|t| t.cond.as_ref()) {
            checker.transition(t);
        }
    }
    out.extend(checker.take_errors().iter().map(|e| e.to_diagnostic()));
    out
}

fn first_span(c: &Chart) -> Span {
    let step = c.steps.first().map(|s| s.name.span);
    let tr = c.transitions.first().map(|t| Span::new(t.span.start, t.span.start));
    match (step, tr) {
        (Some(a), Some(b)) => {
            if a.start <= b.start {
                a
            } else {
                b
            }
        }
        (a, b) => a.or(b).unwrap_or(Span::new(0, 0)),
    }
}

/// A step name as a key, compared as [`key`] compares, borrowed from the
/// tree: the chart's index holds no copy of each name (issue 30).
#[derive(Clone, Copy, Debug)]
struct NoCase<'a>(&'a str);

impl PartialEq for NoCase<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.0.eq_ignore_ascii_case(other.0)
    }
}

impl Eq for NoCase<'_> {}

impl std::hash::Hash for NoCase<'_> {
    fn hash<H: std::hash::Hasher>(&self, h: &mut H) {
        for b in self.0.bytes() {
            h.write_u8(b.to_ascii_uppercase());
        }
        h.write_u8(0xff);
    }
}

/// Each step of a chart by name: its first index.
type StepIndex<'a> = HashMap<NoCase<'a>, usize>;

fn key(i: &Ident) -> String {
    i.text.as_str().to_ascii_uppercase()
}

/// Every step of the sequence, each name once; reports duplicates.
fn step_names<'a>(charts: &[Named<'a>], out: &mut Vec<Diagnostic>) -> Vec<&'a Ident> {
    let mut seen: HashMap<String, Span> = HashMap::new();
    let mut names = Vec::new();
    for s in charts.iter().flat_map(|c| &c.chart.steps) {
        match seen.get(&key(&s.name)) {
            Some(&first) => out.push(Diagnostic::from(SfcError::DuplicateStep {
                span: s.name.span,
                name: s.name.text.to_string(),
                first,
            })),
            None => {
                seen.insert(key(&s.name), s.name.span);
                names.push(&s.name);
            }
        }
    }
    names
}

/// Each step name (upper case) and the chart it is first in.
fn step_charts(charts: &[Named]) -> HashMap<String, String> {
    let mut home = HashMap::new();
    for c in charts {
        for s in &c.chart.steps {
            home.entry(key(&s.name)).or_insert_with(|| c.what.clone());
        }
    }
    home
}

/// One chart: an initial step, known steps in transitions, reachability.
/// `home` says which chart has a step this one names but lacks (made from
/// `charts` when first needed).
fn chart(c: &Named, charts: &[Named], home: &mut Option<HashMap<String, String>>, out: &mut Vec<Diagnostic>) {
    let has_initial = c.chart.steps.iter().any(|s| s.initial);
    if !has_initial {
        out.push(Diagnostic::from(SfcError::NoInitialStep { span: c.at, chart: c.what.clone() }));
    }
    let index: StepIndex<'_> = c.chart.steps.iter().enumerate().rev().map(|(i, s)| (NoCase(&s.name.text), i)).collect();
    for t in &c.chart.transitions {
        for s in t.from.iter().chain(&t.to) {
            if index.contains_key(&NoCase(&s.text)) {
                continue;
            }
            let other_chart = home.get_or_insert_with(|| step_charts(charts)).get(&key(s)).cloned();
            out.push(Diagnostic::from(SfcError::UnknownStep { span: s.span, name: s.text.to_string(), other_chart }));
        }
    }
    // Without an initial step nothing is reachable: that is one error, not
    // a warning per step.
    if c.chart.broken {
        return;
    }
    for s in unreachable(c.chart, &index).into_iter().filter(|_| has_initial) {
        out.push(Diagnostic::from(SfcError::UnreachableStep { span: s.name.span, name: s.name.text.to_string() }));
    }
    unsafe_transitions(c.chart, &index, out);
}

/// Transitions that can activate a step that is still active (W0202).
fn unsafe_transitions(c: &Chart, index: &StepIndex<'_>, out: &mut Vec<Diagnostic>) {
    let known = |list: &[Ident]| {
        let mut v = list.iter().filter_map(|s| index.get(&NoCase(&s.text)).copied()).collect::<Vec<_>>();
        // A filtered collect makes room for four.
        v.shrink_to_fit();
        v
    };
    let edges: Vec<Edge> = c.transitions.iter().map(|t| Edge { from: known(&t.from), to: known(&t.to) }).collect();
    let initial: Vec<usize> = (0..c.steps.len()).filter(|&i| c.steps[i].initial).collect();
    if let Some((ti, si)) = unsafe_edge(c.steps.len(), &initial, &edges) {
        let t = &c.transitions[ti];
        out.push(Diagnostic::from(SfcError::Unsafe {
            span: Span::new(t.span.start, t.to.last().map(|s| s.span.end).unwrap_or(t.span.end)),
            transition: t.display_name(),
            step: c.steps[si].name.text.to_string(),
        }));
    }
}

/// Steps no transition can reach from the initial steps. A transition is
/// taken once all of its source steps are reachable (a simultaneous
/// convergence waits for every branch); each is visited once.
fn unreachable<'c>(c: &'c Chart, index: &StepIndex<'_>) -> Vec<&'c Step> {
    let mut waiting: Vec<usize> = waits(c, index);
    let mut leaving: Vec<Vec<usize>> = vec![Vec::new(); c.steps.len()];
    for (ti, t) in c.transitions.iter().enumerate() {
        for s in t.from.iter().filter_map(|s| index.get(&NoCase(&s.text))) {
            // `FROM (A, A)` waits for A once.
            if leaving[*s].last() != Some(&ti) {
                leaving[*s].push(ti);
            }
        }
    }
    let mut reached = vec![false; c.steps.len()];
    let mut todo: Vec<usize> = (0..c.steps.len()).filter(|&i| c.steps[i].initial).collect();
    while let Some(s) = todo.pop() {
        if std::mem::replace(&mut reached[s], true) {
            continue;
        }
        for &ti in &leaving[s] {
            waiting[ti] -= 1;
            if waiting[ti] == 0 {
                todo.extend(c.transitions[ti].to.iter().filter_map(|s| index.get(&NoCase(&s.text))));
            }
        }
    }
    let first = |i: usize| index.get(&NoCase(&c.steps[i].name.text)) == Some(&i);
    (0..c.steps.len()).filter(|&i| !reached[i] && first(i)).map(|i| &c.steps[i]).collect()
}

/// For each transition, how many distinct known source steps it waits for.
fn waits(c: &Chart, index: &StepIndex<'_>) -> Vec<usize> {
    c.transitions
        .iter()
        .map(|t| {
            let mut s: Vec<usize> = t.from.iter().filter_map(|s| index.get(&NoCase(&s.text)).copied()).collect();
            s.sort_unstable();
            s.dedup();
            s.len()
        })
        .collect()
}

/// Transition names (written ones) are unique in the sequence.
fn transition_names(charts: &[Named], out: &mut Vec<Diagnostic>) {
    let mut seen: HashMap<String, Span> = HashMap::new();
    for n in charts.iter().flat_map(|c| &c.chart.transitions).filter_map(|t| t.name.as_ref()) {
        if let Some(&first) = seen.get(&key(n)) {
            out.push(Diagnostic::from(SfcError::DuplicateTransition { span: n.span, name: n.text.to_string(), first }));
        } else {
            seen.insert(key(n), n.span);
        }
    }
}

/// Actions defined once, associations naming them with a valid qualifier,
/// and no action left unused.
fn actions(seq: &Sequence, charts: &[Named], out: &mut Vec<Diagnostic>) {
    let mut defined: HashMap<String, &Action> = HashMap::new();
    for a in &seq.actions {
        match defined.get(&key(&a.name)) {
            Some(first) => out.push(Diagnostic::from(SfcError::DuplicateAction {
                span: a.name.span,
                name: a.name.text.to_string(),
                first: first.name.span,
            })),
            None => {
                defined.insert(key(&a.name), a);
            }
        }
    }
    let mut used = std::collections::HashSet::new();
    for a in charts.iter().flat_map(|c| &c.chart.steps).flat_map(|s| &s.assocs) {
        if let Some(e) = qualifier(a) {
            out.push(Diagnostic::from(e));
        }
        if defined.contains_key(&key(&a.action)) {
            used.insert(key(&a.action));
        } else {
            out.push(Diagnostic::from(SfcError::UnknownAction {
                span: a.action.span,
                name: a.action.text.to_string(),
            }));
        }
    }
    for a in &seq.actions {
        if !used.contains(&key(&a.name)) && defined.get(&key(&a.name)).map(|d| d.span) == Some(a.span) {
            out.push(Diagnostic::from(SfcError::UnusedAction { span: a.name.span, name: a.name.text.to_string() }));
        }
    }
}

/// LIN's qualifiers (§20.5.5): L, D and E take a time, P N F S R none.
fn qualifier(a: &Assoc) -> Option<SfcError> {
    let q = &a.qualifier;
    let text = q.text.clone();
    let iec = |lin| Some(SfcError::IecQualifier { span: q.span, text: text.to_string(), lin });
    match q.text.as_str().to_ascii_uppercase().as_str() {
        "P" | "N" | "F" | "S" | "R" => {
            a.time.map(|(_, span)| SfcError::ExtraTime { span, qualifier: text.to_string() })
        }
        "L" | "D" | "E" if a.time.is_none() => {
            Some(SfcError::MissingTime { span: q.span, qualifier: text.to_string() })
        }
        "L" | "D" | "E" => None,
        "P1" => iec(Some("P")),
        "P0" => iec(Some("F")),
        "SD" | "DS" | "SL" => iec(None),
        _ => Some(SfcError::UnknownQualifier { span: q.span, text: text.to_string() }),
    }
}

/// A chart action that runs itself, directly or through other chart
/// actions, would nest charts without end (E0212). Each cycle is reported
/// once, at the association that closes it, found by a depth-first walk
/// with an explicit stack.
fn chart_cycles(seq: &Sequence, out: &mut Vec<Diagnostic>) {
    let charts: Vec<(&Action, &Chart)> = seq
        .actions
        .iter()
        .filter_map(|a| match &a.body {
            ActionBody::Chart(c) => Some((a, c)),
            ActionBody::St(_) => None,
        })
        .collect();
    let index: HashMap<String, usize> = charts.iter().enumerate().rev().map(|(i, (a, _))| (key(&a.name), i)).collect();
    let edges: Vec<Vec<(usize, &Assoc)>> = charts
        .iter()
        .map(|(_, c)| {
            let assocs = c.steps.iter().flat_map(|s| &s.assocs);
            assocs.filter_map(|a| index.get(&key(&a.action)).map(|&j| (j, a))).collect()
        })
        .collect();
    // 0: not seen, 1: on the walk's path, 2: done.
    let mut state = vec![0u8; charts.len()];
    for root in 0..charts.len() {
        if state[root] != 0 {
            continue;
        }
        let mut stack = vec![(root, 0usize)];
        state[root] = 1;
        while let Some((node, next)) = stack.pop() {
            let Some(&(to, assoc)) = edges[node].get(next) else {
                state[node] = 2;
                continue;
            };
            stack.push((node, next + 1));
            match state[to] {
                0 => {
                    state[to] = 1;
                    stack.push((to, 0));
                }
                1 => out.push(Diagnostic::from(SfcError::ChartRunsItself {
                    span: assoc.span,
                    chart: charts[node].0.name.text.to_string(),
                    action: assoc.action.text.to_string(),
                })),
                _ => {}
            }
        }
    }
}

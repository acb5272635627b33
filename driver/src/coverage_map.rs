//! From the runtime's counts to source files (ADR 0020): a code block's
//! counts by instruction become hits by line through its line table, its
//! decisions become two branch outcomes each, and a sequence's steps and
//! transitions become named functions at their lines.
//!
//! - A line's hits are its first statement's; a line the code visits at
//!   two separate places (a ladder rung written once for each way in past
//!   crossing jumps) adds both.
//! - A decision is a conditional jump. Outcome 0 is its condition TRUE (an
//!   IF arm entered, a loop gone round, a rung energised), outcome 1 FALSE;
//!   both are `-` when it was never evaluated. Decisions are numbered per
//!   line within their unit, so the numbers do not depend on what else the
//!   file holds.
//! - Functions: each ST, ladder or FST action by its name (its runs), each
//!   step as `step NAME` (times entered) and each transition as
//!   `transition NAME` (times fired).

use crate::coverage::{add_opt, Coverage, FileCoverage};
use linc_runtime::cover::{is_decision, BlockCounts, Counts, UnitCounts};
use linc_runtime::isa::Op;
use linc_runtime::object::{CodeBlock, Unit, UnitKind};
use linc_runtime::ObjectFile;
use std::collections::HashMap;

/// Adds one object's counts to `cov`, under each unit's source file as
/// `path` names it.
pub fn add_object(cov: &mut Coverage, object: &ObjectFile, counts: &Counts, path: &dyn Fn(&str) -> String) {
    for (unit, uc) in object.units.iter().zip(&counts.units) {
        let file = cov.files.entry(path(&unit.file)).or_default();
        add_unit(file, unit, uc);
    }
}

fn add_unit(file: &mut FileCoverage, unit: &Unit, counts: &UnitCounts) {
    let mut per_line: HashMap<u32, u32> = HashMap::new();
    for (block, bc) in unit.blocks.iter().zip(&counts.blocks) {
        add_lines(file, block, bc);
        add_decisions(file, block, bc, &mut per_line);
    }
    match unit.kind {
        UnitKind::Sequence => add_chart_items(file, unit, counts),
        UnitKind::Action | UnitKind::Fst => {
            let entry = unit.blocks.first().zip(counts.blocks.first());
            let (line, runs) = entry.map_or((1, 0), |(b, c)| (first_line(b), hits_at(c, 0)));
            add_function(file, &unit.name, line, runs);
        }
    }
}

fn hits_at(c: &BlockCounts, pc: usize) -> u64 {
    c.hits.get(pc).copied().unwrap_or(0)
}

fn first_line(b: &CodeBlock) -> u32 {
    b.lines.first().map_or(1, |l| l.line.max(1))
}

fn add_function(file: &mut FileCoverage, name: &str, line: u32, hits: u64) {
    let e = file.functions.entry(name.to_string()).or_insert((line.max(1), 0));
    e.1 = e.1.saturating_add(hits);
}

/// Hits by line: each run of line-table entries on one line counts once,
/// with its first statement's hits.
fn add_lines(file: &mut FileCoverage, block: &CodeBlock, c: &BlockCounts) {
    let mut previous = None;
    for entry in &block.lines {
        if previous == Some(entry.line) || entry.line == 0 {
            continue;
        }
        previous = Some(entry.line);
        let e = file.lines.entry(entry.line).or_default();
        *e = e.saturating_add(hits_at(c, entry.op as usize));
    }
}

/// Each decision's two outcomes, at the line of the statement it is in.
fn add_decisions(file: &mut FileCoverage, block: &CodeBlock, c: &BlockCounts, per_line: &mut HashMap<u32, u32>) {
    let mut entries = block.lines.iter().peekable();
    let mut line = 0;
    for (pc, op) in block.ops.0.iter().enumerate() {
        while let Some(e) = entries.next_if(|e| e.op as usize <= pc) {
            line = e.line;
        }
        if !is_decision(op) || line == 0 {
            continue;
        }
        let k = per_line.entry(line).or_default();
        let id = *k;
        *k += 1;
        let (runs, jumps) = (hits_at(c, pc), c.taken.get(pc).copied().unwrap_or(0));
        // A JumpIfFalse jumps when its condition is FALSE.
        let (when_true, when_false) = match op {
            Op::JumpIfTrue { .. } => (jumps, runs.saturating_sub(jumps)),
            _ => (runs.saturating_sub(jumps), jumps),
        };
        let evaluated = runs > 0;
        for (outcome, n) in [(0, when_true), (1, when_false)] {
            let e = file.branches.entry((line, id, outcome)).or_insert(None);
            *e = add_opt(*e, evaluated.then_some(n));
        }
    }
}

/// A sequence's steps (times entered) and transitions (times fired).
fn add_chart_items(file: &mut FileCoverage, unit: &Unit, counts: &UnitCounts) {
    let steps = unit.charts.iter().flat_map(|c| &c.steps);
    for (s, n) in steps.zip(counts.steps.iter().copied().chain(std::iter::repeat(0))) {
        add_function(file, &format!("step {}", s.name), s.line, n);
    }
    let transitions = unit.charts.iter().flat_map(|c| &c.transitions);
    for (t, n) in transitions.zip(counts.transitions.iter().copied().chain(std::iter::repeat(0))) {
        add_function(file, &format!("transition {}", t.name), t.line, n);
    }
}

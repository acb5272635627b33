//! The verifier's part for sequence units: every index of their chart
//! tables is in range, charts nest as a tree of bounded depth, and each
//! code block is used as what it was compiled for — a transition's block
//! ends only by returning a truth value, an action's block only by `Ret`.

use crate::errors::LoadError;
use crate::isa::{Kind, Op};
use crate::object::{ChartRec, Unit, UnitKind};
use linc_format::Code;

pub use linc_format::object::MAX_CHART_DEPTH;

fn bad(u: &Unit, what: impl Into<String>) -> LoadError {
    LoadError::Invalid { code: Code::E0714, action: u.name.clone(), op: 0, what: what.into() }
}

/// An FST unit is one code block whose label `n` is the `Step n` that
/// begins step `n`, for every step of its listing: the engine shows the
/// label as the instruction pointer and never needs to search the code.
fn check_fst(u: &Unit) -> Result<(), LoadError> {
    let [b] = &u.blocks[..] else {
        return Err(bad(u, format!("an FST table with {} code blocks (it has one)", u.blocks.len())));
    };
    if !u.charts.is_empty() || u.steps.is_empty() || b.labels.len() < u.steps.len() {
        return Err(bad(u, "an FST table needs steps, a label for each, and no charts"));
    }
    for n in 0..u.steps.len() {
        let at = b.labels[n] as usize;
        if b.ops.get(at) != Some(&crate::isa::Op::Step { n: n as u16 }) {
            return Err(bad(u, format!("label {n} of an FST table is not where step {n} begins")));
        }
    }
    Ok(())
}

/// What a code block of a sequence is used for.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Use {
    Unused,
    Condition,
    Action,
}

pub fn check_charts(u: &Unit) -> Result<(), LoadError> {
    if u.kind != UnitKind::Fst && !u.steps.is_empty() {
        return Err(bad(u, "a step listing in a unit that is not an FST table"));
    }
    match u.kind {
        UnitKind::Fst => return check_fst(u),
        UnitKind::Action if u.charts.is_empty() => return Ok(()),
        UnitKind::Action => return Err(bad(u, "an action unit with charts")),
        UnitKind::Sequence if u.charts.is_empty() => return Err(bad(u, "a sequence without a chart")),
        UnitKind::Sequence => {}
    }
    let mut uses = vec![Use::Unused; u.blocks.len()];
    let mut depth = vec![0usize; u.charts.len()];
    for (ci, c) in u.charts.iter().enumerate() {
        check_steps(u, c)?;
        for t in &c.transitions {
            let in_range = |v: &[u16]| !v.is_empty() && v.iter().all(|&s| usize::from(s) < c.steps.len());
            if !in_range(&t.from) || !in_range(&t.to) {
                return Err(bad(u, format!("transition `{}` names a step the chart does not have", t.name)));
            }
            mark(u, &mut uses, usize::from(t.block), Use::Condition)?;
        }
        for a in &c.actions {
            let i = usize::from(a.index);
            match a.kind {
                0 => mark(u, &mut uses, i, Use::Action)?,
                1 if i > ci && i < u.charts.len() => {
                    depth[i] = depth[i].max(depth[ci] + 1);
                    if depth[i] > MAX_CHART_DEPTH {
                        return Err(bad(u, format!("charts nest more than {MAX_CHART_DEPTH} deep")));
                    }
                }
                _ => return Err(bad(u, format!("action `{}` names no code block or later chart", a.name))),
            }
        }
    }
    for (b, used) in uses.iter().enumerate() {
        check_block_ends(u, b, *used)?;
    }
    Ok(())
}

fn check_steps(u: &Unit, c: &ChartRec) -> Result<(), LoadError> {
    for s in &c.steps {
        if 2 * usize::from(s.slot) + 1 >= usize::from(u.retained) {
            return Err(bad(u, format!("step `{}` has no retained slots for .X and .T", s.name)));
        }
        for a in &s.assocs {
            if usize::from(a.action) >= c.actions.len() || !crate::object::is_qualifier(a.qualifier) {
                return Err(bad(u, format!("step `{}` has an association out of range", s.name)));
            }
        }
    }
    Ok(())
}

fn mark(u: &Unit, uses: &mut [Use], block: usize, as_use: Use) -> Result<(), LoadError> {
    match uses.get_mut(block) {
        Some(slot) if *slot == Use::Unused || *slot == as_use => {
            *slot = as_use;
            Ok(())
        }
        Some(_) => Err(bad(u, format!("code block {block} is both a condition and an action"))),
        None => Err(bad(u, format!("code block {block} does not exist"))),
    }
}

/// A condition ends by returning a truth value; an action by `Ret`.
fn check_block_ends(u: &Unit, b: usize, used: Use) -> Result<(), LoadError> {
    // A sequence's blocks share one activation, so none may suspend.
    let ok = |op: &Op| match (op, used) {
        (Op::Return { kind }, Use::Condition) => *kind == Kind::Bool as u8,
        (Op::Ret {}, Use::Condition) | (Op::Return { .. }, _) | (Op::Yield {}, _) => false,
        _ => true,
    };
    match u.blocks[b].ops.iter().position(|op| !ok(op)) {
        Some(at) => Err(LoadError::Invalid {
            code: Code::E0714,
            action: u.name.clone(),
            op: at,
            what: format!(
                "code block {b} does not end as a {}",
                if used == Use::Condition { "condition" } else { "block of actions" }
            ),
        }),
        None => Ok(()),
    }
}

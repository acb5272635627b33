//! FST tables read as sequences (`linc fst to-sfc`): each place a cycle
//! can start from — step 0, and the step after each WT — is a step of the
//! sequence, whose P action is what the table does from there until it
//! leaves (END, a WT, or the last step), written as `to-st` writes a cycle.
//! Its transitions go where the table goes on: after a WT, when the step
//! has been active the wait (in whole 100 ms intervals, as the table
//! counts); after END, at the next scan, to the step of step 0. A step
//! that can leave in more than one way records which in a field the
//! engineer names (`--exit BLOCK.FIELD`), which the transitions test.

use super::{check_budget, longest, post_dominators, post_order, resumes_after, st, Emit, Graph, Node};
use crate::diag::Diagnostic;
use crate::fst::commands::Kind;
use crate::fst::{Arg, Checked, Cmd, Param, Step, Table};
use linc_format::Code;
use std::collections::{BTreeMap, BTreeSet};

/// What the translation is for (see [`super::Target`]), and the field a
/// step that leaves in several ways records its way in (resolved in the
/// database: [`crate::fst::check::field_param`]).
pub struct SfcTarget<'a> {
    pub block: &'a str,
    pub steps_per_cycle: u32,
    pub exit: Option<&'a Param>,
}

/// One place a cycle starts from: the steps it can run (successors
/// first) and where it can go on, with the wait (100 ms intervals) first.
struct Region {
    order: Vec<Node>,
    exits: BTreeSet<(usize, Option<u64>)>,
}

/// The wait of WT `secs`, in 100 ms intervals, as the table counts it.
fn intervals(secs: f32) -> u64 {
    ((f64::from(secs).clamp(0.1, 999_999.0) * 10.0).round() as u64).max(1)
}

/// The regions from step 0 on, each checked; refusals as for `to-st`.
fn regions(
    g: &Graph,
    table: &Table,
    checked: &Checked,
    budget: u32,
) -> Result<BTreeMap<usize, Region>, Vec<Diagnostic>> {
    let n = checked.steps.len();
    let (mut out, mut todo) = (BTreeMap::new(), vec![0usize]);
    while let Some(r) = todo.pop() {
        if out.contains_key(&r) {
            continue;
        }
        if r >= n {
            // After a WT on the last step: the cycle that wakes does nothing.
            out.insert(r, Region { order: Vec::new(), exits: BTreeSet::from([(0, None)]) });
            continue;
        }
        let order = post_order(g, table, r)?;
        super::refuse_steps(g, table, checked, &order, false)?;
        check_budget(g, table, &longest(g, &order), budget, r)?;
        let mut exits = BTreeSet::new();
        for &s in order.iter().filter(|&&s| s < g.exit) {
            match resumes_after(g, checked, s) {
                Some(next) if checked.steps[s].cmd == Cmd::Wt => {
                    let wait = match checked.steps[s].arg1 {
                        Arg::Const(c) => intervals(c),
                        _ => 1,
                    };
                    exits.insert((next, Some(wait)));
                    todo.push(next);
                }
                Some(next) => {
                    exits.insert((next, None));
                }
                None if g.succ[s].1 == Some(g.exit) => {
                    exits.insert((0, None));
                }
                None => {}
            }
        }
        out.insert(r, Region { order, exits });
    }
    Ok(out)
}

/// The sequence of a table, or why it has none.
pub fn to_sfc(table: &Table, checked: &Checked, target: &SfcTarget) -> Result<String, Vec<Diagnostic>> {
    let g = Graph::of(checked, true);
    let regions = regions(&g, table, checked, target.steps_per_cycle)?;
    stops_itself(table, checked, &regions, target.block)?;
    let several = regions.iter().find(|(_, r)| r.exits.len() > 1).map(|(&start, _)| start);
    let exit_text = target.exit.map(|p| format!("[{}.{}]", p.block, p.field));
    let exit = match (several, target.exit) {
        (Some(start), None) => return Err(vec![needs_exit_field(table, start)]),
        (Some(_), Some(f)) => {
            exit_usable(table, checked, f)?;
            exit_text.as_deref()
        }
        (None, _) => None,
    };
    let mut out = header(target, checked.steps.len());
    for (&r, region) in &regions {
        let kind = if r == 0 { "INITIAL_STEP" } else { "STEP" };
        let action = if region.order.is_empty() { String::new() } else { format!(" R{r}(P);") };
        out.push_str(&format!("{kind} S{r}:{action} END_STEP\n"));
    }
    for (&r, region) in &regions {
        for &(next, wait) in &region.exits {
            let mut cond = Vec::new();
            if let (Some(f), true) = (exit, region.exits.len() > 1) {
                cond.push(format!("{f} = {next}"));
            }
            if let Some(k) = wait {
                cond.push(format!("S{r}.T >= {}.{}", k / 10, k % 10));
            }
            let cond = if cond.is_empty() { "TRUE".to_string() } else { cond.join(" AND ") };
            out.push_str(&format!("TRANSITION FROM S{r} TO S{next} := {cond}; END_TRANSITION\n"));
        }
    }
    for (&r, region) in regions.iter().filter(|(_, region)| !region.order.is_empty()) {
        let ipdom = post_dominators(&g, &region.order);
        let mut w = st::Writer::new(target.block, table, checked);
        let record = |next: usize| exit.filter(|_| region.exits.len() > 1).map(|f| format!("{f} := {next};"));
        let mut e = Emit::new(&g, checked, &ipdom, region.order.len(), &record);
        w.line(0, &format!("ACTION R{r}"));
        e.emit(&mut w, r, g.exit, 1).map_err(|_| vec![super::tangled(table)])?;
        w.line(0, "END_ACTION");
        out.push('\n');
        out.push_str(&w.finish());
    }
    Ok(out)
}

/// The parameters a step writes: SAV's target, a history index the
/// command advances, an output point.
fn written(step: &Step) -> impl Iterator<Item = &Param> {
    let (k1, k2) = step.cmd.args();
    let writes = |k: Kind| matches!(k, Kind::Out | Kind::Index | Kind::AoPoint | Kind::DoPoint);
    fn param(a: &Arg) -> Option<&Param> {
        if let Arg::Param(p) = a {
            Some(p)
        } else {
            None
        }
    }
    let first = param(&step.arg1).filter(|_| writes(k1));
    let second = param(&step.arg2).filter(|_| writes(k2));
    first.into_iter().chain(second)
}

fn names(p: &Param, block: &str, field: &str) -> bool {
    p.block.eq_ignore_ascii_case(block) && p.field.eq_ignore_ascii_case(field)
}

/// E0430 at each step that writes the table's own RUNFLG: the table stops
/// itself there, and a sequence does not consult RUNFLG (it runs until its
/// SFC_CON block stops it), so the translation would go on running.
fn stops_itself(
    table: &Table,
    checked: &Checked,
    regions: &BTreeMap<usize, Region>,
    block: &str,
) -> Result<(), Vec<Diagnostic>> {
    let reached: BTreeSet<usize> = regions.values().flat_map(|r| r.order.iter().copied()).collect();
    let refused: Vec<Diagnostic> = reached
        .into_iter()
        .filter(|&n| checked.steps.get(n).is_some_and(|s| written(s).any(|p| names(p, block, "RUNFLG"))))
        .map(|n| {
            let cmd = checked.steps[n].cmd.text();
            Diagnostic::error(Code::E0430, format!("step {n} (`{cmd}`) has no faithful sequence translation"), super::at(table, n))
                .label("the table stops itself here by writing RUNFLG; a sequence does not consult RUNFLG")
                .help("stop the sequence from outside (its SFC_CON block), or translate with `linc fst to-st`, whose action runs only while RUNFLG is 1")
        })
        .collect();
    super::none_refused(refused)
}

/// E0434 when the `--exit` field is one the table itself reads or writes:
/// the sequence's records of where it goes on would change what the table
/// does, or the table would overwrite them.
fn exit_usable(table: &Table, checked: &Checked, exit: &Param) -> Result<(), Vec<Diagnostic>> {
    let uses = |s: &Step| {
        [&s.arg1, &s.arg2].into_iter().any(|a| matches!(a, Arg::Param(p) if names(p, &exit.block, &exit.field)))
    };
    let used: Vec<Diagnostic> = (checked.steps.iter().enumerate())
        .filter(|(_, s)| uses(s))
        .map(|(n, _)| {
            let msg = format!("the exit field {}.{} is used by the table", exit.block, exit.field);
            Diagnostic::error(Code::E0434, msg, super::at(table, n))
                .label("the table uses it here; the sequence would write where the table reads and writes")
                .help("name a numeric field that nothing else uses with --exit BLOCK.FIELD")
        })
        .collect();
    super::none_refused(used)
}

fn needs_exit_field(table: &Table, start: usize) -> Diagnostic {
    Diagnostic::error(
        Code::E0434,
        format!("the cycle from step {start} can go on in more than one way: the sequence needs a field to note which"),
        super::at(table, start),
    )
    .label("from here the table may reach END or a WT, or more than one WT")
    .help("name a numeric field that nothing else uses with --exit BLOCK.FIELD")
}

fn header(t: &SfcTarget, steps: usize) -> String {
    format!(
        "(* `linc fst to-sfc`: {steps} steps of an FST table as a sequence, for block\n   {}, at most {} steps a cycle. Each step is where a cycle can start: its\n   P action is the cycle from there, its transitions where the table goes on.\n   Run it on an SFC_CON block in the FST block's task, with the FST block's\n   FileName cleared. *)\n\n",
        t.block, t.steps_per_cycle
    )
}

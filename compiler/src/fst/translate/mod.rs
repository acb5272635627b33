//! FST tables read as ST (`linc fst to-st`, `docs/fst-translation.md`).
//!
//! A table without waits runs, each cycle, from step 0 until END (or its
//! last step), as long as no path is longer than the block's steps-per-
//! cycle limit: exactly one run of an ST action. The translation is of
//! that action: the control flow from step 0 is an acyclic graph, written
//! as nested IF statements (each branch's arms end where the two paths
//! meet again, its immediate post-dominator), and every command as the
//! statements that do what its instructions do, value for value.
//!
//! A table the translation cannot follow faithfully is refused at the
//! step that stops it, with a code: a command without an ST equivalent
//! (E0430), a loop that only the step budget breaks (E0431), a path longer
//! than the budget (E0432), or control flow too tangled to nest (E0433).
//! A refusal is never a guess.

mod sfc;
mod st;

pub use sfc::{to_sfc, SfcTarget};

use super::{Arg, Checked, Cmd, Table};
use crate::diag::span::Span;
use crate::diag::Diagnostic;
use linc_format::Code;

/// What the translation is for: the FST block that would run the table
/// (its registers are that block's fields), its steps-per-cycle limit and
/// the name of the action written.
pub struct Target<'a> {
    pub block: &'a str,
    pub steps_per_cycle: u32,
    pub action: &'a str,
}

/// Where control goes after a step.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Flow {
    /// The next step (the end of the cycle after the last).
    Next,
    /// The end of the cycle (END).
    Exit,
    /// Always to this step (GO).
    Go(usize),
    /// To this step when the step's condition holds, else the next.
    Branch(usize),
}

/// The node standing for the end of a cycle.
type Node = usize;

struct Graph {
    /// Each step's successors: (when the condition holds, else); one of
    /// them for a step that does not branch. `exit` is the end node.
    succ: Vec<(Node, Option<Node>)>,
    exit: Node,
}

fn flow(step: &super::Step) -> Flow {
    let label = |a: &Arg| match a {
        Arg::Label(s) => Some(*s as usize),
        _ => None,
    };
    match step.cmd {
        Cmd::End => Flow::Exit,
        Cmd::Go => label(&step.arg1).map_or(Flow::Next, Flow::Go),
        Cmd::Eq | Cmd::Ne | Cmd::Lt | Cmd::Le | Cmd::Gt | Cmd::Ge | Cmd::Ct => {
            label(&step.arg2).map_or(Flow::Next, Flow::Branch)
        }
        _ => Flow::Next,
    }
}

impl Graph {
    /// The control flow of one cycle; with `waits`, a WT ends it too.
    fn of(table: &Checked, waits: bool) -> Graph {
        let exit = table.steps.len();
        let next = |i: usize| if i + 1 < exit { i + 1 } else { exit };
        let succ = (table.steps.iter().enumerate())
            .map(|(i, s)| match flow(s) {
                Flow::Next if waits && s.cmd == Cmd::Wt => (exit, None),
                Flow::Next => (next(i), None),
                Flow::Exit => (exit, None),
                Flow::Go(t) => (t.min(exit), None),
                Flow::Branch(t) if t.min(exit) == next(i) => (next(i), None),
                Flow::Branch(t) => (t.min(exit), Some(next(i))),
            })
            .collect();
        Graph { succ, exit }
    }

    fn successors(&self, n: Node) -> impl Iterator<Item = Node> + '_ {
        let (a, b) = self.succ.get(n).copied().unwrap_or((self.exit, None));
        std::iter::once(a).chain(b).filter(move |_| n != self.exit)
    }
}

/// The cell a refusal points at: step `i`'s command.
fn at(table: &Table, i: usize) -> Span {
    table.rows.get(i).map_or_else(|| table.rows.last().map_or(Span::new(0, 0), |r| r.cmd.span), |r| r.cmd.span)
}

/// The steps reachable from `start` in depth-first post-order (every step
/// after all it leads to), or E0431 at the step whose jump closes a loop.
fn post_order(g: &Graph, table: &Table, start: Node) -> Result<Vec<Node>, Vec<Diagnostic>> {
    // 0 unseen, 1 on the current path, 2 done; an explicit stack, so a
    // long table cannot exhaust the thread's.
    let mut state = vec![0u8; g.exit + 1];
    let mut order = Vec::new();
    let mut stack: Vec<(Node, Vec<Node>)> = vec![(start, g.successors(start).collect())];
    state[start] = 1;
    while let Some((n, rest)) = stack.last_mut() {
        let n = *n;
        match rest.pop() {
            Some(s) if state[s] == 1 => return Err(vec![loop_without_wait(table, n, s)]),
            Some(s) if state[s] == 0 => {
                state[s] = 1;
                stack.push((s, g.successors(s).collect()));
            }
            Some(_) => {}
            None => {
                state[n] = 2;
                order.push(n);
                stack.pop();
            }
        }
    }
    Ok(order)
}

fn loop_without_wait(table: &Table, from: usize, to: usize) -> Diagnostic {
    Diagnostic::error(Code::E0431, format!("step {from} goes back to step {to}: a loop without a wait"), at(table, from))
        .label("this jump closes a loop")
        .help("the table repeats this loop across cycles, as many steps a cycle as its limit allows; one run of an ST action cannot do that")
}

/// The most steps a cycle begins on any path from `n` (END and the last
/// step included), for each node in `order` (successors first).
fn longest(g: &Graph, order: &[Node]) -> Vec<u32> {
    let mut len = vec![0u32; g.exit + 1];
    for &n in order.iter().filter(|&&n| n != g.exit) {
        len[n] = 1 + g.successors(n).map(|s| len[s]).max().unwrap_or(0);
    }
    len
}

/// E0432 at the first step the budget does not reach on the longest path
/// from `start`.
fn check_budget(g: &Graph, table: &Table, len: &[u32], budget: u32, start: Node) -> Result<(), Vec<Diagnostic>> {
    if len[start] <= budget {
        return Ok(());
    }
    let (mut n, mut begun) = (start, 0);
    while begun < budget {
        begun += 1;
        n = g.successors(n).max_by_key(|&s| len[s]).unwrap_or(g.exit);
    }
    Err(vec![Diagnostic::error(
        Code::E0432,
        format!("a cycle may run {} steps, more than the block's limit of {budget}", len[start]),
        at(table, n),
    )
    .label(format!("the cycle stops before this step and goes on at the next one (step {n})"))
    .help("the table spreads this path over two cycles; shorten it, or raise STEPS of the FST block")])
}

/// Each node's immediate post-dominator (where the paths from it meet
/// again), for the nodes of `order`.
fn post_dominators(g: &Graph, order: &[Node]) -> Vec<Node> {
    let mut ipdom = vec![g.exit; g.exit + 1];
    let mut depth = vec![0u32; g.exit + 1];
    for &n in order.iter().filter(|&&n| n != g.exit) {
        let mut succ = g.successors(n);
        let first = succ.next().unwrap_or(g.exit);
        let meet = succ.fold(first, |a, b| {
            let (mut a, mut b) = (a, b);
            while a != b {
                if depth[a] >= depth[b] && a != g.exit {
                    a = ipdom[a];
                } else {
                    b = ipdom[b];
                }
            }
            a
        });
        ipdom[n] = meet;
        depth[n] = depth[meet] + 1;
    }
    ipdom
}

/// The ST action of a table without waits, or why it has none.
pub fn to_st(table: &Table, checked: &Checked, target: &Target) -> Result<String, Vec<Diagnostic>> {
    let g = Graph::of(checked, false);
    let order = post_order(&g, table, 0)?;
    refuse_steps(&g, table, checked, &order, true)?;
    let len = longest(&g, &order);
    check_budget(&g, table, &len, target.steps_per_cycle, 0)?;
    let ipdom = post_dominators(&g, &order);
    let mut w = st::Writer::new(target.block, table, checked);
    let mut e = Emit::new(&g, checked, &ipdom, order.len(), &|_| None);
    w.line(0, &format!("ACTION {}", target.action));
    w.line(1, &format!("IF {} = 1 THEN", w.field("RUNFLG")));
    e.emit(&mut w, 0, g.exit, 2).map_err(|_| vec![tangled(table)])?;
    w.line(1, "END_IF;");
    w.line(0, "END_ACTION");
    Ok(st::header(target, checked.steps.len()) + &w.finish())
}

/// E0430 at each step of `order` without a faithful equivalent (`in_one_run`:
/// for an action, where WT is one), in source order.
fn refuse_steps(
    g: &Graph,
    table: &Table,
    checked: &Checked,
    order: &[Node],
    in_one_run: bool,
) -> Result<(), Vec<Diagnostic>> {
    let mut refused: Vec<Diagnostic> = (order.iter().copied())
        .filter(|&n| n < g.exit)
        .filter_map(|n| st::refusal(&checked.steps[n], in_one_run).map(|why| no_equivalent(table, checked, n, why)))
        .collect();
    refused.sort_by_key(|d| d.span.start);
    none_refused(refused)
}

/// `Ok` when nothing was refused, else the refusals.
fn none_refused(refused: Vec<Diagnostic>) -> Result<(), Vec<Diagnostic>> {
    if refused.is_empty() {
        Ok(())
    } else {
        Err(refused)
    }
}

fn no_equivalent(table: &Table, checked: &Checked, n: usize, why: &str) -> Diagnostic {
    let cmd = checked.steps[n].cmd.text();
    Diagnostic::error(Code::E0430, format!("step {n} (`{cmd}`) has no faithful ST translation"), at(table, n))
        .label(why.to_string())
}

fn tangled(table: &Table) -> Diagnostic {
    Diagnostic::error(Code::E0433, "the table's branches are too tangled to write as nested IFs", at(table, 0))
        .label("from this step, the paths cross too often or nest too deeply")
        .help("branches that cross each other must be written once for each way in; here that grows too large")
}

/// The state of writing nested IFs: the graph, its post-dominators, how
/// many more steps may be written (paths that cross are written once for
/// each way in; this bounds the text for any table), and the statement
/// that records where a path leaves the code for (the step the table goes
/// on with: 0 after END or the last step, the step after a WT).
struct Emit<'g> {
    g: &'g Graph,
    checked: &'g Checked,
    ipdom: &'g [Node],
    budget: usize,
    on_exit: &'g dyn Fn(usize) -> Option<String>,
}

/// The step a cycle goes on with after leaving at step `n` (`None`: it
/// does not leave there).
fn resumes_after(g: &Graph, checked: &Checked, n: Node) -> Option<usize> {
    match (g.succ.get(n)?, checked.steps.get(n)?.cmd) {
        ((e, None), Cmd::Wt) if *e == g.exit => Some(n + 1),
        ((e, None), _) if *e == g.exit => Some(0),
        _ => None,
    }
}

/// The most IF statements nested in a translation (ST allows 100).
const MAX_NESTING: usize = 90;

impl<'g> Emit<'g> {
    /// Writing the code of `steps` reachable steps: each may be written 20
    /// times over (paths that cross), and a little more for short tables.
    fn new(
        g: &'g Graph,
        checked: &'g Checked,
        ipdom: &'g [Node],
        steps: usize,
        on_exit: &'g dyn Fn(usize) -> Option<String>,
    ) -> Emit<'g> {
        Emit { g, checked, ipdom, budget: 20 * steps + 1_000, on_exit }
    }

    /// Whether a branch's way to `node` writes nothing before `meet`.
    fn is_empty(&self, node: Node, meet: Node) -> bool {
        node == meet && (node != self.g.exit || (self.on_exit)(0).is_none())
    }

    /// One way of a branch: its steps, or, off the end of the table, what
    /// records that the next cycle starts at step 0.
    fn arm(&mut self, w: &mut st::Writer, node: Node, meet: Node, depth: usize) -> Result<(), ()> {
        if node == self.g.exit {
            if let Some(line) = (self.on_exit)(0) {
                w.line(depth, &line);
            }
            return Ok(());
        }
        self.emit(w, node, meet, depth)
    }

    /// Writes the steps from `n` until `stop`, at indentation `depth`.
    fn emit(&mut self, w: &mut st::Writer, mut n: Node, stop: Node, depth: usize) -> Result<(), ()> {
        while n != stop && n != self.g.exit {
            if self.budget == 0 || depth > MAX_NESTING {
                return Err(());
            }
            self.budget -= 1;
            w.step(n, depth);
            if let Some(line) = resumes_after(self.g, self.checked, n).and_then(self.on_exit) {
                w.line(depth, &line);
            }
            match self.g.succ[n] {
                (next, None) => n = next,
                (when, Some(otherwise)) => {
                    let meet = self.ipdom[n];
                    let cond = w.condition(n);
                    if self.is_empty(when, meet) {
                        w.line(depth, &format!("IF NOT ({cond}) THEN"));
                        self.arm(w, otherwise, meet, depth + 1)?;
                    } else {
                        w.line(depth, &format!("IF {cond} THEN"));
                        self.arm(w, when, meet, depth + 1)?;
                        if !self.is_empty(otherwise, meet) {
                            w.line(depth, "ELSE");
                            self.arm(w, otherwise, meet, depth + 1)?;
                        }
                    }
                    w.line(depth, "END_IF;");
                    n = meet;
                }
            }
        }
        Ok(())
    }
}

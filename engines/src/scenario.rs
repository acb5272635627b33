//! Running a scenario test (`docs/testing.md`): console commands at
//! simulated times and expectations checked after every scan.
//!
//! The scenario's lines run in order. `At` runs the strategy up to a time
//! and gives the console a command; `Run` runs it on; an expectation starts
//! at the current time and is checked after each scan (one period of the
//! fastest task) until it is decided. At the end the strategy runs on until
//! every `within` and `after` is decided. A runtime error of a program
//! fails the scenario too: a test of control logic should not pass while
//! the logic faults.

use crate::isa::Op;
use crate::link::Linked;
use crate::store::Store;
use crate::strategy::Strategy;
use crate::verify::Verified;
use crate::vm::{Activation, Clock, Vm};
use linc_stdlib::Value;

/// What drives the strategy: the console.
pub trait Driver {
    fn strategy(&self) -> &Strategy;
    fn strategy_mut(&mut self) -> &mut Strategy;
    /// One console line; one reply or error (`code`, `message`) per command.
    fn command(&mut self, line: &str) -> Vec<Result<String, (String, String)>>;
    /// The commands of one line, in order (a line may hold several, split
    /// by `;`).
    fn split<'l>(&self, line: &'l str) -> Vec<&'l str> {
        vec![line]
    }
    /// How far one command moves the clock when it runs the strategy
    /// (`ADVANCE`, `SCAN`): the scenario runs those scans itself, checking
    /// its expectations after each, as it does between its own lines.
    fn advances(&self, _command: &str) -> Option<Result<u64, (String, String)>> {
        None
    }
}

/// When an expectation must hold (µs from its line's time).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Check {
    Within(u64),
    After(u64),
    Always,
    Never,
}

/// One line of a scenario, ready to run.
pub enum Step {
    At { line: u32, at_us: u64, command: String },
    Expect { line: u32, check: Check, text: String, object: Verified },
    Run { line: u32, for_us: u64 },
}

/// Why a scenario failed, at which line and simulated time.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    pub line: u32,
    pub at_us: u64,
    pub message: String,
    /// Every field and step variable the expression reads, with its value then.
    pub values: Vec<(String, String)>,
}

/// The values of the fields a scenario names, sampled after every scan
/// when they change (for a VCD file).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Samples {
    pub names: Vec<String>,
    pub watched: Vec<Watched>,
    /// (time µs, variable, value as the store shows it).
    pub changes: Vec<(u64, usize, String)>,
}

/// What a sampled variable is: a field's cell (named directly or through an
/// alias), or a step variable's slot among the strategy's step slots
/// (`2 × step` for `.X`, `2 × step + 1` for `.T`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Watched {
    Cell(u32),
    Step(usize),
}

/// A sampled value, compared before it is formatted.
#[derive(Clone, Debug, PartialEq)]
enum Seen {
    Cell(crate::store::Cell),
    Raw(u32),
}

/// What running a scenario gave.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Report {
    pub failures: Vec<Failure>,
    /// Simulated time at the end, µs.
    pub end_us: u64,
    pub scans: u64,
    pub samples: Samples,
}

/// An expectation being checked.
struct Pending {
    line: u32,
    check: Check,
    text: String,
    from_us: u64,
    linked: Linked,
    act: Activation,
}

/// The scenario's own VM and step-slot buffer.
struct Runner {
    vm: Vm,
    slots: Vec<u32>,
    pending: Vec<Pending>,
    /// Whether `slots` are the strategy's now: every scan and command is
    /// followed by a check, which reads them.
    fresh: bool,
    report: Report,
    /// The watched variables as last sampled.
    last: Vec<Option<Seen>>,
    /// The strategy's time when the scenario started: scenario times count
    /// from it (a warm start continues a saved clock).
    base: u64,
}

/// Runs `steps` against the driver's strategy. `watch` names the fields to
/// sample for a VCD (unknown names are skipped).
pub fn run(driver: &mut dyn Driver, steps: Vec<Step>, watch: &[String]) -> Report {
    let mut r = Runner {
        vm: Vm::new(1_000_000, Clock::new(1, 0)),
        slots: Vec::new(),
        pending: Vec::new(),
        fresh: false,
        report: Report::default(),
        last: Vec::new(),
        base: driver.strategy().elapsed_us(),
    };
    r.report.samples = samples(driver.strategy(), watch);
    r.sample(driver.strategy());
    for step in steps {
        match step {
            Step::At { line, at_us, command } => {
                let now = r.now(driver.strategy());
                if at_us < now {
                    r.fail(line, now, format!("`at` goes back in time (the scenario is at {})", time(now)), Vec::new());
                    continue;
                }
                r.advance(driver, at_us);
                r.commands(driver, line, &command);
            }
            Step::Expect { line, check, text, object } => r.expect(driver.strategy_mut(), line, check, text, object),
            Step::Run { line: _, for_us } => {
                let to = r.now(driver.strategy()).saturating_add(for_us);
                r.advance(driver, to);
            }
        }
    }
    // Run on only as long as a `within` or `after` is still undecided.
    let last = r.pending.iter().filter_map(deadline).max();
    if let Some(to) = last {
        r.advance_while(driver, to, |r| r.pending.iter().any(|p| deadline(p).is_some()));
    }
    r.report.end_us = r.now(driver.strategy());
    r.report
}

fn deadline(p: &Pending) -> Option<u64> {
    match p.check {
        Check::Within(d) | Check::After(d) => Some(p.from_us.saturating_add(d)),
        Check::Always | Check::Never => None,
    }
}

/// Simulated time as a scenario writes it: `1.5s`, `10m`, `2m3.5s`, `1h02m`.
pub fn time(us: u64) -> String {
    let (h, m, s) = (us / 3_600_000_000, us / 60_000_000 % 60, (us % 60_000_000) as f64 / 1e6);
    let secs = if s == 0.0 { String::new() } else { format!("{s}s") };
    match (h, m) {
        (0, 0) => format!("{s}s"),
        (0, _) => format!("{m}m{secs}"),
        _ => format!("{h}h{m:02}m{secs}"),
    }
}

/// The variables of `watch` the strategy has: fields (`BLOCK.FIELD`, or an
/// alias, named as written) and step variables (`Step.X`, `Step.T` of its
/// sequences); other names are skipped, each variable is sampled once.
fn samples(s: &Strategy, watch: &[String]) -> Samples {
    let mut out = Samples::default();
    let steps = s.step_names();
    for name in watch {
        let step = name.split_once('.').and_then(|(step, flag)| {
            let i = steps.iter().position(|n| n.eq_ignore_ascii_case(step))?;
            match flag.to_ascii_uppercase().as_str() {
                "X" => Some(Watched::Step(2 * i)),
                "T" => Some(Watched::Step(2 * i + 1)),
                _ => None,
            }
        });
        let field = crate::console::fields::address(&s.store, name).ok().filter(|a| a.bit.is_none());
        let (w, shown) = match (field, step) {
            (Some(a), _) if name.contains('.') => (Watched::Cell(a.cell), s.store.describe(a.cell)),
            (Some(a), _) => (Watched::Cell(a.cell), name.clone()),
            (None, Some(w)) => (w, name.clone()),
            (None, None) => continue,
        };
        if !out.watched.contains(&w) {
            out.names.push(shown);
            out.watched.push(w);
        }
    }
    out
}

impl Runner {
    /// Scenario time: since the scenario started.
    fn now(&self, s: &Strategy) -> u64 {
        s.elapsed_us().saturating_sub(self.base)
    }

    fn fail(&mut self, line: u32, at_us: u64, message: String, values: Vec<(String, String)>) {
        self.report.failures.push(Failure { line, at_us, message, values });
    }

    /// The commands of a scenario line at its time. One that runs the
    /// strategy (`ADVANCE 1h`) runs scan by scan like the scenario's own
    /// lines, so `never`, `always` and `within` are checked at every scan
    /// it runs, not only at its end.
    fn commands(&mut self, driver: &mut dyn Driver, line: u32, text: &str) {
        for command in driver.split(text) {
            let at_us = self.now(driver.strategy());
            let refused = |code: &str, message: &str| format!("`{}` was refused ({code}): {message}", command.trim());
            match driver.advances(command) {
                Some(Ok(us)) => self.advance(driver, at_us.saturating_add(us)),
                Some(Err((code, message))) => self.fail(line, at_us, refused(&code, &message), Vec::new()),
                None => {
                    self.fresh = false;
                    for reply in driver.command(command) {
                        if let Err((code, message)) = reply {
                            self.fail(line, at_us, refused(&code, &message), Vec::new());
                        }
                    }
                    self.check(driver.strategy_mut());
                }
            }
        }
    }

    /// Runs scan by scan up to `to`, checking after each.
    fn advance(&mut self, driver: &mut dyn Driver, to: u64) {
        self.advance_while(driver, to, |_| true);
    }

    /// [`Runner::advance`], stopping early once `go_on` says so.
    fn advance_while(&mut self, driver: &mut dyn Driver, to: u64, go_on: impl Fn(&Runner) -> bool) {
        loop {
            let now = self.now(driver.strategy());
            let s = driver.strategy_mut();
            if now >= to || !go_on(self) {
                return;
            }
            let step = s.scan_us().min(to - now);
            self.fresh = false;
            let failures = s.run_for(step, None);
            let at = self.now(driver.strategy());
            for e in failures {
                let where_ = format!("{}:{}:{}", e.file, e.line, e.col);
                self.fail(
                    0,
                    at,
                    format!("runtime error {} in `{}` at {where_}: {}", e.code, e.action, e.message),
                    Vec::new(),
                );
            }
            self.report.scans += 1;
            self.check(driver.strategy_mut());
            self.sample(driver.strategy());
        }
    }

    /// Records the watched variables that changed since the last sample
    /// (compared as cells or raw slots, so an unchanged one costs no
    /// formatting).
    fn sample(&mut self, s: &Strategy) {
        let now = self.now(s);
        let smp = &mut self.report.samples;
        if smp.watched.is_empty() {
            return;
        }
        if smp.watched.iter().any(|w| matches!(w, Watched::Step(_))) {
            s.step_slots(&mut self.slots);
        }
        self.last.resize(smp.watched.len(), None);
        for (i, w) in smp.watched.iter().enumerate() {
            let current = match *w {
                Watched::Cell(cell) => s.store.cells.get(cell as usize).cloned().map(Seen::Cell),
                Watched::Step(slot) => self.slots.get(slot).copied().map(Seen::Raw),
            };
            if self.last[i] != current {
                let shown = match (*w, &current) {
                    (Watched::Cell(cell), _) => s.store.show(cell),
                    (Watched::Step(slot), Some(Seen::Raw(raw))) if slot % 2 == 0 => {
                        if *raw != 0 { "TRUE" } else { "FALSE" }.to_string()
                    }
                    (Watched::Step(_), Some(Seen::Raw(raw))) => format!("{:?}", f32::from_bits(*raw)),
                    _ => String::new(),
                };
                self.last[i] = current;
                smp.changes.push((now, i, shown));
            }
        }
    }

    /// Starts an expectation and checks it at once (the others were checked
    /// at this time already: checking them all again for each new one made
    /// setting up a scenario quadratic in its expectations).
    fn expect(&mut self, s: &mut Strategy, line: u32, check: Check, text: String, object: Verified) {
        let now = self.now(s);
        match object.link(&s.store, &[crate::Program { unit: 0, own: None }]) {
            Ok(linked) => {
                let act = Activation::new(&linked, 0, 0);
                if !self.fresh {
                    s.step_slots(&mut self.slots);
                    self.fresh = true;
                }
                let mut p = Pending { line, check, text, from_us: now, linked, act };
                let mut names = None;
                if self.decide(s, &mut p, &mut names) {
                    self.pending.push(p);
                }
            }
            Err(e) => self.fail(line, now, format!("`{text}` can't be linked: {e}"), Vec::new()),
        }
    }

    /// Checks every pending expectation at the strategy's current time.
    fn check(&mut self, s: &mut Strategy) {
        s.step_slots(&mut self.slots);
        self.fresh = true;
        let mut names = None;
        let pending = std::mem::take(&mut self.pending);
        let mut open = Vec::with_capacity(pending.len());
        for mut p in pending {
            if self.decide(s, &mut p, &mut names) {
                open.push(p);
            }
        }
        self.pending = open;
    }

    /// Evaluates one expectation now: true while it is undecided; a failure
    /// is recorded with the values it read (`names`: the strategy's step
    /// names, looked up once for all the failures of a check).
    fn decide(&mut self, s: &mut Strategy, p: &mut Pending, names: &mut Option<Vec<String>>) -> bool {
        let now = self.now(s);
        let due = deadline(p).is_none_or(|d| now >= d);
        let value = evaluate(&mut self.vm, p, &self.slots, &mut s.store);
        let verdict = match (p.check, value) {
            (_, Err(why)) => Some(Err(why)),
            (Check::Within(_), Ok(true)) => Some(Ok(())),
            (Check::Within(d), Ok(false)) if due => Some(Err(format!("`{}` did not hold within {}", p.text, time(d)))),
            (Check::After(d), Ok(v)) if due => {
                Some(if v { Ok(()) } else { Err(format!("`{}` did not hold after {}", p.text, time(d))) })
            }
            (Check::Always, Ok(false)) => Some(Err(format!("`{}` stopped holding (expected always)", p.text))),
            (Check::Never, Ok(true)) => Some(Err(format!("`{}` held (expected never)", p.text))),
            _ => None,
        };
        match verdict {
            None => true,
            Some(Ok(())) => false,
            Some(Err(message)) => {
                let names = names.get_or_insert_with(|| s.step_names());
                let values = reads(&p.linked, &s.store, names, &self.slots);
                self.fail(p.line, now, message, values);
                false
            }
        }
    }
}

/// The expression's value now, over the sequences' current step variables.
/// The expression is an ST expression (no assignments), so running it
/// against the live store only reads it.
fn evaluate(vm: &mut Vm, p: &mut Pending, slots: &[u32], store: &mut Store) -> Result<bool, String> {
    p.act.retained.clear();
    p.act.retained.extend_from_slice(slots);
    p.act.retained.resize(p.linked.unit(0).map_or(0, |u| usize::from(u.retained)), 0);
    match vm.run(&p.linked, &mut p.act, store, None) {
        Ok(_) => match p.act.result.take() {
            Some(Value::Bool(b)) => Ok(b),
            Some(other) => Ok(other.as_bool()),
            None => Err(format!("`{}` gave no value", p.text)),
        },
        Err(e) => Err(format!("`{}` failed ({}): {}", p.text, e.code, e.message)),
    }
}

/// Every field the expression reads and every step variable, with values.
fn reads(linked: &Linked, store: &Store, steps: &[String], slots: &[u32]) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let Some(prog) = linked.program(0) else { return out };
    for t in &prog.targets {
        if !t.is_absent() {
            out.push((store.describe(t.cell), store.show(t.cell)));
        }
    }
    let code = linked.ops(0, 0).unwrap_or_default();
    for op in code {
        if let Op::LoadRet { n } = *op {
            let (step, x) = (usize::from(n / 2), n % 2 == 0);
            let Some(name) = steps.get(step) else { continue };
            let raw = slots.get(usize::from(n)).copied().unwrap_or(0);
            let entry = if x {
                (format!("{name}.X"), if raw != 0 { "TRUE".into() } else { "FALSE".into() })
            } else {
                (format!("{name}.T"), format!("{}s", f32::from_bits(raw)))
            };
            if !out.contains(&entry) {
                out.push(entry);
            }
        }
    }
    out
}

impl Driver for crate::console::Console {
    fn strategy(&self) -> &Strategy {
        &self.strategy
    }

    fn strategy_mut(&mut self) -> &mut Strategy {
        &mut self.strategy
    }

    fn command(&mut self, line: &str) -> Vec<Result<String, (String, String)>> {
        self.execute(line).into_iter().map(|r| r.map_err(|e| (e.code.to_string(), e.message))).collect()
    }

    fn split<'l>(&self, line: &'l str) -> Vec<&'l str> {
        crate::console::commands(line)
    }

    fn advances(&self, command: &str) -> Option<Result<u64, (String, String)>> {
        self.advance_of(command).map(|r| r.map_err(|e| (e.code.to_string(), e.message)))
    }
}

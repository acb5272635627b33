//! The sequence engine (docs/sequences.md), with a host whose conditions the
//! test sets and which records the actions that ran in each scan.
use linc_engines::sequence::chart::{Action, Assoc, Body, Chart, Step, Transition};
use linc_engines::sequence::engine::{Event, Host};
use linc_engines::sequence::{Command, Sequence, Status};
use linc_engines::strategy::qualifier::Qualifier;
use linc_runtime::errors::{Fault, RuntimeError};

/// Conditions by code; the names of the actions run, per scan.
#[derive(Default)]
struct Fake {
    conds: Vec<bool>,
    ran: Vec<String>,
    events: Vec<String>,
    fail_action: Option<usize>,
}

impl Host for Fake {
    fn condition(&mut self, code: usize) -> Result<bool, RuntimeError> {
        Ok(self.conds.get(code).copied().unwrap_or(false))
    }
    fn action(&mut self, code: usize) -> Result<(), RuntimeError> {
        if self.fail_action == Some(code) {
            return Err(RuntimeError::unlocated(Fault::new(linc_runtime::Code::R0001, "division by zero")));
        }
        Ok(())
    }
    fn event(&mut self, e: Event) {
        match e {
            Event::Ran(a) => self.ran.push(a.to_string()),
            other => self.events.push(format!("{other:?}")),
        }
    }
}

fn step(name: &str, initial: bool, assocs: &[(usize, Qualifier, f64)]) -> Step {
    let assocs =
        assocs.iter().map(|&(action, qualifier, t)| Assoc { action, qualifier, time_us: (t * 1e6) as u64 }).collect();
    Step { name: name.into(), initial, slot: 0, assocs }
}

fn tr(name: &str, from: &[usize], to: &[usize], priority: Option<u32>, code: usize) -> Transition {
    Transition { name: name.into(), from: from.to_vec(), to: to.to_vec(), priority, code }
}

fn code_actions(names: &[&str]) -> Vec<Action> {
    names.iter().enumerate().map(|(i, n)| Action { name: n.to_string(), body: Body::Code(i) }).collect()
}

/// Runs `scans` scans `period` seconds apart; returns per scan the actions run.
fn run(
    seq: &mut Sequence,
    host: &mut Fake,
    scans: usize,
    period: f64,
    mut each: impl FnMut(usize, &mut Fake),
) -> Vec<String> {
    let mut out = Vec::new();
    for i in 0..scans {
        each(i, host);
        host.ran.clear();
        seq.scan((i as f64 * period * 1e6).round() as u64, host).expect("scan");
        out.push(host.ran.join(","));
    }
    out
}

/// One step A with every qualifier; A → B when condition 0; B resets S's action.
fn qualifier_chart(t: f64) -> Chart {
    use Qualifier::*;
    Chart {
        steps: vec![
            step("A", true, &[(0, P, 0.0), (1, N, 0.0), (2, L, t), (3, D, t), (4, E, t), (5, F, 0.0), (6, S, 0.0)]),
            step("B", false, &[(6, R, 0.0)]),
        ],
        transitions: vec![tr("A to B", &[0], &[1], None, 0)],
        actions: code_actions(&["p", "n", "l", "d", "e", "f", "s"]),
    }
}

fn qualifier_pattern(period: f64, t: f64, leave_at: usize) -> Vec<String> {
    let mut seq = Sequence::new(qualifier_chart(t));
    seq.command(Command::Run);
    let mut host = Fake { conds: vec![false], ..Fake::default() };
    run(&mut seq, &mut host, 8, period, |i, h| h.conds[0] = i == leave_at)
}

#[test]
fn qualifier_timing_at_one_second() {
    // A active in scans 0..=4 (its transition is true in scan 5), L/D/E at 2 s.
    assert_eq!(
        qualifier_pattern(1.0, 2.0, 5),
        ["p,n,l,s", "n,l,s", "n,d,e,s", "n,d,s", "n,d,s", "f", "", ""],
        "P once; N every scan; L while T < 2 s; D from 2 s; E once at 2 s; F in the leaving scan; \
         S stored until B's R activates (R: not run in that scan)"
    );
}

#[test]
fn qualifier_timing_at_a_tenth_of_a_second() {
    // The same chart with 0.2 s: at 0.1 s per scan, T reaches 0.2 s in scan 2.
    assert_eq!(qualifier_pattern(0.1, 0.2, 5), ["p,n,l,s", "n,l,s", "n,d,e,s", "n,d,s", "n,d,s", "f", "", ""]);
}

#[test]
fn a_step_runs_its_actions_once_before_its_transition_can_fire() {
    let mut seq = Sequence::new(qualifier_chart(1.0));
    seq.command(Command::Run);
    let mut host = Fake { conds: vec![true], ..Fake::default() };
    let ran = run(&mut seq, &mut host, 2, 1.0, |_, _| {});
    assert_eq!(ran, ["p,n,l,s", "f"], "the condition was TRUE from the start");
    assert_eq!(seq.active_steps(), ["B"]);
}

fn divergence(priorities: [Option<u32>; 2]) -> Sequence {
    let chart = Chart {
        steps: vec![step("A", true, &[]), step("B", false, &[]), step("C", false, &[])],
        transitions: vec![tr("AB", &[0], &[1], priorities[0], 0), tr("AC", &[0], &[2], priorities[1], 1)],
        actions: vec![],
    };
    let mut seq = Sequence::new(chart);
    seq.command(Command::Run);
    seq
}

#[test]
fn a_selective_divergence_fires_one_branch_by_priority_or_order() {
    for (priorities, expected) in [([None, None], "B"), ([Some(2), Some(1)], "C"), ([Some(1), Some(2)], "B")] {
        let mut seq = divergence(priorities);
        let mut host = Fake { conds: vec![true, true], ..Fake::default() };
        run(&mut seq, &mut host, 2, 1.0, |_, _| {});
        assert_eq!(seq.active_steps(), [expected], "{priorities:?}");
    }
    // Only the TRUE one fires, whatever its priority.
    let mut seq = divergence([Some(1), Some(2)]);
    let mut host = Fake { conds: vec![false, true], ..Fake::default() };
    run(&mut seq, &mut host, 2, 1.0, |_, _| {});
    assert_eq!(seq.active_steps(), ["C"]);
}

#[test]
fn simultaneous_divergence_and_convergence() {
    let chart = Chart {
        steps: vec![step("A", true, &[]), step("B", false, &[]), step("C", false, &[]), step("D", false, &[])],
        transitions: vec![tr("split", &[0], &[1, 2], None, 0), tr("join", &[1, 2], &[3], None, 1)],
        actions: vec![],
    };
    let mut seq = Sequence::new(chart);
    seq.command(Command::Run);
    let mut host = Fake { conds: vec![true, false], ..Fake::default() };
    run(&mut seq, &mut host, 2, 1.0, |_, _| {});
    assert_eq!(seq.active_steps(), ["B", "C"]);
    host.conds[1] = true;
    seq.scan(2_000_000, &mut host).unwrap();
    assert_eq!(seq.active_steps(), ["D"]);
    assert_eq!(seq.step("B"), Some((false, 1_000_000)), ".T kept after deactivation");
}

#[test]
fn a_chart_action_scans_while_it_runs_and_restarts_after() {
    let child = Chart {
        steps: vec![step("Fwd", true, &[(0, Qualifier::N, 0.0)]), step("Rev", false, &[(1, Qualifier::N, 0.0)])],
        transitions: vec![tr("Fwd to Rev", &[0], &[1], None, 1)],
        actions: vec![
            Action { name: "forward".into(), body: Body::Code(10) },
            Action { name: "reverse".into(), body: Body::Code(11) },
        ],
    };
    let chart = Chart {
        steps: vec![step("Idle", true, &[]), step("Stir", false, &[(0, Qualifier::N, 0.0)])],
        transitions: vec![tr("go", &[0], &[1], None, 0), tr("back", &[1], &[0], None, 2)],
        actions: vec![Action { name: "Stirring".into(), body: Body::Chart(Box::new(child)) }],
    };
    let mut seq = Sequence::new(chart);
    seq.command(Command::Run);
    let mut host = Fake { conds: vec![true, false, false], ..Fake::default() };
    // Idle; Stir (its chart starts at Fwd); Fwd → Rev; back to Idle; Stir again: Fwd, not Rev.
    let ran = run(&mut seq, &mut host, 6, 1.0, |i, h| {
        h.conds[1] = i == 3;
        h.conds[2] = i == 4;
        h.conds[0] = i == 1 || i == 5;
    });
    assert_eq!(ran, ["", "Stirring,forward", "Stirring,forward", "Stirring,reverse", "", "Stirring,forward"]);
    assert_eq!(seq.step("Fwd"), Some((true, 0)), "a chart action's step, found by name");
    assert_eq!(seq.step("Rev"), Some((false, 0)), "reset with its chart when the action stopped");
    // Leaving the chart action leaves its active step: Rev is deactivated
    // in the scan Stir is left, as a trace must say.
    let rev: Vec<&String> = host.events.iter().filter(|e| e.contains("\"Rev\"")).collect();
    assert_eq!(rev, ["Activated(\"Rev\")", "Deactivated(\"Rev\")"], "{:?}", host.events);
}

fn three_steps() -> Sequence {
    let chart = Chart {
        steps: vec![step("S1", true, &[(0, Qualifier::N, 0.0)]), step("S2", false, &[(0, Qualifier::N, 0.0)])],
        transitions: vec![tr("S1 to S2", &[0], &[1], None, 0)],
        actions: code_actions(&["work"]),
    };
    Sequence::new(chart)
}

#[test]
fn sfc_con_reset_stop_hold_run() {
    let mut seq = three_steps();
    let mut host = Fake { conds: vec![false], ..Fake::default() };
    seq.scan(0, &mut host).unwrap();
    assert_eq!((seq.status, seq.active_steps().len(), host.ran.len()), (Status::Reset, 0, 0), "at rest until Run");
    seq.command(Command::Run);
    seq.scan(1_000_000, &mut host).unwrap();
    seq.scan(2_000_000, &mut host).unwrap();
    assert_eq!(seq.step("S1"), Some((true, 1_000_000)));
    // Stop: steps stay active, timers freeze, actions halt.
    seq.command(Command::Stop);
    host.ran.clear();
    seq.scan(5_000_000, &mut host).unwrap();
    assert_eq!((seq.status, seq.step("S1"), host.ran.len()), (Status::Stopped, Some((true, 1_000_000)), 0));
    // Run continues where it stopped; the stopped time does not count.
    seq.command(Command::Run);
    seq.scan(6_000_000, &mut host).unwrap();
    assert_eq!(seq.step("S1"), Some((true, 1_000_000)), "the first scan after a stop adds nothing");
    seq.scan(7_000_000, &mut host).unwrap();
    assert_eq!(seq.step("S1"), Some((true, 2_000_000)));
    // Hold: transitions disabled; timers and actions go on.
    seq.command(Command::Hold);
    host.conds[0] = true;
    host.ran.clear();
    seq.scan(8_000_000, &mut host).unwrap();
    assert_eq!(
        (seq.status, seq.active_steps(), host.ran.as_slice()),
        (Status::Held, vec!["S1"], &["work".to_string()][..])
    );
    assert_eq!(seq.step("S1"), Some((true, 3_000_000)));
    seq.command(Command::Run);
    seq.scan(9_000_000, &mut host).unwrap();
    assert_eq!(seq.active_steps(), ["S2"]);
    // Reset: nothing active, timers zero; Run starts at the initial steps.
    seq.command(Command::Reset);
    assert_eq!((seq.status, seq.active_steps().len(), seq.step("S1")), (Status::Reset, 0, Some((false, 0))));
    seq.command(Command::Run);
    seq.scan(10_000_000, &mut host).unwrap();
    assert_eq!(seq.active_steps(), ["S1"]);
}

#[test]
fn held_steps_and_forced_transitions() {
    let mut seq = three_steps();
    seq.command(Command::Run);
    let mut host = Fake { conds: vec![true], ..Fake::default() };
    seq.monitor.held.insert("s1".into());
    run(&mut seq, &mut host, 3, 1.0, |_, _| {});
    assert_eq!(seq.active_steps(), ["S1"], "a held step stays active though its transition is TRUE");
    seq.monitor.held.clear();
    seq.monitor.forced.insert("S1 to S2".into(), false);
    seq.scan(3_000_000, &mut host).unwrap();
    assert_eq!(seq.active_steps(), ["S1"], "forced hold");
    host.conds[0] = false;
    seq.monitor.forced.insert("S1 to S2".into(), true);
    seq.scan(4_000_000, &mut host).unwrap();
    assert_eq!(seq.active_steps(), ["S2"], "forced continue fires a FALSE transition");
}

#[test]
fn a_runtime_error_stops_the_sequence_until_reset() {
    let mut seq = three_steps();
    seq.command(Command::Run);
    let mut host = Fake { conds: vec![false], fail_action: Some(0), ..Fake::default() };
    assert_eq!(seq.scan(0, &mut host).map_err(|e| e.code.as_str()), Err("R0001"));
    assert_eq!(seq.status, Status::Error);
    seq.command(Command::Run);
    assert_eq!(seq.status, Status::Error, "Run does not clear an error");
    seq.command(Command::Reset);
    assert_eq!(seq.status, Status::Reset);
}

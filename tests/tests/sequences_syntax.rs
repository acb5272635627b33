//! Conformance cases for the `.sfc` sequence front end (issue 8): syntax,
//! recovery and the checks of charts, associations and the ST inside. Each
//! case names the guide section (chapter 9, §20.5) or the decision it covers
//! and asserts the exact codes; the snapshot pins the tree and the rendered
//! diagnostics.

use linc_compiler::diag::render::{self, Format, SourceFiles};
use linc_compiler::sfc::pretty;
use linc_compiler::Context;
use linc_conformance::guide_db;
use linc_runtime::Database;

/// What names in the ST of a case are checked against.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Db {
    /// The guide's database: blocks must exist, fields have types.
    Guide,
    /// No database: any block name is accepted, as one that will exist.
    None,
}

struct Outcome {
    codes: Vec<&'static str>,
    snapshot: String,
}

fn run(section: &str, src: &str, db: Db) -> Outcome {
    let builtin = Database::builtin();
    let ctx = match db {
        Db::Guide => Context::of(Some(guide_db())),
        Db::None => Context::of(Some(&builtin)).unresolved(),
    };
    let r = linc_compiler::check_sequence(src, ctx);
    let mut files = SourceFiles::new();
    let id = files.add("case.sfc".to_string(), src.to_string());
    let mut snapshot = format!("{section} (database: {db:?})\n--- source\n{src}\n--- tree\n");
    snapshot.push_str(&r.tree.as_ref().map(pretty::sequence).unwrap_or_else(|| "(none)\n".into()));
    snapshot.push_str("--- diagnostics\n");
    if r.diagnostics.is_empty() {
        snapshot.push_str("(none)\n");
    }
    for d in &r.diagnostics {
        snapshot.push_str(&render::render(&files, &d.clone().in_file(id), Format::Human));
    }
    assert_eq!(r.program.is_some(), !r.has_errors(), "a checked sequence exactly when there are no errors");
    Outcome { codes: r.diagnostics.iter().map(|d| d.code.as_str()).collect(), snapshot }
}

/// A case that gives exactly these codes (none for a valid one), in order.
macro_rules! case {
    ($name:ident, $section:literal, $db:ident, $src:expr, [$($code:literal),* $(,)?]) => {
        #[test]
        fn $name() {
            let o = run($section, $src, Db::$db);
            insta::assert_snapshot!(stringify!($name), o.snapshot);
            let expected: &[&str] = &[$($code),*];
            assert_eq!(o.codes, expected, "diagnostic codes");
        }
    };
}

/// The example, complete: every qualifier, divergence and
/// convergence, priorities and a chart action.
const BATCH: &str = "\
(* batch.sfc *)
INITIAL_STEP Idle:  Reset(P);              END_STEP
STEP Fill:          FillOn(N); Alarm(D, T#30m); FillOff(F);  END_STEP
STEP Heat:          HeatOn(S); Log(E, T#5s);  END_STEP
STEP Agitate:       Stir(L, T#2m);          END_STEP
STEP Done:          HeatOn(R);              END_STEP
TRANSITION FROM Idle TO Fill := Plant.Start; END_TRANSITION
TRANSITION Full (PRIORITY := 1) FROM Fill TO (Heat, Agitate) := TANK.Level >= 90.0; END_TRANSITION
TRANSITION Abort (PRIORITY := 2) FROM Fill TO Done := Plant.Stop; END_TRANSITION
TRANSITION FROM (Heat, Agitate) TO Done := Heat.T > T#10m AND TIC.PV > 80.0; END_TRANSITION
ACTION Reset
    VALVE1.Out.Bit0 := 0;
END_ACTION
ACTION FillOn
    VALVE1.Out.Bit0 := 1;
END_ACTION
ACTION FillOff
    VALVE1.Out.Bit0 := 0;
END_ACTION
ACTION Alarm
    Plant.Alarm := Fill.X;
END_ACTION
ACTION HeatOn
    PID1.D := 2.0; PID1.S := 1;
END_ACTION
ACTION Log
    Plant.Count := Plant.Count + 1;
END_ACTION
ACTION Stir : CHART
    INITIAL_STEP Fwd: Forward(N); END_STEP
    STEP Rev: Forward(R); END_STEP
    TRANSITION FROM Fwd TO Rev := Fwd.T > T#30s; END_TRANSITION
    TRANSITION FROM Rev TO Fwd := Rev.T > T#30s; END_TRANSITION
END_ACTION
ACTION Forward
    MOTOR.Fwd := TRUE;
END_ACTION
";

case!(s20_5_batch_sequence, "§20.5 the issue's batch sequence", None, BATCH, []);

case!(
    decision_qualifier_letters_are_not_keywords,
    "§20.5.5, issue 8: a field or block called S, D, N or P still works in ST",
    None,
    "INITIAL_STEP S: N(N); D(D, T#1s); END_STEP
ACTION N
    S.D := 2.0; PID1.S := PID1.D + N.P;
END_ACTION
ACTION D
    D.N := S.X;
END_ACTION
",
    []
);

case!(
    s20_5_no_initial_step,
    "§20.5: a chart starts at its initial step",
    None,
    "STEP Idle: END_STEP
STEP Fill: END_STEP
TRANSITION FROM Idle TO Fill := Plant.Start; END_TRANSITION
",
    ["E0202"]
);

case!(
    s10_2_2_chart_action_without_initial_step,
    "§10.2.2: a chart action is a chart, with its own initial step",
    None,
    "INITIAL_STEP Idle: Stir(N); END_STEP
ACTION Stir : CHART
    STEP Fwd: END_STEP
END_ACTION
",
    ["E0202"]
);

case!(
    s20_5_duplicate_step_across_charts,
    "issue 8: step names are unique in the whole sequence, nested charts included, ignoring case",
    None,
    "INITIAL_STEP Idle: Stir(N); END_STEP
STEP IDLE: END_STEP
TRANSITION FROM Idle TO Idle := TRUE; END_TRANSITION
ACTION Stir : CHART
    INITIAL_STEP Idle: END_STEP
END_ACTION
",
    ["E0203", "E0203"]
);

case!(
    s20_5_transition_to_unknown_step,
    "§20.5: a transition joins steps of its chart",
    None,
    "INITIAL_STEP Idle: Stir(N); END_STEP
STEP Fill: END_STEP
TRANSITION FROM Idle TO Filling := Plant.Start; END_TRANSITION
TRANSITION FROM (Fill, Fwd) TO Idle := Plant.Stop; END_TRANSITION
ACTION Stir : CHART
    INITIAL_STEP Fwd: END_STEP
END_ACTION
",
    ["W0201", "E0204", "E0204"]
);

case!(
    s20_5_5_unknown_unused_and_twice_defined_actions,
    "§20.5.5: an association names an action of the sequence",
    None,
    "INITIAL_STEP Idle: FillOn(N); Missing(P); END_STEP
ACTION FillOn
    VALVE1.Out.Bit0 := 1;
END_ACTION
ACTION FILLON
    VALVE1.Out.Bit0 := 0;
END_ACTION
ACTION Spare
    VALVE2.Out.Bit0 := 1;
END_ACTION
",
    ["E0205", "E0206", "W0200"]
);

case!(
    s20_5_5_every_lin_qualifier,
    "§20.5.5: LIN's qualifiers P N L D E F S R; L, D and E take a time",
    None,
    "INITIAL_STEP Idle: A(P); A(N); A(L, T#1s); A(D, T#2m); A(E, T#1h); A(F); A(S); A(R); a(n); END_STEP
ACTION A
    X.Y := 1;
END_ACTION
",
    []
);

case!(
    s20_5_5_iec_only_qualifiers,
    "§20.5.5: P1 is LIN's P, P0 is LIN's F; SD, DS and SL have no LIN equivalent",
    None,
    "INITIAL_STEP Idle: A(P1); A(P0); A(SD, T#1s); A(DS, T#1s); A(SL, T#1s); A(X); END_STEP
ACTION A
    X.Y := 1;
END_ACTION
",
    ["E0208", "E0208", "E0208", "E0208", "E0208", "E0207"]
);

case!(
    s20_5_5_missing_and_extra_time,
    "§20.5.5: L, D and E need a time, P N F S R take none",
    None,
    "INITIAL_STEP Idle: A(L); A(D); A(E); A(N, T#3s); A(S, T#3s); END_STEP
ACTION A
    X.Y := 1;
END_ACTION
",
    ["E0209", "E0209", "E0209", "E0210", "E0210"]
);

case!(
    s20_5_unreachable_step,
    "§20.5: a step no transition leads to never runs (warning)",
    None,
    "INITIAL_STEP Idle: END_STEP
STEP Fill: END_STEP
STEP Drain: END_STEP
STEP Heat: END_STEP
STEP Done: END_STEP
TRANSITION FROM Idle TO Fill := Plant.Start; END_TRANSITION
TRANSITION FROM (Fill, Heat) TO Done := Plant.Stop; END_TRANSITION
",
    ["W0201", "W0201", "W0201"]
);

case!(
    s20_5_divergence_and_convergence_reach_every_step,
    "§20.5: a simultaneous convergence is reached when all of its branches are",
    None,
    "INITIAL_STEP Idle: END_STEP
STEP Heat: END_STEP
STEP Stir: END_STEP
STEP Done: END_STEP
TRANSITION FROM Idle TO (Heat, Stir) := Plant.Start; END_TRANSITION
TRANSITION FROM (Heat, Stir) TO Done := Heat.T > T#10m; END_TRANSITION
TRANSITION FROM Done TO Idle := Done.X; END_TRANSITION
",
    []
);

case!(
    s12_11_transition_not_a_truth_value,
    "§12.11: a transition condition is a truth value",
    Guide,
    "INITIAL_STEP Idle: END_STEP
STEP Fill: END_STEP
TRANSITION FROM Idle TO Fill := TIC_100.PV; END_TRANSITION
TRANSITION FROM Fill TO Idle := TIC_100.PV > 80.0 AND Fill.T > T#1m; END_TRANSITION
",
    ["E0119"]
);

case!(
    s20_5_step_variables_in_actions,
    "§20.5: Step.X and Step.T of the sequence's steps, nested charts included, in every action",
    Guide,
    "INITIAL_STEP Idle: Show(N); Stir(N); END_STEP
ACTION Show
    TIC_100.SL := Idle.T + Fwd.T;
    Dig_A.Out.Bit0 := Fwd.X;
    Dig_A.Out.Bit1 := Nope.X;
END_ACTION
ACTION Stir : CHART
    INITIAL_STEP Fwd: END_STEP
END_ACTION
",
    ["E0120"]
);

case!(
    s20_5_names_follow_identifier_rules,
    "§12.8: step and transition names follow the identifier rules",
    None,
    "INITIAL_STEP VeryLongStep: END_STEP
INITIAL_STEP 2nd: END_STEP
INITIAL_STEP A.B: END_STEP
TRANSITION Go FROM VeryLongStep TO VeryLongStep := TRUE; END_TRANSITION
TRANSITION GO FROM VeryLongStep TO VeryLongStep := TRUE; END_TRANSITION
",
    ["E0005", "E0006", "E0006", "E0211"]
);

case!(
    decision_recovery_one_error_per_item,
    "issue 8: recovery at END_STEP, END_TRANSITION and END_ACTION; checking goes on",
    None,
    "INITIAL_STEP Idle Reset(P); END_STEP
STEP Fill: FillOn(N) END_STEP
TRANSITION FROM Idle Fill := Plant.Start; END_TRANSITION
TRANSITION FROM Fill TO Idle := Plant.Stop END_TRANSITION
TRANSITION FROM Idle TO Fill := Plant.Start +; END_TRANSITION
ACTION Reset
    VALVE1.Out.Bit0 := ;
    VALVE1.Out.Bit1 := 1;
END_ACTION
ACTION FillOn
    VALVE1.Out.Bit0 := 1;
END_ACTION
STEP Late: Nothing(N); END_STEP
",
    ["E0200", "E0200", "E0200", "E0200", "E0010", "E0010", "E0205"]
);

case!(
    decision_missing_end_action_stops_at_next_action,
    "issue 8: an action without END_ACTION ends at the next ACTION",
    None,
    "INITIAL_STEP Idle: A(N); B(N); END_STEP
ACTION A
    X.Y := 1;
ACTION B
    X.Y := 2;
END_ACTION
",
    ["E0010"]
);

case!(
    decision_end_of_file_inside_a_step,
    "issue 8: the file ends inside a step",
    None,
    "INITIAL_STEP Idle: A(N);",
    ["E0205", "E0201"]
);

case!(
    decision_junk_between_items,
    "issue 8: text that is no item is one error, and reading resumes at the next item",
    None,
    "INITIAL_STEP Idle: END_STEP
X := 1; Y := 2;
STEP Fill: END_STEP
TRANSITION FROM Idle TO Fill := TRUE; END_TRANSITION
",
    ["E0200"]
);

case!(
    decision_a_source_named_twice_is_waited_for_once,
    "§20.5: FROM (A, A) is FROM A",
    None,
    "INITIAL_STEP A: END_STEP
STEP B: END_STEP
TRANSITION FROM (A, A) TO (B, B) := TRUE; END_TRANSITION
TRANSITION FROM B TO A := TRUE; END_TRANSITION
",
    []
);

/// Bad input never panics: every prefix of the example, and the example
/// with each token removed, checks without panicking.
#[test]
fn damaged_sequences_never_panic() {
    let builtin = Database::builtin();
    let ctx = Context::of(Some(&builtin)).unresolved();
    let mut ends: Vec<usize> = BATCH.char_indices().map(|(i, _)| i).collect();
    ends.push(BATCH.len());
    let mut errors = 0;
    for &end in &ends {
        errors += usize::from(linc_compiler::check_sequence(&BATCH[..end], ctx).has_errors());
    }
    assert!(errors > ends.len() / 2, "most prefixes are incomplete sequences");
    let words: Vec<&str> = BATCH.split_whitespace().collect();
    for skip in 0..words.len() {
        let text: Vec<&str> = words.iter().enumerate().filter(|(i, _)| *i != skip).map(|(_, w)| *w).collect();
        let _ = linc_compiler::check_sequence(&text.join(" "), ctx);
    }
}

case!(
    s20_5_transition_leaving_a_parallel_branch_is_unsafe,
    "§20.5, issue 8: a transition leaving one branch of a simultaneous divergence (warning \"unsafe\")",
    None,
    "INITIAL_STEP Idle: END_STEP
STEP Heat: END_STEP
STEP Stir: END_STEP
TRANSITION FROM Idle TO (Heat, Stir) := Plant.Start; END_TRANSITION
TRANSITION FROM Heat TO Idle := Heat.T > T#10m; END_TRANSITION
",
    ["W0202"]
);

case!(
    s20_5_divergence_that_never_converges_is_unsafe,
    "§20.5, issue 8: branches that never converge, with the chart coming round again (warning \"unsafe\")",
    None,
    "INITIAL_STEP Idle: END_STEP
STEP Heat: END_STEP
STEP Stir: END_STEP
STEP Hot: END_STEP
TRANSITION FROM Idle TO (Heat, Stir) := Plant.Start; END_TRANSITION
TRANSITION FROM Heat TO Hot := Heat.T > T#10m; END_TRANSITION
TRANSITION FROM Stir TO Idle := Stir.T > T#1m; END_TRANSITION
TRANSITION FROM Hot TO Heat := Hot.T > T#1m; END_TRANSITION
",
    ["W0202"]
);

/// A long chain checks clean and quickly: the checks are linear in the
/// chart, and the unsafe search is bounded.
/// A ring of `n` steps, transition `i` leaving step `i` when `cond(i)`.
fn ring(n: usize, cond: impl Fn(usize) -> String) -> String {
    use std::fmt::Write;
    let mut src = String::from("INITIAL_STEP S0: A(N); END_STEP\n");
    for i in 1..n {
        let _ = writeln!(src, "STEP S{i}: A(N); END_STEP");
    }
    for i in 0..n {
        let _ = writeln!(src, "TRANSITION FROM S{i} TO S{} := {}; END_TRANSITION", (i + 1) % n, cond(i));
    }
    src.push_str("ACTION A\n    X.Y := 1;\nEND_ACTION\n");
    src
}

#[test]
fn long_sequence_checks_clean() {
    let n = 20_000;
    let src = ring(n, |_| "X.Y > 1".into());
    let builtin = Database::builtin();
    let ctx = Context::of(Some(&builtin)).unresolved();
    let started = std::time::Instant::now();
    let r = linc_compiler::check_sequence(&src, ctx);
    eprintln!("{n} steps checked in {:?}", started.elapsed());
    assert!(r.diagnostics.is_empty(), "{:?}", r.diagnostics.first());
    assert_eq!(r.tree.map(|t| (t.chart.steps.len(), t.chart.transitions.len())), Some((n, n)));
}

case!(
    decision_chart_action_ends_at_end_action,
    "§10.2.2, issue 8: a chart action holds steps and transitions only; an ACTION inside it closes it with one error",
    None,
    "INITIAL_STEP Idle: Stir(N); END_STEP
ACTION Stir : CHART
    INITIAL_STEP Fwd: Fwd1(N); END_STEP
ACTION Fwd1
    X.Y := 1;
END_ACTION
",
    ["E0200"]
);

case!(
    decision_priority_is_a_number,
    "issue 8: PRIORITY := n takes a whole number",
    None,
    "INITIAL_STEP Idle: END_STEP
STEP Fill: END_STEP
TRANSITION Go (PRIORITY := high) FROM Idle TO Fill := TRUE; END_TRANSITION
TRANSITION Back (PRIORITY := 2) FROM Fill TO Idle := TRUE; END_TRANSITION
",
    ["E0200"]
);

case!(
    s10_2_2_chart_action_that_runs_itself,
    "§10.2.2, decision: a chart action cannot run itself, directly or through another",
    None,
    "INITIAL_STEP Idle: Stir(N); Mix(N); END_STEP
ACTION Stir : CHART
    INITIAL_STEP Fwd: Stir(N); END_STEP
END_ACTION
ACTION Mix : CHART
    INITIAL_STEP M1: Blend(N); END_STEP
END_ACTION
ACTION Blend : CHART
    INITIAL_STEP B1: Mix(P); END_STEP
END_ACTION
",
    ["E0212", "E0212"]
);

/// Checks a ring of `n` steps whose transitions read the step variables.
fn ring_with_step_variables(n: usize) -> std::time::Duration {
    let src = ring(n, |i| format!("S{i}.T > 1.0 AND S{i}.X"));
    let builtin = Database::builtin();
    let ctx = Context::of(Some(&builtin)).unresolved();
    // Processor time on this thread: how busy the machine is does not count.
    let (r, took) = linc_test_support::work::thread_cpu(|| linc_compiler::check_sequence(&src, ctx));
    assert!(r.diagnostics.is_empty(), "{:?}", r.diagnostics.first());
    took
}

#[test]
fn step_variables_are_looked_up_in_constant_time() {
    // Four times the steps: linear is about 4x; the old linear search per
    // step variable made it 16x.
    let ratio = linc_test_support::work::growth(|big| ring_with_step_variables(if big { 10_000 } else { 2_500 }));
    assert!(ratio < 8.0, "2,500 → 10,000 steps: {ratio:.1}x the work");
}

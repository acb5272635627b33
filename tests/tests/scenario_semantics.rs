//! When scenario expectations pass and fail (docs/testing.md): `within`
//! at the first scan it holds, `after` at its one check, `always` and
//! `never` at every scan, undecided ones run to their deadline, and a
//! runtime error fails the scenario. A counter action adds 1 to REC.N0
//! every 100 ms scan; the driver here has no console commands.

use linc_conformance::exec::compile;
use linc_engines::scenario::{run, Check, Driver, Report, Step};
use linc_engines::strategy::{Strategy, Want, WantKind};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

const DB: &str = r#"{ "blocks": {
    "REC": { "type": "RECIPE" },
    "CNT": { "type": "ACTION", "values": { "FileName": "c.stx", "ActName": "Count", "Trigger": true } }
} }"#;

struct Bare(Strategy);

impl Driver for Bare {
    fn strategy(&self) -> &Strategy {
        &self.0
    }
    fn strategy_mut(&mut self) -> &mut Strategy {
        &mut self.0
    }
    fn command(&mut self, line: &str) -> Vec<Result<String, (String, String)>> {
        vec![Err(("C0000".into(), format!("no console here: {line}")))]
    }
}

fn strategy(action: &str) -> Strategy {
    let db = Database::from_json(DB).expect("db");
    let obj = linc_runtime::load(&compile(action, &db)).expect("load");
    let store = Store::new(db);
    let want = Want {
        block: store.db.block("CNT").unwrap(),
        file: "c.stx".into(),
        action: "Count".into(),
        kind: WantKind::Action,
    };
    Strategy::build(store, vec![obj], &[(want, 0)], Vm::new(100_000, Clock::new(1, 0)), 0.0).expect("build")
}

const COUNT: &str = "ACTION Count\n    REC.N0 := REC.N0 + 1;\nEND_ACTION\n";

fn expect(s: &Strategy, line: u32, check: Check, text: &str) -> Step {
    let obj = linc_compiler::compile_expectation(text, &s.store.db, &s.step_names()).expect("compiles");
    Step::Expect { line, check, text: text.into(), object: linc_runtime::verify::verify(obj).expect("verifies") }
}

fn go(action: &str, steps: impl FnOnce(&Strategy) -> Vec<Step>) -> Report {
    let s = strategy(action);
    let steps = steps(&s);
    run(&mut Bare(s), steps, &["REC.N0".to_string()])
}

fn failed_at(r: &Report) -> Vec<(u32, u64)> {
    r.failures.iter().map(|f| (f.line, f.at_us)).collect()
}

#[test]
fn within_passes_at_the_first_scan_that_holds_and_fails_at_its_deadline() {
    // After the scan at t, N0 = t / 100 ms + 1; it is checked at t + 100 ms.
    let r = go(COUNT, |s| {
        vec![expect(s, 1, Check::Within(1_000_000), "REC.N0 >= 10"), Step::Run { line: 2, for_us: 2_000_000 }]
    });
    assert!(r.failures.is_empty(), "{:?}", r.failures);
    let r = go(COUNT, |s| {
        vec![expect(s, 1, Check::Within(1_000_000), "REC.N0 >= 11"), Step::Run { line: 2, for_us: 2_000_000 }]
    });
    assert_eq!(failed_at(&r), [(1, 1_000_000)]);
    assert_eq!(r.failures[0].values, [("REC.N0".to_string(), "10".to_string())]);
}

#[test]
fn after_is_checked_once_at_its_time() {
    let r = go(COUNT, |s| {
        vec![expect(s, 1, Check::After(500_000), "REC.N0 = 5"), Step::Run { line: 2, for_us: 2_000_000 }]
    });
    assert!(r.failures.is_empty(), "{:?}", r.failures);
    let r = go(COUNT, |s| {
        vec![expect(s, 1, Check::After(500_000), "REC.N0 = 6"), Step::Run { line: 2, for_us: 2_000_000 }]
    });
    assert_eq!(failed_at(&r), [(1, 500_000)]);
}

#[test]
fn always_and_never_hold_at_every_scan_until_the_end() {
    let r = go(COUNT, |s| {
        vec![
            expect(s, 1, Check::Always, "REC.N0 < 25"),
            expect(s, 2, Check::Never, "REC.N0 = 30"),
            Step::Run { line: 3, for_us: 3_000_000 },
        ]
    });
    assert_eq!(failed_at(&r), [(1, 2_500_000), (2, 3_000_000)], "N0 reaches 25 after the scan at 2.4 s, 30 at 2.9 s");
    let r = go(COUNT, |s| vec![expect(s, 1, Check::Always, "REC.N0 < 100"), Step::Run { line: 2, for_us: 3_000_000 }]);
    assert!(r.failures.is_empty());
}

#[test]
fn undecided_expectations_run_to_their_deadline() {
    let r = go(COUNT, |s| vec![expect(s, 1, Check::Within(5_000_000), "REC.N0 = 40")]);
    assert!(r.failures.is_empty(), "{:?}", r.failures);
    assert_eq!(r.end_us, 4_000_000, "decided after the scan at 3.9 s that made it true");
    let r = go(COUNT, |s| vec![expect(s, 1, Check::After(2_000_000), "REC.N0 = 20")]);
    assert!(r.failures.is_empty(), "{:?}", r.failures);
    assert_eq!(r.end_us, 2_000_000);
}

#[test]
fn commands_at_times_and_their_errors() {
    let r = go(COUNT, |_| vec![Step::At { line: 4, at_us: 300_000, command: "M REC.N0=1".into() }]);
    assert_eq!(failed_at(&r), [(4, 300_000)]);
    assert!(r.failures[0].message.contains("was refused (C0000)"), "{}", r.failures[0].message);
    let r = go(COUNT, |_| {
        vec![Step::Run { line: 1, for_us: 1_000_000 }, Step::At { line: 2, at_us: 500_000, command: "NOW".into() }]
    });
    assert_eq!(failed_at(&r), [(2, 1_000_000)], "an `at` in the past fails");
}

#[test]
fn a_runtime_error_fails_the_scenario() {
    let divide = "ACTION Count\n    REC.N0 := REC.N0 + 1;\n    REC.N1 := 10 / (5 - REC.N0);\nEND_ACTION\n";
    let r = go(divide, |_| vec![Step::Run { line: 1, for_us: 1_000_000 }]);
    assert_eq!(r.failures.len(), 1, "{:?}", r.failures);
    assert!(r.failures[0].message.contains("runtime error R0001"), "{}", r.failures[0].message);
    assert_eq!(r.failures[0].at_us, 500_000, "the fifth scan divides by zero");
}

#[test]
fn samples_record_changes_for_the_vcd() {
    let r = go(COUNT, |_| vec![Step::Run { line: 1, for_us: 300_000 }]);
    let s = &r.samples;
    assert_eq!(s.names, ["REC.N0"]);
    let changes: Vec<(u64, &str)> = s.changes.iter().map(|(t, _, v)| (*t, v.as_str())).collect();
    assert_eq!(changes, [(0, "0"), (100_000, "1"), (200_000, "2"), (300_000, "3")]);
}

/// Setting up `n` expectations and deciding them at one scan: time linear
/// in `n` (each new expectation checked all the pending ones again, so
/// 20,000 `expect` lines took 22 s to start).
fn expectations(n: usize) -> std::time::Duration {
    let s = strategy(COUNT);
    let object = |text: &str| expect(&s, 0, Check::Always, text);
    let mut steps: Vec<Step> = (0..n)
        .map(|i| {
            let Step::Expect { object, text, .. } = object(&format!("REC.N0 >= {}", -(i as i64))) else {
                unreachable!()
            };
            Step::Expect {
                line: i as u32 + 1,
                check: if i % 2 == 0 { Check::Always } else { Check::Within(1) },
                text,
                object,
            }
        })
        .collect();
    steps.push(Step::Run { line: 0, for_us: 100_000 });
    let mut driver = Bare(s);
    // The runner's work on this thread, in processor time (how busy the
    // machine is does not count).
    let (r, took) = linc_test_support::work::thread_cpu(|| run(&mut driver, steps, &[]));
    assert!(r.failures.is_empty(), "{:?}", r.failures.first());
    took
}

#[test]
fn expectations_are_set_up_in_linear_time() {
    let r = linc_test_support::work::growth(|big| expectations(if big { 4_000 } else { 1_000 }));
    assert!(r < 7.0, "4x the expectations took {r:.1}x the work");
}

/// Runs the scenario against the real console, whose ADVANCE and SCAN
/// commands run the strategy.
fn go_console(action: &str, steps: impl FnOnce(&Strategy) -> Vec<Step>) -> Report {
    let s = strategy(action);
    let steps = steps(&s);
    run(&mut linc_engines::console::Console::new(s), steps, &["REC.N0".to_string()])
}

#[test]
fn expectations_are_checked_at_every_scan_a_console_advance_runs() {
    // `at 0s ADVANCE 1h`: N0 passes 5 in the first half second of the
    // hour; `never` fails at that scan, not after the hour (it used to be
    // checked only when the ADVANCE had finished, and passed).
    let r = go_console(COUNT, |s| {
        vec![expect(s, 1, Check::Never, "REC.N0 = 5"), Step::At { line: 2, at_us: 0, command: "ADVANCE 1h".into() }]
    });
    assert_eq!(failed_at(&r), [(1, 500_000)]);
    assert_eq!(r.end_us, 3_600_000_000);
    // `within` is decided at the first scan that holds during the ADVANCE.
    let r = go_console(COUNT, |s| {
        vec![
            expect(s, 1, Check::Within(1_000_000), "REC.N0 >= 10"),
            expect(s, 2, Check::Always, "REC.N0 < 30"),
            Step::At { line: 3, at_us: 0, command: "NOW; ADVANCE 5s; SCAN".into() },
        ]
    });
    assert_eq!(failed_at(&r), [(2, 3_000_000)], "{:?}", r.failures);
    assert_eq!(r.end_us, 5_100_000, "ADVANCE 5s then one 100 ms SCAN");
    // Every scan is sampled for the VCD, as between lines.
    assert_eq!(r.samples.changes.len(), 52, "the start and 51 scans");
    // An ADVANCE that does not parse is refused, located at its line.
    let r = go_console(COUNT, |_| vec![Step::At { line: 4, at_us: 0, command: "ADVANCE never".into() }]);
    assert_eq!(failed_at(&r), [(4, 0)]);
    assert!(r.failures[0].message.contains("C0008"), "{}", r.failures[0].message);
}

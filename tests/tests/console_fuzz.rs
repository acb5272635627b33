//! Hostile input for the console and scenario files: random and mutated
//! command lines against a running strategy, and random scenario texts
//! through the reader. Nothing may panic; every refusal is a coded error
//! (`C…` for the console, `E05…` for scenario lines).

use linc_conformance::exec::compile;
use linc_conformance::rng::Rng;
use linc_engines::console::Console;
use linc_engines::strategy::{Strategy, Want, WantKind};
use linc_runtime::vm::{Clock, Vm};
use linc_runtime::{Database, Store};

const DB: &str = r#"{ "blocks": {
    "REC": { "type": "RECIPE" }, "PID1": { "type": "PID" }, "DIG": { "type": "DIGOUT" },
    "W": { "type": "WIDESTR" }, "T": { "type": "TIMEDATE" },
    "CNT": { "type": "ACTION", "values": { "FileName": "c.stx", "ActName": "Count", "Trigger": true } }
} }"#;

const ACTION: &str = "ACTION Count\n    REC.N0 := REC.N0 + 1;\n    REC.A0 := REC.A0 + 0.5;\n    DIG.Out.Bit1 := NOT DIG.Out.Bit1;\nEND_ACTION\n";

/// Pieces commands are made of.
const WORDS: &[&str] = &[
    "D",
    "M",
    "F",
    "F?",
    "P?",
    "START",
    "STOP",
    "PSTOP",
    "SUSPEND",
    "RESET",
    "HOLD",
    "RUN",
    "HOLDSTEP",
    "RELEASESTEP",
    "FORCETRANS",
    "ADVANCE",
    "SCAN",
    "NOW",
    "ERR?",
    "ERRCLR",
    "ERRRAISE",
    "SAVE",
    "DISPLAY",
    "MODIFY",
    "FORCE",
    "OFF",
    "REC.A0",
    "REC.A0-",
    "REC.N0",
    "REC.N7-",
    "PID1.Mode",
    "PID1.SP",
    "DIG.Out",
    "DIG.Out.Bit3",
    "W.VAL1",
    "T.Date1",
    "CNT",
    "CNT.Active",
    "=",
    "=N",
    "=1",
    "=-5",
    "=1e39",
    "='a;b'",
    "='$N'",
    "=AUTO",
    "100ms",
    "1s",
    "T#2.5s",
    "0s",
    "-1s",
    "€5s",
    "R0001",
    "R9999",
    ";",
    ",",
    " ",
    "  ",
    "\"",
    "'",
    "é",
    "\u{1b}[31m",
    "(*",
    "*)",
    "18446744073709551616",
    "Full",
    "Fill",
];

fn strategy() -> Strategy {
    let db = Database::from_json(DB).expect("db");
    let obj = linc_runtime::load(&compile(ACTION, &db)).expect("load");
    let store = Store::new(db);
    let block = store.db.block("CNT").expect("CNT");
    let want = Want { block, file: "c.stx".into(), action: "Count".into(), kind: WantKind::Action };
    Strategy::build(store, vec![obj], &[(want, 0)], Vm::new(100_000, Clock::new(1, 0)), 0.0).expect("build")
}

fn line(rng: &mut Rng) -> String {
    let n = 1 + rng.below(6);
    let mut s = String::new();
    for i in 0..n {
        if i > 0 && !rng.one_in(3) {
            s.push(' ');
        }
        s.push_str(WORDS[rng.below(WORDS.len())]);
    }
    s
}

#[test]
fn random_console_lines_never_panic_and_refusals_are_coded() {
    let mut console = Console::new(strategy());
    let (mut ok, mut refused) = (0u32, 0u32);
    for case in 0..20_000u64 {
        let mut rng = Rng::new(case);
        let text = line(&mut rng);
        // Keep simulated time bounded: long ADVANCEs are legal but slow.
        if text.contains("ADVANCE") && !(text.contains("100ms") || text.contains(" 1s")) {
            continue;
        }
        for reply in console.execute(&text) {
            match reply {
                Ok(_) => ok += 1,
                Err(e) => {
                    assert!(e.code.as_str().starts_with('C'), "{text:?} gave {e:?}");
                    refused += 1;
                }
            }
        }
        console.take_failures();
    }
    assert!(ok > 200 && refused > 1_000, "both kinds of outcome reached: {ok} ok, {refused} refused");
    // The console still works afterwards.
    let replies = console.execute("M REC.A7=1.5; D REC.A7");
    assert_eq!(replies.last(), Some(&Ok("REC.A7 = 1.5".to_string())), "{replies:?}");
}

#[test]
fn random_scenario_texts_never_panic() {
    const PIECES: &[&str] = &[
        "strategy p.json",
        "program x.sfc",
        "db d.json",
        "at",
        "expect",
        "within",
        "after",
        "always",
        "never",
        "run",
        "5s",
        "1h30m",
        "T#",
        "-1s",
        "€5s",
        "99999d",
        "M REC.A0=1",
        "REC.N0 > 3",
        "Fill.X AND",
        "(*",
        "*)",
        "#",
        "\n",
        "\r\n",
        " ",
        "é",
        "\u{0}",
    ];
    for case in 0..20_000u64 {
        let mut rng = Rng::new(case);
        let n = rng.below(40);
        let text: String = (0..n).map(|_| PIECES[rng.below(PIECES.len())]).collect::<Vec<_>>().join(" ");
        let (scenario, diagnostics) = linc_driver::scenarios::file::parse(&text);
        for d in &diagnostics {
            assert!(d.code.as_str().starts_with("E05"), "{d:?}");
            assert!(d.span.end <= text.len() && text.is_char_boundary(d.span.start), "{d:?} in {text:?}");
        }
        for l in &scenario.lines {
            if let linc_driver::scenarios::file::Action::Expect { span, .. } = &l.action {
                assert!(span.end <= text.len() && text.is_char_boundary(span.start) && text.is_char_boundary(span.end));
            }
        }
    }
}

//! Conformance cases for the FST front end (ROCLINK 800 appendix B): one
//! case per error and warning code, each a small table checked against a
//! ROC800 database, and the manual's own tables, which must check clean.
//! The snapshot pins the table and the rendered diagnostics; the case also
//! asserts the exact codes.

use linc_compiler::diag::render::{self, Format, SourceFiles};
use linc_compiler::fst::{check, reader, Checked, Cmd};
use linc_compiler::Diagnostic;
use linc_runtime::Database;

const DB: &str = r#"{"device": "ROC800", "blocks": {
    "FST 1": {"type": "FST"}, "SFP 1": {"type": "SFP"}, "AIN 3-1": {"type": "AIN"},
    "DOU 4-1": {"type": "DOU"}, "DOU 4-2": {"type": "DOU"}, "AOU 5-1": {"type": "AOU"},
    "HIST 9": {"type": "HIST", "values": {"ARCHTYP": "FSTDATA"}}}}"#;

const HEADER: &str = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2,COMMENT\n";

fn db() -> Database {
    Database::from_json(DB).unwrap_or_else(|e| panic!("test database: {e}"))
}

/// Reads and checks a table as `linc` does: the reader's diagnostics, then
/// the checker's. The checker gives a table exactly when it found no error;
/// one from the reader also stops the table here.
fn run(src: &str) -> (Option<Checked>, Vec<Diagnostic>) {
    let db = db();
    let (table, mut diagnostics) = reader::read(src);
    let (checked, more) = check::check(&table, Some(&db));
    let unknown_command = table.rows.iter().any(|r| Cmd::parse(&r.cmd.text).is_none());
    let clean = !unknown_command && !more.iter().any(Diagnostic::is_error);
    assert_eq!(checked.is_some(), clean, "checked exactly when clean");
    diagnostics.extend(more);
    let clean = !diagnostics.iter().any(Diagnostic::is_error);
    (checked.filter(|_| clean), diagnostics)
}

fn snapshot(section: &str, src: &str, diagnostics: &[Diagnostic]) -> String {
    let mut files = SourceFiles::new();
    let id = files.add("case.csv".to_string(), src.to_string());
    let mut out = format!("{section}\n--- source\n{src}--- diagnostics\n");
    if diagnostics.is_empty() {
        out.push_str("(none)\n");
    }
    for d in diagnostics {
        out.push_str(&render::render(&files, &d.clone().in_file(id), Format::Human));
    }
    out
}

/// A case: the rows after the header give exactly these codes, in order.
macro_rules! case {
    ($name:ident, $section:literal, $rows:expr, [$($code:literal),* $(,)?]) => {
        #[test]
        fn $name() {
            let src = format!("{HEADER}{}", $rows);
            let (checked, diagnostics) = run(&src);
            insta::assert_snapshot!(stringify!($name), snapshot($section, &src, &diagnostics));
            let codes: Vec<&str> = diagnostics.iter().map(|d| d.code.as_str()).collect();
            let expected: &[&str] = &[$($code),*];
            assert_eq!(codes, expected, "diagnostic codes");
            assert_eq!(checked.is_some(), expected.iter().all(|c| c.starts_with('W')));
        }
    };
}

#[test]
fn e0400_no_header() {
    let src = "0,,VAL,\"AIN 3-1,EU\",,\n1,,END,,,\n";
    let (checked, diagnostics) = run(src);
    insta::assert_snapshot!("e0400_no_header", snapshot("B.1: the header row", src, &diagnostics));
    assert_eq!(diagnostics.iter().map(|d| d.code.as_str()).collect::<Vec<_>>(), ["E0400"]);
    assert!(checked.is_none());
}

case!(e0401_unquoted_tlp, "RFC 4180: a cell with a comma is quoted", "0,,VAL,AIN 3-1,EU,,\n1,,END,,,\n", ["E0401"]);
case!(e0401_quote_not_closed, "RFC 4180: quotes close", "0,,MSG,\"Pump on,,\n1,,END,,,\n", ["E0401"]);
case!(
    e0402_step_gap,
    "B.1.1: steps count up from 0",
    "0,,VAL,\"SFP 1,DATA1\",,\n2,,SAV,\"SFP 1,DATA2\",,\n3,,END,,,\n",
    ["E0402"]
);
case!(e0403_unknown_command, "Table B-9: the commands", "0,,VALL,\"SFP 1,DATA1\",,\n1,,END,,,\n", ["E0403"]);
case!(
    w0400_rows_after_blank_command,
    "B.1.3: a blank command ends the program",
    "0,,VAL,\"SFP 1,DATA1\",,\n1,,,,,\n2,,SAV,\"SFP 1,DATA2\",,\n3,,END,,,\n",
    ["W0400"]
);
case!(e0404_label_too_long, "B.1.2: six alphanumeric characters", "0,PUMP_ON,DO,DOU 4-1,1,\n1,,END,,,\n", ["E0404"]);
case!(e0405_label_is_a_command, "B.1.2: no command names as labels", "0,END,VAL,1,,\n1,,END,,,\n", ["E0405"]);
case!(
    e0406_label_twice,
    "B.1.2: labels identify one step",
    "0,LOOP,VAL,\"SFP 1,DATA1\",,\n1,LOOP,SAV,\"SFP 1,DATA2\",,\n2,,GO,LOOP,,\n",
    ["E0406"]
);
case!(
    e0407_unknown_label,
    "B.1.2: branching to a label (Table B-4, misspelt)",
    "0,,GO,PMPOF,,\n1,PUMPON,DO,DOU 4-1,1,\n2,PMPOFF,DO,DOU 4-2,0,\n",
    ["E0407"]
);
case!(
    e0408_second_end,
    "Table B-9: END",
    "0,,VAL,\"SFP 1,DATA1\",,\n1,,>,10,HIGH,\n2,,END,,,\n3,HIGH,DO,DOU 4-1,1,\n4,,END,,,\n",
    ["E0408"]
);
case!(
    e0409_argument_not_used,
    "Table B-9: VAL takes one argument",
    "0,,VAL,\"SFP 1,DATA1\",5,\n1,,END,,,\n",
    ["E0409"]
);
case!(e0410_missing_argument, "Table B-9: SAV needs its parameter", "0,,VAL,1,,\n1,,SAV,,,\n2,,END,,,\n", ["E0410"]);
case!(
    e0411_step_number_as_label,
    "B.1.2: branches go to labels",
    "0,,VAL,\"SFP 1,DATA1\",,\n1,,>=,50,3,\n2,,END,,,\n3,HIGH,DO,DOU 4-1,1,\n",
    ["E0411"]
);
case!(e0412_label_as_value, "B.1.4: arguments are values", "0,CHECK,VAL,CHECK,,\n1,,END,,,\n", ["E0412"]);
case!(e0413_save_to_constant, "Table B-9: SAV writes a parameter", "0,,VAL,1,,\n1,,SAV,3,,\n2,,END,,,\n", ["E0413"]);
case!(e0414_text_parameter, "B.1.4: numeric parameters", "0,,VAL,\"AIN 3-1,UNITS\",,\n1,,END,,,\n", ["E0414"]);
case!(
    e0415_save_to_read_only,
    "Table B-9: SAV to a read-only parameter",
    "0,,VAL,1,,\n1,,SAV,\"AIN 3-1,ALARM\",,\n2,,END,,,\n",
    ["E0415"]
);
case!(e0416_timer_5, "Table B-9: four timers", "0,,ST,5,100,\n1,WAIT,CT,1,WAIT,\n2,,END,,,\n", ["E0416"]);
case!(e0417_wait_too_short, "Table B-9: WT 0.1 to 999,999 s", "0,,WT,0.05,,\n1,,END,,,\n", ["E0417"]);
case!(
    e0417_and_over_8_bits,
    "Table B-9: AND on 8 bits",
    "0,,VAL,\"FST 1,MISC1\",,\n1,,AND,256,,\n2,,END,,,\n",
    ["E0417"]
);
case!(e0418_day_month_swapped, "Table B-9: DIS month/day", "0,,DIS,9,2311,\n1,,END,,,\n", ["E0418"]);
case!(e0419_number_too_large, "B.1.4: constants are REAL", "0,,VAL,1e40,,\n1,,END,,,\n", ["E0419"]);
case!(e0420_empty_parameter, "B.1.4: TLP syntax", "0,,VAL,\"SFP 1,\",,\n1,,END,,,\n", ["E0420"]);
case!(e0421_unknown_point, "B.1.4: points of the database", "0,,VAL,\"SFP 2,DATA1\",,\n1,,END,,,\n", ["E0421"]);
case!(e0422_unknown_parameter, "B.1.4: parameters of a point", "0,,VAL,\"AIN 3-1,HIALM\",,\n1,,END,,,\n", ["E0422"]);
case!(e0423_no_default_parameter, "B.1.4: default parameters", "0,,VAL,SFP 1,,\n1,,END,,,\n", ["E0423"]);
case!(e0424_fb107_type_number, "numeric TLPs: ROC800 types", "0,,VAL,\"17,0,2\",,\n1,,END,,,\n", ["E0424"]);
case!(e0425_second_soft_point, "numeric TLPs: logical numbers", "0,,VAL,\"98,1,2\",,\n1,,END,,,\n", ["E0425"]);
case!(e0426_parameter_40, "numeric TLPs: parameter numbers", "0,,VAL,\"98,0,40\",,\n1,,END,,,\n", ["E0426"]);
case!(e0427_do_on_an_input, "Table B-9: DO drives a DOU", "0,,DO,\"AIN 3-1\",1,\n1,,END,,,\n", ["E0427"]);
case!(
    w0401_alarm_text_cut,
    "Table B-9: ALM keeps 10 characters",
    "0,,ALM,High level alarm,\"AIN 3-1\",\n1,,END,,,\n",
    ["W0401"]
);

/// Checks a table that must be clean and returns its steps' arguments.
fn clean(src: &str) -> Checked {
    let (checked, diagnostics) = run(src);
    assert!(diagnostics.is_empty(), "{diagnostics:?}");
    checked.expect("a clean table is checked")
}

#[test]
fn the_manuals_tables_check_clean() {
    use linc_compiler::fst::Arg;
    let b4 = clean(&format!("{HEADER}0,,GO,PMPOFF,,\n1,PUMPON,DO,DOU 4-1,1,\n2,PMPOFF,DO,DOU 4-2,0,\n"));
    assert_eq!(b4.steps[0].arg1, Arg::Label(2));
    assert_eq!(b4.steps.last().map(|s| s.cmd), Some(Cmd::End));
    let b6 = clean(&format!(
        "{HEADER}0,CKHIAL,VAL,\"AIN 3-1,EU\",,\n1,,>=,\"AIN 3-1,HIAL\",PUMPON,\n2,,END,,,\n3,PUMPON,DO,DOU 4-1,1,turn the pump on\n"
    ));
    assert_eq!(b6.steps[1].arg2, Arg::Label(3));
    let b5 = clean(&format!(
        "{HEADER}0,,VAL,\"SFP 1,DATA1\",,\n1,,WDB,9,\"FST 1,R3\",\n2,,WTM,10,\"FST 1,R4\",\n3,,WT,5,,\n4,,END,,,\n"
    ));
    assert_eq!(b5.steps.len(), 5);
    assert_eq!(b5.steps[3].arg1, Arg::Const(5.0));
}

/// Every FST page's examples do what the page says: the Right table checks
/// clean, the Wrong one gives the page's code.
#[test]
fn the_explanations_examples_hold() {
    let fst_codes = linc_compiler::diag::codes::CODES.iter().filter(|c| c.as_str()[1..].starts_with("04"));
    let mut pages = 0;
    for code in fst_codes {
        let blocks: Vec<&str> =
            code.explanation().split("```csv\n").skip(1).filter_map(|b| b.split("```").next()).collect();
        let [wrong, right] = blocks[..] else { panic!("{code}: one Wrong and one Right table") };
        let (_, d) = run(right);
        assert!(d.is_empty(), "{code} Right: {d:?}");
        assert!(translated(code.as_str(), right).is_empty(), "{code} Right does not translate");
        let (_, mut d) = run(wrong);
        d.extend(translated(code.as_str(), wrong));
        assert!(d.iter().any(|d| d.code == *code), "{code} Wrong gives {d:?}");
        pages += 1;
    }
    assert_eq!(pages, 35);
}

/// The refusals of the translation a page is about (E0430–E0434: E0434 is
/// `to-sfc`'s, the others `to-st`'s); none for the front end's own codes.
fn translated(code: &str, src: &str) -> Vec<Diagnostic> {
    let Some(kind) = ["E0430", "E0431", "E0432", "E0433", "E0434"].iter().position(|c| *c == code) else {
        return Vec::new();
    };
    let (table, _) = reader::read(src);
    let Some(checked) = run(src).0 else { return Vec::new() };
    let result = if kind == 4 {
        let target = linc_compiler::fst::translate::SfcTarget { block: "FST 1", steps_per_cycle: 20, exit: None };
        linc_compiler::fst::translate::to_sfc(&table, &checked, &target)
    } else {
        let target = linc_compiler::fst::translate::Target { block: "FST 1", steps_per_cycle: 20, action: "T" };
        linc_compiler::fst::translate::to_st(&table, &checked, &target)
    };
    result.err().unwrap_or_default()
}

/// Tables made of random pieces of real ones (quotes, delimiters, line
/// ends, commands, TLPs, non-ASCII text) never panic the reader, the
/// checker or the listing, and every diagnostic points inside the text, on
/// character boundaries, so that it renders.
#[test]
fn random_tables_are_read_and_checked_without_panics() {
    use linc_conformance::rng::Rng;
    const PIECES: &[&str] = &[
        ",",
        ",",
        ",",
        ";",
        "\n",
        "\r\n",
        "\"",
        "\"\"",
        " ",
        "0",
        "1",
        "2",
        "17,0,2",
        "98,0,2",
        "VAL",
        "SAV",
        "GO",
        "END",
        "ST",
        "CT",
        "WDB",
        "DIS",
        "MSG",
        ">=",
        "LOOP",
        "PMPOFF",
        "AIN 3-1,EU",
        "\"SFP 1,DATA1\"",
        "DOU 4-1",
        "FST 1,TMR1",
        "1e39",
        "-3.5",
        "é",
        "€uro",
        "\u{feff}",
        "STEP",
        "LABEL,CMD,ARGUMENT1,ARGUMENT2",
    ];
    let db = db();
    let mut rng = Rng::new(0x05ee_df57);
    for round in 0..3000 {
        let mut src = if round % 2 == 0 { HEADER.to_string() } else { String::new() };
        for _ in 0..rng.below(60) {
            src.push_str(PIECES[rng.below(PIECES.len())]);
        }
        let (table, mut diagnostics) = reader::read(&src);
        let (checked, more) = check::check(&table, Some(&db));
        diagnostics.extend(more);
        let _ = linc_compiler::fst::list::listing(&table, None);
        if let Some(c) = checked {
            assert_eq!(c.steps.last().map(|s| s.cmd), Some(Cmd::End), "{src:?}");
        }
        for d in &diagnostics {
            for span in std::iter::once(d.span).chain(d.secondary.iter().map(|l| l.span)) {
                assert!(span.start <= span.end && span.end <= src.len(), "{src:?}: {d:?}");
                assert!(src.is_char_boundary(span.start) && src.is_char_boundary(span.end), "{src:?}: {d:?}");
            }
        }
        let _ = snapshot("random", &src, &diagnostics);
    }
}

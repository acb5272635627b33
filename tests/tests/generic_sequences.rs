//! Generic sequences (guide §9.1.4): the three levels of mapping against the
//! guide's database, diagnostics located in the `.sfc` text, and the text
//! rewrites that keep comments and layout.
use linc_compiler::sfc::generic::{bind, generalise, generic_names, parse_map, specialise, Named};
use linc_compiler::sfc::{check_generic, parser};
use linc_compiler::Context;
use linc_conformance::guide_db;

const MAP: &str = r#"{
  "KilnController": "TIC_100",
  "TempHiFlag": "Dig_A.Out",
  "PressureAlarm": "PIC_004.Alarms.HighAbs",
  "HeatSP": "Setpoint"
}"#;

const GENERIC: &str = "(* kiln *)
INITIAL_STEP Run: Act(N); END_STEP
ACTION Act
    KilnController.SL := 50.0;   (* block *)
    TempHiFlag.Bit3 := PressureAlarm;  (* block.field, block.field.subfield *)
    HeatSP := KilnController.PV;
END_ACTION
";

const SPECIFIC: &str = "(* kiln *)
INITIAL_STEP Run: Act(N); END_STEP
ACTION Act
    TIC_100.SL := 50.0;   (* block *)
    Dig_A.Out.Bit3 := PIC_004.Alarms.HighAbs;  (* block.field, block.field.subfield *)
    Setpoint := TIC_100.PV;
END_ACTION
";

fn codes(src: &str) -> Vec<(&'static str, String)> {
    let (map, errors) = parse_map(MAP);
    assert!(errors.is_empty(), "{errors:?}");
    let (db, errors) = bind(&map, guide_db(), true);
    assert!(errors.is_empty(), "{errors:?}");
    let named = Named { map, file: "kiln.map.json".into() };
    let report = check_generic(src, Context::of(Some(&db)), &named, false);
    report.diagnostics.iter().map(|d| (d.code.as_str(), src[d.span.start..d.span.end].to_string())).collect()
}

#[test]
fn all_three_levels_resolve_through_the_map() {
    assert_eq!(codes(GENERIC), []);
}

#[test]
fn errors_point_at_the_generic_names_in_the_sequence() {
    let src = GENERIC.replace("Bit3", "Bit19").replace("HeatSP := ", "PressureAlarm := ");
    let got = codes(&src);
    let kinds: Vec<(&str, &str)> = got.iter().map(|(c, t)| (*c, t.as_str())).collect();
    assert_eq!(kinds, [("E0102", "Bit19"), ("E0108", "PressureAlarm")], "{got:?}");
}

#[test]
fn a_name_the_map_lacks_is_e0250() {
    let src = GENERIC.replace("HeatSP := ", "CoolSP := ").replace("PressureAlarm;", "PressureAlarmFlag;");
    // A 17-character name is too long even for a generic name (E0005).
    let got = codes(&src);
    assert_eq!(got, [("E0005", "PressureAlarmFlag".to_string()), ("E0250", "CoolSP".to_string())]);
}

#[test]
fn specialise_and_generalise_keep_comments_and_layout() {
    let (map, _) = parse_map(MAP);
    let (seq, _) = parser::parse(GENERIC);
    assert_eq!(specialise(GENERIC, &seq, &map), SPECIFIC);
    let (seq, _) = parser::parse(SPECIFIC);
    // `Setpoint` is an alias of the database: the map entry names it as written.
    assert_eq!(generalise(SPECIFIC, &seq, &map), GENERIC);
}

#[test]
fn generic_names_leave_out_blocks_aliases_and_steps() {
    let src = "INITIAL_STEP Run: Act(N); END_STEP
ACTION Act
    Kiln.SL := Run.T + TIC_100.PV + Setpoint + Other.A;
    Kiln.PV := 1.0;
END_ACTION
";
    let (seq, _) = parser::parse(src);
    assert_eq!(generic_names(&seq, guide_db()), ["Kiln", "Other"]);
}

#[test]
fn a_step_named_like_a_generic_name_is_e0255() {
    let src = GENERIC.replace("Run", "HeatSP");
    assert_eq!(codes(&src), [("E0255", "HeatSP".to_string())]);
}

/// A map file's errors are worded as the map file's (they said "the
/// database is not valid JSON"), and point into it, an empty one too.
#[test]
fn map_file_errors_name_the_map_file() {
    let cases = [
        ("{ \"Reactor\": R1 }", "the map file is not valid JSON: expected a value", (13, 14)),
        ("", "the map file is not valid JSON: the text ends where a value should be", (0, 0)),
        ("{\"a\": \"R1\"} x", "the map file is not valid JSON: unexpected text after the end of the value", (12, 13)),
        ("{\"A\": \"R1\", \"A\": \"R2\"}", "key `A` appears twice in one JSON object", (12, 15)),
    ];
    for (text, message, (start, end)) in cases {
        let (map, errors) = parse_map(text);
        assert!(map.entries().is_empty(), "{text:?}");
        let d: Vec<_> = errors.iter().map(|e| e.to_diagnostic()).collect();
        assert_eq!(d.len(), 1, "{text:?}: {d:?}");
        assert_eq!(d[0].code, "E0251");
        assert!(d[0].message.starts_with(message), "{text:?}: {}", d[0].message);
        assert!(!d[0].message.contains("database"), "{}", d[0].message);
        assert_eq!((d[0].span.start, d[0].span.end), (start, end), "{text:?}");
    }
}

//! The run-time rules of the issue and the guide, one test each.
use linc_conformance::exec::{run, run_in};
use linc_runtime::Database;

fn db(json: &str) -> Database {
    Database::from_json(json).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn guide_shift_register() {
    let r = run("FOR TC001:=0 to 6 DO (*Analogue shift register*)\n   Block_5.Val1{TC001}:=Block_5.Val1{TC001 + 1};\nEND_FOR;\nBlock_5.Val1{7}:=50;\n");
    assert_eq!(r.error, None);
    let vals: Vec<String> = (1..=8).map(|i| r.get(&format!("Block_5.Val{i}"))).collect();
    assert_eq!(vals, ["2.0", "3.0", "4.0", "5.0", "6.0", "7.0", "8.0", "50.0"]);
}

const ARRAY_DB: &str = r#"{
  "templates": { "ARR": { "fields": { "V0": "REAL", "V1": "REAL", "V2": "REAL", "V3": "REAL", "V4": "REAL", "V5": "REAL",
                                      "V6": "REAL", "V7": "REAL", "V8": "REAL", "V9": "REAL", "V10": "REAL", "V11": "REAL" } } },
  "blocks": { "Arr": { "type": "ARR", "values": { "V0": 1, "V1": 2, "V2": 3, "V3": 4, "V4": 5, "V5": 6, "V6": 7, "V7": 8, "V8": 9, "V9": 10, "V10": 11 } },
              "Res": { "type": "RECIPE" },
              "PIC_004": { "type": "PID" } },
  "aliases": { "f": "Arr.V0", "avg": "Res.A0" }
}"#;

#[test]
fn guide_for_averaging_loop() {
    // 0 TO 10 BY 2 visits offsets 0, 2, 4, 6, 8, 10: six values (the guide
    // says "five times"; its loop runs six), then divides by 5 as written.
    let src = "avg:=0;\nFOR PIC_004.PV := 0 TO 10 BY 2 DO\navg := avg+f[PIC_004.PV]; (* offset value *)\nEND_FOR;\navg:=avg/5;\n";
    let r = run_in(&db(ARRAY_DB), src, 1, 1.0);
    assert_eq!(r.error, None);
    assert_eq!(r.get("Res.A0"), "7.2"); // (1+3+5+7+9+11)/5
    assert_eq!(r.get("PIC_004.PV"), "12.0");
}

#[test]
fn guide_while_averaging_loop() {
    let src = "avg:=0;\nPIC_004.PV := 0;\nWHILE PIC_004.PV<5 DO\navg := avg+f[PIC_004.PV];\nPIC_004.PV := PIC_004.PV+1;\nEND_WHILE;\navg:=avg/5;\n";
    let r = run_in(&db(ARRAY_DB), src, 1, 1.0);
    assert_eq!(r.error, None);
    assert_eq!(r.get("Res.A0"), "3.0"); // (1+2+3+4+5)/5
}

#[test]
fn guide_bitfield_assignments() {
    let r = run("Dig_A.Out:=96;\nDig_B.Out.Bit0:=1;\nRecipe.N0 := Dig_B.Out XOR 96;\nSEQ4.Hold:=(PIC_005.PV > 30) AND Dig_B.Out.Bit5;\n");
    assert_eq!(r.error, None);
    assert_eq!(r.get("Dig_A.Out"), "96");
    assert_eq!(
        (r.get("Dig_A.Out.Bit5"), r.get("Dig_A.Out.Bit6"), r.get("Dig_A.Out.Bit7")),
        ("1".into(), "1".into(), "0".into())
    );
    assert_eq!(r.get("Dig_B.Out"), "33");
    assert_eq!(r.get("Recipe.N0"), "65"); // 33 XOR 96
    assert_eq!(r.get("SEQ4.Hold"), "TRUE");
}

#[test]
fn bitfields_keep_their_low_bits_and_read_in_range() {
    let r = run("Dig_A.Out := 300;\n[DG_CONN3.W Field1] := 16#FFFF;\nRecipe.N0 := [DG_CONN3.W Field1];\n");
    assert_eq!(r.error, None);
    assert_eq!(r.get("Dig_A.Out"), "44"); // 300 AND 255
    assert_eq!(r.get("Recipe.N0"), "-1"); // 16-bit fields read -32768..32767
}

#[test]
fn guide_string_to_mode_ignores_case() {
    let r = run("PIC_004.Mode:=\"CASCADE\";\npid1.mode:=\"manual\";\n");
    assert_eq!(r.error, None);
    assert_eq!(r.get("PIC_004.Mode"), "'CASCADE'");
    assert_eq!(r.get("pid1.Mode"), "'MANUAL'");
}

#[test]
fn guide_dollar_conversions_into_bseq_wstr_but_not_string() {
    let r = run("RAW_COM.Buffer1:=\"a$62c\";\nWIDESTR2.VAL1:=\"r$F4le\";\nSFC_CON.FileName:=\"a$62c\";\n");
    assert_eq!(r.error, None);
    assert_eq!(r.get("RAW_COM.Buffer1"), "'abc'");
    assert_eq!(r.get("WIDESTR2.VAL1"), "'r$F4le'"); // the byte F4, printed escaped
    assert_eq!(r.get("SFC_CON.FileName"), "'a$$62c'"); // kept as written: a $ 6 2 c
}

#[test]
fn string_field_assigned_to_bseq_is_decoded_but_function_results_are_not() {
    let r = run(
        "SFC_CON.FileName := 'x$41';\nRAW_COM.Buffer1 := SFC_CON.FileName;\nRAW_COM.Buffer2 := CONCAT('$24', '41');\n",
    );
    assert_eq!(r.error, None);
    assert_eq!(r.get("RAW_COM.Buffer1"), "'xA'");
    assert_eq!(r.get("RAW_COM.Buffer2"), "'$$41'"); // CONCAT gave the bytes $ 4 1; not decoded again
}

#[test]
fn integer_arithmetic_stays_integer_and_truncates() {
    let r = run("Recipe.N0 := 7 / 2;\nRecipe.N1 := -7 / 2;\nRecipe.N2 := 7 MOD 3;\nRecipe.A0 := 7 / 2;\nRecipe.A1 := 7 / 2.0;\nRecipe.N3 := 2147483647 + Recipe.N7 + 1;\n");
    assert_eq!(r.error, None);
    assert_eq!([r.get("Recipe.N0"), r.get("Recipe.N1"), r.get("Recipe.N2")], ["3", "-3", "1"]);
    assert_eq!([r.get("Recipe.A0"), r.get("Recipe.A1")], ["3.0", "3.5"]);
    assert_eq!(r.get("Recipe.N3"), "-2147483648"); // 32-bit wrap
}

#[test]
fn real_into_integer_rounds_half_away_from_zero() {
    let r = run(
        "Recipe.N0 := 2.5;\nRecipe.N1 := -2.5;\nRecipe.N2 := 1.4999;\nRecipe.N3 := Recipe.A7 + 0.5;\nRecipe.A0 := 3;\n",
    );
    assert_eq!(r.error, None);
    assert_eq!([r.get("Recipe.N0"), r.get("Recipe.N1"), r.get("Recipe.N2"), r.get("Recipe.N3")], ["3", "-3", "1", "1"]);
    assert_eq!(r.get("Recipe.A0"), "3.0");
}

#[test]
fn and_or_xor_are_16_bit_on_integers_and_logical_on_booleans() {
    let r = run("Recipe.N0 := Recipe.N7 + 16#1FFFF AND 16#FFFF;\nRecipe.N1 := 5 OR 2;\nRecipe.N2 := 6 XOR 3;\nRecipe.N3 := Recipe.N7 + 16#10001 AND 16#10003;\nDig_A.Out.Bit0 := TRUE AND FALSE;\nDig_A.Out.Bit1 := TRUE XOR FALSE;\nDig_A.Out.Bit2 := NOT 5;\n");
    assert_eq!(r.error, None);
    assert_eq!([r.get("Recipe.N0"), r.get("Recipe.N1"), r.get("Recipe.N2"), r.get("Recipe.N3")], ["-1", "7", "5", "1"]);
    assert_eq!([r.get("Dig_A.Out.Bit0"), r.get("Dig_A.Out.Bit1"), r.get("Dig_A.Out.Bit2")], ["0", "1", "0"]);
}

#[test]
fn integer_conditions_and_time_constants() {
    let r = run("IF Recipe.N7 + 2 THEN Recipe.N0 := 1; END_IF;\nIF Recipe.N7 THEN Recipe.N1 := 1; END_IF;\nRecipe.A0 := T#1h;\nRecipe.A1 := T#1d12.2h;\nRecipe.A2 := T#4m13.0s;\n");
    assert_eq!(r.error, None);
    assert_eq!([r.get("Recipe.N0"), r.get("Recipe.N1")], ["1", "0"]);
    assert_eq!([r.get("Recipe.A0"), r.get("Recipe.A1"), r.get("Recipe.A2")], ["3600.0", "130320.0", "253.0"]);
}

#[test]
fn string_comparisons() {
    let r = run("SFC_CON.FileName := 'abc';\nDig_A.Out.Bit0 := SFC_CON.FileName = 'ABC';\nDig_A.Out.Bit1 := SFC_CON.FileName <> 'ABC';\nDig_A.Out.Bit2 := EQUAL(SFC_CON.FileName, 'ABC');\nDig_A.Out.Bit3 := 'aa' < SFC_CON.FileName;\nDig_A.Out.Bit4 := 'ab' > 'aaa';\nDig_A.Out.Bit5 := 'aa' >= 'aaa';\n");
    assert_eq!(r.error, None);
    let bits: Vec<String> = (0..6).map(|i| r.get(&format!("Dig_A.Out.Bit{i}"))).collect();
    assert_eq!(bits, ["1", "1", "0", "1", "1", "0"]);
}

#[test]
fn unknown_enum_name_at_run_time_is_an_error_and_earlier_writes_stay() {
    let r = run("SFC_CON.FileName := 'BOGUS';\nPIC_004.Mode := SFC_CON.FileName;\nRecipe.N0 := 1;\n");
    assert_eq!(r.code(), Some("R0004"));
    let e = r.error.as_ref().map(|e| (e.line, e.col, e.action.clone(), e.file.clone()));
    assert_eq!(e, Some((2, 1, "test".to_string(), "test.st".to_string())));
    assert_eq!(r.get("SFC_CON.FileName"), "'BOGUS'");
    assert_eq!(r.get("PIC_004.Mode"), "'MANUAL'");
    assert_eq!(r.get("Recipe.N0"), "0");
}

#[test]
fn offsets_walk_template_order_and_real_offsets_round() {
    let r = run("Block_5.Val1{2.5} := 9;\nCounters.N0 := 3;\nDig_A.Out := 0;\nDig_A.Out.Bit0{Counters.N0} := 1;\nDig_A.Out{1}.Bit1 := 1;\nRecipe.A0 := Block_5.PV{8};\n");
    assert_eq!(r.error, None);
    assert_eq!(r.get("Block_5.Val4"), "9.0");
    assert_eq!(r.get("Dig_A.Out"), "8");
    assert_eq!(r.get("Dig_A.In"), "2");
    assert_eq!(r.get("Recipe.A0"), "8.0");
}

#[test]
fn leaving_the_run_is_a_runtime_error() {
    let r = run("Counters.N0 := 8;\nBlock_5.Val1{Counters.N0} := 1;\n");
    assert_eq!(r.code(), Some("R0003"));
    let r = run("Counters.N0 := 8;\nDig_A.Out.Bit0{Counters.N0} := 1;\n");
    assert_eq!(r.code(), Some("R0003"));
    let r = run("Counters.N0 := -1;\nRecipe.A0 := Block_5.Val2{Counters.N0};\n");
    assert_eq!(r.code(), Some("R0003"));
}

#[test]
fn for_index_may_be_any_numeric_field_and_keeps_its_value_on_exit() {
    let r = run("FOR PIC_004.PV := 0 TO 10 BY 2.5 DO Counters.N0 := Counters.N0 + 1; END_FOR;\nFOR Counters.N1 := 1 TO 10 DO IF Counters.N1 = 4 THEN EXIT; END_IF; END_FOR;\nFOR Counters.N2 := 1 TO 3 DO END_FOR;\nFOR Counters.N3 := 3 TO 1 BY -1 DO Counters.N4 := Counters.N4 + 1; END_FOR;\n");
    assert_eq!(r.error, None);
    assert_eq!([r.get("Counters.N0"), r.get("PIC_004.PV")], ["5", "12.5"]);
    assert_eq!(
        [r.get("Counters.N1"), r.get("Counters.N2"), r.get("Counters.N3"), r.get("Counters.N4")],
        ["4", "4", "0", "3"]
    );
}

#[test]
fn suppress_sets_clips_and_counts_down() {
    let r = run("ANIN_005.Alarms.HiLevel.Suppress := 3600;\nRecipe.N0 := ANIN_005.Alarms.HiLevel.Suppress;\nANIN_005.Alarms.LoLevel.Suppress := 10000000;\nRecipe.N1 := ANIN_005.Alarms.LoLevel.Suppress;\nANIN_005.Alarms.Suppress := -1;\nRecipe.N2 := ANIN_005.Alarms.Suppress;\nANIN_005.Alarms.HiHi.Suppress := 50;\nANIN_005.Alarms.HiHi.Suppress := -5;\nRecipe.N3 := ANIN_005.Alarms.HiHi.Suppress;\n");
    assert_eq!(r.error, None);
    assert_eq!(
        [r.get("Recipe.N0"), r.get("Recipe.N1"), r.get("Recipe.N2"), r.get("Recipe.N3")],
        ["3600", "7776000", "-1", "50"]
    );
    let src = "IF Counters.N0 = 0 THEN ANIN_005.Alarms.HiLevel.Suppress := 100; END_IF;\nCounters.N0 := Counters.N0 + 1;\nCounters.N1 := ANIN_005.Alarms.HiLevel.Suppress;\n";
    let r = run_in(linc_conformance::guide_db(), src, 3, 10.0);
    assert_eq!([r.get("Counters.N0"), r.get("Counters.N1")], ["3", "80"]);
}

#[test]
fn runtime_errors_stop_at_the_failing_statement() {
    let r = run("Counters.N0 := 1;\nCounters.N1 := 1 / Counters.N5;\nCounters.N2 := 1;\n");
    assert_eq!(r.code(), Some("R0001"));
    assert_eq!([r.get("Counters.N0"), r.get("Counters.N2")], ["1", "0"]);
    assert_eq!(run("Recipe.A0 := 1.0 / Recipe.A7;\n").code(), Some("R0001"));
    assert_eq!(run("Recipe.N0 := 5 MOD Recipe.N7;\n").code(), Some("R0002"));
    assert_eq!(run("Recipe.A0 := SQRT(Recipe.A7 - 1);\n").code(), Some("R0005"));
    assert_eq!(run("Recipe.A0 := LN(Recipe.A7);\n").code(), Some("R0005"));
}

#[test]
fn no_nan_or_infinity_is_ever_written() {
    let r = run("Recipe.A0 := 5;\nRecipe.A0 := (Recipe.A7 - 8) ** 0.5;\n");
    assert_eq!(r.code(), Some("R0005"));
    assert_eq!(r.get("Recipe.A0"), "5.0");
    let r = run("Recipe.A1 := 5;\nRecipe.A1 := 1.0E38 * (Recipe.A7 + 10.0);\n");
    assert_eq!(r.code(), Some("R0005"));
    assert_eq!(r.get("Recipe.A1"), "5.0");
    let r = run("Recipe.A0 := (Recipe.A7) ** 2;\nRecipe.A1 := 2 ** 10;\n");
    assert_eq!((r.get("Recipe.A0"), r.get("Recipe.A1")), ("0.0".into(), "1024.0".into()));
    assert_eq!(run("Recipe.A0 := (Recipe.A7) ** 0;\n").code(), Some("R0005"));
}

#[test]
fn watchdog_stops_an_endless_loop_within_its_budget_naming_its_line() {
    let r = run("Counters.N0 := 0;\nWHILE 1 DO\n  Counters.N0 := Counters.N0 + 1;\nEND_WHILE;\n");
    let turns: u64 = r.get("Counters.N0").parse().expect("a count");
    let e = r.error.expect("watchdog");
    // Counted, not timed: the budget is instructions, and each turn of the
    // loop takes several (test, load, add, store, jump).
    let budget = linc_runtime::vm::DEFAULT_WATCHDOG;
    assert!(turns > budget / 20 && turns < budget / 3, "{turns} turns of the loop within {budget} instructions");
    assert_eq!((e.code.as_str(), e.line, e.col), ("R0006", 2, 1));
    assert!(e.message.contains("line 2"), "{}", e.message);
    // A FOR whose body resets its index never ends (a step of 0 is E0121).
    let r = run("REPEAT\n  FOR Counters.N0 := 1 TO 10 DO Counters.N0 := 1;\n  END_FOR;\nUNTIL FALSE END_REPEAT;\n");
    assert_eq!(r.error.map(|e| (e.code.as_str(), e.line)), Some(("R0006", 2)));
}

#[test]
fn suppressed_alarms_read_false() {
    let db = db(
        r#"{ "blocks": { "AI": { "type": "ANIN", "values": { "Alarms": { "HiLevel": true } } }, "R": { "type": "RECIPE" } } }"#,
    );
    let src = "R.N0 := AI.Alarms.HiLevel;\nAI.Alarms.HiLevel.Suppress := T#1d.12.2h;\nR.N1 := AI.Alarms.HiLevel;\nR.N2 := AI.Alarms.HiLevel.Suppress;\nAI.Alarms.HiLevel.Suppress := 0;\nR.N3 := AI.Alarms.HiLevel;\nAI.Alarms.Suppress := -1;\nR.N4 := AI.Alarms.HiLevel;\n";
    let r = run_in(&db, src, 1, 1.0);
    assert_eq!(r.error, None);
    let got: Vec<String> = (0..5).map(|i| r.get(&format!("R.N{i}"))).collect();
    assert_eq!(got, ["1", "0", "130320", "1", "0"]);
}

#[test]
fn equality_ignores_case_only_between_strings() {
    let r = run("RAW_COM.Buffer1 := 'abc';\nDig_A.Out.Bit0 := RAW_COM.Buffer1 = 'ABC';\nDig_A.Out.Bit1 := RAW_COM.Buffer1 = 'abc';\nSFC_CON.FileName := 'abc';\nDig_A.Out.Bit2 := SFC_CON.FileName = 'ABC';\n");
    assert_eq!(r.error, None);
    assert_eq!([r.get("Dig_A.Out.Bit0"), r.get("Dig_A.Out.Bit1"), r.get("Dig_A.Out.Bit2")], ["0", "1", "1"]);
}

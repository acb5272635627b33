//! The object fuzz's corpus: action files, a sequence and an FST table,
//! compiled, and the database they are compiled against.

use linc_conformance::exec::compile;
use linc_conformance::guide_db;
use linc_runtime::object::ObjectFile;

/// The corpus: loops, offsets, bit offsets, strings with CONCAT and FORMAT,
/// ENUM writes, alarm suppression, several actions in one file, own-block
/// actions, real arithmetic and library calls.
const SOURCES: &[&str] = &[
    "Counters.N0 := 0;\nFOR Counters.N1 := 0 TO 6 DO\n  Block_5.Val1{Counters.N1} := Block_5.Val1{Counters.N1 + 1} * 2.0;\n  IF Counters.N1 MOD 2 = 0 THEN Dig_A.Out.Bit0{Counters.N0} := 1; END_IF;\nEND_FOR;\nRAW_COM.Buffer1 := CONCAT('a$62', FORMAT('05I', Counters.N1));\nPIC_004.Mode := 'auto';\nANIN_005.Alarms.HiLevel.Suppress := 60;\nWHILE Counters.N0 < 3 DO Counters.N0 := Counters.N0 + 1; END_WHILE;\n",
    "ACTION Startup\n  TIC_100.SL := REC1.A4;\n  PIC_004.Mode := \"CASCADE\";\n  IF PIC_004.PV < 10 THEN\n    Dig_B.Out.Bit0 := 1;\n    RECORD.A4 := ANIN_004.HR;\n  ELSE\n    Dig_B.Out.Bit1 := 1;\n  END_IF;\n  SEQ4.Hold := (PIC_005.PV > 30) AND Dig_B.Out.Bit5;\nEND_ACTION\n\nACTION Modbus : RAW_COM\n  Tx_Value := CONCAT('$01$03', FORMAT(\"C\", SHR16(I1, 8)));\n  Tx_Value := CONCAT(Tx_Value, FORMAT(\"C\", I1 AND 255));\n  Tx_Value := CONCAT(Tx_Value, '$00$02');\n  I2 := CRC(Tx_Value, 1, 16#8005, 16#FFFF);\n  Tx_Value := REPLACE_INT16(CONCAT(Tx_Value, '$00$00'), LEN(Tx_Value) + 1, I2, 0);\nEND_ACTION\n\nACTION Shift\n  FOR Counters.N0 := 0 TO 6 DO\n    Block_5.Val1{Counters.N0} := Block_5.Val1{Counters.N0 + 1};\n  END_FOR;\n  Block_5.Val1{7} := Block_5.PV;\nEND_ACTION\n",
    "FOR Counters.N0 := 0 TO 6 DO\n  Block_5.Val1{Counters.N0} := Block_5.Val1{Counters.N0 + 1} * 1.5 + Recipe.A0;\nEND_FOR;\nIF Dig_A.Out.Bit3 AND Recipe.N0 MOD 2 = 0 THEN Dig_B.Out.Bit0 := NOT Dig_B.Out.Bit0; END_IF;\nRecipe.N0 := Recipe.N0 + ROUND(SQRT(Recipe.A1 + 4.0)) + MAX(1, Recipe.N1, 3);\nRecipe.A2 := Recipe.A1 ** 2.0 / (Recipe.A3 + 1.0);\nANIN_005.Alarms.HiLevel.Suppress := 10;\n",
    "RAW_COM.Buffer1 := 'x';\nWHILE LEN(RAW_COM.Buffer1) < 40 DO\n  RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, FORMAT('05I', LEN(RAW_COM.Buffer1)));\nEND_WHILE;\nIF RAW_COM.Buffer1 = 'X' THEN PIC_005.Mode := 'MANUAL'; ELSE PIC_005.Mode := 'AUTO'; END_IF;\nCounters.N2 := FIND(RAW_COM.Buffer1, '0', 1);\n",
    "FOR Counters.N1 := 0 TO 7 DO\n  Dig_A.Out.Bit0{Counters.N1} := (Counters.N1 MOD 3) = 0;\n  Dig_B.Out.Bit1{Counters.N1 MOD 4} := Dig_A.Out.Bit0{Counters.N1};\nEND_FOR;\nCounters.N3 := Counters.N3 + 1;\nIF Counters.N3 > 100 THEN Counters.N3 := 0; END_IF;\n",
    "ACTION Ramp : PID\n  SL := SL + 0.5;\n  IF SL > 100.0 THEN SL := 0.0; END_IF;\n  Mode := 'AUTO';\nEND_ACTION\nACTION Alarm\n  Dig_B.Out.Bit2 := ANIN_005.Alarms.HiLevel;\n  ANIN_004.Alarms.HiLevel.Suppress := 5;\n  REC1.N0 := REC1.N0 + 1;\nEND_ACTION\n",
];

/// A compiled object, as bytes and decoded.
pub struct Seed {
    pub bytes: Vec<u8>,
    pub obj: ObjectFile,
}

/// A sequence over the guide database: every qualifier, a parallel branch,
/// priorities, step variables and a chart action.
const SEQUENCE: &str = "INITIAL_STEP Idle: Count(P); END_STEP
STEP Fill: Count(N); Late(D, T#3s); Once(E, T#2s); Bye(F); END_STEP
STEP Heat: Keep(S); Brief(L, T#2s); END_STEP
STEP Stir: Stirring(N); END_STEP
STEP Done: Keep(R); END_STEP
TRANSITION FROM Idle TO Fill := Counters.N0 >= 1; END_TRANSITION
TRANSITION Full (PRIORITY := 2) FROM Fill TO (Heat, Stir) := Fill.T >= 4.0; END_TRANSITION
TRANSITION Stop (PRIORITY := 1) FROM Fill TO Done := Recipe.N3 = 7; END_TRANSITION
TRANSITION FROM (Heat, Stir) TO Done := Heat.T > 3.0 AND Stir.X; END_TRANSITION
TRANSITION FROM Done TO Idle := TRUE; END_TRANSITION
ACTION Count
    Counters.N0 := Counters.N0 + 1;
END_ACTION
ACTION Late
    Recipe.A0 := Fill.T * 2.0;
END_ACTION
ACTION Once
    Dig_A.Out.Bit1 := NOT Dig_A.Out.Bit1;
END_ACTION
ACTION Bye
    RAW_COM.Buffer1 := CONCAT(RAW_COM.Buffer1, 'x');
END_ACTION
ACTION Keep
    Recipe.N1 := Recipe.N1 + 1;
END_ACTION
ACTION Brief
    Block_5.Val1{Recipe.N1 MOD 8} := Heat.T;
END_ACTION
ACTION Stirring : CHART
    INITIAL_STEP Fwd: Turn(N); END_STEP
    STEP Rev: Turn(N); END_STEP
    TRANSITION FROM Fwd TO Rev := Fwd.T >= 1.0; END_TRANSITION
    TRANSITION FROM Rev TO Fwd := Rev.T >= 1.0; END_TRANSITION
END_ACTION
ACTION Turn
    Recipe.N2 := Recipe.N2 + 1;
END_ACTION
";

/// The guide's database with ROC points for the FST table of the corpus.
pub fn fuzz_db() -> &'static linc_runtime::Database {
    static DB: std::sync::OnceLock<linc_runtime::Database> = std::sync::OnceLock::new();
    DB.get_or_init(|| {
        let text = include_str!("../../../examples/guide/plant.db.json").replacen(
            "\"blocks\": {",
            r#""blocks": { "FST 1": { "type": "FST" }, "SFP 1": { "type": "SFP" }, "DOU 4-1": { "type": "DOU" },
               "HIST 9": { "type": "HIST", "values": { "ARCHTYP": "FSTDATA", "PERIODIC": 8 } },
               "HIST 3": { "type": "HIST", "values": { "ARCHTYP": "CURRENT", "ARCHPT": "SFP 1,DATA1" } },"#,
            1,
        );
        linc_runtime::Database::from_json(&text).expect("the fuzz database loads")
    })
}

/// An FST table using every FST-only instruction.
const TABLE: &str = "STEP,LABEL,CMD,ARGUMENT1,ARGUMENT2
0,TOP,VAL,\"SFP 1,DATA1\",
1,,+,1.5,
2,,SAV,\"SFP 1,DATA1\",
3,,WDB,9,\"FST 1,R3\"
4,,WTM,9,\"FST 1,R4\"
5,,RDB,9,\"FST 1,R5\"
6,,MHV,3,\"FST 1,R6\"
7,,GTE,1700000000,4
8,,ALM,HIGH,\"SFP 1,DATA1\"
9,,DWK,,
10,,TDO,DOU 4-1,0.5
11,,CT,1,TOP
12,,ST,1,3
13,,BRK,\"FST 1,R9\",
14,,WT,0.3,
15,,/,\"FST 1,R2\",
16,,**,\"FST 1,R2\",
17,,GO,TOP,
";

pub fn corpus() -> Vec<Seed> {
    let ctx = linc_compiler::Context::of(Some(guide_db()));
    let (diagnostics, table) = linc_compiler::fst::compile(TABLE, "table", "table.csv", Some(fuzz_db()));
    let table = table.unwrap_or_else(|| panic!("the corpus table compiles: {diagnostics:?}")).to_bytes();
    let (diagnostics, seq) = linc_compiler::sfc::compile_sequence(SEQUENCE, "seq", "seq.sfc", ctx);
    let seq = seq.unwrap_or_else(|| panic!("the corpus sequence compiles: {diagnostics:?}")).to_bytes();
    SOURCES
        .iter()
        .map(|src| compile(src, guide_db()))
        .chain([seq, table])
        .map(|bytes| {
            let obj = ObjectFile::from_bytes(&bytes).expect("a compiled object decodes");
            Seed { bytes, obj }
        })
        .collect()
}

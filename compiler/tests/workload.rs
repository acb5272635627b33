//! A realistic generated workload: action files of many actions over the
//! guide database, with IF/ELSIF/ELSE, FOR loops with offsets, assignments to
//! database fields, function calls and comments. Shared by the benchmark
//! (`benches/check.rs`) and the linearity test (`tests/linear.rs`).

/// About `bytes` bytes of actions, each about 1 KB (a 5 MB file has about
/// 5,000 actions).
#[allow(dead_code)]
pub fn actions(bytes: usize) -> String {
    let mut out = String::with_capacity(bytes + 2048);
    let mut i = 0u32;
    while out.len() < bytes {
        let n = i % 7;
        let m = (i / 7) % 5;
        out.push_str(&format!(
            "ACTION Act{i} (* generated action {i} *)\n\
             (* Level control: trim the setpoint from the recipe, then the outputs. *)\n\
             IF PIC_004.PV < {i}.5 AND Dig_A.Out.Bit{n} THEN\n\
             \x20   TIC_100.SL := REC1.A{n} * 1.5 + (Block_5.PV - {i}) / Const.A7;\n\
             \x20   Dig_B.Out.Bit{n} := NOT Dig_A.Out.Bit{n} OR (PIC_005.PV > 30);\n\
             ELSIF Recipe.N{n} MOD 3 = {m} THEN\n\
             \x20   Raw1.I2 := CRC(Raw1.Tx_Value, 1, 16#8005, 16#FFFF);\n\
             \x20   Recipe.A{n} := MAX(Recipe.A0, Recipe.A1, SQRT(ABS(PIC_004.PV)), {m}.25);\n\
             ELSE\n\
             \x20   PIC_004.Mode := \"AUTO\"; (* back to automatic *)\n\
             \x20   ANIN_005.Alarms.HiLevel.Suppress := T#4m;\n\
             END_IF;\n\
             FOR Counters.N0 := 0 TO 6 DO\n\
             \x20   Block_5.Val1{{Counters.N0}} := Block_5.Val1{{Counters.N0 + 1}} + T#1m30s;\n\
             END_FOR;\n\
             WHILE Counters.N1 < {m} DO\n\
             \x20   Counters.N1 := Counters.N1 + 1;\n\
             END_WHILE;\n\
             END_ACTION\n\n"
        ));
        i += 1;
    }
    out
}

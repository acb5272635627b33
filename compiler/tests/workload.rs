//! A realistic generated workload: action files of many actions over the
//! guide database, with IF/ELSIF/ELSE, FOR loops with offsets, assignments to
//! database fields, function calls and comments. Shared by the benchmark
//! (`benches/check.rs`) and the linearity test (`tests/linear.rs`); and a
//! sequence of many steps, shared by the sequence tests of memory and time.

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

/// A sequence of `n` steps in a ring (about 100 bytes a step), each
/// running an action and left by a timed transition to the next when its
/// time is at least `after` seconds (a REAL literal, as `1.0`).
#[allow(dead_code)]
pub fn ring(n: usize, after: &str) -> String {
    let mut out = String::new();
    for i in 0..n {
        let kw = if i == 0 { "INITIAL_STEP" } else { "STEP" };
        out.push_str(&format!("{kw} S{i}: Count(N); END_STEP\n"));
    }
    for i in 0..n {
        out.push_str(&format!("TRANSITION FROM S{i} TO S{} := S{i}.T >= {after}; END_TRANSITION\n", (i + 1) % n));
    }
    out.push_str("ACTION Count\n    R1.Batches := R1.Batches + 1;\nEND_ACTION\n");
    out
}

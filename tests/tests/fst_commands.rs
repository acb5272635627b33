//! Every command of ROCLINK 800 Table B-9: its effect on RR, CF and the
//! branch it takes, and the engine's timing (WT, BRK, timers) at 100 ms
//! resolution (docs/fst.md). Each table runs in FST 1 of a ROC800 database
//! with task 1 at 100 ms, starting 2026-01-05 06:00:00 (a Monday).

use linc_conformance::fst::{num, run, table, text, traced, POINTS};

/// Runs rows for one cycle (time 0 only).
fn once(rows: &[&str], fst: &str) -> linc_engines::strategy::Strategy {
    run(&table(rows), fst, 50)
}

#[test]
fn math_add_subtract_multiply_divide() {
    let s = once(
        &[
            ",VAL,10,",
            ",+,5,",
            ",SAV,\"FST 1,R1\",",
            ",-,20,",
            ",SAV,\"FST 1,R2\",",
            ",*,-2,",
            ",SAV,\"FST 1,R3\",",
            ",/,4,",
            ",SAV,\"FST 1,R4\",",
            ",/,0,",
            ",SAV,\"FST 1,R5\",",
            ",END,,",
        ],
        r#""CMPFLG": 7"#,
    );
    assert_eq!(num(&s, "FST 1.R1"), 15.0);
    assert_eq!(num(&s, "FST 1.R2"), -5.0);
    assert_eq!(num(&s, "FST 1.R3"), 10.0);
    assert_eq!(num(&s, "FST 1.R4"), 2.5);
    assert_eq!(num(&s, "FST 1.R5"), 2.5, "/ by 0 leaves RR unchanged");
    assert_eq!(num(&s, "FST 1.CMPFLG"), 7.0, "math leaves CF alone");
}

#[test]
fn math_with_database_arguments_and_overflow() {
    let s = once(
        &[",VAL,\"AIN 3-1,EU\",", ",+,\"AIN 3-1,HIAL\",", ",SAV,\"FST 1,R1\",", ",VAL,3e38,", ",*,10,", ",END,,"],
        "",
    );
    assert_eq!(num(&s, "FST 1.R1"), 132.0);
    assert_eq!(num(&s, "FST 1.RR"), 3e38_f32 as f64, "an overflowing product leaves RR unchanged");
}

#[test]
fn power_only_for_positive_rr() {
    let s = once(
        &[
            ",VAL,2,",
            ",**,10,",
            ",SAV,\"FST 1,R1\",",
            ",VAL,-2,",
            ",**,2,",
            ",SAV,\"FST 1,R2\",",
            ",VAL,0,",
            ",**,2,",
            ",SAV,\"FST 1,R3\",",
            ",VAL,4,",
            ",**,0.5,",
            ",END,,",
        ],
        "",
    );
    assert_eq!(num(&s, "FST 1.R1"), 1024.0);
    assert_eq!(num(&s, "FST 1.R2"), -2.0, "RR <= 0: no operation");
    assert_eq!(num(&s, "FST 1.R3"), 0.0);
    assert_eq!(num(&s, "FST 1.RR"), 2.0);
}

#[test]
fn a_power_that_overflows_leaves_rr_unchanged_and_the_table_running() {
    // 10 ** 100 and 2 ** R1 (R1 = 1000) are no single-precision numbers:
    // RR stays, as after / 0, and the table goes on (no fault, RUNFLG 1).
    let s = once(
        &[
            ",VAL,10,",
            ",**,100,",
            ",SAV,\"FST 1,R2\",",
            ",VAL,2,",
            ",**,\"FST 1,R1\",",
            ",SAV,\"FST 1,R3\",",
            ",VAL,0.5,",
            ",**,-1000,",
            ",END,,",
        ],
        r#""R1": 1000"#,
    );
    assert_eq!(num(&s, "FST 1.R2"), 10.0);
    assert_eq!(num(&s, "FST 1.R3"), 2.0);
    assert_eq!(num(&s, "FST 1.RR"), 0.5, "0.5 ** -1000 overflows too");
    assert_eq!(num(&s, "FST 1.RUNFLG"), 1.0);
    let s = run(&table(&[",VAL,\"FST 1,R4\",", ",+,1,", ",SAV,\"FST 1,R4\",", ",**,1e6,", ",END,,"]), "", 250);
    assert_eq!(num(&s, "FST 1.R4"), 3.0, "three cycles, each past the overflow");
}

#[test]
fn abs_exp_int() {
    let s = once(
        &[
            ",VAL,-3.5,",
            ",ABS,,",
            ",SAV,\"FST 1,R1\",",
            ",VAL,1,",
            ",EXP,,",
            ",SAV,\"FST 1,R2\",",
            ",VAL,100,",
            ",EXP,,",
            ",SAV,\"FST 1,R3\",",
            ",VAL,-2.7,",
            ",INT,,",
            ",SAV,\"FST 1,R4\",",
            ",VAL,2.7,",
            ",INT,,",
            ",END,,",
        ],
        "",
    );
    assert_eq!(num(&s, "FST 1.R1"), 3.5);
    assert_eq!(num(&s, "FST 1.R2"), std::f32::consts::E as f64);
    assert_eq!(num(&s, "FST 1.R3"), 100.0, "e ** 100 is no single-precision number: RR unchanged");
    assert_eq!(num(&s, "FST 1.R4"), -2.0, "INT truncates towards zero");
    assert_eq!(num(&s, "FST 1.RR"), 2.0);
}

#[test]
fn log_ln_sqr_and_their_domains() {
    let s = once(
        &[
            ",VAL,1000,",
            ",LOG,,",
            ",SAV,\"FST 1,R1\",",
            ",VAL,-1,",
            ",LOG,,",
            ",SAV,\"FST 1,R2\",",
            ",VAL,1,",
            ",EXP,,",
            ",LN,,",
            ",SAV,\"FST 1,R3\",",
            ",VAL,0,",
            ",LN,,",
            ",SAV,\"FST 1,R4\",",
            ",VAL,16,",
            ",SQR,,",
            ",SAV,\"FST 1,R5\",",
            ",VAL,-4,",
            ",SQR,,",
            ",SAV,\"FST 1,R6\",",
            ",VAL,0,",
            ",SQR,,",
            ",END,,",
        ],
        r#""STEPS": 30"#,
    );
    assert_eq!(num(&s, "FST 1.R1"), 3.0);
    assert_eq!(num(&s, "FST 1.R2"), -1.0, "LOG of RR <= 0: no operation");
    assert!((num(&s, "FST 1.R3") - 1.0).abs() < 1e-6);
    assert_eq!(num(&s, "FST 1.R4"), 0.0, "LN of 0: no operation");
    assert_eq!(num(&s, "FST 1.R5"), 4.0);
    assert_eq!(num(&s, "FST 1.R6"), -4.0, "SQR of RR < 0: no operation");
    assert_eq!(num(&s, "FST 1.RR"), 0.0, "SQR of 0 is 0");
}

#[test]
fn p3_uses_registers_1_to_4() {
    let s = once(&[",VAL,2,", ",P3,,", ",END,,"], r#""R1": 1, "R2": 2, "R3": 3, "R4": 4"#);
    assert_eq!(num(&s, "FST 1.RR"), 26.0, "1·8 + 2·4 + 3·2 + 4");
}

#[test]
fn logical_commands_work_on_the_8_bit_flag() {
    let rows = |cmd: &str, arg: &str| vec![",VAL,1.5,".to_string(), format!(",{cmd},{arg},"), ",END,,".to_string()];
    let go = |cmd: &str, arg: &str, cf: u32| {
        let r = rows(cmd, arg);
        let r: Vec<&str> = r.iter().map(String::as_str).collect();
        let s = once(&r, &format!(r#""CMPFLG": {cf}"#));
        assert_eq!(num(&s, "FST 1.RR"), 1.5, "{cmd} leaves RR alone");
        num(&s, "FST 1.CMPFLG")
    };
    assert_eq!(go("NOT", "", 0), 1.0);
    assert_eq!(go("NOT", "", 5), 0.0);
    assert_eq!(go("AND", "10", 12), 8.0);
    assert_eq!(go("OR", "10", 12), 14.0);
    assert_eq!(go("XOR", "10", 12), 6.0);
    assert_eq!(go("OR", "\"AIN 3-1,EU\"", 1), 43.0, "42 | 1");
    let s = once(&[",VAL,300,", ",SAV,\"FST 1,R1\",", ",AND,\"FST 1,R1\",", ",END,,"], r#""CMPFLG": 255"#);
    assert_eq!(num(&s, "FST 1.CMPFLG"), 255.0, "a value above 255 is limited to 255");
}

/// RR compared with 5 by `cmd`; R1 = 1 when the branch was taken.
fn branch(cmd: &str, rr: &str) -> f64 {
    let rows = [
        format!(",VAL,{rr},"),
        format!(",{cmd},5,YES"),
        ",END,,".into(),
        "YES,VAL,1,".into(),
        ",SAV,\"FST 1,R1\",".into(),
    ];
    let r: Vec<&str> = rows.iter().map(String::as_str).collect();
    let s = once(&r, r#""CMPFLG": 3"#);
    assert_eq!(num(&s, "FST 1.CMPFLG"), 3.0);
    num(&s, "FST 1.R1")
}

#[test]
fn comparisons_branch_to_argument2() {
    for (cmd, below, equal, above) in [
        ("==", 0.0, 1.0, 0.0),
        ("!=", 1.0, 0.0, 1.0),
        ("<", 1.0, 0.0, 0.0),
        ("<=", 1.0, 1.0, 0.0),
        (">", 0.0, 0.0, 1.0),
        (">=", 0.0, 1.0, 1.0),
    ] {
        assert_eq!(branch(cmd, "4"), below, "4 {cmd} 5");
        assert_eq!(branch(cmd, "5"), equal, "5 {cmd} 5");
        assert_eq!(branch(cmd, "6"), above, "6 {cmd} 5");
    }
}

#[test]
fn equality_is_bit_for_bit() {
    let s = once(
        &[
            ",VAL,-0,",
            ",==,0,YES",
            ",!=,0,NO",
            "YES,VAL,1,",
            ",SAV,\"FST 1,R1\",",
            ",GO,DONE,",
            "NO,VAL,2,",
            ",SAV,\"FST 1,R1\",",
            "DONE,END,,",
        ],
        "",
    );
    assert_eq!(num(&s, "FST 1.R1"), 2.0, "-0 and 0 differ bit for bit: == not taken, != taken");
    let s = once(&[",VAL,0.1,", ",==,0.1,YES", ",END,,", "YES,VAL,1,", ",SAV,\"FST 1,R1\","], "");
    assert_eq!(num(&s, "FST 1.R1"), 1.0);
}

#[test]
fn st_sets_a_timer_and_ct_branches_while_it_runs() {
    // Each cycle: count in R1 while timer 1 runs, in R2 after.
    let t = table(&[
        ",VAL,\"FST 1,R3\",",
        ",==,1,CHECK",
        ",ST,1,5",
        ",VAL,1,",
        ",SAV,\"FST 1,R3\",",
        "CHECK,CT,1,RUN",
        ",VAL,\"FST 1,R2\",",
        ",+,1,",
        ",SAV,\"FST 1,R2\",",
        ",END,,",
        "RUN,VAL,\"FST 1,R1\",",
        ",+,1,",
        ",SAV,\"FST 1,R1\",",
    ]);
    // Cycles at 0, 100, …, 900 ms: the timer is 5 at 0 ms and counts down
    // by one per 100 ms, so CT branches at 0–400 ms and falls through from
    // 500 ms (when it reaches 0).
    let s = run(&t, "", 950);
    assert_eq!(num(&s, "FST 1.R1"), 5.0);
    assert_eq!(num(&s, "FST 1.R2"), 5.0);
    assert_eq!(num(&s, "FST 1.TMR1"), 0.0);
    let s = run(&t, "", 250);
    assert_eq!(num(&s, "FST 1.TMR1"), 3.0, "5 at 0 ms, 3 at 200 ms");
}

#[test]
fn timers_of_another_fst_and_by_number() {
    let s = once(&[",ST,\"FST 1,TMR4\",30", ",ST,2,12.6", ",ST,3,-5", ",END,,"], "");
    assert_eq!(num(&s, "FST 1.TMR4"), 30.0);
    assert_eq!(num(&s, "FST 1.TMR2"), 13.0, "rounded");
    assert_eq!(num(&s, "FST 1.TMR3"), 0.0, "below 0 is 0");
}

#[test]
fn timers_count_down_whether_or_not_their_table_runs() {
    // FST 1 sets a timer of FST 2, which runs no table (ST works "for any
    // of the available FSTs"): it counts down all the same.
    let points = format!(r#"{{ "device": "ROC800", "blocks": {{ {POINTS}, "FST 2": {{ "type": "FST" }} }} }}"#);
    let db = linc_runtime::Database::from_json(&points).expect("database");
    let t = table(&[
        ",VAL,\"FST 1,R1\",",
        ",==,1,DONE",
        ",ST,\"FST 2,TMR1\",30",
        ",VAL,1,",
        ",SAV,\"FST 1,R1\",",
        "DONE,END,,",
    ]);
    let mut s = linc_conformance::fst::strategy(&t, db);
    assert!(s.run_for(1_050_000, None).is_empty());
    assert_eq!(num(&s, "FST 2.TMR1"), 20.0, "30 at 0 ms, ten intervals later");
    // A table that is stopped (RUNFLG 0) keeps counting its timers.
    let s = run(&table(&[",END,,"]), r#""RUNFLG": 0, "TMR1": 20, "TMR4": 3"#, 1050);
    assert_eq!((num(&s, "FST 1.TMR1"), num(&s, "FST 1.TMR4")), (10.0, 0.0));
    // In a 1 s task the table sees ten intervals gone between two cycles:
    // R2 keeps what CT's timer held at the second cycle.
    let slow =
        format!(r#"{{ "device": "ROC800", "tasks": {{ "1": {{ "period": "T#1s" }} }}, "blocks": {{ {POINTS} }} }}"#);
    let db = linc_runtime::Database::from_json(&slow).expect("database");
    let t = table(&[
        ",VAL,\"FST 1,TMR1\",",
        ",SAV,\"FST 1,R2\",",
        ",VAL,\"FST 1,R1\",",
        ",==,1,DONE",
        ",ST,1,25",
        ",VAL,1,",
        ",SAV,\"FST 1,R1\",",
        "DONE,END,,",
    ]);
    let mut s = linc_conformance::fst::strategy(&t, db);
    assert!(s.run_for(1_050_000, None).is_empty());
    assert_eq!((num(&s, "FST 1.R2"), num(&s, "FST 1.TMR1")), (15.0, 15.0), "25 at 0 s, 15 at 1 s");
}

#[test]
fn wt_suspends_for_whole_100_ms_intervals() {
    // R1 counts the passes through step 0; WT 0.5 then END: a pass every
    // 600 ms (0.5 s asleep, then END ends its cycle, then step 0 next cycle).
    let t = table(&[",VAL,\"FST 1,R1\",", ",+,1,", ",SAV,\"FST 1,R1\",", ",WT,0.5,", ",END,,"]);
    for (ms, passes) in [(50, 1.0), (550, 1.0), (650, 2.0), (1150, 2.0), (1250, 3.0)] {
        assert_eq!(num(&run(&t, "", ms), "FST 1.R1"), passes, "after {ms} ms");
    }
    // A WT from a parameter is limited to 0.1 s.
    let t = table(&[",VAL,\"FST 1,R1\",", ",+,1,", ",SAV,\"FST 1,R1\",", ",WT,\"FST 1,R2\",", ",END,,"]);
    assert_eq!(num(&run(&t, "", 950), "FST 1.R1"), 5.0, "WT 0 sleeps 100 ms: passes at 0, 200, … 800 ms");
}

#[test]
fn brk_delays_each_following_command() {
    // After BRK 3, one command runs per 300 ms.
    let t = table(&[",BRK,3,", ",VAL,1,", ",SAV,\"FST 1,R1\",", ",VAL,2,", ",SAV,\"FST 1,R2\",", ",END,,"]);
    let at = |ms| {
        let s = run(&t, "", ms);
        (num(&s, "FST 1.R1"), num(&s, "FST 1.R2"), num(&s, "FST 1.BRK"))
    };
    assert_eq!(at(50), (0.0, 0.0, 3.0), "BRK at 0 ms; VAL waits until 300 ms");
    assert_eq!(at(350), (0.0, 0.0, 3.0), "VAL at 300 ms");
    assert_eq!(at(650), (1.0, 0.0, 3.0), "SAV at 600 ms");
    assert_eq!(at(1250), (1.0, 2.0, 3.0), "SAV at 1200 ms");
    // BRK 0 ends the delay at once: everything in the first cycle.
    let s = run(&table(&[",BRK,0,", ",VAL,1,", ",SAV,\"FST 1,R1\",", ",END,,"]), "", 50);
    assert_eq!(num(&s, "FST 1.R1"), 1.0);
}

/// (time in ms, step) of each step the trace shows.
fn step_times(lines: &[String]) -> Vec<(u64, u64)> {
    lines
        .iter()
        .filter_map(|l| serde_json::from_str::<serde_json::Value>(l).ok())
        .filter_map(|v| Some(((v["time"].as_f64()? * 1000.0).round() as u64, v["step"].as_u64()?)))
        .collect()
}

#[test]
fn brk_delays_step_0_after_end_too() {
    // B-15: once BRK is set, a delay comes "between the executions of each
    // subsequent command", END and the step 0 after it included.
    let t = table(&[",BRK,3,", ",VAL,\"FST 1,R1\",", ",+,1,", ",SAV,\"FST 1,R1\",", ",END,,"]);
    let (s, lines) = traced(&t, "", 2450);
    let expected = [(0, 0), (300, 1), (600, 2), (900, 3), (1200, 4), (1500, 0), (1800, 1), (2100, 2), (2400, 3)];
    assert_eq!(step_times(&lines), expected);
    assert_eq!(num(&s, "FST 1.R1"), 2.0);
    // Without a trace (several steps per VM run) the timing is the same.
    assert_eq!(num(&run(&t, "", 2350), "FST 1.R1"), 1.0, "the second SAV is at 2400 ms");
}

#[test]
fn steps_per_cycle_bound_a_loop() {
    let t = table(&["LOOP,+,1,", ",GO,LOOP,"]);
    assert_eq!(num(&run(&t, "", 50), "FST 1.RR"), 10.0, "20 steps: ten additions");
    assert_eq!(num(&run(&t, "", 250), "FST 1.RR"), 30.0, "three cycles");
    assert_eq!(num(&run(&t, r#""STEPS": 4"#, 50), "FST 1.RR"), 2.0);
}

#[test]
fn dwk_and_mnd_read_the_simulated_clock() {
    let s = once(&[",DWK,,", ",SAV,\"FST 1,R1\",", ",MND,,", ",END,,"], "");
    assert_eq!(num(&s, "FST 1.R1"), 2.0, "2026-01-05 is a Monday");
    assert_eq!(num(&s, "FST 1.RR"), 360.0, "06:00");
}

#[test]
fn ao_and_do_send_nothing_in_manual() {
    let t = table(&[",VAL,7.5,", ",AO,AOU 5-1,12.5", ",DO,DOU 4-1,0.5", ",END,,"]);
    let s = run(&t, "", 50);
    assert_eq!(num(&s, "AOU 5-1.EU"), 12.5);
    assert_eq!(num(&s, "DOU 4-1.STATUS"), 1.0, "any non-zero value turns a DO on");
    assert_eq!(num(&s, "FST 1.RR"), 7.5);
    let mut s = linc_conformance::fst::strategy(&t, linc_conformance::fst::database(""));
    for path in ["AOU 5-1.MODE", "DOU 4-1.MODE"] {
        let (b, f) = path.rsplit_once('.').unwrap();
        let c = s.store.cell_of(s.store.db.block(b).unwrap(), f).unwrap();
        s.store.cells[c as usize] = linc_runtime::store::Cell::Int(1);
    }
    assert!(s.run_for(50_000, None).is_empty());
    assert_eq!(num(&s, "AOU 5-1.EU"), 0.0, "manual: nothing sent");
    assert_eq!(num(&s, "DOU 4-1.STATUS"), 0.0);
}

#[test]
fn tdo_turns_an_output_on_for_a_time() {
    let t =
        table(&[",VAL,\"FST 1,R1\",", ",==,1,DONE", ",TDO,DOU 4-1,2", ",VAL,1,", ",SAV,\"FST 1,R1\",", "DONE,END,,"]);
    let s = run(&t, "", 50);
    assert_eq!((num(&s, "DOU 4-1.STATUS"), num(&s, "DOU 4-1.TDOON")), (1.0, 2.0));
    assert_eq!(num(&run(&t, "", 1950), "DOU 4-1.STATUS"), 1.0);
    assert_eq!(num(&run(&t, "", 2050), "DOU 4-1.STATUS"), 0.0, "off after 2 s");
}

#[test]
fn val_and_sav_convert_to_the_parameter() {
    let s = once(
        &[
            ",VAL,\"DOU 4-1,STATUS\",",
            ",+,2.5,",
            ",SAV,\"FST 1,TMR1\",",
            ",SAV,\"FST 1,R1\",",
            ",VAL,300,",
            ",SAV,\"FST 1,CMPFLG\",",
            ",VAL,-1,",
            ",SAV,\"FST 1,MISC1\",",
            ",END,,",
        ],
        "",
    );
    assert_eq!(num(&s, "FST 1.TMR1"), 3.0, "2.5 rounds half away from zero");
    assert_eq!(num(&s, "FST 1.R1"), 2.5);
    assert_eq!(num(&s, "FST 1.CMPFLG"), 255.0, "an 8-bit parameter is limited to 0-255");
    assert_eq!(num(&s, "FST 1.MISC1"), 0.0);
}

#[test]
fn wdb_wtm_rdb_use_fst_history_points() {
    let t = table(&[
        ",VAL,\"FST 1,R3\",",
        ",+,1.5,",
        ",SAV,\"FST 1,R3\",",
        ",WDB,9,\"FST 1,R1\"",
        ",WTM,10,\"FST 1,R2\"",
        ",RDB,9,0",
        ",SAV,\"FST 1,R4\",",
        ",END,,",
    ]);
    // Cycles at 0 … 500 ms: six writes into an archive of 4 entries.
    let s = run(&t, "", 550);
    assert_eq!(num(&s, "FST 1.R1"), 2.0, "index 0,1,2,3,0,1 then 2 next");
    assert_eq!(num(&s, "FST 1.R2"), 2.0);
    assert_eq!(num(&s, "FST 1.R4"), 7.5, "index 0 was written again by the fifth pass (RR 7.5)");
    let s = run(&table(&[",RDB,10,1", ",END,,"]), "", 50);
    assert_eq!(num(&s, "FST 1.RR"), 0.0, "an entry never written reads 0");
    let s = run(&table(&[",WTM,10,0", ",RDB,10,0", ",END,,"]), "", 50);
    assert_eq!(num(&s, "FST 1.RR"), linc_conformance::fst::START as f32 as f64, "WTM: seconds since 1970");
}

#[test]
fn history_reads_and_gte() {
    let s = once(
        &[
            ",GTE,1700000000,2",
            ",SAV,\"FST 1,R1\",",
            ",GTE,1700000000,0",
            ",SAV,\"FST 1,R2\",",
            ",GTE,1700000000,3",
            ",END,,",
        ],
        "",
    );
    assert_eq!(num(&s, "FST 1.R1"), 2023.0);
    assert_eq!(num(&s, "FST 1.R2"), 11.0);
    assert_eq!(num(&s, "FST 1.RR"), 22.0);
    let s =
        once(&[",DIS,9,1225", ",SAV,\"FST 1,R1\",", ",DIN,9,1225", ",SAV,\"FST 1,R2\",", ",PIS,9,105", ",END,,"], "");
    assert_eq!(num(&s, "FST 1.R1"), -1.0, "no entry on 25 December");
    assert_eq!(num(&s, "FST 1.R2"), -1.0);
    assert_eq!(num(&s, "FST 1.RR"), -1.0, "nothing logged yet on 5 January");
    let s = run(
        &table(&[
            ",WDB,9,0",
            ",PIS,9,105",
            ",SAV,\"FST 1,R1\",",
            ",PIN,9,105",
            ",SAV,\"FST 1,R2\",",
            ",PHV,9,0",
            ",SAV,\"FST 1,R3\",",
            ",PHT,9,0",
            ",END,,",
        ]),
        "",
        50,
    );
    assert_eq!((num(&s, "FST 1.R1"), num(&s, "FST 1.R2")), (0.0, 1.0), "one periodic entry on 5 January, at 0");
    assert_eq!(num(&s, "FST 1.RR"), linc_conformance::fst::START as f32 as f64);
}

#[test]
fn daily_and_minute_history_of_a_logged_point() {
    // From 23:58:00 the table raises AIN 3-1's EU by 1 every 100 ms; the
    // logger samples it each minute (before the tasks of that instant) and
    // at midnight into the daily archive.
    let t = table(&[
        ",VAL,\"AIN 3-1,EU\",",
        ",+,1,",
        ",SAV,\"AIN 3-1,EU\",",
        ",DHV,3,0",
        ",SAV,\"FST 1,R1\",",
        ",DHT,3,0",
        ",SAV,\"FST 1,R2\",",
        ",MHV,3,59",
        ",SAV,\"FST 1,R3\",",
        ",MHV,3,0",
        ",SAV,\"FST 1,R4\",",
        ",DIS,3,106",
        ",SAV,\"FST 1,R5\",",
        ",DIN,3,106",
        ",END,,",
    ]);
    let start = linc_conformance::fst::START + 18.0 * 3600.0 - 120.0;
    let mut s = linc_conformance::fst::strategy_at(&t, linc_conformance::fst::database(""), start);
    assert!(s.run_for(180_000_000, None).is_empty());
    assert_eq!(num(&s, "FST 1.R3"), 642.0, "23:59:00: 42 + 600 steps of 1");
    assert_eq!(num(&s, "FST 1.R4"), 1242.0, "00:00:00");
    assert_eq!(num(&s, "FST 1.R1"), 1242.0, "the daily entry of midnight");
    assert_eq!(num(&s, "FST 1.R2"), 1_767_657_600.0, "stamped 2026-01-06 00:00:00");
    assert_eq!((num(&s, "FST 1.R5"), num(&s, "FST 1.RR")), (0.0, 1.0), "one daily entry on 6 January, at index 0");
}

#[test]
fn go_msg_end_alm_evt() {
    let t = table(&[
        ",GO,SKIP,",
        ",VAL,99,",
        "SKIP,VAL,\"FST 1,R1\",",
        ",+,1,",
        ",SAV,\"FST 1,R1\",",
        ",MSG,Pumping since dawn,\"FST 1,R1\"",
        ",ALM,HIGH LEVEL ALARM,\"AIN 3-1,EU\"",
        ",EVT,START,7",
        ",END,,",
        ",VAL,99,",
    ]);
    let s = run(&t, "", 250);
    assert_eq!(num(&s, "FST 1.R1"), 3.0, "END: each cycle starts again at step 0");
    assert_eq!(num(&s, "FST 1.RR"), 3.0, "GO skipped VAL 99, and steps after END never ran");
    assert_eq!(text(&s, "FST 1.MSG1"), "'Pumping since dawn'");
    assert_eq!(num(&s, "FST 1.MSGDAT"), 3.0);
    let alarms: Vec<_> = s.store.roc.alarms.iter().map(|e| (e.text.to_string(), e.value, e.source.clone())).collect();
    assert_eq!(alarms.len(), 3);
    assert_eq!(alarms[0], ("HIGH LEVEL".to_string(), 42.0, "FST 1".to_string()), "the first 10 characters");
    let events: Vec<_> = s.store.roc.events.iter().map(|e| (e.text.to_string(), e.value)).collect();
    assert_eq!(events, vec![("START".to_string(), 7.0); 3]);
}

#[test]
fn run_flag_stops_and_restarts() {
    let t = table(&[",VAL,\"FST 1,R1\",", ",+,1,", ",SAV,\"FST 1,R1\",", ",END,,"]);
    assert_eq!(num(&run(&t, r#""RUNFLG": 0"#, 550), "FST 1.R1"), 0.0, "RUNFLG 0: not running");
    assert_eq!(num(&run(&t, "", 550), "FST 1.R1"), 6.0, "started when the database does not say");
}

/// The instruction offset of each step of `rows`, as `linc fst list` shows.
fn offsets(rows: &[&str]) -> Vec<u32> {
    let db = linc_conformance::fst::database("");
    let (_, object) = linc_compiler::fst::compile(&table(rows), "t", "t.csv", Some(&db));
    linc_compiler::fst::offsets(&object.expect("compiles")).expect("offsets")
}

#[test]
fn ip_points_at_the_next_step_to_run() {
    // "IP … the storage location of the next function to be executed."
    let ends = [",VAL,1,", ",+,1,", ",END,,", ",VAL,9,"];
    assert_eq!(num(&run(&table(&ends), "", 50), "FST 1.IP"), 0.0, "after END: step 0");
    let falls_off = [",VAL,1,", ",+,1,"];
    assert_eq!(num(&run(&table(&falls_off), "", 50), "FST 1.IP"), 0.0, "after the last step: step 0");
    let waits = [",VAL,1,", ",WT,1,", ",+,1,", ",END,,"];
    let ip = f64::from(offsets(&waits)[2]);
    assert_eq!(num(&run(&table(&waits), "", 50), "FST 1.IP"), ip, "asleep in WT: the step after it");
    // END stands before the last step, a WT: the cycle ends after it.
    let last_wt = [",GO,W,", ",END,,", "W,WT,1,"];
    assert_eq!(num(&run(&table(&last_wt), "", 50), "FST 1.IP"), 0.0, "a WT as last step: step 0 next");
    let brk = [",BRK,2,", ",VAL,1,", ",END,,"];
    let ip = f64::from(offsets(&brk)[1]);
    assert_eq!(num(&run(&table(&brk), "", 50), "FST 1.IP"), ip, "BRK: the step after it, when the delay ends");
    // The steps-per-cycle limit stops a loop: the next cycle begins step 1.
    let l = ["LOOP,+,1,", ",GO,LOOP,"];
    let ip = f64::from(offsets(&l)[1]);
    assert_eq!(num(&run(&table(&l), r#""STEPS": 3"#, 50), "FST 1.IP"), ip, "steps 0, 1, 0 ran");
    assert_eq!(num(&run(&table(&l), r#""STEPS": 4"#, 50), "FST 1.IP"), 0.0, "steps 0, 1, 0, 1 ran");
}

#[test]
fn a_table_stopped_and_started_again_begins_at_step_0_at_once() {
    use linc_engines::strategy::ProgramState;
    // Each pass counts in R1, then sleeps 10 s.
    let t = table(&[",VAL,\"FST 1,R1\",", ",+,1,", ",SAV,\"FST 1,R1\",", ",WT,10,", ",END,,"]);
    let runflg = |s: &mut linc_engines::strategy::Strategy, v: i32| {
        let c = s.store.cell_of(s.store.db.block("FST 1").unwrap(), "RUNFLG").unwrap();
        s.store.cells[c as usize] = linc_runtime::store::Cell::Int(v);
    };
    // Through RUNFLG, from ST or the console's write.
    let mut s = linc_conformance::fst::strategy(&t, linc_conformance::fst::database(""));
    assert!(s.run_for(250_000, None).is_empty());
    assert_eq!(num(&s, "FST 1.R1"), 1.0, "asleep until 10 s");
    runflg(&mut s, 0);
    assert!(s.run_for(200_000, None).is_empty());
    runflg(&mut s, 1);
    assert!(s.run_for(100_000, None).is_empty());
    assert_eq!(num(&s, "FST 1.R1"), 2.0, "RUNFLG 0 then 1: step 0 at once, not at 10 s");
    // Through the console's STOP and START of the program.
    let mut s = linc_conformance::fst::strategy(&t, linc_conformance::fst::database(""));
    let block = s.store.db.block("FST 1").unwrap();
    assert!(s.run_for(250_000, None).is_empty());
    assert!(s.set_program_state(block, ProgramState::Inactive));
    assert!(s.run_for(200_000, None).is_empty());
    assert_eq!(num(&s, "FST 1.RUNFLG"), 0.0);
    assert!(s.set_program_state(block, ProgramState::Running));
    assert!(s.run_for(100_000, None).is_empty());
    assert_eq!(num(&s, "FST 1.R1"), 2.0, "STOP then START: step 0 at once, not at 10 s");
    assert_eq!(num(&s, "FST 1.RUNFLG"), 1.0);
    // Stopped and started between two cycles, before any cycle saw RUNFLG 0.
    let mut s = linc_conformance::fst::strategy(&t, linc_conformance::fst::database(""));
    assert!(s.run_for(250_000, None).is_empty());
    assert!(s.set_program_state(block, ProgramState::Inactive));
    assert!(s.set_program_state(block, ProgramState::Running));
    assert!(s.run_for(100_000, None).is_empty());
    assert_eq!(num(&s, "FST 1.R1"), 2.0, "STOP and START at once: step 0 at the next cycle");
}

#[test]
fn a_missing_point_stops_the_table_with_run_flag_5() {
    let t = table(&[",VAL,1,", ",SAV,\"FST 1,R1\",", ",VAL,\"SFP 1,DATA1\",", ",END,,"]);
    let db = linc_conformance::fst::database("");
    let (_, object) = linc_compiler::fst::compile(&t, "t", "t.csv", Some(&db));
    let object = object.expect("compiles");
    let offsets = linc_compiler::fst::offsets(&object).expect("offsets");
    let verified = linc_runtime::verify::verify(object).expect("verifies");
    // The same table against a database without SFP 1.
    let mut text = linc_conformance::fst::POINTS.replace(r#""SFP 1": { "type": "SFP" },"#, "");
    text = format!(r#"{{ "blocks": {{ {text} }} }}"#);
    let other = linc_runtime::Database::from_json(&text).expect("database");
    let store = linc_runtime::Store::new(other);
    let block = store.db.block("FST 1").unwrap();
    let want = linc_engines::strategy::Want {
        block,
        file: "t.csv".into(),
        action: String::new(),
        kind: linc_engines::strategy::WantKind::Fst,
    };
    let vm = linc_runtime::vm::Vm::new(1_000_000, linc_runtime::vm::Clock::new(1, 0));
    let mut s = linc_engines::strategy::Strategy::build(store, vec![verified], &[(want, 0)], vm, 0.0).expect("links");
    let errors = s.run_for(250_000, None);
    assert_eq!(errors.len(), 1, "stopped once, not at every cycle");
    assert_eq!(errors[0].code, "R0010");
    assert!(errors[0].message.contains("SFP 1.DATA1"), "{}", errors[0].message);
    assert_eq!(errors[0].line, 4, "the CSV line of step 2");
    assert_eq!(num(&s, "FST 1.RUNFLG"), 5.0);
    assert_eq!(num(&s, "FST 1.R1"), 1.0, "steps before the fault ran");
    assert_eq!(num(&s, "FST 1.IP"), f64::from(offsets[2]), "IP at the failing step");
}

#[test]
fn the_trace_records_each_step_with_rr_and_cf() {
    let t = table(&[",VAL,2,", ",+,3,", ",ALM,HI,9", ",END,,"]);
    let (_, lines) = traced(&t, r#""CMPFLG": 4"#, 50);
    let steps: Vec<&String> = lines.iter().filter(|l| l.contains("\"step\"")).collect();
    assert_eq!(steps.len(), 4, "{lines:#?}");
    assert!(steps[1].contains(r#""step":1"#) && steps[1].contains(r#""cmd":"+ 3""#), "{}", steps[1]);
    assert!(steps[1].contains(r#""RR":5.0"#) && steps[1].contains(r#""CF":4"#), "{}", steps[1]);
    assert!(lines.iter().any(|l| l.contains(r#""alarm":"HI""#) && l.contains(r#""value":9.0"#)), "{lines:#?}");
}

//! History points: configuration, the FST commands and the logger.

use super::*;

/// 2023-11-14 00:00:00, a Tuesday.
const T0: i64 = 1_699_920_000;

fn db(blocks: &str) -> Database {
    Database::from_json(&format!(r#"{{"blocks": {{ {blocks} }}}}"#)).unwrap()
}

fn history(blocks: &str) -> History {
    History::from_db(&db(blocks))
}

fn fst(n: u16, kind: &str, periodic: u32) -> String {
    format!(r#""HIST {n}": {{"type": "HIST", "values": {{"ARCHTYP": "{kind}", "PERIODIC": {periodic}}}}}"#)
}

fn code(r: Result<impl std::fmt::Debug, HistError>) -> String {
    match r {
        Err(e) => {
            assert_eq!(e.code, "R0011");
            e.message
        }
        Ok(v) => panic!("expected a halt, got {v:?}"),
    }
}

#[test]
fn points_are_the_hist_blocks_named_by_number() {
    let h = history(
        r#""HIST9": {"type": "HIST"}, "hist 12": {"type": "HIST", "values": {"PERIODIC": 100, "DAILY": 7, "PERIOD": 15}},
           "HIST 0": {"type": "HIST"}, "HIST 201": {"type": "HIST"}, "FLOWHIST": {"type": "HIST"},
           "H IST 9": {"type": "HIST"}, "HIST 3": {"type": "SFP"}"#,
    );
    let numbers: Vec<u16> = h.points().iter().map(|p| p.number).collect();
    assert_eq!(numbers, [9, 12], "HIST 3 is a soft point, not a history point");
    let p9 = h.point(9).unwrap();
    assert_eq!(p9.block, "HIST9");
    assert_eq!(p9.kind, ArchiveType::None, "ARCHTYP defaults to NONE");
    let sizes = |p: &Point| [Archive::Periodic, Archive::Daily, Archive::Minute].map(|a| p.archive(a).len());
    assert_eq!((sizes(p9), p9.period), ([840, 35, 60], 60), "0 means the defaults");
    let p12 = h.point(12).unwrap();
    assert_eq!((sizes(p12), p12.period), ([100, 7, 60], 15));
    let notes = h.notes().join("\n");
    for bad in ["`HIST 0`", "`HIST 201`", "`FLOWHIST`", "`H IST 9` is history point 9 again (after `HIST9`)"] {
        assert!(notes.contains(bad), "{bad} in {notes}");
    }
    assert_eq!(h.notes().len(), 4);
}

#[test]
fn unusable_sizes_and_periods_are_replaced_and_noted() {
    let h = history(
        r#""HIST 1": {"type": "HIST", "values": {"PERIODIC": -5, "DAILY": 1000, "PERIOD": 7}},
           "HIST 2": {"type": "HIST", "values": {"ARCHTYP": "current", "ARCHPT": "SFP 1", "PERIODIC": 99999}}"#,
    );
    let p1 = h.point(1).unwrap();
    assert_eq!(p1.archive(Archive::Periodic).len(), DEFAULT_PERIODIC);
    assert_eq!(p1.archive(Archive::Daily).len(), MAX_DAILY);
    assert_eq!(p1.period, 60, "7 minutes do not divide a day");
    let p2 = h.point(2).unwrap();
    assert_eq!(p2.kind, ArchiveType::Current, "ARCHTYP ignores case");
    assert_eq!(p2.archive(Archive::Periodic).len(), MAX_PERIODIC);
    assert_eq!(h.notes().len(), 5, "{:?}", h.notes());
    assert_eq!(split_archpt(" SFP 1 , DATA1 "), Some(("SFP 1", "DATA1")));
    assert_eq!(split_archpt("SFP 1,"), None);
    assert_eq!(split_archpt("A,B,C"), None);
}

#[test]
fn wdb_writes_at_the_index_and_wraps_the_next_one() {
    let mut h = history(&fst(9, "FSTDATA", 3));
    assert_eq!(h.write(9.0, 0.0, Some(1.5), T0), Ok(1.0));
    assert_eq!(h.write(9.0, 1.0, Some(2.5), T0 + 5), Ok(2.0));
    assert_eq!(h.write(9.0, 2.0, Some(3.5), T0 + 10), Ok(0.0), "past the last index comes 0");
    assert_eq!(h.read(HistFn::Rdb, 9.0, 2.0), Ok((3.5, 0.0)));
    assert_eq!(h.read(HistFn::Rdb, 9.0, 0.0), Ok((1.5, 1.0)));
    assert_eq!(h.read(HistFn::Phv, 9.0, 1.0), Ok((2.5, 1.0)), "PHV reads the same archive, index unchanged");
    assert_eq!(h.read(HistFn::Pht, 9.0, 1.0), Ok(((T0 + 5) as f32, 1.0)));
    let p = h.point(9).unwrap();
    assert_eq!(p.archive(Archive::Periodic)[1], Entry { stamp: T0 + 5, value: 2.5 });
}

#[test]
fn indexes_outside_the_archive_halt() {
    let mut h = history(&fst(9, "FSTDATA", 3));
    for idx in [3.0, -1.0, 0.5, f32::NAN, f32::INFINITY, 1e30] {
        let m = code(h.write(9.0, idx, Some(1.0), T0));
        assert!(m.contains("invalid history index"), "{m}");
        code(h.read(HistFn::Rdb, 9.0, idx));
        code(h.read(HistFn::Phv, 9.0, idx));
    }
    code(h.read(HistFn::Dhv, 9.0, 35.0));
    assert_eq!(h.read(HistFn::Dhv, 9.0, 34.0), Ok((0.0, 34.0)), "never written: value 0");
    assert_eq!(h.read(HistFn::Dht, 9.0, 34.0), Ok((0.0, 34.0)), "never written: stamp 0");
    assert_eq!(h.read(HistFn::Mhv, 9.0, 59.0), Ok((0.0, 59.0)));
    code(h.read(HistFn::Mhv, 9.0, 60.0));
    assert_eq!(h.write(9.0, -0.0, Some(1.0), T0), Ok(1.0), "-0 is index 0");
}

#[test]
fn invalid_history_points_halt() {
    let mut h = history(&format!("{}, {}", fst(9, "FSTDATA", 3), fst(10, "CURRENT", 3)));
    for hp in [0.0, 201.0, 9.5, -9.0, f32::NAN] {
        let m = code(h.write(hp, 0.0, Some(1.0), T0));
        assert!(m.contains("invalid history point"), "{m}");
        code(h.read(HistFn::Phv, hp, 0.0));
    }
    let m = code(h.read(HistFn::Dis, 7.0, 1114.0));
    assert!(m.contains("no block `HIST 7`"), "{m}");
    let m = code(h.write(10.0, 0.0, None, T0));
    assert!(m.contains("WTM needs an FST history point") && m.contains("CURRENT"), "{m}");
    code(h.read(HistFn::Rdb, 10.0, 0.0));
    assert_eq!(h.read(HistFn::Phv, 10.0, 0.0), Ok((0.0, 0.0)), "PHV reads any point");
}

#[test]
fn wtm_stores_the_time_in_single_precision_and_the_exact_stamp() {
    let mut h = history(&format!("{}, {}, {}", fst(9, "FSTDATA", 4), fst(10, "FSTSEC", 4), fst(11, "FSTMIN", 4)));
    let now = 1_700_000_001;
    assert_eq!(h.write(10.0, 0.0, None, now), Ok(1.0));
    let sec = h.point(10).unwrap().archive(Archive::Periodic)[0];
    assert_eq!(sec.stamp, now, "the stamp keeps the second");
    assert_eq!(sec.value, 1_700_000_000.0, "f32 holds 1.7e9 only to 128 s");
    h.write(11.0, 0.0, None, 1_699_999_999 - 60 * 60).unwrap();
    let min = h.point(11).unwrap().archive(Archive::Periodic)[0];
    assert_eq!(min.value, 1_699_996_380_i64 as f32, "22:12:59 the hour before is stored as 21:12:00");
    assert_eq!(min.stamp, 1_699_996_399);
    h.write(9.0, 3.0, None, now).unwrap();
    assert_eq!(h.read(HistFn::Rdb, 9.0, 3.0), Ok((now as f32, 0.0)), "WTM on FSTDATA stores seconds");
    h.write(10.0, 1.0, Some(42.0), now).unwrap();
    assert_eq!(h.read(HistFn::Rdb, 10.0, 1.0), Ok((42.0, 2.0)), "WDB on a time point stores RR");
    let (month, _) = h.read(HistFn::Gte, sec.value, 0.0).unwrap();
    assert_eq!(month, 11.0, "GTE reads a WTM value back");
}

#[test]
fn day_searches_find_the_first_index_and_count() {
    let mut h = history(&fst(9, "FSTDATA", 6));
    let nov14 = T0;
    let nov15 = T0 + DAY;
    // Index: 0 Nov 15 01:00, 1 Nov 15 02:00, 2 unwritten, 3 Nov 14 22:00, 4 Nov 14 23:00, 5 Nov 15 00:00.
    for (i, t) in [(0, nov15 + 3600), (1, nov15 + 7200), (3, nov14 + 22 * 3600), (4, nov14 + 23 * 3600), (5, nov15)] {
        h.write(9.0, i as f32, Some(i as f32), t).unwrap();
    }
    assert_eq!(h.read(HistFn::Pis, 9.0, 1114.0), Ok((3.0, 1114.0)));
    assert_eq!(h.read(HistFn::Pin, 9.0, 1114.0), Ok((2.0, 1114.0)));
    assert_eq!(h.read(HistFn::Pis, 9.0, 1115.0), Ok((5.0, 1115.0)), "the earliest stamp, past the wrap");
    assert_eq!(h.read(HistFn::Pin, 9.0, 1115.0), Ok((3.0, 1115.0)));
    for missing in [1116.0, 101.0, 1332.0, 0.0, -1.0, 1114.5, f32::NAN] {
        assert_eq!(h.read(HistFn::Pis, 9.0, missing).map(|r| r.0), Ok(-1.0), "{missing}");
        assert_eq!(h.read(HistFn::Pin, 9.0, missing).map(|r| r.0), Ok(-1.0), "{missing}");
    }
    assert_eq!(h.read(HistFn::Dis, 9.0, 1114.0), Ok((-1.0, 1114.0)), "the daily archive is empty");
    assert_eq!(h.read(HistFn::Din, 9.0, 1114.0), Ok((-1.0, 1114.0)));
    assert_eq!(h.read(HistFn::Pis, 9.0, 101.0), Ok((-1.0, 101.0)), "unwritten entries (stamp 0) are not 1 January");
}

#[test]
fn gte_through_read_halts_on_a_bad_element() {
    let h = History::default();
    assert_eq!(h.read(HistFn::Gte, 1_700_000_000.0, 2.0), Ok((2023.0, 2.0)));
    assert_eq!(h.read(HistFn::Gte, 1_700_000_000.0, 3.0), Ok((22.0, 3.0)));
    for e in [6.0, -1.0, 2.5, f32::NAN] {
        let m = code(h.read(HistFn::Gte, 1_700_000_000.0, e));
        assert!(m.contains("invalid time element"), "{m}");
    }
    let m = code(h.read(HistFn::Gte, f32::INFINITY, 0.0));
    assert!(m.contains("invalid time"), "{m}");
}

#[test]
fn hist_fn_numbers_round_trip() {
    for (i, f) in HistFn::ALL.iter().enumerate() {
        assert_eq!(HistFn::from_u8(i as u8), Some(*f));
        assert_eq!(*f as u8, i as u8);
    }
    assert_eq!(HistFn::from_u8(11), None);
    assert_eq!(HistFn::Pin.name(), "PIN");
}

fn logged_day() -> History {
    let mut h = history(
        r#""HIST 1": {"type": "HIST", "values": {"ARCHTYP": "CURRENT", "ARCHPT": "SFP 1,DATA1"}},
           "HIST 2": {"type": "HIST", "values": {"ARCHTYP": "FSTDATA"}}"#,
    );
    let mut asked = Vec::new();
    for t in T0..=T0 + DAY {
        // The archive point reads the minutes since the start.
        h.sample(t, &mut |archpt| {
            asked.push(archpt.to_string());
            Some(((t - T0) / 60) as f32)
        });
    }
    assert_eq!(asked.len(), 1440, "read once per call that passes a boundary");
    assert!(asked.iter().all(|a| a == "SFP 1,DATA1"));
    h
}

#[test]
fn a_current_point_logged_over_a_day() {
    let h = logged_day();
    let p = h.point(1).unwrap();
    let written = |a| p.archive(a).iter().filter(|e| e.is_written()).count();
    assert_eq!(written(Archive::Minute), 60);
    assert_eq!(written(Archive::Periodic), 24, "hourly, PERIOD 60");
    assert_eq!(written(Archive::Daily), 1);
    assert_eq!(h.read(HistFn::Mhv, 1.0, 0.0), Ok((1440.0, 0.0)), "midnight is minute 0");
    assert_eq!(h.read(HistFn::Mhv, 1.0, 1.0), Ok((1381.0, 1.0)), "23:01");
    assert_eq!(h.read(HistFn::Phv, 1.0, 0.0), Ok((60.0, 0.0)), "01:00 is the first periodic entry");
    assert_eq!(h.read(HistFn::Pht, 1.0, 8.0), Ok(((T0 + 9 * 3600) as f32, 8.0)));
    assert_eq!(h.read(HistFn::Phv, 1.0, 23.0), Ok((1440.0, 23.0)));
    assert_eq!(h.read(HistFn::Dhv, 1.0, 0.0), Ok((1440.0, 0.0)));
    assert_eq!(h.read(HistFn::Dht, 1.0, 0.0), Ok(((T0 + DAY) as f32, 0.0)));
    assert_eq!(h.read(HistFn::Pis, 1.0, 1114.0), Ok((0.0, 1114.0)));
    assert_eq!(h.read(HistFn::Pin, 1.0, 1114.0), Ok((23.0, 1114.0)), "01:00 to 23:00");
    assert_eq!(h.read(HistFn::Pin, 1.0, 1115.0), Ok((1.0, 1115.0)), "midnight belongs to the new day");
    assert_eq!(h.read(HistFn::Dis, 1.0, 1115.0), Ok((0.0, 1115.0)));
    assert_eq!(h.read(HistFn::Dis, 1.0, 1114.0), Ok((-1.0, 1114.0)));
    let fst = h.point(2).unwrap();
    assert!(fst.archive(Archive::Periodic).iter().all(|e| !e.is_written()), "the logger leaves FST points alone");
}

#[test]
fn a_clock_jump_logs_each_boundary_up_to_the_archive_size() {
    let mut h = history(
        r#""HIST 1": {"type": "HIST", "values": {"ARCHTYP": "CURRENT", "ARCHPT": "SFP 1,DATA1", "PERIODIC": 50, "DAILY": 3, "PERIOD": 30}}"#,
    );
    h.sample(T0, &mut |_| Some(1.0));
    h.sample(T0 + 10 * DAY, &mut |_| Some(2.0));
    let p = h.point(1).unwrap();
    let stamps = |a| -> Vec<i64> { p.archive(a).iter().map(|e| e.stamp).collect() };
    assert_eq!(stamps(Archive::Daily), [T0 + 8 * DAY, T0 + 9 * DAY, T0 + 10 * DAY], "the last three midnights");
    let periodic = stamps(Archive::Periodic);
    assert_eq!(periodic.first(), Some(&(T0 + 10 * DAY - 49 * 1800)), "the last 50 half hours, oldest first");
    assert_eq!(periodic.last(), Some(&(T0 + 10 * DAY)));
    assert!(p.archive(Archive::Minute).iter().all(|e| e.value == 2.0 && e.stamp > T0 + 10 * DAY - 3600));
    // A hundred years in one step still does bounded work.
    h.sample(T0 + 36_525 * DAY, &mut |_| None);
    let p = h.point(1).unwrap();
    assert_eq!(p.archive(Archive::Daily).iter().filter(|e| e.stamp > T0 + 36_000 * DAY).count(), 3);
    assert!(p.archive(Archive::Periodic).iter().all(|e| e.value == 0.0), "an unreadable ARCHPT logs 0");
}

#[test]
fn the_first_call_and_a_clock_set_back_log_nothing() {
    let mut h = history(r#""HIST 1": {"type": "HIST", "values": {"ARCHTYP": "CURRENT", "ARCHPT": "A,B"}}"#);
    h.sample(T0, &mut |_| Some(1.0));
    h.sample(T0 - 3600, &mut |_| Some(1.0));
    h.sample(T0 - 3600, &mut |_| Some(1.0));
    let p = h.point(1).unwrap();
    assert!(p.archive(Archive::Minute).iter().all(|e| !e.is_written()), "the boundary at T0 was the start");
    h.sample(T0 - 3540, &mut |_| Some(3.0));
    assert_eq!(h.read(HistFn::Mhv, 1.0, 1.0), Ok((3.0, 1.0)), "logging resumes from the time set back to");
}

/// Appendix B.5: point 9 FST data, point 10 FST time in seconds; the FST
/// loops VAL SFP 1 DATA1, WDB 9 R1, WTM 10 R2, WT 5.
#[test]
fn the_manuals_example_fst() {
    let mut h = history(&format!("{}, {}", fst(9, "FSTDATA", 0), fst(10, "FSTSEC", 0)));
    let (mut r1, mut r2) = (0.0_f32, 0.0_f32);
    for cycle in 0..842 {
        let now = T0 + 5 * cycle;
        r1 = h.write(9.0, r1, Some(cycle as f32), now).unwrap();
        r2 = h.write(10.0, r2, None, now).unwrap();
    }
    assert_eq!((r1, r2), (2.0, 2.0), "840 entries: the indexes wrapped");
    assert_eq!(h.read(HistFn::Rdb, 9.0, 0.0), Ok((840.0, 1.0)), "the 841st write overwrote index 0");
    assert_eq!(h.read(HistFn::Rdb, 9.0, 2.0), Ok((2.0, 3.0)));
    let (t, _) = h.read(HistFn::Rdb, 10.0, 2.0).unwrap();
    assert_eq!(t, (T0 + 10) as f32);
    assert_eq!(h.read(HistFn::Gte, t, 1.0), Ok((14.0, 1.0)));
}

#[test]
fn the_state_serialises_points_logs_and_times() {
    let d = db(&fst(9, "FSTMIN", 3));
    let mut s = RocState::new(&d);
    s.alarms.push(LogEntry::new(T0, "TANK HIGH LEVEL", 97.5, "FST 1"));
    s.history.write(9.0, 1.0, Some(0.25), T0 + 61).unwrap();
    let j = s.to_json();
    assert_eq!(j["alarms"]["entries"][0]["text"], "TANK HIGH ");
    assert_eq!(j["events"]["total"], 0);
    let p = &j["history"]["points"][0];
    assert_eq!(
        (p["number"].clone(), p["type"].clone(), p["block"].clone()),
        (9.into(), "FSTMIN".into(), "HIST 9".into())
    );
    assert_eq!(p["periodic"].as_array().map(Vec::len), Some(1), "only written entries");
    assert_eq!(p["periodic"][0]["index"], 1);
    assert_eq!(p["periodic"][0]["time"], "2023-11-14T00:01:01");
    assert_eq!(p["periodic"][0]["value"], 0.25);
    assert_eq!(p["sizes"]["periodic"], 3);
}

//! `linc test --shard K/N` and `--list`: four shards run separately give
//! the same pass/fail set as one run, every scenario in exactly one shard,
//! the split the same on every call.
mod common;

use std::collections::BTreeMap;

/// (name, passed) of every test case of a JUnit report.
fn cases(xml: &str) -> BTreeMap<String, bool> {
    let mut out = BTreeMap::new();
    for part in xml.split("<testcase ").skip(1) {
        let name = part.split("name=\"").nth(1).and_then(|r| r.split('"').next()).expect("a name").to_string();
        let body = part.split("</testcase>").next().unwrap_or("");
        out.insert(name, !body.contains("<failure"));
    }
    out
}

#[test]
fn four_shards_give_the_same_results_as_one_run() {
    let dir = linc_test_support::fresh_dir("shards");
    let plant = std::fs::canonicalize(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/ladder/plant.json")).unwrap();
    // 24 small scenarios on the ladder example; every third one fails, and
    // they press different inputs, so they cover different rungs.
    for i in 0..24 {
        let expect = if i % 3 == 0 { "Dig_1b.Out" } else { "NOT Dig_1b.Out" };
        let press = format!("at {}ms M Dig_{}a.In=1\n", 100 * (i % 3), 1 + i % 6);
        let text = format!("strategy {}\n{press}expect always {expect}\nrun 300ms\n", plant.display());
        std::fs::write(dir.join(format!("s{i:02}.ltest")), text).unwrap();
    }
    let d = dir.to_string_lossy().into_owned();
    let all_xml = dir.join("all.xml").to_string_lossy().into_owned();
    let all_info = dir.join("all.info").to_string_lossy().into_owned();
    let o = common::linc(&["test", &d, "--junit", &all_xml, "--coverage", "lcov", "-o", &all_info]);
    assert_eq!(o.status.code(), Some(1), "some fail");
    let all = cases(&std::fs::read_to_string(&all_xml).unwrap());
    assert_eq!((all.len(), all.values().filter(|p| !**p).count()), (24, 8));
    let listed = common::stdout(&common::linc(&["test", &d, "--list"]));
    assert_eq!(listed.lines().count(), 24);
    let mut merged = BTreeMap::new();
    let mut listed_shards = Vec::new();
    let mut infos = Vec::new();
    for k in 1..=4 {
        let shard = format!("{k}/4");
        let list = common::stdout(&common::linc(&["test", &d, "--shard", &shard, "--list"]));
        assert_eq!(list, common::stdout(&common::linc(&["test", &d, "--shard", &shard, "--list"])), "stable");
        assert!(!list.is_empty(), "shard {shard} holds some of 24 scenarios");
        listed_shards.extend(list.lines().map(String::from));
        let xml = dir.join(format!("shard{k}.xml")).to_string_lossy().into_owned();
        let info = dir.join(format!("shard{k}.info")).to_string_lossy().into_owned();
        common::linc(&["test", &d, "--shard", &shard, "--junit", &xml, "--coverage", "lcov", "-o", &info]);
        infos.push(info);
        let part = cases(&std::fs::read_to_string(&xml).unwrap());
        assert_eq!(part.len(), list.lines().count());
        for (name, passed) in part {
            assert!(merged.insert(name, passed).is_none(), "a scenario in two shards");
        }
    }
    listed_shards.sort();
    assert_eq!(listed_shards, listed.lines().map(String::from).collect::<Vec<_>>(), "the shards cover the suite once");
    assert_eq!(merged, all, "the same pass/fail set");
    // The shards' coverage, merged, is the single run's, byte for byte.
    let merged_info = dir.join("merged.info").to_string_lossy().into_owned();
    let mut args: Vec<&str> = vec!["test", "--merge-coverage"];
    args.extend(infos.iter().map(String::as_str));
    args.extend(["-o", &merged_info]);
    let o = common::linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let single = std::fs::read_to_string(&all_info).unwrap();
    assert!(single.contains("interlock.ld") && single.contains("BRDA:"), "{single}");
    assert_eq!(std::fs::read_to_string(&merged_info).unwrap(), single);
    // And a run on one thread counts what a run on several does.
    let serial_info = dir.join("serial.info").to_string_lossy().into_owned();
    common::linc(&["test", &d, "--jobs", "1", "--coverage", "lcov", "-o", &serial_info]);
    assert_eq!(std::fs::read_to_string(&serial_info).unwrap(), single);
    let bad = common::linc(&["test", &d, "--shard", "5/4"]);
    assert_eq!(bad.status.code(), Some(2));
}

#[test]
fn merged_coverage_files_add_up_to_the_same_bytes_in_any_order() {
    let dir = linc_test_support::fresh_dir("merge-coverage");
    let a = "TN:\nSF:plant/sim.stx\nFN:5,Tank\nFNDA:3,Tank\nFNF:1\nFNH:1\nBRDA:7,0,0,2\nBRDA:7,0,1,0\nBRF:2\nBRH:1\nDA:6,3\nDA:8,0\nLF:2\nLH:1\nend_of_record\n";
    let b = "TN:\nSF:plant/sim.stx\nFN:5,Tank\nFNDA:1,Tank\nFNF:1\nFNH:1\nBRDA:7,0,0,0\nBRDA:7,0,1,1\nBRF:2\nBRH:1\nDA:6,1\nDA:8,1\nLF:2\nLH:2\nend_of_record\n\
             TN:\nSF:plant/other.stx\nDA:1,0\nLF:1\nLH:0\nend_of_record\n";
    std::fs::write(dir.join("a.info"), a).unwrap();
    std::fs::write(dir.join("b.info"), b).unwrap();
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let o = common::linc(&["test", "--merge-coverage", &p("a.info"), &p("b.info"), "-o", &p("ab.info")]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    assert!(
        common::stdout(&o).contains("plant/sim.stx") && common::stdout(&o).contains("TOTAL"),
        "{}",
        common::stdout(&o)
    );
    let ab = std::fs::read_to_string(dir.join("ab.info")).unwrap();
    assert!(
        ab.contains("DA:6,4\nDA:8,1\n") && ab.contains("BRDA:7,0,0,2\nBRDA:7,0,1,1\n") && ab.contains("FNDA:4,Tank"),
        "{ab}"
    );
    assert!(ab.contains("SF:plant/other.stx"), "{ab}");
    common::linc(&["test", "--merge-coverage", &p("b.info"), &p("a.info"), "-o", &p("ba.info")]);
    assert_eq!(std::fs::read_to_string(dir.join("ba.info")).unwrap(), ab, "order does not matter");
    // Not lcov: located at its line.
    std::fs::write(dir.join("bad.info"), "SF:x\nDA:1,1\nnonsense\n").unwrap();
    let o =
        common::linc(&["test", "--merge-coverage", &p("bad.info"), "-o", &p("out.info"), "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("bad.info:3:1: error[E0912]"), "{}", common::stderr(&o));
    // A line number past 32 bits is refused, not cut into line 6's count.
    std::fs::write(dir.join("wide.info"), "SF:plant/sim.stx\nDA:4294967302,9\nend_of_record\n").unwrap();
    let o = common::linc(&["test", "--merge-coverage", &p("a.info"), &p("wide.info"), "-o", &p("w.info")]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("error[E0912]") && common::stderr(&o).contains("line number"));
    assert!(!dir.join("w.info").exists());
    // Never over an input.
    let o = common::linc(&["test", "--merge-coverage", &p("a.info"), "-o", &p("a.info")]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(dir.join("a.info")).unwrap(), a);
}

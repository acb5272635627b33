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
    // 24 small scenarios on the ladder example; every third one fails.
    for i in 0..24 {
        let expect = if i % 3 == 0 { "Dig_1b.Out" } else { "NOT Dig_1b.Out" };
        let text = format!("strategy {}\nexpect always {expect}\nrun 300ms\n", plant.display());
        std::fs::write(dir.join(format!("s{i:02}.ltest")), text).unwrap();
    }
    let d = dir.to_string_lossy().into_owned();
    let all_xml = dir.join("all.xml").to_string_lossy().into_owned();
    let o = common::linc(&["test", &d, "--junit", &all_xml]);
    assert_eq!(o.status.code(), Some(1), "some fail");
    let all = cases(&std::fs::read_to_string(&all_xml).unwrap());
    assert_eq!((all.len(), all.values().filter(|p| !**p).count()), (24, 8));
    let listed = common::stdout(&common::linc(&["test", &d, "--list"]));
    assert_eq!(listed.lines().count(), 24);
    let mut merged = BTreeMap::new();
    let mut listed_shards = Vec::new();
    for k in 1..=4 {
        let shard = format!("{k}/4");
        let list = common::stdout(&common::linc(&["test", &d, "--shard", &shard, "--list"]));
        assert_eq!(list, common::stdout(&common::linc(&["test", &d, "--shard", &shard, "--list"])), "stable");
        assert!(!list.is_empty(), "shard {shard} holds some of 24 scenarios");
        listed_shards.extend(list.lines().map(String::from));
        let xml = dir.join(format!("shard{k}.xml")).to_string_lossy().into_owned();
        common::linc(&["test", &d, "--shard", &shard, "--junit", &xml]);
        let part = cases(&std::fs::read_to_string(&xml).unwrap());
        assert_eq!(part.len(), list.lines().count());
        for (name, passed) in part {
            assert!(merged.insert(name, passed).is_none(), "a scenario in two shards");
        }
    }
    listed_shards.sort();
    assert_eq!(listed_shards, listed.lines().map(String::from).collect::<Vec<_>>(), "the shards cover the suite once");
    assert_eq!(merged, all, "the same pass/fail set");
    let bad = common::linc(&["test", &d, "--shard", "5/4"]);
    assert_eq!(bad.status.code(), Some(2));
}

//! `linc draw`: pictures of example files, drawn plain or as a run leaves
//! them, and trends of trace files, with their errors.
mod common;

use common::{linc, stderr, stdout};

/// The opening tags of the groups whose id starts with `prefix`, as
/// `(id, class)`.
fn groups(svg: &str, prefix: &str) -> Vec<(String, String)> {
    let pat = format!("<g id=\"{prefix}");
    svg.match_indices(&pat)
        .map(|(at, _)| {
            let tag = &svg[at..at + svg[at..].find('>').expect("tag ends")];
            let attr = |name: &str| {
                let start = tag.find(&format!("{name}=\"")).map(|i| i + name.len() + 2).expect("attribute");
                tag[start..start + tag[start..].find('"').expect("quote")].to_string()
            };
            (attr("id"), attr("class"))
        })
        .collect()
}

fn with_class<'a>(gs: &'a [(String, String)], class: &str) -> Vec<&'a str> {
    gs.iter().filter(|(_, c)| c.split(' ').any(|w| w == class)).map(|(id, _)| id.as_str()).collect()
}

#[test]
fn a_sequence_is_drawn_plain_and_as_a_run_leaves_it() {
    let o = linc(&["draw", "examples/sequences/batch.sfc"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let plain = stdout(&o);
    assert!(plain.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"linc sfc\""));
    assert!(with_class(&groups(&plain, "step-"), "active").is_empty());
    // After 45 s of the plant the batch is filling (it started at 2 s).
    let args = ["draw", "examples/sequences/batch.sfc", "--db", "examples/sequences/plant.json", "--for", "45s"];
    let o = linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let run = stdout(&o);
    let steps = groups(&run, "step-");
    assert_eq!(steps.len(), groups(&plain, "step-").len());
    assert_eq!(with_class(&steps, "active"), ["step-Fill"]);
    assert!(run.contains("T#43s"), "the step time is shown");
    // The same run twice draws the same picture.
    assert_eq!(stdout(&linc(&args)), run);
}

#[test]
fn rungs_show_power_flow_after_a_run() {
    let o = linc(&["draw", "examples/ladder/interlock.ld", "--db", "examples/ladder/plant.json", "--cycles", "2"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = stdout(&o);
    let rungs = groups(&svg, "rung-");
    assert_eq!(rungs.len(), 8);
    // Rung 5's jump to _End is taken (`[/Dig_5b.In]` passes): rungs 6–8
    // did not run, so they carry no power whatever their contacts read.
    assert_eq!(with_class(&rungs, "powered"), ["rung-4", "rung-5"]);
    assert_eq!(with_class(&rungs, "skipped"), ["rung-6", "rung-7", "rung-8"]);
    for n in 6..=8 {
        let body = rung_body(&svg, n);
        assert!(!body.contains("wire on") && !body.contains("class=\"element on"), "rung {n}: {body}");
        assert!(body.contains(&format!("<title>rung {n} did not run")), "rung {n} says why it is grey");
    }
    // Values are coloured by state: TRUE energised, FALSE dim.
    assert!(svg.contains("class=\"value true\" text-anchor=\"middle\">TRUE<"));
    assert!(svg.contains("class=\"value false\" text-anchor=\"middle\">FALSE<"));
    assert!(!svg.contains("class=\"value\" text-anchor=\"middle\">TRUE<"));
    assert!(svg.contains("text.value.true { fill: var(--on)") && svg.contains("text.value.false { fill: var(--dim)"));
    let plain = stdout(&linc(&["draw", "examples/ladder/interlock.ld"]));
    assert!(with_class(&groups(&plain, "rung-"), "powered").is_empty());
}

/// The SVG of group `rung-N`, up to the next rung.
fn rung_body(svg: &str, n: usize) -> &str {
    let start = svg.find(&format!("<g id=\"rung-{n}\"")).expect("rung");
    let end = svg[start + 1..].find("<g id=\"rung-").map_or(svg.len(), |e| start + 1 + e);
    &svg[start..end]
}

/// Which rungs ran is what the run recorded, not what the values say
/// afterwards: here the rung after the label clears the jump's contact, so
/// from the values alone the jump looks not taken and rung 2 powered.
#[test]
fn a_rung_a_taken_jump_skipped_is_drawn_not_run_even_when_its_jump_reads_false_now() {
    let src = "(* skip *)\n[Dig_1b.Out] -> JUMP Over;\n[Dig_2a.In] -> (Dig_2c.Out);\nOver: -> (R Dig_1b.Out);\n";
    let file = common::temp_file("draw-skip", "skip.ld", src);
    let db = format!("{}/../examples/ladder/plant.json", env!("CARGO_MANIFEST_DIR"));
    let args = ["draw", &file, "--db", &db, "--cycles", "1", "--set", "Dig_1b.Out=TRUE", "--set", "Dig_2a.In=TRUE"];
    let o = linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = stdout(&o);
    let rungs = groups(&svg, "rung-");
    assert_eq!(with_class(&rungs, "skipped"), ["rung-2"]);
    assert_eq!(with_class(&rungs, "powered"), ["rung-3"]);
    assert!(rung_body(&svg, 2).contains(">TRUE<"), "its contact still shows its value");
    assert!(!rung_body(&svg, 2).contains("wire on"));
    // Without a cycle nothing ran, and nothing is drawn as skipped.
    let o = linc(&["draw", &file, "--db", &db, "--set", "Dig_1b.Out=TRUE", "--set", "Dig_2a.In=TRUE"]);
    assert!(with_class(&groups(&stdout(&o), "rung-"), "skipped").is_empty());
}

#[test]
fn an_fst_table_shows_its_current_step() {
    let db = "examples/fst/plant.json";
    let o = linc(&["draw", "examples/fst/pump.csv", "--db", db, "--block", "FST 1", "--for", "10s"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = stdout(&o);
    let steps = groups(&svg, "fst-step-");
    assert_eq!(with_class(&steps, "current").len(), 1);
    assert!(svg.contains("RR = ") && svg.contains("CF = "));
    assert!(svg.contains(">R1 = ") && svg.contains("   R10 = "), "the registers, five to a line");
    // Four FST blocks run in that database: which one must be said.
    let o = linc(&["draw", "examples/fst/pump.csv", "--db", db, "--for", "10s"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn a_trend_is_drawn_from_a_trace_and_bad_traces_are_located() {
    let dir = common::temp_dir("draw-trend");
    let trace = dir.join("t.jsonl");
    let t = trace.to_str().unwrap();
    let o = linc(&["run", "examples/sequences/plant.json", "--for", "60s", "--trace", t]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let o = linc(&["draw", t, "--field", "R1.Level", "--field", "R1.FillVlv", "--from", "10s", "--to", "50s"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let svg = stdout(&o);
    assert!(svg.contains("class=\"linc trend\""));
    assert!(svg.contains(">R1.Level<") && svg.contains(">R1.FillVlv<"));
    assert!(svg.contains(">BATCH<"), "a strip for the sequence");
    let o = linc(&["draw", t, "--field", "No.Such"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0911]"), "{}", stderr(&o));
    let bad = dir.join("bad.jsonl");
    std::fs::write(&bad, "{\"time\":0,\"field\":\"A.B\",\"new\":\"1\"}\nnot json\n").unwrap();
    let o = linc(&["draw", bad.to_str().unwrap(), "--field", "A.B"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E0910]: line 2"), "{}", stderr(&o));
}

#[test]
fn the_picture_is_written_atomically_and_never_over_an_input() {
    let dir = common::temp_dir("draw-out");
    let src = dir.join("b.sfc");
    std::fs::copy("../examples/sequences/batch.sfc", &src).unwrap();
    let out = dir.join("b.svg");
    let o = linc(&["draw", src.to_str().unwrap(), "-o", out.to_str().unwrap()]);
    assert_eq!((o.status.code(), stdout(&o).as_str()), (Some(0), ""), "{}", stderr(&o));
    let drawn = std::fs::read_to_string(&out).unwrap();
    assert_eq!(drawn, stdout(&linc(&["draw", src.to_str().unwrap()])));
    let before = std::fs::read_to_string(&src).unwrap();
    let o = linc(&["draw", src.to_str().unwrap(), "-o", src.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert_eq!(std::fs::read_to_string(&src).unwrap(), before);
    // A flag that means nothing for the file is refused, not ignored.
    let o = linc(&["draw", src.to_str().unwrap(), "--field", "A.B"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

#[test]
fn options_that_mean_nothing_for_the_file_are_refused() {
    let seq = "examples/sequences/batch.sfc";
    let db = "examples/sequences/plant.json";
    for args in [
        vec!["draw", seq, "--set", "R1.Level=5"],
        vec!["draw", seq, "--seed", "3"],
        vec!["draw", seq, "--db", db, "--for", "10s", "--period", "0"],
        vec!["draw", seq, "--db", db, "--for", "10s", "--period", "-1"],
        vec!["draw", "examples/ladder/interlock.ld", "--now", "2026-01-05T06:00:00"],
        vec!["draw", "examples/fst/pump.csv", "--block", "FST 1"],
    ] {
        let o = linc(&args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains("error[E0903]"), "{args:?}: {}", stderr(&o));
    }
}

#[test]
fn a_trend_range_is_checked_and_a_run_that_faults_exits_1() {
    let dir = common::temp_dir("draw-range");
    let trace = dir.join("t.jsonl");
    let t = trace.to_str().unwrap();
    assert_eq!(linc(&["run", "examples/sequences/plant.json", "--for", "2m", "--trace", t]).status.code(), Some(0));
    let o = linc(&["draw", t, "--field", "R1.Level", "--from", "0s", "--to", "1m"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    for bad in [["--from", "1m", "--to", "30s"], ["--from", "soon", "--to", "1m"]] {
        let mut args = vec!["draw", t, "--field", "R1.Level"];
        args.extend_from_slice(&bad);
        assert_eq!(linc(&args).status.code(), Some(2), "{bad:?}");
    }
    let o = linc(&["draw", t, "--field", "R1.Level", "--db", "examples/sequences/plant.json"]);
    assert_eq!(o.status.code(), Some(2), "a trace is drawn as recorded");
    // A rung that divides by zero: the fault is reported, the rungs still drawn, the status 1.
    let ld = dir.join("div.ld");
    std::fs::write(&ld, "-> Recipe.N1 := 10 / Recipe.N0;\n").unwrap();
    let o = linc(&["draw", ld.to_str().unwrap(), "--db", common::DB, "--cycles", "1"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    assert!(stderr(&o).contains("error[R0001]"), "{}", stderr(&o));
    assert!(stdout(&o).contains("<g id=\"rung-1\""));
    // With --db alone the rungs show the database's values as they stand.
    let o = linc(&["draw", "examples/ladder/interlock.ld", "--db", "examples/ladder/plant.json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(!with_class(&groups(&stdout(&o), "rung-"), "powered").is_empty());
}

//! The server's API over real HTTP on 127.0.0.1, in process, with an
//! independent client (ureq): reads, refused writes without
//! `--allow-writes`, tokens, foreign origins, controls through the console
//! engine, 20 clients streaming events at once, and a served run that ends
//! where `linc run` would.

mod common;

use common::{plant, serve};
use linc_serve::{Config, Server, Speed};
use serde_json::Value;
use std::io::BufRead;
use std::time::{Duration, Instant};

fn config(speed: Speed, writes: bool, token: Option<&str>) -> Config {
    Config {
        speed,
        token: token.map(String::from),
        allow_writes: writes,
        ..Config::new("127.0.0.1:0".parse().unwrap())
    }
}

fn agent() -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .timeout_global(Some(Duration::from_secs(20)))
        .build()
        .into()
}

/// `(status, body)` of a GET.
fn get(s: &Server, path: &str, headers: &[(&str, &str)]) -> (u16, String) {
    let mut req = agent().get(format!("http://{}{path}", s.addr()));
    for (k, v) in headers {
        req = req.header(*k, *v);
    }
    let mut resp = req.call().expect("GET");
    (resp.status().as_u16(), resp.body_mut().read_to_string().expect("body"))
}

fn command_as(s: &Server, line: &str, headers: &[(&str, &str)]) -> (u16, Value) {
    let mut req = agent().post(format!("http://{}/api/command", s.addr())).header("Content-Type", "application/json");
    for (k, v) in headers {
        req = req.header(*k, *v);
    }
    let mut resp = req.send(serde_json::json!({ "command": line }).to_string()).expect("POST");
    let status = resp.status().as_u16();
    (status, serde_json::from_str(&resp.body_mut().read_to_string().expect("body")).expect("JSON"))
}

fn command(s: &Server, line: &str) -> (u16, Value) {
    command_as(s, line, &[])
}

fn json(body: &str) -> Value {
    serde_json::from_str(body).expect("JSON")
}

#[test]
fn a_read_only_monitor_reads_and_refuses_writes() {
    let s = serve("examples/sequences/plant.json", config(Speed::Times(1.0), false, None));
    let (code, body) = get(&s, "/api/programs", &[]);
    assert_eq!(code, 200);
    let status = json(&body);
    assert_eq!(status["writes"], false);
    let batch = status["programs"].as_array().unwrap().iter().find(|p| p["block"] == "BATCH").expect("BATCH");
    assert_eq!((batch["kind"].as_str(), batch["picture"].as_str()), (Some("sequence"), Some("sfc")));
    let (code, body) = get(&s, "/api/blocks/R1", &[]);
    assert_eq!(code, 200);
    let r1 = json(&body);
    assert!(r1["fields"].as_array().unwrap().iter().any(|f| f["name"] == "Level"), "{r1}");
    assert_eq!(get(&s, "/api/blocks/NOPE", &[]).0, 404);
    let (code, svg) = get(&s, "/api/pictures/BATCH", &[]);
    assert_eq!(code, 200);
    assert!(svg.contains("<g id=\"step-Fill\" class=\"step"), "{svg}");
    assert_eq!(get(&s, "/api/pictures/SIM", &[]).0, 404, "an ST action has no picture");
    let (code, page) = get(&s, "/", &[]);
    assert!(code == 200 && page.contains("<script src=\"app.js\">"));
    // Reading commands run; writing ones are refused with 403 and change nothing.
    let (code, reply) = command(&s, "D R1.Level");
    assert_eq!(code, 200);
    assert_eq!(reply["replies"][0]["ok"], true, "{reply}");
    let before = json(&get(&s, "/api/blocks/R1", &[]).1);
    for line in ["M R1.Level=55", "D R1.Level; F R1.Level=1", "RESET BATCH", "HOLDSTEP BATCH Fill", "ADVANCE 1m"] {
        let (code, reply) = command(&s, line);
        assert_eq!(code, 403, "{line}: {reply}");
    }
    let after = json(&get(&s, "/api/blocks/R1", &[]).1);
    assert_eq!(before["fields"].as_array().map(Vec::len), after["fields"].as_array().map(Vec::len));
    assert!(after["fields"].as_array().unwrap().iter().all(|f| f["forced"] == false));
    // Only JSON posts, and nothing from another origin.
    let mut resp = agent()
        .post(format!("http://{}/api/command", s.addr()))
        .header("Content-Type", "text/plain")
        .send("D R1.Level")
        .unwrap();
    assert_eq!(resp.status().as_u16(), 415, "{}", resp.body_mut().read_to_string().unwrap());
    let (code, _) = command_as(&s, "D R1.Level", &[("Origin", "http://evil.example")]);
    assert_eq!(code, 403);
    let (code, reply) = command(&s, &format!("D {}", "X".repeat(5000)));
    assert_eq!(code, 400, "{reply}");
    s.stop();
}

#[test]
fn with_writes_controls_go_through_the_console_engine() {
    let s = serve("examples/sequences/plant.json", config(Speed::Times(1.0), true, None));
    let (code, reply) = command(&s, "F Plant.N1=0; M Plant.N1=1; F Plant.N1=N; NOSUCH");
    assert_eq!(code, 200);
    let r = reply["replies"].as_array().unwrap();
    assert_eq!(r.len(), 4, "{reply}");
    assert_eq!((r[0]["ok"].as_bool(), r[1]["code"].as_str()), (Some(true), Some("C0009")), "forced: {reply}");
    assert_eq!((r[2]["ok"].as_bool(), r[3]["code"].as_str()), (Some(true), Some("C0001")), "{reply}");
    let (_, reply) = command(&s, "HOLDSTEP BATCH Idle");
    assert_eq!(reply["replies"][0]["reply"], "BATCH.Idle held", "{reply}");
    let svg = get(&s, "/api/pictures/BATCH", &[]).1;
    assert!(
        svg.contains("<g id=\"step-Idle\" class=\"step held\"")
            || svg.contains("<g id=\"step-Idle\" class=\"step active held\""),
        "{svg}"
    );
    // A raised error names its program, shown as failed.
    let (_, reply) = command(&s, "ERRRAISE R0001 SIM");
    assert_eq!(reply["replies"][0]["ok"], true, "{reply}");
    // (The status is what the plant last published: ten times a second.)
    let status = || json(&get(&s, "/api/programs", &[]).1);
    let failed = |st: &Value| {
        let sim = st["programs"].as_array().unwrap().iter().find(|p| p["block"] == "SIM").cloned().unwrap();
        sim["failed"] == Value::Bool(true) && st["error"]["code"] == "R0001"
    };
    common::eventually("the raised error in the status", || failed(&status()));
    // ADVANCE moves the clock; real time goes on from there.
    let (_, reply) = command(&s, "ADVANCE 1h");
    assert_eq!(reply["replies"][0]["ok"], true, "{reply}");
    common::eventually("an hour later in the status", || status()["elapsed"].as_f64().is_some_and(|t| t >= 3600.0));
    s.stop();
}

#[test]
fn a_token_is_required_when_set() {
    let s = serve("examples/sequences/plant.json", config(Speed::Times(1.0), false, Some("s3cret")));
    assert_eq!(get(&s, "/api/programs", &[]).0, 401);
    assert_eq!(get(&s, "/api/programs", &[("Authorization", "Bearer wrong")]).0, 401);
    assert_eq!(get(&s, "/api/programs?token=s3cre", &[]).0, 401);
    assert_eq!(get(&s, "/", &[]).0, 401, "the page too");
    assert_eq!(get(&s, "/api/programs", &[("Authorization", "Bearer s3cret")]).0, 200);
    assert_eq!(get(&s, "/api/programs?token=s3cret", &[]).0, 200);
    // As the specifications read them: the query percent-decoded, the
    // scheme in any case.
    assert_eq!(get(&s, "/api/programs?token=s%33cr%65t", &[]).0, 200);
    assert_eq!(get(&s, "/api/programs", &[("Authorization", "bearer s3cret")]).0, 200);
    assert_eq!(get(&s, "/api/programs?token=s3cre", &[]).0, 401);
    assert_eq!(command_as(&s, "NOW", &[]).0, 401);
    assert_eq!(command_as(&s, "NOW", &[("Authorization", "Bearer s3cret")]).0, 200);
    s.stop();
    // Off loopback a token is not optional.
    let mut cfg = config(Speed::Times(1.0), false, None);
    cfg.addr = "0.0.0.0:0".parse().unwrap();
    let e = linc_serve::start(plant("examples/sequences/plant.json"), cfg).err().expect("refused");
    assert!(e.to_string().contains("--token"), "{e}");
}

/// Reads one event stream until it has seen `values` and `picture` events
/// (and a status), then returns what it saw.
fn stream(addr: std::net::SocketAddr) -> Vec<String> {
    let resp = agent().get(format!("http://{addr}/api/events")).call().expect("stream");
    assert_eq!(resp.headers().get("content-type").and_then(|v| v.to_str().ok()), Some("text/event-stream"));
    let mut seen = Vec::new();
    let reader = std::io::BufReader::new(resp.into_body().into_reader());
    for line in reader.lines() {
        let Ok(line) = line else { break };
        if let Some(name) = line.strip_prefix("event: ") {
            seen.push(name.to_string());
        }
        if ["status", "values", "picture"].iter().all(|n| seen.iter().any(|s| s == n)) {
            break;
        }
    }
    seen
}

#[test]
fn twenty_clients_stream_events_at_once() {
    let s = serve("examples/sequences/plant.json", config(Speed::Times(20.0), false, None));
    let addr = s.addr();
    let clients: Vec<_> = (0..20).map(|_| std::thread::spawn(move || stream(addr))).collect();
    for c in clients {
        let seen = c.join().expect("client");
        assert!(seen.iter().any(|e| e == "values") && seen.iter().any(|e| e == "picture"), "{seen:?}");
    }
    // A stream still open (its headers have arrived) ends when the server
    // stops: the reader sees the end of the body.
    let resp = agent().get(format!("http://{addr}/api/events")).call().expect("stream");
    let reader = std::thread::spawn(move || std::io::BufReader::new(resp.into_body().into_reader()).lines().count());
    s.stop();
    reader.join().expect("reader ends");
}

#[test]
fn a_served_run_ends_where_linc_run_would() {
    let mut cfg = config(Speed::Max, false, None);
    cfg.until_us = Some(600_000_000);
    let s = serve("examples/sequences/plant.json", cfg);
    s.wait_finished();
    let served = s.stop();
    let mut alone = plant("examples/sequences/plant.json").into_strategy().expect("a strategy");
    let failures = alone.run_for(600_000_000, None);
    assert!(failures.is_empty());
    assert_eq!(served.console.strategy.elapsed_us(), 600_000_000);
    assert_eq!(served.console.strategy.store.cells, alone.store.cells);
    assert_eq!(served.late, 0);
}

/// At speed 1 the plant follows the wall clock: three simulated seconds
/// take three seconds and every scan of them runs (none skipped, however
/// the machine is loaded: a late one still runs). What keeps scans on time
/// is counted, not timed: a streaming client and the page's questions put
/// at most a handful of requests between two scans. (Late scans are a
/// measurement of the machine: the README's hour-long runs count them.)
/// A client that asks one question after another has one waiting at most.
#[test]
fn at_speed_one_every_scan_runs_and_clients_wait_their_turn() {
    let mut cfg = config(Speed::Times(1.0), false, None);
    cfg.until_us = Some(3_000_000);
    let s = serve("examples/strategy/plant.json", cfg);
    let addr = s.addr();
    // A client streams while the plant runs, and another asks questions.
    std::thread::spawn(move || {
        if let Ok(resp) = agent().get(format!("http://{addr}/api/events")).call() {
            let _ = std::io::BufReader::new(resp.into_body().into_reader()).lines().count();
        }
    });
    let t = Instant::now();
    while !s.finished() {
        let _ = get(&s, "/api/blocks/TANK1", &[]);
    }
    let wall = t.elapsed();
    let done = s.stop();
    assert!(wall >= Duration::from_millis(2900), "real time: {wall:?}");
    // Task 1 runs every 100 ms: the instants 0, 0.1 … 2.9 s.
    assert!(done.scans >= 30, "{}", done.scans);
    assert!(done.busiest <= 1, "{} requests of one client waited for a scan", done.busiest);
    eprintln!("at speed 1: {} scans, {} late", done.scans, done.late);
}

#[test]
fn a_trend_starts_with_the_recent_past() {
    let s = serve("examples/sequences/plant.json", config(Speed::Times(20.0), false, None));
    // Thirty simulated seconds of filling, published as they went.
    let trend = || json(&get(&s, "/api/trend/r1.level", &[]).1);
    common::eventually("30 s of simulated time", || trend()["now"].as_f64().is_some_and(|now| now >= 30.0));
    common::eventually("5 points of the trend", || trend()["points"].as_array().is_some_and(|p| p.len() >= 5));
    let (code, body) = get(&s, "/api/trend/r1.level", &[]);
    assert_eq!(code, 200, "{body}");
    let t = json(&body);
    assert_eq!(t["field"], "R1.Level", "named as the database names it");
    let points = t["points"].as_array().expect("points");
    assert!(points.len() >= 5, "30 simulated seconds of filling: {t}");
    let times: Vec<f64> = points.iter().map(|p| p[0].as_f64().unwrap()).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]) && times.last() <= t["now"].as_f64().as_ref());
    assert_eq!(get(&s, "/api/trend/R1.Nope", &[]).0, 404);
    // The page's trend is linc-draw's, served as a picture: the level on a
    // plot with a value scale, the valve as a strip, a time axis.
    let (code, svg) = get(&s, "/api/pictures/trend%3A60%3Ar1.level%2CR1.FillVlv", &[]);
    assert_eq!(code, 200, "{svg}");
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"linc trend\""), "{svg}");
    assert!(svg.contains("<g id=\"trend-R1.Level\" class=\"series\">"), "{svg}");
    assert!(svg.contains("<g id=\"strip-R1.FillVlv\" class=\"strip\">"), "{svg}");
    assert_eq!(svg.matches("class=\"dim\" text-anchor=\"end\"").count(), 5, "a value scale of five: {svg}");
    assert!(svg.matches("class=\"dim\" text-anchor=\"middle\">").count() >= 4, "a time axis: {svg}");
    assert_eq!(get(&s, "/api/pictures/trend%3A60%3AR1.Nope", &[]).0, 404);
    assert_eq!(get(&s, "/api/pictures/trend%3A0%3AR1.Level", &[]).0, 404, "a window of no time");
    s.stop();
}

/// The live ladder shows what the action's last execution ran: the
/// example's rung 5 jumps to `_End`, so rungs 6–8 are drawn not run.
#[test]
fn the_live_ladder_shows_the_rungs_a_taken_jump_skipped() {
    let s = serve("examples/ladder/plant.json", config(Speed::Times(20.0), false, None));
    let class = |svg: &str, n: usize| {
        let open = format!("<g id=\"rung-{n}\" class=\"");
        let rest = svg.find(&open).map_or("", |i| &svg[i + open.len()..]);
        rest[..rest.find('"').unwrap_or(0)].to_string()
    };
    common::eventually("a scan of the ladder", || class(&get(&s, "/api/pictures/LAD", &[]).1, 6) == "rung skipped");
    let svg = get(&s, "/api/pictures/LAD", &[]).1;
    let classes: Vec<String> = (1..=8).map(|n| class(&svg, n)).collect();
    assert_eq!(classes[3..], ["rung powered", "rung powered", "rung skipped", "rung skipped", "rung skipped"]);
    s.stop();
}

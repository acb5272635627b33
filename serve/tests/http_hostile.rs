//! The HTTP server as a hostile client sees it, over real TCP on
//! 127.0.0.1 with hand-written requests (every byte of each is the test's):
//! a DNS-rebinding page's `Host`, origins that differ only in scheme or
//! port, empty tokens, near-JSON media types, errors that must be JSON, the
//! connection cap, and `ADVANCE` bounded and counted.

mod common;

use common::{plant, serve};
use linc_serve::{Config, Limits, Server};
use serde_json::Value;
use std::io::{Read, Write};
use std::net::TcpStream;
use std::time::Duration;

const PLANT: &str = "examples/sequences/plant.json";

fn writes() -> Config {
    Config { allow_writes: true, ..common::config() }
}

/// Sends `head` (without the final blank line) and `body`, with
/// `Connection: close`, and returns the status and the body as JSON.
fn raw(s: &Server, head: &str, body: &str) -> (u16, Value) {
    let mut t = TcpStream::connect(s.addr()).unwrap();
    t.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let req = format!("{head}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}", body.len());
    t.write_all(req.as_bytes()).unwrap();
    let mut out = Vec::new();
    t.read_to_end(&mut out).unwrap();
    parse(&out)
}

fn parse(out: &[u8]) -> (u16, Value) {
    let text = String::from_utf8_lossy(out);
    let (head, body) = text.split_once("\r\n\r\n").unwrap_or_else(|| panic!("no response head: {text:?}"));
    let status = head.split(' ').nth(1).and_then(|c| c.parse().ok()).unwrap_or_else(|| panic!("{head}"));
    assert!(head.to_ascii_lowercase().contains("content-type: application/json"), "not JSON: {head}");
    let length =
        head.lines().find_map(|l| l.to_ascii_lowercase().strip_prefix("content-length:").map(|n| n.trim().to_string()));
    if let Some(n) = length {
        assert_eq!(n.parse::<usize>().ok(), Some(body.len()), "Content-Length says {n}, the body has {}", body.len());
    }
    let json = serde_json::from_str(body).unwrap_or_else(|e| panic!("{e}: body {body:?}"));
    (status, json)
}

fn host(s: &Server) -> String {
    format!("127.0.0.1:{}", s.addr().port())
}

#[test]
fn a_request_naming_another_host_is_refused_whatever_it_asks() {
    let s = serve(PLANT, writes());
    let port = s.addr().port();
    let evil = format!("evil.example:{port}");
    for (method, path, body) in [
        ("GET", "/", ""),
        ("GET", "/api/programs", ""),
        ("GET", "/api/blocks", ""),
        ("GET", "/api/events", ""),
        ("POST", "/api/command", r#"{"command": "M FILLER.Level=5"}"#),
        ("GET", "/no/such/page", ""),
    ] {
        let head = format!(
            "{method} {path} HTTP/1.1\r\nHost: {evil}\r\nOrigin: http://{evil}\r\nContent-Type: application/json"
        );
        let (status, v) = raw(&s, &head, body);
        assert_eq!(status, 421, "{method} {path}: {v}");
        assert!(v["error"].as_str().unwrap().contains("--allow-host"), "{v}");
    }
    // A port other than the server's is another host too.
    let (status, _) = raw(&s, &format!("GET /api/programs HTTP/1.1\r\nHost: 127.0.0.1:{}", port + 1), "");
    assert_eq!(status, 421);
    // The loopback names and the bound address are the server's own.
    for name in ["127.0.0.1", "localhost", "[::1]"] {
        let (status, _) = raw(&s, &format!("GET /api/programs HTTP/1.1\r\nHost: {name}:{port}"), "");
        assert_eq!(status, 200, "{name}");
    }
    s.stop();
    // A name given with --allow-host is allowed, and no other.
    let s = serve(PLANT, Config { allow_hosts: vec!["plant.example".into()], ..writes() });
    let port = s.addr().port();
    let (status, _) = raw(&s, &format!("GET /api/programs HTTP/1.1\r\nHost: PLANT.example:{port}"), "");
    assert_eq!(status, 200);
    let (status, _) = raw(&s, &format!("GET /api/programs HTTP/1.1\r\nHost: evil.example:{port}"), "");
    assert_eq!(status, 421);
    s.stop();
}

#[test]
fn an_origin_must_match_in_scheme_host_and_port() {
    let s = serve(PLANT, writes());
    let h = host(&s);
    let post = |origin: &str| {
        let head =
            format!("POST /api/command HTTP/1.1\r\nHost: {h}\r\nOrigin: {origin}\r\nContent-Type: application/json");
        raw(&s, &head, r#"{"command": "NOW"}"#).0
    };
    assert_eq!(post(&format!("http://{h}")), 200);
    assert_eq!(post(&format!("https://{h}")), 403, "another scheme");
    assert_eq!(post(&format!("http://127.0.0.1:{}", s.addr().port() + 1)), 403, "another port");
    assert_eq!(post("null"), 403, "a sandboxed frame or a file");
    s.stop();
}

#[test]
fn only_application_json_is_a_command() {
    let s = serve(PLANT, writes());
    let h = host(&s);
    for (ct, want) in [
        ("application/json", 200),
        ("application/json; charset=utf-8", 200),
        ("application/jsonp", 415),
        ("application/json-patch+json", 415),
        ("text/plain", 415),
    ] {
        let head = format!("POST /api/command HTTP/1.1\r\nHost: {h}\r\nContent-Type: {ct}");
        assert_eq!(raw(&s, &head, r#"{"command": "NOW"}"#).0, want, "{ct}");
    }
    s.stop();
}

#[test]
fn every_error_is_a_json_body() {
    let s = serve(PLANT, writes());
    let h = host(&s);
    let cases = [
        (format!("GET /no/such/page HTTP/1.1\r\nHost: {h}"), String::new(), 404),
        (format!("GET /api/command HTTP/1.1\r\nHost: {h}"), String::new(), 405),
        (format!("DELETE /api/blocks HTTP/1.1\r\nHost: {h}"), String::new(), 405),
        (format!("GET /api/blocks/%FF%FE HTTP/1.1\r\nHost: {h}"), String::new(), 400),
        (
            format!("POST /api/command HTTP/1.1\r\nHost: {h}\r\nContent-Type: application/json"),
            format!(r#"{{"command": "{}"}}"#, "D ".repeat(40_000)),
            413,
        ),
        (format!("POST /api/command HTTP/1.1\r\nHost: {h}\r\nContent-Type: application/json"), "{".into(), 400),
    ];
    for (head, body, want) in cases {
        let (status, v) = raw(&s, &head, &body);
        assert_eq!(status, want, "{head}: {v}");
        assert!(v["error"].as_str().is_some_and(|e| !e.is_empty()), "{head}: {v}");
    }
    s.stop();
}

#[test]
fn every_response_forbids_frames_referrers_sniffing_and_foreign_scripts() {
    let s = serve(PLANT, writes());
    let h = host(&s);
    for path in ["/", "/app.js", "/api/programs", "/no/such/page"] {
        let mut t = TcpStream::connect(s.addr()).unwrap();
        t.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
        t.write_all(format!("GET {path} HTTP/1.1\r\nHost: {h}\r\nConnection: close\r\n\r\n").as_bytes()).unwrap();
        let mut out = Vec::new();
        t.read_to_end(&mut out).unwrap();
        let head = String::from_utf8_lossy(&out).split("\r\n\r\n").next().unwrap().to_ascii_lowercase();
        for needle in [
            "content-security-policy: default-src 'self'; script-src 'self';",
            "frame-ancestors 'none'",
            "x-frame-options: deny",
            "x-content-type-options: nosniff",
            "referrer-policy: no-referrer",
        ] {
            assert!(head.contains(needle), "{path} lacks {needle}:\n{head}");
        }
    }
    s.stop();
}

#[test]
fn an_empty_or_blank_token_is_refused_at_the_start() {
    for token in ["", "   ", "\t"] {
        let cfg = Config { token: Some(token.into()), ..common::config() };
        let e = linc_serve::start(plant(PLANT), cfg).err().expect("refused");
        assert_eq!(e.diagnostics()[0].code, linc_format::Code::E0903);
        assert!(e.to_string().contains("empty or blank"), "{e}");
    }
}

#[test]
fn clients_over_the_cap_get_a_json_503_and_are_logged() {
    let lines = std::sync::Arc::new(std::sync::Mutex::new(Vec::<String>::new()));
    let kept = lines.clone();
    let limits = Limits { max_clients: 2, ..Limits::default() };
    let log: linc_serve::Log = std::sync::Arc::new(move |l| kept.lock().unwrap().push(l));
    let s = serve(PLANT, Config { limits, log, ..common::config() });
    // Two connections hold the two places (accepted in the order made).
    let held: Vec<TcpStream> = (0..2).map(|_| TcpStream::connect(s.addr()).unwrap()).collect();
    let mut third = TcpStream::connect(s.addr()).unwrap();
    third.set_read_timeout(Some(Duration::from_secs(30))).unwrap();
    let mut out = Vec::new();
    third.read_to_end(&mut out).unwrap();
    let (status, v) = parse(&out);
    assert_eq!(status, 503);
    assert!(v["error"].as_str().unwrap().contains("too many connections"), "{v}");
    drop(held);
    // Once they are gone, a client is served again.
    common::eventually("a place freed", || {
        TcpStream::connect(s.addr()).is_ok_and(|mut t| {
            let req = format!("GET /api/programs HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\r\n", host(&s));
            let mut out = Vec::new();
            t.write_all(req.as_bytes()).is_ok() && t.read_to_end(&mut out).is_ok() && out.starts_with(b"HTTP/1.1 200")
        })
    });
    s.stop();
    let log = lines.lock().unwrap().join("\n");
    assert!(log.contains("http: refused 127.0.0.1:"), "{log}");
    assert!(log.contains("2 clients is the limit"), "{log}");
}

#[test]
fn advance_is_bounded_and_its_scans_are_counted() {
    let s = serve(PLANT, writes());
    let h = host(&s);
    let post = |line: &str| {
        let head = format!("POST /api/command HTTP/1.1\r\nHost: {h}\r\nContent-Type: application/json");
        raw(&s, &head, &serde_json::json!({ "command": line }).to_string())
    };
    let (status, v) = post("ADVANCE 366d");
    assert_eq!(status, 200);
    assert_eq!(v["replies"][0]["code"], "C0013", "{v}");
    let before = raw(&s, &format!("GET /api/programs HTTP/1.1\r\nHost: {h}"), "").1["scans"].as_u64().unwrap();
    // The example's one task runs every second: 100 s is 100 scans.
    let (_, v) = post("ADVANCE 100s");
    assert_eq!(v["replies"][0]["ok"], true, "{v}");
    let done = s.stop();
    assert!(done.scans >= before + 100, "{} scans after {before} and an ADVANCE of 100", done.scans);
}

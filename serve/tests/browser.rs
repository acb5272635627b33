//! The monitor page in a real browser: Debian's headless Chromium, driven
//! over WebDriver by chromedriver (both installed by `.ci/run`). The page
//! of the sequences example is opened; the test waits until `#step-Fill`
//! has class `active`, clicks a step on the page to hold it and sees the
//! hold in `/api/programs`, adds a trend, saves screenshots under
//! `target/monitor/`, and requires that the browser logged no error.
//!
//! Without chromium and chromedriver the test says so and passes, unless
//! `LINC_REQUIRE_BROWSER` is set (as `.ci/run` sets it).

mod common;

use base64::Engine;
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
const CHROMIUM: &str = "/usr/bin/chromium";
const DRIVER: &str = "/usr/bin/chromedriver";

fn agent() -> ureq::Agent {
    ureq::Agent::config_builder()
        .http_status_as_error(false)
        .timeout_global(Some(Duration::from_secs(60)))
        .build()
        .into()
}

/// A WebDriver session on chromedriver; the driver is killed on drop.
struct Browser {
    driver: Child,
    base: String,
    session: String,
}

impl Drop for Browser {
    fn drop(&mut self) {
        let _ = agent().delete(format!("{}/session/{}", self.base, self.session)).call();
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

fn call(method: &str, url: &str, body: Option<Value>) -> Value {
    let a = agent();
    let mut resp = match (method, body) {
        ("GET", _) => a.get(url).call(),
        ("DELETE", _) => a.delete(url).call(),
        (_, b) => a.post(url).header("Content-Type", "application/json").send(b.unwrap_or(json!({})).to_string()),
    }
    .unwrap_or_else(|e| panic!("{method} {url}: {e}"));
    let text = resp.body_mut().read_to_string().expect("body");
    serde_json::from_str(&text).unwrap_or_else(|_| panic!("{method} {url}: not JSON: {text}"))
}

impl Browser {
    fn start(profile: &Path) -> Browser {
        let port = std::net::TcpListener::bind("127.0.0.1:0").unwrap().local_addr().unwrap().port();
        let driver = Command::new(DRIVER)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start chromedriver");
        let base = format!("http://127.0.0.1:{port}");
        let t = Instant::now();
        while agent().get(format!("{base}/status")).call().is_err() {
            assert!(t.elapsed() < Duration::from_secs(60), "chromedriver did not start");
            std::thread::sleep(Duration::from_millis(100));
        }
        let args = [
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--window-size=1280,1400",
        ]
        .iter()
        .map(|s| s.to_string())
        .chain([format!("--user-data-dir={}", profile.display())])
        .collect::<Vec<_>>();
        let caps = json!({"capabilities": {"alwaysMatch": {
            "browserName": "chrome",
            "goog:chromeOptions": {"binary": CHROMIUM, "args": args},
            "goog:loggingPrefs": {"browser": "ALL"}
        }}});
        let mut b = Browser { driver, base, session: String::new() };
        let v = call("POST", &format!("{}/session", b.base), Some(caps));
        b.session = v["value"]["sessionId"].as_str().unwrap_or_else(|| panic!("no session: {v}")).to_string();
        b
    }

    fn url(&self, path: &str) -> String {
        format!("{}/session/{}{path}", self.base, self.session)
    }

    fn script(&self, js: &str) -> Value {
        call("POST", &self.url("/execute/sync"), Some(json!({"script": js, "args": []})))["value"].clone()
    }

    fn wait_for(&self, js: &str, what: &str) {
        let t = Instant::now();
        while self.script(js) != json!(true) {
            assert!(t.elapsed() < Duration::from_secs(60), "waited a minute for {what}");
            std::thread::sleep(Duration::from_millis(100));
        }
    }

    fn screenshot(&self, to: &Path) {
        let v = call("GET", &self.url("/screenshot"), None);
        let png = base64::engine::general_purpose::STANDARD.decode(v["value"].as_str().expect("PNG")).expect("base64");
        assert!(png.starts_with(b"\x89PNG"));
        std::fs::write(to, png).expect("write screenshot");
    }

    fn click(&self, css: &str) {
        let v = call("POST", &self.url("/element"), Some(json!({"using": "css selector", "value": css})));
        let id = v["value"].as_object().and_then(|o| o.values().next()).and_then(Value::as_str);
        let id = id.unwrap_or_else(|| panic!("no element {css}: {v}")).to_string();
        let r = call("POST", &self.url(&format!("/element/{id}/click")), Some(json!({})));
        assert!(r["value"].is_null(), "click {css}: {r}");
    }

    /// Every entry of the browser's log (console messages, page errors).
    fn log(&self) -> Vec<Value> {
        let v = call("POST", &self.url("/se/log"), Some(json!({"type": "browser"})));
        v["value"].as_array().cloned().unwrap_or_else(|| panic!("browser log: {v}"))
    }
}

fn shots() -> PathBuf {
    let dir = Path::new(ROOT).join("target/monitor");
    std::fs::create_dir_all(&dir).expect("target/monitor");
    dir
}

#[test]
fn the_monitor_page_shows_the_running_sequence_and_holds_a_step() {
    if !Path::new(CHROMIUM).exists() || !Path::new(DRIVER).exists() {
        assert!(
            std::env::var_os("LINC_REQUIRE_BROWSER").is_none(),
            "{CHROMIUM} and {DRIVER} are needed (apt-get install chromium chromium-driver)"
        );
        eprintln!("skipped: no {CHROMIUM} or {DRIVER} (.ci/run installs them)");
        return;
    }
    let cfg = linc_serve::Config {
        speed: linc_serve::Speed::Times(2.0),
        allow_writes: true,
        ..linc_serve::Config::new("127.0.0.1:0".parse().unwrap())
    };
    let server = common::serve("examples/sequences/plant.json", cfg);
    let profile = linc_test_support::temp_dir("chromium-profile");
    let b = Browser::start(&profile);
    call("POST", &b.url("/url"), Some(json!({"url": format!("http://{}/", server.addr())})));
    b.wait_for("return !!document.querySelector('#step-Fill.active')", "#step-Fill to be active");
    let dir = shots();
    b.screenshot(&dir.join("sequence-running.png"));
    // Hold a step from the page: a click on the step in the live chart.
    b.wait_for("return !document.body.classList.contains('readonly')", "the controls");
    // On the step's box, as an engineer clicks it (the group's centre may be between its parts).
    b.click("#step-Heat rect");
    let api = format!("http://{}/api/programs", server.addr());
    let t = Instant::now();
    loop {
        let status: Value = call("GET", &api, None);
        let batch = status["programs"].as_array().unwrap().iter().find(|p| p["block"] == "BATCH").cloned().unwrap();
        if batch["held"] == json!(["Heat"]) {
            break;
        }
        assert!(t.elapsed() < Duration::from_secs(60), "the hold never reached the plant: {batch}");
        std::thread::sleep(Duration::from_millis(100));
    }
    b.wait_for("return !!document.querySelector('#step-Heat.held')", "the page to show the hold");
    b.screenshot(&dir.join("sequence-held.png"));
    // A trend chosen on the page starts with the recent past and is drawn.
    b.script("document.querySelector('#trend-field').value = 'R1.Level'; document.querySelector('#trend-form').requestSubmit(); return true;");
    b.wait_for("return !!document.querySelector('#trend svg path')", "the trend of R1.Level");
    b.screenshot(&dir.join("trend.png"));
    let errors: Vec<Value> = b.log().into_iter().filter(|e| e["level"] == "SEVERE").collect();
    assert!(errors.is_empty(), "the page logged errors: {errors:?}");
    drop(b);
    server.stop();
}

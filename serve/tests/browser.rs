//! The monitor page in a real browser: Debian's headless Chromium, driven
//! over WebDriver by chromedriver (both installed by `.ci/run`). The page
//! of the sequences example is opened; the test waits until `#step-Fill`
//! has class `active`, clicks a step on the page to hold it and sees the
//! hold in `/api/programs`, adds a trend, and requires that the browser
//! logged no error. The ladder example's page must grey out the rungs a
//! taken jump skipped and colour values by state; the FST example's
//! program list and picture must name the same current step. Each test
//! saves screenshots under `target/ci-artifacts/monitor/` (docs/testing.md),
//! which CI keeps as artifacts.
//!
//! A page served on another name (DNS rebinding: `evil.test`, mapped to
//! 127.0.0.1 by Chromium's resolver rules) has every API call refused.
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
        Browser::start_with(profile, &[])
    }

    /// A browser with `extra` command-line switches.
    fn start_with(profile: &Path, extra: &[&str]) -> Browser {
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
        .chain(extra)
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

/// Where the screenshots go: kept by CI as artifacts (docs/testing.md).
fn shots() -> PathBuf {
    let dir = Path::new(ROOT).join("target/ci-artifacts/monitor");
    std::fs::create_dir_all(&dir).expect("target/ci-artifacts/monitor");
    dir
}

/// One browser at a time: the tests run on threads of one process, and
/// two Chromiums on a small CI machine only slow each other down.
static ONE_BROWSER: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// Whether the browser is there; without it the test passes, unless
/// `LINC_REQUIRE_BROWSER` is set.
fn have_browser() -> bool {
    if !Path::new(CHROMIUM).exists() || !Path::new(DRIVER).exists() {
        assert!(
            std::env::var_os("LINC_REQUIRE_BROWSER").is_none(),
            "{CHROMIUM} and {DRIVER} are needed (apt-get install chromium chromium-driver)"
        );
        eprintln!("skipped: no {CHROMIUM} or {DRIVER} (.ci/run installs them)");
        return false;
    }
    true
}

/// Serves `db` (writes allowed, at `speed` times real time) and opens its
/// page in a new browser.
fn open(db: &str, speed: f64, tag: &str) -> (linc_serve::Server, Browser) {
    let cfg = linc_serve::Config {
        speed: linc_serve::Speed::Times(speed),
        allow_writes: true,
        ..linc_serve::Config::new("127.0.0.1:0".parse().unwrap())
    };
    let server = common::serve(db, cfg);
    let profile = linc_test_support::temp_dir(&format!("chromium-profile-{tag}"));
    let b = Browser::start(&profile);
    call("POST", &b.url("/url"), Some(json!({"url": format!("http://{}/", server.addr())})));
    (server, b)
}

fn no_errors_logged(b: &Browser) {
    let errors: Vec<Value> = b.log().into_iter().filter(|e| e["level"] == "SEVERE").collect();
    assert!(errors.is_empty(), "the page logged errors: {errors:?}");
}

#[test]
fn the_monitor_page_shows_the_running_sequence_and_holds_a_step() {
    let _one = ONE_BROWSER.lock().unwrap_or_else(|e| e.into_inner());
    if !have_browser() {
        return;
    }
    let (server, b) = open("examples/sequences/plant.json", 2.0, "sequence");
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
    b.wait_for(
        "const g = document.getElementById('trend-R1.Level');
         return !!(g && g.closest('#trend svg.linc.trend') && g.querySelector('polyline'));",
        "the trend of R1.Level",
    );
    // The trend is linc-draw's: a value scale and a time axis with ticks
    // in simulated time, not a bare sparkline.
    let axes = b.script(
        "const t = [...document.querySelectorAll('#trend svg.trend text.dim')];
         const ticks = t.filter(e => e.getAttribute('text-anchor') === 'middle').map(e => e.textContent);
         const scale = t.filter(e => e.getAttribute('text-anchor') === 'end').map(e => e.textContent);
         return [ticks.length, ticks.every(x => /^([0-9]+m)?[0-9.]+s$/.test(x)), scale.length,
                 scale.every(x => Number.isFinite(Number(x)))];",
    );
    let axes = axes.as_array().expect("axes").clone();
    assert!(axes[0].as_u64().unwrap_or(0) >= 2, "time ticks: {axes:?}");
    assert_eq!((&axes[1], &axes[2], &axes[3]), (&json!(true), &json!(5), &json!(true)), "{axes:?}");
    b.script("document.querySelector('#trend').scrollIntoView(); return true;");
    b.screenshot(&dir.join("trend.png"));
    no_errors_logged(&b);
    drop(b);
    server.stop();
}

/// The ladder example's rung 5 jumps to `_End` (`[/Dig_5b.In]` passes):
/// the live page draws rungs 6–8 as not run, with no power, and colours
/// each value by its state.
#[test]
fn the_live_ladder_greys_the_rungs_a_taken_jump_skipped() {
    let _one = ONE_BROWSER.lock().unwrap_or_else(|e| e.into_inner());
    if !have_browser() {
        return;
    }
    let (server, b) = open("examples/ladder/plant.json", 1.0, "ladder");
    b.wait_for("return !!document.querySelector('#rung-6.skipped')", "#rung-6 drawn as not run");
    let classes = b.script(
        "return [...document.querySelectorAll('#pictures g.rung')].map(g => g.id + ' ' + g.getAttribute('class'));",
    );
    assert_eq!(
        classes,
        json!([
            "rung-1 rung",
            "rung-2 rung",
            "rung-3 rung",
            "rung-4 rung powered",
            "rung-5 rung powered",
            "rung-6 rung skipped",
            "rung-7 rung skipped",
            "rung-8 rung skipped"
        ]),
    );
    let on = b.script("return document.querySelectorAll('#rung-7 .on, #rung-8 .on, #rung-6 .on').length;");
    assert_eq!(on, json!(0), "no power in a rung that did not run");
    // The skipped rung is drawn dashed and faded, as computed by the browser.
    let look = b.script(
        "const w = document.querySelector('#rung-7 line.wire'); const g = document.querySelector('#rung-7');
         return [getComputedStyle(w).strokeDasharray, getComputedStyle(g).opacity];",
    );
    assert_eq!(look, json!(["4px, 3px", "0.55"]));
    // TRUE in the energised green, FALSE grey: not the same colour (rung 2's
    // contacts read FALSE, its negated coil's Dig_2c.Out TRUE).
    let fills = b.script(
        "const f = (s) => getComputedStyle(document.querySelector('#rung-2 ' + s)).fill;
         return [f('text.value.true'), f('text.value.false')];",
    );
    let fills = fills.as_array().expect("two colours").clone();
    assert_ne!(fills[0], fills[1], "TRUE and FALSE look different");
    assert!(
        matches!(fills[0].as_str(), Some("rgb(26, 127, 55)") | Some("rgb(63, 185, 80)")),
        "TRUE is green: {fills:?}"
    );
    b.screenshot(&shots().join("ladder-skipped-rungs.png"));
    no_errors_logged(&b);
    drop(b);
    server.stop();
}

/// The FST example's program list and the table's picture name the same
/// current step: the one the table goes on with. The table is suspended
/// first, so that both show one state.
#[test]
fn the_fst_program_row_and_its_picture_name_the_same_step() {
    let _one = ONE_BROWSER.lock().unwrap_or_else(|e| e.into_inner());
    if !have_browser() {
        return;
    }
    let (server, b) = open("examples/fst/plant.json", 4.0, "fst");
    b.wait_for(
        "return !!document.querySelector('#pictures .picture[data-block=\"FST 1\"] .fst-step.current')",
        "the table's picture",
    );
    common::console_line(&server, "SUSPEND FST 1");
    let agree = "const row = [...document.querySelectorAll('#programs tbody tr')]
                   .find(tr => tr.children[0].textContent === 'FST 1');
                 const m = row && /^step (\\d+) /.exec(row.children[4].textContent);
                 const cur = document.querySelector('#pictures .picture[data-block=\"FST 1\"] .fst-step.current');
                 return !!(m && row.children[3].textContent === 'suspended' && cur && cur.id === 'fst-step-' + m[1]);";
    b.wait_for(agree, "the program list and the picture to name the same step");
    b.screenshot(&shots().join("fst-current-step.png"));
    no_errors_logged(&b);
    drop(b);
    server.stop();
}

/// The page a rebinding attacker serves from `evil.test:PORT` before the
/// name is re-pointed: once the monitor listens on the same port, its
/// script calls every API as same-origin and records what came back.
const ATTACK: &str = r#"<!doctype html><meta charset="utf-8"><title>cat pictures</title>
<script>
async function attack() {
  const calls = [
    ["page", "/", {}],
    ["programs", "/api/programs", {}],
    ["blocks", "/api/blocks", {}],
    ["picture", "/api/pictures/BATCH", {}],
    ["trend", "/api/trend/R1.Level", {}],
    ["events", "/api/events", {}],
    ["command", "/api/command", {method: "POST", headers: {"Content-Type": "application/json"},
                                 body: JSON.stringify({command: "M R1.Level=99"})}],
  ];
  const out = {};
  for (const [name, path, init] of calls) {
    try {
      const r = await fetch(path, init);
      out[name] = {status: r.status, body: (await r.text()).slice(0, 300)};
    } catch (e) {
      out[name] = {error: String(e)};
    }
  }
  window.results = out;
}
</script>"#;

/// Serves [`ATTACK`] on `listener` to each request until `done`, with
/// `Connection: close` so the browser keeps no connection to it.
fn serve_attack(listener: std::net::TcpListener, done: std::sync::Arc<std::sync::atomic::AtomicBool>) {
    listener.set_nonblocking(true).expect("nonblocking");
    while !done.load(std::sync::atomic::Ordering::Relaxed) {
        match listener.accept() {
            Ok((mut c, _)) => {
                use std::io::{Read, Write};
                c.set_nonblocking(false).expect("blocking");
                c.set_read_timeout(Some(Duration::from_secs(1))).expect("timeout");
                let mut buf = [0u8; 4096];
                // Chromium opens spare connections ahead of need: one that
                // asks nothing is closed unanswered, or the page written to
                // it would be read as the answer to the next request on it.
                if !c.read(&mut buf).is_ok_and(|n| n > 0) {
                    continue;
                }
                let head = format!(
                    "HTTP/1.1 200 OK\r\nContent-Type: text/html\r\nCache-Control: no-store\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                    ATTACK.len()
                );
                let _ = c.write_all(head.as_bytes());
                let _ = c.write_all(ATTACK.as_bytes());
            }
            Err(_) => std::thread::sleep(Duration::from_millis(20)),
        }
    }
}

/// DNS rebinding, as a browser lives it: a page loaded from `evil.test`
/// (Chromium resolves the name to 127.0.0.1), whose name then points at
/// the engineer's monitor on the same port. Every call its script makes is
/// same-origin to the browser, and every one is refused by the server
/// (421, the `Host` is not one it answers to), the write included.
#[test]
fn a_page_on_another_name_is_refused_every_api_call() {
    if !have_browser() {
        return;
    }
    let _one = ONE_BROWSER.lock().unwrap_or_else(|e| e.into_inner());
    let profile = linc_test_support::temp_dir("chromium-rebind");
    let b = Browser::start_with(&profile, &["--host-resolver-rules=MAP evil.test 127.0.0.1"]);
    let listener = std::net::TcpListener::bind("127.0.0.1:0").expect("a port");
    let port = listener.local_addr().expect("address").port();
    let done = std::sync::Arc::new(std::sync::atomic::AtomicBool::new(false));
    let attacker = {
        let done = done.clone();
        std::thread::spawn(move || serve_attack(listener, done))
    };
    call("POST", &b.url("/url"), Some(json!({"url": format!("http://evil.test:{port}/")})));
    b.wait_for("return typeof attack === 'function'", "the attacker's page");
    done.store(true, std::sync::atomic::Ordering::Relaxed);
    attacker.join().expect("the attacker's server");
    // The name now leads to the monitor, with writes allowed.
    let cfg = linc_serve::Config {
        allow_writes: true,
        ..linc_serve::Config::new(format!("127.0.0.1:{port}").parse().unwrap())
    };
    let server = common::serve("examples/sequences/plant.json", cfg);
    let before = common::api(&server, "R1", "Level");
    b.script("attack(); return true;");
    b.wait_for("return !!window.results", "the attack's calls");
    let results = b.script("return window.results;");
    for name in ["page", "programs", "blocks", "picture", "trend", "events", "command"] {
        let r = &results[name];
        assert_eq!(r["status"], 421, "{name}: {r}");
        let body: Value = serde_json::from_str(r["body"].as_str().unwrap_or("")).unwrap_or(Value::Null);
        assert!(body["error"].as_str().is_some_and(|e| e.contains("evil.test")), "{name}: {r}");
    }
    b.screenshot(&shots().join("rebinding-refused.png"));
    assert_eq!(common::api(&server, "R1", "Level"), before, "the write did not happen");
    drop(b);
    server.stop();
}

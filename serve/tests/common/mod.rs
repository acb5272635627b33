//! What the wire tests share: a served example plant and the monitor's
//! view of a field.
#![allow(dead_code)]

use linc_driver::plant::{Plant, PlantSpec};
use linc_serve::{Config, Server};
use std::path::Path;

pub const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// 2026-01-05 06:00 UTC, when every served test plant starts.
pub const T0: i64 = 1_767_592_800;

/// The plant `db` (relative to the repository, or absolute) as `linc
/// serve` builds it, from [`T0`].
pub fn plant(db: &str) -> Plant {
    let path = if Path::new(db).is_absolute() { Path::new(db).to_path_buf() } else { Path::new(ROOT).join(db) };
    let spec = PlantSpec { now: Some(T0), ..PlantSpec::strategy(path) };
    linc_driver::plant::build(&spec).unwrap_or_else(|p| panic!("{p}"))
}

/// Serves the plant `db` with `cfg`; wire log lines are dropped unless
/// `cfg` keeps them.
pub fn serve(db: &str, cfg: Config) -> Server {
    linc_serve::start(plant(db), cfg).unwrap_or_else(|p| panic!("{p}"))
}

/// A quiet configuration on loopback port 0: build on it with `..`.
pub fn config() -> Config {
    Config { log: std::sync::Arc::new(|_| {}), ..Config::new("127.0.0.1:0".parse().unwrap()) }
}

/// A field's value as the monitor's API shows it.
pub fn api(s: &Server, block: &str, field: &str) -> String {
    let url = format!("http://{}/api/blocks/{}", s.addr(), block.replace(' ', "%20"));
    let body = ureq::get(&url).call().expect("GET").body_mut().read_to_string().expect("body");
    let v: serde_json::Value = serde_json::from_str(&body).expect("JSON");
    let f = v["fields"].as_array().unwrap().iter().find(|f| f["name"] == field).expect("field");
    f["value"].as_str().unwrap().to_string()
}

/// Runs a console line on the served plant through the API.
pub fn console_line(s: &Server, line: &str) {
    let url = format!("http://{}/api/command", s.addr());
    let body = serde_json::json!({ "command": line }).to_string();
    ureq::post(&url).header("Content-Type", "application/json").send(body).expect("command");
}

/// Waits until `cond` holds (polled every 20 ms). Not a timing assertion:
/// the minute is only there to end a test that would otherwise hang, far
/// beyond what any load on the machine explains.
pub fn eventually(what: &str, mut cond: impl FnMut() -> bool) {
    let deadline = std::time::Instant::now() + std::time::Duration::from_secs(60);
    while !cond() {
        assert!(std::time::Instant::now() < deadline, "{what} never happened");
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
}

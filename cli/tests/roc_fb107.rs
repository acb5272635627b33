//! `linc roc poll` against `linc serve --roc` of the FB107 example, both as
//! processes over TCP on 127.0.0.1 and over a serial line (two
//! pseudo-terminals joined as by a null-modem cable): the module's command list beyond
//! 180/181 — the §6.1.2 layout of opcode 120 word for word, a day of
//! hourly values with 128 and 130, the device clock set with 8, and a
//! device reached behind another by store and forward (§6.3). The
//! expected words come from the archives `linc run --out` writes of the
//! same run (docs/fst-history.md), not from the device's replies.
mod common;

use serde_json::Value;
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

const HEAD: &str = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n";

/// A copy of examples/roc with a one-second task (a day runs quickly),
/// its store-and-forward link to 5,2 at `far` if given.
fn plant_copy(tag: &str, far: Option<&str>) -> PathBuf {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples/roc");
    let dir = linc_test_support::fresh_dir(tag);
    for f in ["drain.csv", "sim.stx"] {
        std::fs::copy(src.join(f), dir.join(f)).unwrap();
    }
    let text = std::fs::read_to_string(src.join("plant.json")).unwrap();
    let text = text.replacen('{', r#"{ "tasks": { "1": { "period": 1 } },"#, 1);
    let text = text.replace("127.0.0.1:4001", far.unwrap_or("127.0.0.1:4001"));
    std::fs::write(dir.join("plant.json"), text).unwrap();
    dir
}

/// How the host reaches the device: over TCP, or over a serial line the
/// device answers on at one end.
enum Via {
    Tcp,
    #[cfg(unix)]
    Serial(common::null_modem::NullModem),
}

/// A served plant; its ROC address (TCP), how the host reaches it, and
/// its log once stopped.
struct Device(std::process::Child, String, Vec<String>);

impl Device {
    fn start(db: &Path, unit: &str, extra: &[&str], via: &Via) -> Device {
        let db = db.to_string_lossy().into_owned();
        let mut args = vec!["serve", &db, "--http", "127.0.0.1:0", "--roc", "127.0.0.1:0", "--roc-address", unit];
        args.extend(["--allow-writes", "--speed", "0.001"]);
        #[cfg(unix)]
        if let Via::Serial(line) = via {
            args.extend(["--roc-serial", &line.paths[0], "--baud", "19200"]);
        }
        args.extend(extra);
        let mut child = common::spawn(&args);
        let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
        let _serving = lines.next().expect("a line").expect("text");
        let roc = lines.next().expect("the ROC line").expect("text");
        assert!(roc.starts_with(&format!("ROC protocol device {unit} on 127.0.0.1:")), "{roc}");
        let addr = roc.rsplit(' ').next().unwrap().to_string();
        let link = match via {
            Via::Tcp => vec!["--host".to_string(), addr.clone()],
            #[cfg(unix)]
            Via::Serial(line) => {
                let serial = lines.next().expect("the serial line").expect("text");
                assert!(serial.contains(&format!("on serial {}", line.paths[0])), "{serial}");
                vec!["--serial".into(), line.paths[1].clone(), "--baud".into(), "19200".into()]
            }
        };
        Device(child, addr, link)
    }

    /// Stops the device and returns what it logged.
    fn log(mut self) -> String {
        let _ = self.0.kill();
        let _ = self.0.wait();
        let mut text = String::new();
        self.0.stderr.take().unwrap().read_to_string(&mut text).unwrap();
        text
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Runs a command list against `dev` from `words`; the words after.
fn poll(dev: &Device, dir: &Path, cmds: &str, words: &str) -> (String, Value) {
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    std::fs::write(p("cmds.csv"), format!("{HEAD}{cmds}")).unwrap();
    std::fs::write(p("words.json"), words).unwrap();
    let (c, w, out) = (p("cmds.csv"), p("words.json"), p("out.json"));
    let mut args: Vec<&str> = vec!["roc", "poll"];
    args.extend(dev.2.iter().map(String::as_str));
    args.extend(["--commands", &c, "--words", &w, "--out", &out, "--timeout", "5s"]);
    let o = common::linc(&args);
    assert_eq!(o.status.code(), Some(0), "{}{}", common::stdout(&o), common::stderr(&o));
    (common::stdout(&o), serde_json::from_str(&std::fs::read_to_string(p("out.json")).unwrap()).unwrap())
}

/// Word `i` of a word table written by `--out` (runs by start address).
fn word(w: &Value, i: usize) -> u16 {
    for (start, run) in w.as_object().unwrap().iter().filter(|(k, _)| *k != "status") {
        let s: usize = start.parse().unwrap();
        let run = run.as_array().unwrap();
        if (s..s + run.len()).contains(&i) {
            return run[i - s].as_i64().unwrap() as u16;
        }
    }
    0
}

/// A float in two words, low word first (docs/roc-host.md).
fn float_words(v: f32) -> [u16; 2] {
    [v.to_bits() as u16, (v.to_bits() >> 16) as u16]
}

/// 2026-01-05 06:00 and 43 hours on (01:00 on 7 January): the logger has
/// written every hour from 07:00 on 5 January, and two midnights.
fn a_day_and_a_half(tag: &str) -> (PathBuf, Value) {
    let dir = plant_copy(tag, None);
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let args = ["run", &p("plant.json"), "--now", "2026-01-05T06:00:00", "--for", "43h", "--state", &p("state.json")];
    let o = common::linc(&[&args[..], &["--out", &p("after.json")]].concat());
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let after: Value = serde_json::from_str(&std::fs::read_to_string(p("after.json")).unwrap()).unwrap();
    (dir, after["roc"].clone())
}

#[test]
fn pointers_a_day_of_hours_and_the_clock_over_tcp() {
    pointers_a_day_of_hours_and_the_clock(Via::Tcp, "roc-fb107-day");
}

#[cfg(unix)]
#[test]
fn pointers_a_day_of_hours_and_the_clock_over_a_serial_line() {
    let line = common::null_modem::NullModem::new();
    pointers_a_day_of_hours_and_the_clock(Via::Serial(line), "roc-fb107-day-serial");
}

fn pointers_a_day_of_hours_and_the_clock(via: Via, tag: &str) {
    let (dir, roc) = a_day_and_a_half(tag);
    let state = dir.join("state.json").to_string_lossy().into_owned();
    let dev = Device::start(&dir.join("plant.json"), "25,2", &["--state", &state], &via);
    // 120 into words 0…; 128 of 6 January (point 1) into 100…; 130: 24
    // hourly values of point 1 from index 17 into 200…; 8 sets the clock
    // to 12:30:00 on 6 January 2026 from words 40….
    let cmds = "1,25,2,120,0,0,0,0,0,0\n1,25,2,128,3,20,100,0,0,0\n1,25,2,130,4,30,200,0,0,0\n1,25,2,8,6,40,0,0,0,0\n";
    let words = r#"{"20": [1, 6, 1], "30": [0, 1, 24, 17], "40": [0, 30, 12, 6, 1, 26]}"#;
    let (said, w) = poll(&dev, &dir, cmds, words);
    assert_eq!(said.lines().filter(|l| l.ends_with(": done")).count(), 4, "{said}");
    // §6.1.2's layout of opcode 120: six INT words, four BIN, two INT, six
    // BIN. The pointers: where each log and archive writes next.
    let total = |log: &str| roc[log]["total"].as_u64().unwrap() as u16;
    let expected = [total("alarms") % 240, total("events") % 240, 43, 0, 0, 0, 2, 0, 0, 0, 240, 240, 35, 0, 0, 0, 0, 0];
    let got: Vec<u16> = (0..18).map(|i| word(&w, i)).collect();
    assert_eq!(got, expected);
    // 128: point, month, day, hour and minute now, the day's first index,
    // then the 24 hours — the periodic entries stamped on 6 January.
    assert_eq!((0..6).map(|i| word(&w, 100 + i)).collect::<Vec<_>>(), [1, 1, 6, 1, 0, 17]);
    let point1 = &roc["history"]["points"][0];
    assert_eq!(point1["number"], 1);
    let hours: Vec<f32> = point1["periodic"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["time"].as_str().unwrap().starts_with("2026-01-06T"))
        .map(|e| e["value"].as_f64().unwrap() as f32)
        .collect();
    assert_eq!(hours.len(), 24);
    for (h, v) in hours.iter().enumerate() {
        let at = 106 + 2 * h;
        assert_eq!([word(&w, at), word(&w, at + 1)], float_words(*v), "hour {h} by 128");
        let at = 203 + 2 * h;
        assert_eq!([word(&w, at), word(&w, at + 1)], float_words(*v), "hour {h} by 130");
    }
    let daily = point1["daily"].as_array().unwrap().iter().find(|e| e["time"] == "2026-01-06T00:00:00").unwrap();
    assert_eq!([word(&w, 154), word(&w, 155)], float_words(daily["value"].as_f64().unwrap() as f32));
    assert_eq!((word(&w, 170), word(&w, 200), word(&w, 201), word(&w, 202)), (3, 0, 1, 24));
    assert!(dev.log().contains("set the clock to 2026-01-06T12:30:00"));
    drop(via);
}

#[test]
fn store_and_forward_reaches_a_device_behind_another_over_tcp() {
    store_and_forward_reaches_a_device_behind_another(Via::Tcp, "tcp");
}

/// The host on a serial line to the relay, the relay on TCP to the far
/// device (a radio network's gateway).
#[cfg(unix)]
#[test]
fn store_and_forward_reaches_a_device_behind_another_over_a_serial_line() {
    let line = common::null_modem::NullModem::new();
    store_and_forward_reaches_a_device_behind_another(Via::Serial(line), "serial");
}

fn store_and_forward_reaches_a_device_behind_another(via: Via, tag: &str) {
    let far_dir = plant_copy(&format!("roc-fb107-far-{tag}"), None);
    let far = Device::start(&far_dir.join("plant.json"), "5,2", &["--set", "SFP 1.DATA1=55.5"], &Via::Tcp);
    let relay_dir = plant_copy(&format!("roc-fb107-relay-{tag}"), Some(&far.1));
    let relay = Device::start(&relay_dir.join("plant.json"), "25,2", &[], &via);
    // Read SFP 1 DATA1 (TLP 17,0,2) through 25,2 from 5,2: the path in
    // words 50… (host 3,1, then 25,2 and 5,2), as §6.3 stores it.
    let cmds = "1,25,2,180,1,0,10,0,0,50\n1,25,2,180,1,0,20,0,0,0\n";
    let words = r#"{"0": [17, 0, 2], "50": [3, 1, 25, 2, 5, 2, 0, 0, 0, 0]}"#;
    let (said, w) = poll(&relay, &relay_dir, cmds, words);
    assert_eq!(said.lines().filter(|l| l.ends_with(": done")).count(), 2, "{said}");
    assert_eq!([word(&w, 10), word(&w, 11)], float_words(55.5), "the far device's value");
    assert_eq!([word(&w, 20), word(&w, 21)], float_words(80.0), "the relay's own");
    let log = relay.log();
    assert!(log.contains(&format!("passed a store-and-forward frame to 5,2 at {}", far.1)), "{log}");
    drop(far);
    drop(via);
}

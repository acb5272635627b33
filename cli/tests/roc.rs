//! `linc roc poll` against `linc serve --roc`, both as processes over TCP
//! on 127.0.0.1: the communication module manual's §6.1.1 example word for
//! word, its status codes for an unknown TLP and a timeout, and located
//! errors in its files; the same example over a serial line
//! (`--serial`, `--roc-serial`) on pseudo-terminals, word for word as
//! over TCP.
mod common;

use std::io::{BufRead, BufReader};

/// The manual's §6.1.1 command list: read TLPs 3,0,2 and 3,1,2 into words
/// 50…, then write words 100… (integers) to the same TLPs.
const EXAMPLE: &str = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD
1,25,2,180,2,0,50,0,0,0
1,25,2,181,2,0,100,2,0,0
";

/// A served example plant as unit 25, group 2; its ROC address.
struct Device(std::process::Child, String);

impl Device {
    fn start() -> Device {
        let mut child = common::spawn(&[
            "serve",
            "examples/roc/plant.json",
            "--http",
            "127.0.0.1:0",
            "--roc",
            "127.0.0.1:0",
            "--roc-address",
            "25,2",
            "--allow-writes",
            "--speed",
            "0.001",
        ]);
        let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
        let _serving = lines.next().expect("a line").expect("text");
        let roc = lines.next().expect("the ROC line").expect("text");
        let addr = roc.rsplit(' ').next().expect("an address").to_string();
        assert!(roc.starts_with("ROC protocol device 25,2 on 127.0.0.1:"), "{roc}");
        Device(child, addr)
    }
}

impl Drop for Device {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn poll(dev: &Device, dir: &std::path::Path, cmds: &str, words: &str, out: &str) -> std::process::Output {
    poll_on(&["--host", &dev.1], dir, cmds, words, out)
}

/// `linc roc poll` to the device `link` names (`--host …`, `--serial …`).
fn poll_on(link: &[&str], dir: &std::path::Path, cmds: &str, words: &str, out: &str) -> std::process::Output {
    std::fs::write(dir.join("cmds.csv"), cmds).unwrap();
    std::fs::write(dir.join("words.json"), words).unwrap();
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    let args = ["roc", "poll", "--commands", &p("cmds.csv"), "--words", &p("words.json")];
    let mut all: Vec<String> = args.iter().chain(link).map(|s| s.to_string()).collect();
    all.extend(["--out".to_string(), p(out), "--timeout".into(), "300ms".into()]);
    common::linc(&all.iter().map(String::as_str).collect::<Vec<_>>())
}

#[test]
fn the_manuals_example_word_for_word() {
    let dev = Device::start();
    let dir = linc_test_support::fresh_dir("roc-example");
    let o = poll(&dev, &dir, EXAMPLE, r#"{"0": [3, 0, 2, 3, 1, 2], "100": [500, 1000]}"#, "after1.json");
    assert_eq!(o.status.code(), Some(0), "{}{}", common::stdout(&o), common::stderr(&o));
    assert_eq!(common::stdout(&o), "command 1 (line 2): 180 to 25,2: done\ncommand 2 (line 3): 181 to 25,2: done\n");
    // The read ran first: words 50 and 51 hold the scan periods the plant
    // started with (1 s and 5 s); the write then set them to 500 and 1000.
    let after = std::fs::read_to_string(dir.join("after1.json")).unwrap();
    assert_eq!(
        after,
        "{\n  \"0\": [3, 0, 2, 3, 1, 2],\n  \"50\": [1, 5],\n  \"100\": [500, 1000],\n  \"status\": [0, 0]\n}\n"
    );
    // Polled again from the table it wrote: the read now sees 500 and 1000.
    let o = poll(&dev, &dir, EXAMPLE, &after, "after2.json");
    assert_eq!(o.status.code(), Some(0));
    let after = std::fs::read_to_string(dir.join("after2.json")).unwrap();
    assert_eq!(
        after,
        "{\n  \"0\": [3, 0, 2, 3, 1, 2],\n  \"50\": [500, 1000],\n  \"100\": [500, 1000],\n  \"status\": [0, 0]\n}\n"
    );
}

#[test]
fn an_unknown_tlp_and_a_timeout_have_the_modules_codes() {
    let dev = Device::start();
    let dir = linc_test_support::fresh_dir("roc-errors");
    // Logical 7 of point type 3 does not exist; unit 26 does not answer.
    let cmds = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD
1,25,2,180,1,0,50,0,0,0
1,26,2,180,1,3,60,0,0,0
";
    let o = poll(&dev, &dir, cmds, r#"{"0": [3, 7, 2, 3, 0, 2]}"#, "out.json");
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        common::stdout(&o),
        "command 1 (line 2): 180 to 25,2: error 23: ROC error 3: invalid logical number\n\
         command 2 (line 3): 180 to 26,2: error 8: timeout: no reply after 3 attempts\n"
    );
    let out = std::fs::read_to_string(dir.join("out.json")).unwrap();
    assert!(out.ends_with("\"status\": [23, 8]\n}\n"), "{out}");
    assert!(!out.contains("\"50\"") && !out.contains("\"60\""), "nothing stored on an error: {out}");
}

#[test]
fn file_errors_are_located_and_outputs_never_overwrite_inputs() {
    let dir = linc_test_support::fresh_dir("roc-files");
    std::fs::write(
        dir.join("cmds.csv"),
        "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n1,25,2,181,2,0,100,3,0,0\n",
    )
    .unwrap();
    let cmds = dir.join("cmds.csv").to_string_lossy().into_owned();
    let o = common::linc(&["roc", "poll", "--host", "127.0.0.1:9", "--commands", &cmds, "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("cmds.csv:2:20: error[E0922]: TYPE of a 181"), "{}", common::stderr(&o));
    std::fs::write(dir.join("w.json"), "{\"0\": [1, 70000]}").unwrap();
    std::fs::write(dir.join("cmds.csv"), EXAMPLE).unwrap();
    let w = dir.join("w.json").to_string_lossy().into_owned();
    let o = common::linc(&["roc", "poll", "--host", "127.0.0.1:9", "--commands", &cmds, "--words", &w]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("E0920"), "{}", common::stderr(&o));
    std::fs::write(dir.join("w.json"), "{}").unwrap();
    let o = common::linc(&["roc", "poll", "--host", "127.0.0.1:9", "--commands", &cmds, "--words", &w, "--out", &w]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("E0902"), "{}", common::stderr(&o));
    assert_eq!(std::fs::read_to_string(dir.join("w.json")).unwrap(), "{}", "the input is untouched");
}

#[test]
fn the_protocol_decides_which_commands_a_list_may_hold() {
    let dir = linc_test_support::fresh_dir("roc-protocol");
    let head = "PORT,SLV UNIT,SLV GROUP,OP CODE,CNT,SRC ADDR,DEST ADDR,TYPE,POLL TIME,STORE FWD\n";
    let p = |f: &str| dir.join(f).to_string_lossy().into_owned();
    std::fs::write(dir.join("log.csv"), format!("{head}1,25,2,120,0,0,50,0,0,0\n")).unwrap();
    std::fs::write(dir.join("fwd.csv"), format!("{head}1,25,2,180,1,0,50,0,0,40\n")).unwrap();
    let poll = |cmds: &str, protocol: &str| {
        let (cmds, none) = (p(cmds), "127.0.0.1:9");
        let args = ["roc", "poll", "--host", none, "--commands", &cmds, "--protocol", protocol, "--timeout", "50ms"];
        common::linc(&[&args[..], &["--message-format", "short"]].concat())
    };
    // A ROC Plus device has no opcode 120 and no store and forward.
    let o = poll("log.csv", "rocplus");
    assert_eq!(o.status.code(), Some(2));
    assert!(
        common::stderr(&o).contains("log.csv:2:8: error[E0923]: opcode 120 is the ROC protocol's"),
        "{}",
        common::stderr(&o)
    );
    let o = poll("fwd.csv", "rocplus");
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("fwd.csv:2:23: error[E0923]: store and forward"), "{}", common::stderr(&o));
    // The ROC protocol takes both; nothing answers on port 9.
    for cmds in ["log.csv", "fwd.csv"] {
        let o = poll(cmds, "roc");
        assert_eq!(o.status.code(), Some(1), "{}", common::stderr(&o));
        assert!(common::stdout(&o).ends_with("to 25,2: error 8: timeout: no reply after 3 attempts\n"));
    }
    assert_eq!(poll("log.csv", "modbus").status.code(), Some(2));
    // 180 and 181 are the same in both dialects: the manual's example runs
    // the same with `--protocol rocplus` against the FB107 device.
    let dev = Device::start();
    std::fs::write(dir.join("cmds.csv"), EXAMPLE).unwrap();
    std::fs::write(dir.join("words.json"), r#"{"0": [3, 0, 2, 3, 1, 2], "100": [500, 1000]}"#).unwrap();
    let (cmds, words) = (p("cmds.csv"), p("words.json"));
    let o = common::linc(&[
        "roc",
        "poll",
        "--host",
        &dev.1,
        "--commands",
        &cmds,
        "--words",
        &words,
        "--protocol",
        "rocplus",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    assert_eq!(common::stdout(&o), "command 1 (line 2): 180 to 25,2: done\ncommand 2 (line 3): 181 to 25,2: done\n");
}

#[test]
fn serve_modbus_answers_over_tcp_and_a_database_without_a_map_is_refused() {
    use std::io::{Read, Write};
    let mut child = common::spawn(&[
        "serve",
        "examples/roc/plant.json",
        "--http",
        "127.0.0.1:0",
        "--modbus",
        "0",
        "--speed",
        "0.001",
    ]);
    let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
    let _serving = lines.next().expect("a line").expect("text");
    let line = lines.next().expect("the Modbus line").expect("text");
    assert!(line.starts_with("Modbus TCP server on 127.0.0.1:"), "{line}");
    let addr = line.rsplit(' ').next().unwrap().to_string();
    let mut t = std::net::TcpStream::connect(&addr).expect("connect");
    t.set_read_timeout(Some(std::time::Duration::from_secs(5))).unwrap();
    // Read holding registers 0-1: the setpoint, 80.0 high word first.
    t.write_all(&[0, 9, 0, 0, 0, 6, 1, 3, 0, 0, 0, 2]).unwrap();
    let mut reply = [0u8; 13];
    t.read_exact(&mut reply).unwrap();
    assert_eq!(reply, [0, 9, 0, 0, 0, 7, 1, 3, 4, 0x42, 0xA0, 0, 0]);
    let _ = child.kill();
    let _ = child.wait();
    let o = common::linc(&["serve", "examples/fst/plant.json", "--http", "127.0.0.1:0", "--modbus", "0"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(common::stderr(&o).contains("--modbus needs a \"modbus\" register map"), "{}", common::stderr(&o));
}

/// The manual's example run twice (the second time from the table the
/// first wrote) with `poll`: what the first run said, and the two tables.
fn example_twice(
    dir: &std::path::Path,
    poll: impl Fn(&std::path::Path, &str, &str, &str) -> std::process::Output,
) -> (String, String, String) {
    let o = poll(dir, EXAMPLE, r#"{"0": [3, 0, 2, 3, 1, 2], "100": [500, 1000]}"#, "after1.json");
    assert_eq!(o.status.code(), Some(0), "{}{}", common::stdout(&o), common::stderr(&o));
    let after1 = std::fs::read_to_string(dir.join("after1.json")).unwrap();
    let o2 = poll(dir, EXAMPLE, &after1, "after2.json");
    assert_eq!(o2.status.code(), Some(0), "{}{}", common::stdout(&o2), common::stderr(&o2));
    (common::stdout(&o), after1, std::fs::read_to_string(dir.join("after2.json")).unwrap())
}

#[cfg(unix)]
#[test]
fn the_manuals_example_over_a_serial_line_matches_tcp_word_for_word() {
    let tcp = Device::start();
    let dir = linc_test_support::fresh_dir("roc-example-tcp");
    let over_tcp = example_twice(&dir, |d, c, w, o| poll(&tcp, d, c, w, o));
    // The device on one end of the line (and on TCP: one device answers
    // on both), the host on the other.
    let line = common::null_modem::NullModem::new();
    let mut child = common::spawn(&[
        "serve",
        "examples/roc/plant.json",
        "--http",
        "127.0.0.1:0",
        "--roc",
        "127.0.0.1:0",
        "--roc-serial",
        &line.paths[0],
        "--baud",
        "19200",
        "--roc-address",
        "25,2",
        "--allow-writes",
        "--speed",
        "0.001",
    ]);
    let mut lines = BufReader::new(child.stdout.take().expect("stdout")).lines();
    let _serving = lines.next().expect("a line").expect("text");
    let roc = lines.next().expect("the ROC line").expect("text");
    assert!(roc.starts_with("ROC protocol device 25,2 on 127.0.0.1:"), "{roc}");
    let serial = lines.next().expect("the serial line").expect("text");
    assert_eq!(serial, format!("ROC protocol device 25,2 on serial {} at 19200 baud", line.paths[0]));
    let dir = linc_test_support::fresh_dir("roc-example-serial");
    let link = ["--serial", &line.paths[1], "--baud", "19200"];
    let over_serial = example_twice(&dir, |d, c, w, o| poll_on(&link, d, c, w, o));
    let _ = child.kill();
    let _ = child.wait();
    assert_eq!(over_serial, over_tcp);
    assert!(over_tcp.2.contains("\"50\": [500, 1000]"), "the second run read what the first wrote: {}", over_tcp.2);
}

#[test]
fn a_serial_port_that_cant_be_opened_is_e0905_before_any_request() {
    let dir = linc_test_support::fresh_dir("roc-serial-missing");
    let link = ["--serial", "/dev/linc-no-such-tty", "--baud", "9600", "--message-format", "short"];
    let o = poll_on(&link, &dir, EXAMPLE, "{}", "out.json");
    assert_eq!(o.status.code(), Some(2));
    let want = "/dev/linc-no-such-tty:1:1: error[E0905]: can't open the serial port `/dev/linc-no-such-tty`";
    assert!(common::stderr(&o).starts_with(want), "{}", common::stderr(&o));
    assert!(!dir.join("out.json").exists(), "nothing written");
    let o = common::linc(&["roc", "poll", "--host", "127.0.0.1:9", "--baud", "9600", "--commands", "x.csv"]);
    assert_eq!(o.status.code(), Some(2), "--baud means nothing over TCP");
    assert!(common::stderr(&o).contains("error[E0903]"), "{}", common::stderr(&o));
}

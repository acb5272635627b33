//! `linc lsp` as an editor runs it: the real binary over stdio, spoken to
//! by a client written here (framing and JSON by hand, independent of the
//! server's crates): initialize, open a file with an error and receive the
//! diagnostic, fix it and receive an empty list, hover, complete, go to
//! definition, shut down and exit. And the same binary fed hostile bytes:
//! it answers each with an error and keeps its open documents.

mod common;

use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Read, Write};
use std::process::ChildStdin;
use std::sync::mpsc::{channel, Receiver};
use std::time::Duration;

struct Peer {
    input: ChildStdin,
    messages: Receiver<Value>,
    next: i64,
}

/// Reads `Content-Length` framed messages from the server's output.
fn reader(out: impl Read + Send + 'static) -> Receiver<Value> {
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        let mut r = BufReader::new(out);
        loop {
            let mut length = None;
            loop {
                let mut line = String::new();
                if r.read_line(&mut line).unwrap_or(0) == 0 {
                    return;
                }
                let line = line.trim_end();
                if line.is_empty() {
                    break;
                }
                if let Some(v) = line.strip_prefix("Content-Length: ") {
                    length = v.parse::<usize>().ok();
                }
            }
            let mut body = vec![0; length.expect("Content-Length")];
            r.read_exact(&mut body).expect("body");
            if tx.send(serde_json::from_slice(&body).expect("JSON")).is_err() {
                return;
            }
        }
    });
    rx
}

impl Peer {
    fn send(&mut self, v: Value) {
        let body = v.to_string();
        self.send_raw(format!("Content-Length: {}\r\n\r\n{body}", body.len()).as_bytes());
    }

    fn send_raw(&mut self, bytes: &[u8]) {
        self.input.write_all(bytes).expect("write");
        self.input.flush().expect("flush");
    }

    /// The next answer (not a notification).
    fn next_answer(&mut self) -> Value {
        loop {
            let m = self.next_message();
            if m.get("method").is_none() {
                return m;
            }
        }
    }

    fn next_message(&mut self) -> Value {
        self.messages.recv_timeout(Duration::from_secs(30)).expect("a message from linc lsp")
    }

    fn request(&mut self, method: &str, params: Value) -> Value {
        self.next += 1;
        let id = self.next;
        self.send(json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }));
        loop {
            let m = self.next_message();
            if m["id"] == id {
                assert!(m.get("error").is_none(), "{method}: {m}");
                return m["result"].clone();
            }
        }
    }

    fn notify(&mut self, method: &str, params: Value) {
        self.send(json!({ "jsonrpc": "2.0", "method": method, "params": params }));
    }

    /// The next diagnostics published for `uri` at `version`.
    fn diagnostics(&mut self, uri: &str, version: i64) -> Value {
        loop {
            let m = self.next_message();
            if m["method"] == "textDocument/publishDiagnostics"
                && m["params"]["uri"] == uri
                && m["params"]["version"] == version
            {
                return m["params"]["diagnostics"].clone();
            }
        }
    }
}

fn file_uri(path: &std::path::Path) -> String {
    format!("file://{}", path.display())
}

#[test]
fn an_editor_session_over_stdio() {
    let root = common::temp_dir("lsp-e2e");
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/strategy/");
    for f in ["plant.json", "actions.stx", "modbus.stx"] {
        std::fs::copy(format!("{examples}{f}"), root.join(f)).expect("copy");
    }
    let good = std::fs::read_to_string(root.join("actions.stx")).expect("actions");
    let bad = good.replace("TANK1.Pump := TRUE;", "TANK1.Pmp := TRUE;");
    let mut child = common::spawn(&["lsp"]);
    let messages = reader(child.stdout.take().expect("stdout"));
    let mut peer = Peer { input: child.stdin.take().expect("stdin"), messages, next: 0 };

    let init = peer.request(
        "initialize",
        json!({ "processId": null, "rootUri": file_uri(&root), "capabilities": {},
                "initializationOptions": { "debounceMs": 20 } }),
    );
    assert_eq!(init["serverInfo"]["name"], "linc");
    assert_eq!(init["capabilities"]["hoverProvider"], true);
    peer.notify("initialized", json!({}));

    let uri = file_uri(&root.join("actions.stx"));
    peer.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uri, "languageId": "lin-st", "version": 1, "text": bad } }),
    );
    let d = peer.diagnostics(&uri, 1);
    assert_eq!(d.as_array().map(Vec::len), Some(1), "{d}");
    assert_eq!(d[0]["code"], "E0101");
    assert_eq!(d[0]["message"].as_str().map(|m| m.starts_with("`TANK1` has no field `Pmp`")), Some(true), "{d}");

    peer.notify(
        "textDocument/didChange",
        json!({ "textDocument": { "uri": uri, "version": 2 }, "contentChanges": [{ "text": good }] }),
    );
    assert_eq!(peer.diagnostics(&uri, 2), json!([]));

    let line = good.lines().position(|l| l.contains("TANK1.Level := TANK1.Level + TANK1.Inflow")).expect("line");
    let at = json!({ "textDocument": { "uri": uri }, "position": { "line": line, "character": 16 } });
    let hover = peer.request("textDocument/hover", at.clone());
    let text = hover["contents"]["value"].as_str().expect("hover text");
    assert!(text.starts_with("**TANK1.Level** : `REAL`"), "{text}");

    let completion = peer.request("textDocument/completion", at.clone());
    let labels: Vec<&str> = completion.as_array().expect("items").iter().filter_map(|i| i["label"].as_str()).collect();
    assert_eq!(labels, ["Level", "Inflow", "Outflow", "Valve", "Pump", "HighCnt"], "after `TANK1.`");

    let def = peer.request("textDocument/definition", at);
    assert_eq!(def["uri"], file_uri(&root.join("plant.json")));
    assert_eq!(def["range"]["start"]["line"], 5, "the field in the template: {def}");

    assert_eq!(peer.request("shutdown", Value::Null), Value::Null);
    peer.notify("exit", Value::Null);
    drop(peer);
    let status = child.wait().expect("exit");
    assert_eq!(status.code(), Some(0));
}

/// The findings of a hostile test round (issue 28): a 32-byte header
/// claiming 100 GB (it used to abort the server on a failed allocation), a
/// malformed header, a body that is not JSON and JSON that is no message
/// each get an error answer, in order; the document opened before them is
/// still there for the hover after them; `exit` without `shutdown` gives
/// exit status 1, as the protocol says.
#[test]
fn hostile_bytes_are_answered_and_the_session_survives() {
    let root = common::temp_dir("lsp-hostile");
    let examples = concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/strategy/");
    for f in ["plant.json", "actions.stx", "modbus.stx"] {
        std::fs::copy(format!("{examples}{f}"), root.join(f)).expect("copy");
    }
    let text = std::fs::read_to_string(root.join("actions.stx")).expect("actions");
    let mut child = common::spawn(&["lsp"]);
    let messages = reader(child.stdout.take().expect("stdout"));
    let mut peer = Peer { input: child.stdin.take().expect("stdin"), messages, next: 0 };
    peer.request("initialize", json!({ "processId": null, "rootUri": file_uri(&root), "capabilities": {} }));
    peer.notify("initialized", json!({}));
    let uri = file_uri(&root.join("actions.stx"));
    peer.notify(
        "textDocument/didOpen",
        json!({ "textDocument": { "uri": uri, "languageId": "lin-st", "version": 1, "text": text } }),
    );

    let huge = b"Content-Length: 100000000000\r\n\r\n";
    assert_eq!(huge.len(), 32);
    peer.send_raw(huge);
    peer.send_raw(b"Content-Length: twelve\r\n\r\n");
    peer.send_raw(b"Content-Length: 9\r\n\r\n{\"id\": 1,");
    peer.send_raw(b"Content-Length: 22\r\n\r\n{\"id\": 5, \"params\": 1}");
    let answers: Vec<(Value, Value)> =
        (0..4).map(|_| peer.next_answer()).map(|m| (m["id"].clone(), m["error"]["code"].clone())).collect();
    assert_eq!(
        answers,
        [
            (Value::Null, json!(-32600)),
            (Value::Null, json!(-32700)),
            (Value::Null, json!(-32700)),
            (json!(5), json!(-32600)),
        ]
    );

    let line = text.lines().position(|l| l.contains("TANK1.Level := TANK1.Level + TANK1.Inflow")).expect("line");
    let at = json!({ "textDocument": { "uri": uri }, "position": { "line": line, "character": 16 } });
    let hover = peer.request("textDocument/hover", at);
    let hover = hover["contents"]["value"].as_str().expect("hover text");
    assert!(hover.starts_with("**TANK1.Level** : `REAL`"), "the open document survived: {hover}");

    peer.notify("exit", Value::Null);
    drop(peer);
    let status = child.wait().expect("exit");
    assert_eq!(status.code(), Some(1), "exit without shutdown");
}

/// Before `initialize`, a request is answered "not initialized" (-32002),
/// an `initialize` whose parameters don't read "invalid params" (-32602),
/// and the session goes on; `exit` then ends it with status 1.
#[test]
fn before_initialize_requests_are_refused_and_exit_gives_status_1() {
    let mut child = common::spawn(&["lsp"]);
    let messages = reader(child.stdout.take().expect("stdout"));
    let mut peer = Peer { input: child.stdin.take().expect("stdin"), messages, next: 0 };
    peer.send(json!({ "jsonrpc": "2.0", "id": 7, "method": "textDocument/hover", "params": {} }));
    let m = peer.next_answer();
    assert_eq!((&m["id"], &m["error"]["code"]), (&json!(7), &json!(-32002)), "{m}");
    peer.send(json!({ "jsonrpc": "2.0", "id": 8, "method": "initialize", "params": { "capabilities": 3 } }));
    let m = peer.next_answer();
    assert_eq!((&m["id"], &m["error"]["code"]), (&json!(8), &json!(-32602)), "{m}");
    peer.notify("exit", Value::Null);
    drop(peer);
    assert_eq!(child.wait().expect("exit").code(), Some(1), "exit before initialize, without shutdown");
}

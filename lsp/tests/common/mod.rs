//! An in-process client: the server runs on a thread over lsp-server's
//! in-memory connection; requests and notifications are JSON as a client
//! sends them; answers are normalised (the workspace folder becomes
//! `$ROOT`) for snapshots.

#![allow(dead_code)]

use lsp_server::{Connection, Message, Notification, Request, RequestId};
use serde_json::{json, Value};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

pub struct Client {
    pub conn: Connection,
    pub root: PathBuf,
    thread: Option<std::thread::JoinHandle<()>>,
    next: i32,
    /// Notifications received while waiting for something else.
    pub inbox: Vec<Notification>,
}

/// A fresh workspace folder `tag` holding `files` (name → text).
pub fn workspace(tag: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = linc_test_support::fresh_dir(tag);
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().expect("parent")).expect("dir");
        std::fs::write(path, text).expect("write");
    }
    dir
}

pub fn example(path: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../examples");
    std::fs::read_to_string(root.join(path)).expect("example")
}

impl Client {
    pub fn start(root: &Path, options: Value) -> Client {
        let (server, client) = Connection::memory();
        let thread = std::thread::spawn(move || {
            let _ = linc_lsp::serve(&server);
        });
        let mut c = Client { conn: client, root: root.to_path_buf(), thread: Some(thread), next: 0, inbox: Vec::new() };
        let root_uri = c.uri("");
        let init = json!({
            "processId": null,
            "rootUri": root_uri,
            "capabilities": {},
            "workspaceFolders": [{ "uri": root_uri, "name": "ws" }],
            "initializationOptions": options,
        });
        c.request("initialize", init);
        c.notify("initialized", json!({}));
        c
    }

    pub fn uri(&self, name: &str) -> String {
        let path = if name.is_empty() { self.root.clone() } else { self.root.join(name) };
        lsp_types::Url::from_file_path(path).expect("uri").to_string()
    }

    pub fn notify(&mut self, method: &str, params: Value) {
        let n = Notification::new(method.to_string(), params);
        self.conn.sender.send(Message::Notification(n)).expect("send");
    }

    /// The result of a request (an error response panics).
    pub fn request(&mut self, method: &str, params: Value) -> Value {
        match self.answer(method, params) {
            Ok(v) => v,
            Err(e) => panic!("{method} failed: {e}"),
        }
    }

    /// The result of a request, or its error message.
    pub fn answer(&mut self, method: &str, params: Value) -> Result<Value, String> {
        self.next += 1;
        let id = RequestId::from(self.next);
        let r = Request::new(id.clone(), method.to_string(), params);
        self.conn.sender.send(Message::Request(r)).expect("send");
        loop {
            match self.conn.receiver.recv_timeout(Duration::from_secs(20)).expect("answer") {
                Message::Response(resp) if resp.id == id => {
                    if let Some(e) = resp.error {
                        return Err(e.message);
                    }
                    return Ok(resp.result.unwrap_or(Value::Null));
                }
                Message::Notification(n) => self.inbox.push(n),
                _ => {}
            }
        }
    }

    pub fn open(&mut self, name: &str, text: &str) {
        let uri = self.uri(name);
        let lang = name.rsplit('.').next().unwrap_or("");
        self.notify(
            "textDocument/didOpen",
            json!({ "textDocument": { "uri": uri, "languageId": lang, "version": 1, "text": text } }),
        );
    }

    pub fn change(&mut self, name: &str, version: i32, text: &str) {
        let uri = self.uri(name);
        self.notify(
            "textDocument/didChange",
            json!({ "textDocument": { "uri": uri, "version": version }, "contentChanges": [{ "text": text }] }),
        );
    }

    /// The next diagnostics published for `name`.
    pub fn diagnostics(&mut self, name: &str) -> Value {
        let uri = self.uri(name);
        let deadline = Instant::now() + Duration::from_secs(20);
        loop {
            if let Some(i) =
                self.inbox.iter().position(|n| n.method == "textDocument/publishDiagnostics" && n.params["uri"] == uri)
            {
                return self.inbox.remove(i).params;
            }
            let wait = deadline.saturating_duration_since(Instant::now());
            if let Message::Notification(n) = self.conn.receiver.recv_timeout(wait).expect("diagnostics") {
                self.inbox.push(n);
            }
        }
    }

    /// The diagnostics published for `name` at `version` (earlier ones are
    /// skipped).
    pub fn diagnostics_at(&mut self, name: &str, version: i32) -> Value {
        loop {
            let d = self.diagnostics(name);
            if d["version"] == version {
                return d;
            }
        }
    }

    /// `textDocument/<method>` at a position given as the text before the
    /// cursor's line and column (0-based).
    pub fn at(&mut self, method: &str, name: &str, line: u32, character: u32) -> Value {
        let uri = self.uri(name);
        self.request(
            &format!("textDocument/{method}"),
            json!({ "textDocument": { "uri": uri }, "position": { "line": line, "character": character } }),
        )
    }

    pub fn clone_at(&mut self, method: &str, name: &str, line: u32, character: u32) -> Value {
        self.at(method, name, line, character)
    }

    /// [`Client::at`]'s answer as [`Client::show`] writes it.
    pub fn at_shown(&mut self, method: &str, name: &str, line: u32, character: u32) -> String {
        let v = self.at(method, name, line, character);
        self.show(&v)
    }

    /// A request's answer as [`Client::show`] writes it.
    pub fn request_shown(&mut self, method: &str, params: Value) -> String {
        let v = self.request(method, params);
        self.show(&v)
    }

    /// A value as pretty JSON with the workspace folder written `$ROOT`.
    pub fn show(&self, v: &Value) -> String {
        let root = self.uri("");
        serde_json::to_string_pretty(v).expect("json").replace(&root, "$ROOT")
    }

    pub fn shutdown(mut self) {
        self.request("shutdown", Value::Null);
        self.notify("exit", Value::Null);
        if let Some(t) = self.thread.take() {
            t.join().expect("server thread");
        }
    }
}

/// The 0-based line and UTF-16 column of the first `needle` in `text`,
/// plus `shift` columns.
pub fn pos(text: &str, needle: &str, shift: u32) -> (u32, u32) {
    let at = text.find(needle).unwrap_or_else(|| panic!("{needle:?} not in text"));
    let line = text[..at].matches('\n').count() as u32;
    let col = text[..at].rsplit('\n').next().unwrap_or("").encode_utf16().count() as u32;
    (line, col + shift)
}

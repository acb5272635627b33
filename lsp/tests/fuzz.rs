//! Random edit sessions against the server in process: open an example
//! (or a random mix of languages), apply random edits (ranges anywhere,
//! even past the end; text with comments, quotes, brackets, non-ASCII),
//! and after each edit ask for something at a random place. No request
//! may fail with an internal error and no handler may panic. `cargo test`
//! runs a few hundred sessions; `LINC_LSP_FUZZ=100000` runs the long fuzz.

mod common;

use common::{example, workspace};
use linc_lsp::Server;
use linc_test_support::Rng;
use lsp_server::{ErrorCode, Notification, Request, RequestId};
use serde_json::{json, Value};
use std::time::{Duration, Instant};

const PIECES: [&str; 40] = [
    "IF ",
    "THEN\n",
    "END_IF;",
    "ELSE",
    "FOR ",
    "DO",
    "END_FOR;",
    ":=",
    ";",
    "(*",
    "*)",
    "'",
    "\"",
    "$",
    "[",
    "]",
    "{",
    "}",
    "(",
    ")",
    "->",
    "|",
    ".",
    ",",
    "TANK1.",
    "R1.Level",
    "Plant.",
    "STEP X: A(N); END_STEP",
    "ACTION ",
    "END_ACTION",
    "TRANSITION FROM Idle TO Fill := TRUE; END_TRANSITION",
    "\n",
    "é",
    "😀",
    "16#",
    "T#5s",
    "ABS(",
    "\"AIN 2-1,EU\"",
    "0,,VAL,",
    "JUMP ",
];

const FILES: [(&str, &str); 7] = [
    ("strategy/actions.stx", "actions.stx"),
    ("strategy/modbus.stx", "modbus.stx"),
    ("sequences/batch.sfc", "batch.sfc"),
    ("ladder/interlock.ld", "interlock.ld"),
    ("fst/pump.csv", "pump.csv"),
    ("strategy/plant.json", "plant.json"),
    ("guide/broken.st", "broken.st"),
];

const METHODS: [&str; 10] = [
    "textDocument/hover",
    "textDocument/completion",
    "textDocument/definition",
    "textDocument/references",
    "textDocument/documentSymbol",
    "textDocument/semanticTokens/full",
    "textDocument/formatting",
    "textDocument/rename",
    "textDocument/prepareRename",
    "workspace/symbol",
];

fn sessions() -> u64 {
    std::env::var("LINC_LSP_FUZZ").ok().and_then(|v| v.parse().ok()).unwrap_or(300)
}

struct Fuzz {
    server: Server,
    rng: Rng,
    next: i32,
    uri: String,
    version: i32,
    lines: u32,
}

impl Fuzz {
    fn position(&mut self) -> Value {
        let line = self.rng.below(self.lines as usize + 3) as u32;
        json!({ "line": line, "character": self.rng.below(90) })
    }

    fn request(&mut self, method: &str, params: Value) {
        self.next += 1;
        let resp = self.server.request(Request::new(RequestId::from(self.next), method.into(), params.clone()));
        if let Some(e) = resp.error {
            assert_ne!(e.code, ErrorCode::InternalError as i32, "{method} {params} failed: {}", e.message);
        }
    }

    fn edit(&mut self) {
        let (start, end) = (self.position(), self.position());
        let mut text = String::new();
        for _ in 0..self.rng.below(4) {
            text.push_str(PIECES[self.rng.below(PIECES.len())]);
        }
        self.version += 1;
        let change = if self.rng.one_in(40) {
            json!({ "text": text })
        } else {
            json!({ "range": { "start": start, "end": end }, "text": text })
        };
        let params =
            json!({ "textDocument": { "uri": self.uri, "version": self.version }, "contentChanges": [change] });
        self.server.notification(Notification::new("textDocument/didChange".into(), params));
        self.lines = self.lines.saturating_add(text.matches('\n').count() as u32);
    }

    fn ask(&mut self) {
        let method = METHODS[self.rng.below(METHODS.len())];
        let doc = json!({ "uri": self.uri });
        let params = match method {
            "workspace/symbol" => json!({ "query": PIECES[self.rng.below(PIECES.len())] }),
            "textDocument/documentSymbol" | "textDocument/semanticTokens/full" => json!({ "textDocument": doc }),
            "textDocument/formatting" => {
                json!({ "textDocument": doc, "options": { "tabSize": 4, "insertSpaces": true } })
            }
            "textDocument/references" => json!({ "textDocument": doc, "position": self.position(),
                                                  "context": { "includeDeclaration": true } }),
            "textDocument/rename" => json!({ "textDocument": doc, "position": self.position(), "newName": "Nm" }),
            _ => json!({ "textDocument": doc, "position": self.position() }),
        };
        self.request(method, params);
    }

    /// Diagnostics now, and quick fixes for them.
    fn diagnose(&mut self) {
        for msg in self.server.due_diagnostics(Instant::now() + Duration::from_secs(3600)) {
            let lsp_server::Message::Notification(n) = msg else { continue };
            let diagnostics = n.params["diagnostics"].clone();
            let range = json!({ "start": self.position(), "end": self.position() });
            let params = json!({ "textDocument": { "uri": self.uri }, "range": range,
                                 "context": { "diagnostics": diagnostics } });
            self.request("textDocument/codeAction", params);
        }
    }
}

fn texts() -> Vec<(String, &'static str)> {
    FILES.iter().map(|(path, name)| (example(path), *name)).collect()
}

#[test]
fn random_edit_sessions_never_fail_the_server() {
    let texts = texts();
    let files: Vec<(&str, &str)> = texts.iter().map(|(t, n)| (*n, t.as_str())).collect();
    let root = workspace("lsp-fuzz", &files);
    let root_uri = lsp_types::Url::from_file_path(&root).expect("uri");
    let params: lsp_types::InitializeParams = serde_json::from_value(json!({
        "processId": null, "rootUri": root_uri, "capabilities": {}, "initializationOptions": { "debounceMs": 0 }
    }))
    .expect("params");
    let mut f = Fuzz {
        server: linc_lsp::server_for(&params),
        rng: Rng::new(19),
        next: 0,
        uri: String::new(),
        version: 0,
        lines: 0,
    };
    for session in 0..sessions() {
        let (text, name) = &texts[f.rng.below(texts.len())];
        f.uri = lsp_types::Url::from_file_path(root.join(name)).expect("file uri").to_string();
        f.version = 1;
        f.lines = text.matches('\n').count() as u32;
        let open = json!({ "textDocument": { "uri": f.uri, "languageId": "", "version": 1, "text": text } });
        f.server.notification(Notification::new("textDocument/didOpen".into(), open));
        for _ in 0..1 + f.rng.below(12) {
            f.edit();
            for _ in 0..1 + f.rng.below(3) {
                f.ask();
            }
            if f.rng.one_in(3) {
                f.diagnose();
            }
        }
        f.diagnose();
        let close = json!({ "textDocument": { "uri": f.uri } });
        f.server.notification(Notification::new("textDocument/didClose".into(), close));
        assert_eq!(f.server.panics, 0, "a handler panicked in session {session}");
    }
}

/// Requests on one very long line take work linear in it (4× the line
/// within 8× the processor time): semantic tokens, hover and completion at
/// its end.
#[test]
fn a_long_line_costs_linear_time() {
    let root = workspace("lsp-long-line", &[]);
    let root_uri = lsp_types::Url::from_file_path(&root).expect("uri");
    let params: lsp_types::InitializeParams =
        serde_json::from_value(json!({ "processId": null, "rootUri": root_uri, "capabilities": {} })).expect("params");
    let mut server = linc_lsp::server_for(&params);
    let mut time = |n: usize| {
        let text = "TIC.PV := ABS(1); (* c *) ".repeat(n);
        let uri = lsp_types::Url::from_file_path(root.join(format!("l{n}.st"))).expect("uri").to_string();
        let open = json!({ "textDocument": { "uri": uri, "languageId": "", "version": 1, "text": text } });
        server.notification(Notification::new("textDocument/didOpen".into(), open));
        let end = json!({ "line": 0, "character": text.len() - 20 });
        // The server answers on this thread: its processor time is the work.
        linc_test_support::work::thread_cpu(|| {
            for (i, method) in
                ["textDocument/semanticTokens/full", "textDocument/hover", "textDocument/completion"].iter().enumerate()
            {
                let params = json!({ "textDocument": { "uri": uri }, "position": end });
                let r = server.request(Request::new(RequestId::from(i as i32), method.to_string(), params));
                assert!(r.error.is_none(), "{method}: {:?}", r.error);
            }
        })
        .1
    };
    time(1_000);
    let r = linc_test_support::work::growth(|big| time(if big { 16_000 } else { 4_000 }));
    assert!(r < 8.0, "4x the statements took {r:.1}x the work");
}

//! The server's loop: documents, the workspace's databases, requests
//! dispatched to the features, and diagnostics published a little after
//! the last change (debounced), so typing is not slowed by checking.

use crate::text::LineIndex;
use crate::workspace::Workspace;
use lsp_server::{Connection, ErrorCode, Message, Notification, Request, RequestId, Response};
use lsp_types::notification::{self as note, Notification as _};
use lsp_types::request::{self as req, Request as _};
use lsp_types::{PublishDiagnosticsParams, TextDocumentContentChangeEvent, Url};
use serde_json::Value;
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How long after the last change diagnostics wait, unless the client's
/// initialization options say otherwise (`{"debounceMs": 0}`).
pub const DEBOUNCE: Duration = Duration::from_millis(150);

/// The language of a document.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    St,
    Sfc,
    Ladder,
    Fst,
    Json,
    Other,
}

impl Lang {
    pub fn of(path: &Path, language_id: &str) -> Lang {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("").to_ascii_lowercase();
        match (ext.as_str(), language_id) {
            ("st" | "stx", _) | (_, "lin-st") => Lang::St,
            ("sfc", _) | (_, "lin-sfc") => Lang::Sfc,
            ("ld", _) | (_, "lin-ladder") => Lang::Ladder,
            ("csv", _) | (_, "roc-fst") => Lang::Fst,
            ("json", _) | (_, "json") => Lang::Json,
            _ => Lang::Other,
        }
    }

    /// A file name with the extension the compiler classifies by.
    pub fn file_name(self, path: &Path) -> String {
        let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("file");
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        match self {
            Lang::St if ext.eq_ignore_ascii_case("st") || ext.eq_ignore_ascii_case("stx") => format!("{stem}.{ext}"),
            Lang::St => format!("{stem}.stx"),
            Lang::Sfc => format!("{stem}.sfc"),
            Lang::Ladder => format!("{stem}.ld"),
            Lang::Fst => format!("{stem}.csv"),
            Lang::Json | Lang::Other => format!("{stem}.{ext}"),
        }
    }
}

/// An open document.
pub struct Doc {
    pub uri: Url,
    pub path: PathBuf,
    pub text: String,
    pub version: i32,
    pub lang: Lang,
    pub index: LineIndex,
    /// Every name of the text as the checker resolves it, computed by the
    /// first request that needs it and kept until the text or a database
    /// changes: resolving checks the whole file (14 ms for 5,000 lines),
    /// which every hover and completion did again before.
    pub(crate) names: std::cell::OnceCell<linc_compiler::names::Names>,
}

impl Doc {
    pub fn new(uri: Url, text: String, version: i32, language_id: &str) -> Doc {
        let path = uri.to_file_path().unwrap_or_else(|_| PathBuf::from(uri.path()));
        let lang = Lang::of(&path, language_id);
        let index = LineIndex::new(&text);
        Doc { uri, path, text, version, lang, index, names: std::cell::OnceCell::new() }
    }

    /// Applies one change; ranges outside the text are clamped.
    pub fn apply(&mut self, change: TextDocumentContentChangeEvent) {
        match change.range {
            None => self.text = change.text,
            Some(r) => {
                let a = self.index.offset(&self.text, r.start);
                let b = self.index.offset(&self.text, r.end).max(a);
                self.text.replace_range(a..b, &change.text);
            }
        }
        self.index = LineIndex::new(&self.text);
        self.names.take();
    }
}

pub struct Server {
    pub docs: HashMap<Url, Doc>,
    pub ws: Workspace,
    pending: HashMap<Url, Instant>,
    debounce: Duration,
    /// Requests whose handler panicked (answered with an error; the fuzz
    /// test requires none).
    pub panics: usize,
    pub shutting_down: bool,
}

impl Server {
    pub fn new(ws: Workspace, debounce: Duration) -> Server {
        Server { docs: HashMap::new(), ws, pending: HashMap::new(), debounce, panics: 0, shutting_down: false }
    }

    /// Runs until the client sends `exit` or the connection closes.
    pub fn run(&mut self, conn: &Connection) {
        loop {
            let wait = self
                .pending
                .values()
                .min()
                .map_or(Duration::from_secs(3600), |d| d.saturating_duration_since(Instant::now()));
            match conn.receiver.recv_timeout(wait) {
                Ok(Message::Request(r)) => {
                    let resp = self.request(r);
                    if conn.sender.send(Message::Response(resp)).is_err() {
                        return;
                    }
                }
                Ok(Message::Notification(n)) => {
                    if n.method == note::Exit::METHOD {
                        return;
                    }
                    self.notification(n);
                }
                Ok(Message::Response(_)) => {}
                Err(crossbeam_timeout) if crossbeam_timeout.is_timeout() => {}
                Err(_) => return,
            }
            for msg in self.due_diagnostics(Instant::now()) {
                if conn.sender.send(msg).is_err() {
                    return;
                }
            }
        }
    }

    /// Answers a request; a handler that panics gives an internal error.
    pub fn request(&mut self, r: Request) -> Response {
        let id = r.id.clone();
        if r.method == req::Shutdown::METHOD {
            self.shutting_down = true;
            return Response::new_ok(id, Value::Null);
        }
        match catch_unwind(AssertUnwindSafe(|| self.dispatch(&r.method, r.params))) {
            Ok(Ok(v)) => Response::new_ok(id, v),
            Ok(Err(e)) => error(id, e),
            Err(_) => {
                self.panics += 1;
                Response::new_err(id, ErrorCode::InternalError as i32, format!("linc lsp failed on {}", r.method))
            }
        }
    }

    fn dispatch(&mut self, method: &str, params: Value) -> Result<Value, Failure> {
        fn p<T: serde::de::DeserializeOwned>(v: Value) -> Result<T, Failure> {
            serde_json::from_value(v).map_err(|e| Failure::Params(e.to_string()))
        }
        let v = match method {
            req::HoverRequest::METHOD => to(crate::hover::hover(self, &p(params)?)),
            req::Completion::METHOD => to(crate::complete::complete(self, &p(params)?)),
            req::GotoDefinition::METHOD => to(crate::nav::definition(self, &p(params)?)),
            req::References::METHOD => to(crate::nav::references(self, &p(params)?)),
            req::Rename::METHOD => to(crate::nav::rename(self, &p(params)?).map_err(Failure::Request)?),
            req::PrepareRenameRequest::METHOD => to(crate::nav::prepare_rename(self, &p(params)?)),
            req::DocumentSymbolRequest::METHOD => to(crate::symbols::document(self, &p(params)?)),
            req::WorkspaceSymbolRequest::METHOD => to(crate::symbols::workspace(self, &p(params)?)),
            req::SemanticTokensFullRequest::METHOD => to(crate::symbols::semantic(self, &p(params)?)),
            req::Formatting::METHOD => to(crate::actions::format(self, &p(params)?)),
            req::CodeActionRequest::METHOD => to(crate::actions::code_actions(self, &p(params)?)),
            _ => return Err(Failure::Method(method.to_string())),
        };
        Ok(v)
    }

    pub fn notification(&mut self, n: Notification) {
        let _ = catch_unwind(AssertUnwindSafe(|| self.note(n))).map_err(|_| self.panics += 1);
    }

    fn note(&mut self, n: Notification) {
        match n.method.as_str() {
            note::DidOpenTextDocument::METHOD => {
                let Ok(p) = serde_json::from_value::<lsp_types::DidOpenTextDocumentParams>(n.params) else { return };
                let d = p.text_document;
                let doc = Doc::new(d.uri.clone(), d.text, d.version, &d.language_id);
                self.opened(doc);
            }
            note::DidChangeTextDocument::METHOD => {
                let Ok(p) = serde_json::from_value::<lsp_types::DidChangeTextDocumentParams>(n.params) else { return };
                let uri = p.text_document.uri;
                let Some(doc) = self.docs.get_mut(&uri) else { return };
                doc.version = p.text_document.version;
                for c in p.content_changes {
                    doc.apply(c);
                }
                let (path, text, lang) = (doc.path.clone(), doc.text.to_string(), doc.lang);
                let later = Instant::now() + self.debounce;
                if lang == Lang::Json && self.ws.update(&path, &text) {
                    self.recheck_all(later);
                }
                self.pending.insert(uri, later);
            }
            note::DidCloseTextDocument::METHOD => {
                let Ok(p) = serde_json::from_value::<lsp_types::DidCloseTextDocumentParams>(n.params) else { return };
                self.pending.remove(&p.text_document.uri);
                // A database closed unsaved is the disk's again.
                if let Some(doc) = self.docs.remove(&p.text_document.uri).filter(|d| d.lang == Lang::Json) {
                    self.reload(&doc.path);
                }
            }
            note::DidChangeWatchedFiles::METHOD => {
                let Ok(p) = serde_json::from_value::<lsp_types::DidChangeWatchedFilesParams>(n.params) else { return };
                for change in p.changes {
                    let open = self.docs.contains_key(&change.uri);
                    match change.uri.to_file_path() {
                        Ok(path) if !open && Lang::of(&path, "") == Lang::Json => self.reload(&path),
                        _ => {}
                    }
                }
            }
            _ => {}
        }
    }

    fn opened(&mut self, doc: Doc) {
        let uri = doc.uri.clone();
        if doc.lang == Lang::Json && self.ws.update(&doc.path, &doc.text) {
            self.recheck_all(Instant::now());
        }
        self.docs.insert(uri.clone(), doc);
        self.pending.insert(uri, Instant::now());
    }

    /// A database changed: every open document is checked again at `at`.
    fn recheck_all(&mut self, at: Instant) {
        for (uri, doc) in &mut self.docs {
            doc.names.take();
            self.pending.insert(uri.clone(), at);
        }
    }

    /// Reads a database JSON from disk again (changed or deleted there).
    fn reload(&mut self, path: &Path) {
        let text = crate::workspace::read(path).unwrap_or_default();
        if self.ws.update(path, &text) {
            self.recheck_all(Instant::now());
        }
    }

    /// The diagnostics of every document whose wait is over.
    pub fn due_diagnostics(&mut self, now: Instant) -> Vec<Message> {
        let due: Vec<Url> = self.pending.iter().filter(|(_, &t)| t <= now).map(|(u, _)| u.clone()).collect();
        let mut out = Vec::new();
        for uri in due {
            self.pending.remove(&uri);
            let Some(doc) = self.docs.get(&uri) else { continue };
            let diagnostics = match catch_unwind(AssertUnwindSafe(|| crate::analysis::diagnostics(&self.ws, doc))) {
                Ok(d) => d,
                Err(_) => {
                    self.panics += 1;
                    Vec::new()
                }
            };
            let mut diagnostics = diagnostics;
            for d in &mut diagnostics {
                // A fix's offsets hold for this version only.
                if let Some(data) = d.data.as_mut() {
                    data["version"] = doc.version.into();
                }
            }
            let params = PublishDiagnosticsParams { uri, diagnostics, version: Some(doc.version) };
            out.push(Message::Notification(Notification::new(note::PublishDiagnostics::METHOD.into(), params)));
        }
        out
    }

    /// The open document.
    pub fn doc(&self, uri: &Url) -> Option<&Doc> {
        self.docs.get(uri)
    }
}

pub enum Failure {
    Params(String),
    Method(String),
    /// The request cannot be done (a rename to a name that is not one).
    Request(String),
}

fn error(id: RequestId, f: Failure) -> Response {
    match f {
        Failure::Params(m) => Response::new_err(id, ErrorCode::InvalidParams as i32, m),
        Failure::Method(m) => Response::new_err(id, ErrorCode::MethodNotFound as i32, format!("unknown method {m}")),
        Failure::Request(m) => Response::new_err(id, ErrorCode::RequestFailed as i32, m),
    }
}

fn to<T: serde::Serialize>(v: T) -> Value {
    serde_json::to_value(v).unwrap_or(Value::Null)
}

//! `linc lsp`: a language server over stdio for LIN ST actions, sequences,
//! ladder and FST tables, and the strategy database JSON (ADR 0016,
//! docs/editors.md). The rules are the compiler's and the database's own:
//! diagnostics are exactly `linc check`'s, hover and completion read the
//! database and the function table, formatting is `linc fmt`.

mod actions;
mod analysis;
mod complete;
mod hover;
mod nav;
mod resolve;
mod server;
mod symbols;
mod text;
mod transport;
mod workspace;

use lsp_server::{Connection, ErrorCode, Message, RequestId, Response};
use lsp_types::{
    CodeActionProviderCapability, CompletionOptions, HoverProviderCapability, InitializeParams, OneOf, RenameOptions,
    SemanticTokensFullOptions, SemanticTokensOptions, SemanticTokensServerCapabilities, ServerCapabilities, ServerInfo,
    TextDocumentSyncCapability, TextDocumentSyncKind, WorkDoneProgressOptions,
};
pub use server::Server;
use server::DEBOUNCE;
use std::path::PathBuf;
use std::time::Duration;
pub use transport::MAX_MESSAGE;

/// The client's initialization options linc reads.
#[derive(Default, serde::Deserialize)]
#[serde(rename_all = "camelCase")]
struct Options {
    /// The database every file is checked against.
    database: Option<String>,
    /// Milliseconds between the last change and the diagnostics.
    debounce_ms: Option<u64>,
}

pub fn capabilities() -> ServerCapabilities {
    ServerCapabilities {
        text_document_sync: Some(TextDocumentSyncCapability::Kind(TextDocumentSyncKind::INCREMENTAL)),
        hover_provider: Some(HoverProviderCapability::Simple(true)),
        completion_provider: Some(CompletionOptions {
            trigger_characters: Some(vec![".".into(), "'".into(), "\"".into(), ",".into()]),
            ..CompletionOptions::default()
        }),
        definition_provider: Some(OneOf::Left(true)),
        references_provider: Some(OneOf::Left(true)),
        document_symbol_provider: Some(OneOf::Left(true)),
        workspace_symbol_provider: Some(OneOf::Left(true)),
        document_formatting_provider: Some(OneOf::Left(true)),
        rename_provider: Some(OneOf::Right(RenameOptions {
            prepare_provider: Some(true),
            work_done_progress_options: WorkDoneProgressOptions::default(),
        })),
        code_action_provider: Some(CodeActionProviderCapability::Simple(true)),
        semantic_tokens_provider: Some(SemanticTokensServerCapabilities::SemanticTokensOptions(
            SemanticTokensOptions {
                legend: symbols::legend(),
                full: Some(SemanticTokensFullOptions::Bool(true)),
                range: None,
                work_done_progress_options: WorkDoneProgressOptions::default(),
            },
        )),
        ..ServerCapabilities::default()
    }
}

/// How a session ended, which the command turns into its exit status: the
/// protocol asks for 0 when `exit` follows `shutdown`, 1 when it does not
/// (the client may have crashed, or stopped the server in a hurry).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// `shutdown` was received before `exit` (or the end of the input).
    Shutdown,
    /// `exit`, or the end of the input, came without `shutdown`.
    NoShutdown,
}

impl Ending {
    /// The process exit status the protocol gives this ending.
    pub fn status(self) -> u8 {
        match self {
            Ending::Shutdown => 0,
            Ending::NoShutdown => 1,
        }
    }
}

/// Serves one client over standard input and output, through the bounded
/// framing of [`transport`] (not lsp-server's, which trusts its input).
pub fn run_stdio() -> Result<Ending, String> {
    serve_io(std::io::stdin(), std::io::stdout())
}

/// Serves one client over any byte streams, as [`run_stdio`] does over
/// standard input and output.
pub fn serve_io(
    input: impl std::io::Read + Send + 'static,
    output: impl std::io::Write + Send + 'static,
) -> Result<Ending, String> {
    let (conn, io) = transport::connect(input, output);
    let ending = serve(&conn);
    drop(conn);
    io.join().map_err(|e| e.to_string())?;
    ending
}

/// Initializes with the client, then serves it until `exit`.
pub fn serve(conn: &Connection) -> Result<Ending, String> {
    let Some((id, params)) = initialize_start(conn) else { return Ok(Ending::NoShutdown) };
    let result = lsp_types::InitializeResult {
        capabilities: capabilities(),
        server_info: Some(ServerInfo { name: "linc".into(), version: Some(env!("CARGO_PKG_VERSION").into()) }),
    };
    let result = serde_json::to_value(result).map_err(|e| e.to_string())?;
    conn.sender.send(Response::new_ok(id, result).into()).map_err(|e| e.to_string())?;
    let mut server = server_for(&params);
    server.run(conn);
    Ok(if server.shutting_down { Ending::Shutdown } else { Ending::NoShutdown })
}

/// Waits for `initialize`, answering any other request with "not
/// initialized" (-32002) and an `initialize` whose parameters don't read
/// with "invalid params" (-32602), as the protocol asks; `None` when the
/// client sends `exit` first or goes away (an ending without shutdown).
/// lsp-server's own version ends the session on either, with no status.
fn initialize_start(conn: &Connection) -> Option<(RequestId, InitializeParams)> {
    for msg in &conn.receiver {
        match msg {
            Message::Request(req) if req.method == "initialize" => {
                match serde_json::from_value::<InitializeParams>(req.params) {
                    Ok(params) => return Some((req.id, params)),
                    Err(e) => {
                        let why = format!("initialize: {e}");
                        conn.sender
                            .send(Response::new_err(req.id, ErrorCode::InvalidParams as i32, why).into())
                            .ok()?;
                    }
                }
            }
            Message::Request(req) => {
                let why = format!("`{}` before initialize", req.method);
                let r = Response::new_err(req.id, ErrorCode::ServerNotInitialized as i32, why);
                conn.sender.send(r.into()).ok()?;
            }
            Message::Notification(n) if n.method == "exit" => return None,
            Message::Notification(_) | Message::Response(_) => {}
        }
    }
    None
}

/// The server a client's initialization asks for.
pub fn server_for(params: &InitializeParams) -> Server {
    let options: Options =
        params.initialization_options.clone().and_then(|v| serde_json::from_value(v).ok()).unwrap_or_default();
    let mut roots: Vec<PathBuf> =
        params.workspace_folders.iter().flatten().filter_map(|f| f.uri.to_file_path().ok()).collect();
    #[allow(deprecated)]
    if roots.is_empty() {
        roots.extend(params.root_uri.as_ref().and_then(|u| u.to_file_path().ok()));
    }
    let chosen = options.database.map(|d| {
        let p = PathBuf::from(d);
        match roots.first() {
            Some(root) if p.is_relative() => root.join(p),
            _ => p,
        }
    });
    let debounce = options.debounce_ms.map_or(DEBOUNCE, Duration::from_millis);
    Server::new(workspace::Workspace::new(roots, chosen), debounce)
}

//! The HTTP side: the monitor page and its assets (embedded: no CDN, works
//! offline), the JSON API and the event stream. Handlers ask the plant
//! thread and wait for its answer; they never touch the strategy.

use crate::http_guard::{foreign_origin, hardened, host_of, is_json, json_errors, refuse, Hosts};
use crate::wire::Limits;
use crate::{Ask, Event, Reply};
use axum::body::Body;
use axum::extract::rejection::QueryRejection;
use axum::extract::{Path, Query, Request, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::middleware::Next;
use axum::response::sse::{Event as SseEvent, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use axum_extra::headers::authorization::{Authorization, Bearer};
use axum_extra::typed_header::TypedHeaderRejection;
use axum_extra::TypedHeader;
use serde_json::{json, Value};
use std::collections::HashMap;
use std::convert::Infallible;
use std::sync::mpsc::Sender;
use std::sync::{Arc, Mutex};
use tokio::sync::{broadcast, oneshot, watch};

/// The longest console line the API takes (as the console's own).
const MAX_LINE: usize = 4096;

/// The largest body `POST /api/command` reads: a line of [`MAX_LINE`]
/// bytes, every one escaped in JSON, with room to spare.
const MAX_BODY: usize = 8 * MAX_LINE;

/// What a client over the connection cap is sent before it is closed,
/// its length counted from the body (a hand-counted one was one too many).
static BUSY: std::sync::LazyLock<Vec<u8>> = std::sync::LazyLock::new(|| {
    let body = json!({ "error": "too many connections: try again in a moment" }).to_string();
    let head = "HTTP/1.1 503 Service Unavailable\r\nContent-Type: application/json\r\nConnection: close";
    format!("{head}\r\nContent-Length: {}\r\n\r\n{body}", body.len()).into_bytes()
});

#[derive(Clone)]
pub struct AppState {
    asks: Sender<Ask>,
    events: broadcast::Sender<Arc<Event>>,
    status: Arc<Mutex<Value>>,
    token: Option<Arc<str>>,
    /// The names a request may address the server by.
    hosts: Arc<Hosts>,
    /// How long a request's body may take to arrive.
    request_time: std::time::Duration,
    /// Tells open event streams to end when the server stops.
    closing: watch::Receiver<bool>,
    close: Arc<watch::Sender<bool>>,
}

impl AppState {
    pub fn new(
        asks: Sender<Ask>,
        events: broadcast::Sender<Arc<Event>>,
        status: Arc<Mutex<Value>>,
        access: (Option<String>, Hosts, Limits),
    ) -> AppState {
        let (token, hosts, limits) = access;
        let (close, closing) = watch::channel(false);
        AppState {
            asks,
            events,
            status,
            token: token.map(Arc::from),
            hosts: Arc::new(hosts),
            request_time: limits.request,
            closing,
            close: Arc::new(close),
        }
    }

    /// Asks the plant thread; `None` when it has stopped.
    async fn ask<T>(&self, make: impl FnOnce(oneshot::Sender<T>) -> Ask) -> Option<T> {
        let (reply, answer) = oneshot::channel();
        self.asks.send(make(reply)).ok()?;
        answer.await.ok()
    }
}

/// The wire servers that run beside the HTTP one, on the same runtime.
pub struct Wires {
    pub roc: Option<(std::net::TcpListener, crate::wire::roc_server::Station)>,
    /// The ROC device's serial port, opened, and its address.
    pub(crate) roc_serial: Option<(crate::wire::serial::Port, crate::wire::roc_server::Station)>,
    /// The Modbus listener and the unit of the map.
    pub modbus: Option<(std::net::TcpListener, u8)>,
    pub asks: Sender<Ask>,
    pub limits: crate::wire::Limits,
    pub log: crate::wire::Log,
}

/// Serves on `rt` until `closed` fires, then ends the event streams and
/// returns.
pub fn serve(
    rt: tokio::runtime::Runtime,
    listener: std::net::TcpListener,
    state: AppState,
    wires: Wires,
    closed: oneshot::Receiver<()>,
) {
    let close = state.close.clone();
    let closing = state.closing.clone();
    let app = router(state);
    rt.block_on(async move {
        let Ok(listener) = tokio::net::TcpListener::from_std(listener) else { return };
        let plant = (wires.asks.clone(), wires.limits, wires.log.clone());
        if let Some((l, station)) = wires.roc {
            if let Ok(l) = tokio::net::TcpListener::from_std(l) {
                let wire = move || crate::wire::roc_server::Roc::new(station.clone());
                tokio::spawn(crate::wire::net::accept_wire(l, plant.clone(), closing.clone(), wire));
            }
        }
        if let Some((port, station)) = wires.roc_serial {
            let wire = move || crate::wire::roc_server::Roc::new(station.clone());
            tokio::spawn(crate::wire::serial::serve(port, plant.clone(), closing.clone(), wire));
        }
        if let Some((l, unit)) = wires.modbus {
            if let Ok(l) = tokio::net::TcpListener::from_std(l) {
                let wire = move || crate::wire::modbus_server::Modbus::new(unit);
                tokio::spawn(crate::wire::net::accept_wire(l, plant.clone(), closing.clone(), wire));
            }
        }
        let how = crate::wire::net::Listen {
            what: "http",
            busy: &BUSY,
            drain: true,
            limits: wires.limits,
            log: wires.log.clone(),
        };
        let (limits, conns) = (wires.limits, closing.clone());
        let http = crate::wire::net::accept(listener, how, closing, move |stream, _| {
            let _ = stream.set_nodelay(true);
            crate::http_conn::connection(stream, app.clone(), limits, conns.clone())
        });
        let shutdown = async move {
            let _ = closed.await;
            let _ = close.send(true);
        };
        tokio::join!(http, shutdown);
    });
    rt.shutdown_timeout(std::time::Duration::from_secs(1));
}

fn router(state: AppState) -> Router {
    Router::new()
        .route("/", get(|| async { asset("text/html; charset=utf-8", include_str!("../assets/index.html")) }))
        .route("/app.js", get(|| async { asset("text/javascript; charset=utf-8", include_str!("../assets/app.js")) }))
        .route("/style.css", get(|| async { asset("text/css; charset=utf-8", include_str!("../assets/style.css")) }))
        .route("/favicon.svg", get(|| async { asset("image/svg+xml", include_str!("../assets/favicon.svg")) }))
        .route("/api/programs", get(programs))
        .route("/api/blocks", get(blocks))
        .route("/api/blocks/{name}", get(block))
        .route("/api/pictures/{name}", get(picture))
        .route("/api/trend/{path}", get(trend))
        .route("/api/events", get(events))
        .route("/api/command", post(command))
        .fallback(|| async { refuse(StatusCode::NOT_FOUND, "no such page or API (docs/serve.md lists them)") })
        .layer(axum::middleware::from_fn_with_state(state.clone(), guard))
        .layer(axum::middleware::map_response(json_errors))
        .layer(axum::middleware::map_response(hardened))
        .with_state(state)
}

fn asset(kind: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, kind), (header::CACHE_CONTROL, "no-cache")], body).into_response()
}

/// Who may ask (http_guard.rs): a request must name this server in its
/// `Host` (what stops DNS rebinding), come from no other origin (a page
/// elsewhere must not drive the plant through the engineer's browser), and
/// carry the token when one is set: `Authorization: Bearer TOKEN` (the
/// scheme in any case) or, for the page and its event stream, which can't
/// set headers, `?token=TOKEN` (percent-decoded), as axum's extractors
/// read them.
async fn guard(
    State(s): State<AppState>,
    bearer: Result<TypedHeader<Authorization<Bearer>>, TypedHeaderRejection>,
    query: Result<Query<HashMap<String, String>>, QueryRejection>,
    req: Request,
    next: Next,
) -> Response {
    let host = host_of(req.headers(), req.uri()).unwrap_or_default();
    if !s.hosts.allows(&host) {
        let why = format!(
            "this server does not answer to the name `{host}`: use its address, or start it with --allow-host NAME"
        );
        return refuse(StatusCode::MISDIRECTED_REQUEST, &why);
    }
    if foreign_origin(req.headers(), &host) {
        return refuse(StatusCode::FORBIDDEN, "requests from another origin are refused");
    }
    if let Some(token) = &s.token {
        // A header or query that does not parse carries no token.
        let bearer = bearer.as_ref().ok().map(|TypedHeader(Authorization(b))| b.token());
        let query = query.as_ref().ok().and_then(|Query(q)| q.get("token")).map(String::as_str);
        let given = bearer.or(query);
        if !given.is_some_and(|g| same(g.as_bytes(), token.as_bytes())) {
            let why = if given.is_none() { "this server needs its token" } else { "wrong token" };
            let mut r = refuse(StatusCode::UNAUTHORIZED, why);
            r.headers_mut().insert(header::WWW_AUTHENTICATE, HeaderValue::from_static("Bearer"));
            return r;
        }
    }
    next.run(req).await
}

/// Compares in time independent of where the two differ.
fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |d, (x, y)| d | (x ^ y)) == 0
}

async fn programs(State(s): State<AppState>) -> Response {
    let status = s.status.lock().map(|v| v.clone()).unwrap_or(Value::Null);
    Json(status).into_response()
}

async fn blocks(State(s): State<AppState>) -> Response {
    match s.ask(|reply| Ask::Blocks { reply }).await {
        Some(v) => Json(v).into_response(),
        None => refuse(StatusCode::SERVICE_UNAVAILABLE, "the plant has stopped"),
    }
}

async fn block(State(s): State<AppState>, Path(name): Path<String>) -> Response {
    match s.ask(|reply| Ask::Block { name: name.clone(), reply }).await {
        Some(Some(v)) => Json(v).into_response(),
        Some(None) => refuse(StatusCode::NOT_FOUND, &format!("the database has no block `{name}`")),
        None => refuse(StatusCode::SERVICE_UNAVAILABLE, "the plant has stopped"),
    }
}

async fn picture(State(s): State<AppState>, Path(name): Path<String>) -> Response {
    match s.ask(|reply| Ask::Picture { name: name.clone(), reply }).await {
        Some(Some(svg)) => ([(header::CONTENT_TYPE, "image/svg+xml")], svg).into_response(),
        Some(None) => refuse(StatusCode::NOT_FOUND, &format!("block `{name}` runs no sequence, ladder or FST table")),
        None => refuse(StatusCode::SERVICE_UNAVAILABLE, "the plant has stopped"),
    }
}

/// `GET /api/trend/BLOCK.FIELD`: the field's recent changes (up to 15
/// simulated minutes) and its value now.
async fn trend(State(s): State<AppState>, Path(path): Path<String>) -> Response {
    match s.ask(|reply| Ask::Trend { path: path.clone(), reply }).await {
        Some(Some(v)) => Json(v).into_response(),
        Some(None) => refuse(StatusCode::NOT_FOUND, &format!("`{path}` is not a field of the database")),
        None => refuse(StatusCode::SERVICE_UNAVAILABLE, "the plant has stopped"),
    }
}

/// `POST /api/command`: `{"command": "M TANK1.Level=50"}` (JSON only: a
/// form on another site can't send it without asking first).
async fn command(State(s): State<AppState>, headers: HeaderMap, body: Body) -> Response {
    if !is_json(&headers) {
        return refuse(StatusCode::UNSUPPORTED_MEDIA_TYPE, "send {\"command\": \"…\"} as application/json");
    }
    let body = match tokio::time::timeout(s.request_time, axum::body::to_bytes(body, MAX_BODY)).await {
        Ok(Ok(b)) => b,
        Ok(Err(_)) => return refuse(StatusCode::PAYLOAD_TOO_LARGE, "a command body is at most 32 KiB"),
        Err(_) => return refuse(StatusCode::REQUEST_TIMEOUT, "the request's body took too long to arrive"),
    };
    let line = match serde_json::from_slice::<Value>(&body).ok().and_then(|v| v["command"].as_str().map(String::from)) {
        Some(l) => l,
        None => return refuse(StatusCode::BAD_REQUEST, "expected {\"command\": \"a console command line\"}"),
    };
    if line.len() > MAX_LINE || line.contains('\n') {
        return refuse(StatusCode::BAD_REQUEST, "a command line is one line of at most 4096 bytes");
    }
    match s.ask(|reply| Ask::Command { line, reply }).await {
        Some(Reply::Refused) => {
            refuse(StatusCode::FORBIDDEN, "this monitor is read-only: start linc serve with --allow-writes")
        }
        Some(Reply::Done { replies, failures }) => {
            let replies: Vec<Value> = replies
                .into_iter()
                .map(|r| match r {
                    Ok(reply) => json!({"ok": true, "reply": reply}),
                    Err(e) => json!({"ok": false, "code": e.code.as_str(), "message": e.message}),
                })
                .collect();
            Json(json!({"replies": replies, "failures": failures})).into_response()
        }
        None => refuse(StatusCode::SERVICE_UNAVAILABLE, "the plant has stopped"),
    }
}

/// `GET /api/events`: Server-Sent Events — `status`, `values` (changed
/// fields only), `picture` — at most ten times a second; `resync` when a
/// slow client missed some (it should fetch again).
async fn events(State(s): State<AppState>) -> Response {
    let rx = s.events.subscribe();
    let closing = s.closing.clone();
    let stream = futures_util::stream::unfold((rx, closing), |(mut rx, mut closing)| async move {
        if *closing.borrow() {
            return None;
        }
        let next = tokio::select! {
            r = rx.recv() => r,
            _ = closing.changed() => return None,
        };
        let event = match next {
            Ok(e) => SseEvent::default().event(e.name).data(e.data.as_str()),
            Err(broadcast::error::RecvError::Lagged(_)) => SseEvent::default().event("resync").data("{}"),
            Err(broadcast::error::RecvError::Closed) => return None,
        };
        Some((Ok::<_, Infallible>(event), (rx, closing)))
    });
    Sse::new(stream).keep_alive(KeepAlive::default()).into_response()
}

//! Who may ask the HTTP server anything (docs/serve.md, "Security"): the
//! `Host` a request names, the `Origin` a browser sends, the token — and
//! the rule that every error, whoever makes it, is a JSON body.
//!
//! The `Host` check is what stops DNS rebinding: a page on any site whose
//! name is re-pointed to 127.0.0.1 is same-origin with the server as far
//! as the browser knows, so only the name it asked for (`evil.example`)
//! tells the request apart from the engineer's own page.

use axum::body::Body;
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use serde_json::json;
use std::net::{IpAddr, SocketAddr};

/// The names and the port a request may address the server by.
#[derive(Clone, Debug)]
pub struct Hosts {
    port: u16,
    /// The address the server listens on; unspecified (`0.0.0.0`) means
    /// any of the machine's addresses.
    bound: IpAddr,
    /// Names given with `--allow-host`, in lower case.
    names: Vec<String>,
}

impl Hosts {
    pub fn new(bound: SocketAddr, names: &[String]) -> Hosts {
        let names = names.iter().map(|n| n.trim_end_matches('.').to_ascii_lowercase()).collect();
        Hosts { port: bound.port(), bound: bound.ip(), names }
    }

    /// Whether `host` (a `Host` header: `name[:port]`, `[v6][:port]`)
    /// names this server: a loopback name or address, the address it is
    /// bound to (any address when bound to all of them), or a name given
    /// with `--allow-host`; with this server's port (or none, on port 80).
    pub fn allows(&self, host: &str) -> bool {
        let Some((name, port)) = split_host(host) else { return false };
        if port.unwrap_or(80) != self.port {
            return false;
        }
        let name = name.trim_end_matches('.').to_ascii_lowercase();
        match name.trim_start_matches('[').trim_end_matches(']').parse::<IpAddr>() {
            Ok(ip) => ip.is_loopback() || ip == self.bound || self.bound.is_unspecified(),
            Err(_) => name == "localhost" || self.names.contains(&name),
        }
    }
}

/// `name[:port]` or `[v6][:port]`, split; `None` when it is neither.
fn split_host(host: &str) -> Option<(&str, Option<u16>)> {
    let host = host.trim();
    let (name, port) = if host.starts_with('[') {
        let end = host.find(']')? + 1;
        let rest = &host[end..];
        let port = if rest.is_empty() { None } else { Some(rest.strip_prefix(':')?) };
        (&host[..end], port)
    } else {
        match host.split_once(':') {
            Some((n, p)) => (n, Some(p)),
            None => (host, None),
        }
    };
    let valid = |c: char| c.is_ascii_alphanumeric() || "-._[]:".contains(c);
    if name.is_empty() || !name.chars().all(valid) {
        return None;
    }
    let port = match port {
        Some(p) => Some(p.parse().ok()?),
        None => None,
    };
    Some((name, port))
}

/// The `Host` a request names: its header, or the authority of its URI.
pub fn host_of(headers: &HeaderMap, uri: &axum::http::Uri) -> Option<String> {
    match headers.get(header::HOST) {
        Some(h) => h.to_str().ok().map(String::from),
        None => uri.authority().map(|a| a.to_string()),
    }
}

/// Whether an `Origin` header names another origin than this server as
/// the request addressed it: scheme (`http`: the server speaks nothing
/// else), host and port must all match. `Origin: null` (a sandboxed frame,
/// a file) is foreign; no `Origin` at all is a tool, not a page.
pub fn foreign_origin(headers: &HeaderMap, host: &str) -> bool {
    let Some(origin) = headers.get(header::ORIGIN) else { return false };
    let Some(origin) = origin.to_str().ok() else { return true };
    let Some(rest) = origin.strip_prefix("http://") else { return true };
    let (Some((o_name, o_port)), Some((h_name, h_port))) = (split_host(rest), split_host(host)) else {
        return true;
    };
    !(o_name.eq_ignore_ascii_case(h_name) && o_port.unwrap_or(80) == h_port.unwrap_or(80))
}

/// Whether a `Content-Type` is exactly `application/json` (parameters
/// such as `charset` allowed): `application/jsonp` or `text/json` are not.
pub fn is_json(headers: &HeaderMap) -> bool {
    headers.get(header::CONTENT_TYPE).and_then(|v| v.to_str().ok()).is_some_and(json_type)
}

fn json_type(t: &str) -> bool {
    t.split(';').next().unwrap_or("").trim().eq_ignore_ascii_case("application/json")
}

/// An error as every error of the API is: a status and `{"error": why}`.
pub fn refuse(status: StatusCode, why: &str) -> Response {
    (status, Json(json!({ "error": why }))).into_response()
}

/// What every response says about how a browser may use it: scripts and
/// everything else only from the server itself (an SVG drawn from a
/// database's names can't run a script however it is written), never in
/// a frame of another page (no clickjacking of the controls), no referrer
/// (a `?token=` in the page's address must not leak to a link's target),
/// no guessing of content types, and nothing of the API kept in a cache.
pub async fn hardened(mut r: Response) -> Response {
    const CSP: &str = "default-src 'self'; script-src 'self'; style-src 'self' 'unsafe-inline'; \
                       img-src 'self' data:; connect-src 'self'; object-src 'none'; base-uri 'none'; \
                       form-action 'self'; frame-ancestors 'none'";
    let h = r.headers_mut();
    h.insert(header::CONTENT_SECURITY_POLICY, HeaderValue::from_static(CSP));
    h.insert(header::X_FRAME_OPTIONS, HeaderValue::from_static("DENY"));
    h.insert(header::X_CONTENT_TYPE_OPTIONS, HeaderValue::from_static("nosniff"));
    h.insert(header::REFERRER_POLICY, HeaderValue::from_static("no-referrer"));
    if !h.contains_key(header::CACHE_CONTROL) {
        h.insert(header::CACHE_CONTROL, HeaderValue::from_static("no-store"));
    }
    r
}

/// The largest error body of another layer that is kept as the message
/// when it is turned into JSON.
const KEPT_ERROR: usize = 1024;

/// Turns an error response that is not JSON (axum's own rejections: an
/// unknown path or method, a body too large, a path that is not UTF-8)
/// into `{"error": why}` with the same status and headers, so a client
/// parses every error one way.
pub async fn json_errors(r: Response) -> Response {
    let status = r.status();
    if !(status.is_client_error() || status.is_server_error()) || is_json(r.headers()) {
        return r;
    }
    let (mut parts, body) = r.into_parts();
    let text = axum::body::to_bytes(body, KEPT_ERROR).await.unwrap_or_default();
    let text = String::from_utf8_lossy(&text).trim().to_string();
    let why = match (text.is_empty(), status) {
        (false, _) => text,
        (true, StatusCode::NOT_FOUND) => "no such page or API (docs/serve.md lists them)".to_string(),
        (true, StatusCode::METHOD_NOT_ALLOWED) => "that method is not allowed here".to_string(),
        (true, s) => s.canonical_reason().unwrap_or("refused").to_ascii_lowercase(),
    };
    let body = json!({ "error": why }).to_string();
    parts.headers.insert(header::CONTENT_TYPE, HeaderValue::from_static("application/json"));
    parts.headers.remove(header::CONTENT_LENGTH);
    Response::from_parts(parts, Body::from(body))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hosts(bound: &str, names: &[&str]) -> Hosts {
        let names: Vec<String> = names.iter().map(|s| s.to_string()).collect();
        Hosts::new(bound.parse().unwrap(), &names)
    }

    #[test]
    fn only_loopback_names_the_bound_address_and_allowed_names_pass() {
        let h = hosts("127.0.0.1:8080", &["plant.example"]);
        for ok in
            ["127.0.0.1:8080", "localhost:8080", "LOCALHOST:8080", "[::1]:8080", "plant.example:8080", "127.0.0.2:8080"]
        {
            assert!(h.allows(ok), "{ok}");
        }
        for bad in [
            "evil.example:8080",
            "127.0.0.1:8081",
            "127.0.0.1",
            "localhost.evil.example:8080",
            "",
            "127.0.0.1:8080:1",
            "[::1",
            "10.0.0.5:8080",
            "a b:8080",
        ] {
            assert!(!h.allows(bad), "{bad}");
        }
    }

    #[test]
    fn bound_to_every_address_any_address_passes_but_no_unnamed_name() {
        let h = hosts("0.0.0.0:80", &[]);
        assert!(h.allows("10.0.0.5"));
        assert!(h.allows("192.168.1.9:80"));
        assert!(!h.allows("scada.example"));
        let h = hosts("10.0.0.5:8080", &[]);
        assert!(h.allows("10.0.0.5:8080"));
        assert!(!h.allows("10.0.0.6:8080"));
    }

    fn origin(o: &str) -> HeaderMap {
        let mut h = HeaderMap::new();
        h.insert(header::ORIGIN, HeaderValue::from_str(o).unwrap());
        h
    }

    #[test]
    fn origin_must_match_scheme_host_and_port() {
        assert!(!foreign_origin(&origin("http://127.0.0.1:8080"), "127.0.0.1:8080"));
        assert!(!foreign_origin(&origin("http://LOCALHOST:8080"), "localhost:8080"));
        assert!(!foreign_origin(&origin("http://localhost"), "localhost:80"));
        assert!(!foreign_origin(&HeaderMap::new(), "localhost:8080"));
        for bad in [
            "https://127.0.0.1:8080",
            "http://127.0.0.1:8081",
            "http://evil.example:8080",
            "null",
            "ws://127.0.0.1:8080",
        ] {
            assert!(foreign_origin(&origin(bad), "127.0.0.1:8080"), "{bad}");
        }
    }

    #[test]
    fn only_the_exact_json_media_type_is_json() {
        let ct = |t: &str| {
            let mut h = HeaderMap::new();
            h.insert(header::CONTENT_TYPE, HeaderValue::from_str(t).unwrap());
            is_json(&h)
        };
        assert!(ct("application/json"));
        assert!(ct("Application/JSON; charset=utf-8"));
        assert!(!ct("application/jsonp"));
        assert!(!ct("application/json-seq"));
        assert!(!ct("text/plain; application/json"));
        assert!(!is_json(&HeaderMap::new()));
    }
}

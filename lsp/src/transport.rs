//! The protocol's framing over a byte stream (`Content-Length` headers, a
//! blank line, a JSON body), read here rather than by lsp-server's
//! `Connection::stdio`, which trusts its input: it allocates whatever
//! length a header claims (a 33-byte `Content-Length: 100000000000` aborted
//! the server) and ends on the first malformed header or body, losing
//! every open document. This reader bounds everything it keeps — a header
//! line, the number of header lines, a message ([`MAX_MESSAGE`]) — grows a
//! body only as its bytes arrive, and answers what it cannot use with a
//! JSON-RPC error instead of stopping:
//!
//! - a malformed header block or a body that is not JSON: parse error
//!   (-32700), `id: null`;
//! - JSON that is not a request, notification or response: invalid request
//!   (-32600), with the message's `id` when it has a usable one;
//! - a message over the limit: invalid request (-32600), `id: null`,
//!   answered at once; its body is skipped without being stored, up to its
//!   claimed end or to the next `Content-Length:` header, whichever comes
//!   first (a `Content-Length:` can start no line of a JSON text, so a
//!   client that claimed a length it never sends is heard again).
//!
//! The server thread sees only well-formed messages, through an
//! `lsp_server::Connection` whose channels these threads feed; one writer
//! thread writes the server's messages and the reader's errors, one frame
//! at a time.

use crossbeam_channel::{bounded, never, select, Receiver, Sender};
use lsp_server::{Connection, ErrorCode, Message, Notification, Request, Response};
use serde::Deserialize;
use serde_json::{json, Value};
use std::io::{self, BufRead, BufReader, Read, Write};
use std::thread::JoinHandle;

/// The largest message read (64 MiB): a document of tens of megabytes
/// still fits; a claimed length beyond it is refused before anything is
/// allocated.
pub const MAX_MESSAGE: u64 = 64 << 20;
/// The longest header line kept (a real one is about 30 bytes).
const MAX_HEADER_LINE: usize = 1024;
/// The most header lines in one message (the protocol defines two).
const MAX_HEADERS: usize = 32;
/// How much of a body is read (and allocated) at a time.
const CHUNK: usize = 64 << 10;
/// The header a lost reader looks for to find the next message.
const RESYNC: &[u8] = b"Content-Length:";

/// What the reader made of the next bytes of the stream.
#[derive(Debug)]
pub enum Next {
    Message(Message),
    /// A message that cannot be used, and the error response that answers it.
    Refused(Value),
    /// The end of the stream (a message cut by it is dropped).
    End,
}

/// A line of a header block.
enum Line {
    Text(Vec<u8>),
    TooLong,
    End,
}

/// Reads framed messages from a byte stream, within bounds.
pub struct Reader<R> {
    input: R,
    limit: u64,
    /// Bytes already taken from the input that start the next line (the
    /// `Content-Length:` a skip stopped at).
    carry: Vec<u8>,
}

impl<R: BufRead> Reader<R> {
    /// A reader refusing messages over `limit` bytes.
    pub fn new(input: R, limit: u64) -> Reader<R> {
        Reader { input, limit, carry: Vec::new() }
    }

    /// The next message, or why the next bytes are none.
    pub fn next_message(&mut self) -> io::Result<Next> {
        let length = match self.headers()? {
            None => return Ok(Next::End),
            Some(Ok(length)) => length,
            Some(Err(why)) => return Ok(Next::Refused(refusal(Value::Null, ErrorCode::ParseError, why))),
        };
        if length > self.limit {
            self.skip(length)?;
            let why = format!("a message of {length} bytes is over the limit of {}", size(self.limit));
            return Ok(Next::Refused(refusal(Value::Null, ErrorCode::InvalidRequest, why)));
        }
        let Some(body) = self.body(length as usize)? else { return Ok(Next::End) };
        Ok(classify(&body))
    }

    /// The `Content-Length` of the next header block, or what is wrong
    /// with the block; `None` at the end of the stream. Blank lines before
    /// a block are skipped.
    fn headers(&mut self) -> io::Result<Option<Result<u64, String>>> {
        let mut length: Option<u64> = None;
        let mut problem: Option<String> = None;
        let mut count = 0;
        loop {
            let line = match self.line()? {
                Line::End => return Ok(None),
                Line::TooLong => Err(format!("a header line is longer than {MAX_HEADER_LINE} bytes")),
                Line::Text(t) if t.is_empty() && count == 0 => continue,
                Line::Text(t) if t.is_empty() => break,
                Line::Text(t) => header(&t),
            };
            count += 1;
            if count > MAX_HEADERS {
                problem.get_or_insert_with(|| format!("more than {MAX_HEADERS} header lines"));
            }
            match line {
                Ok(Some(n)) if length.is_some_and(|l| l != n) => {
                    problem.get_or_insert_with(|| "two different Content-Length headers".into());
                }
                Ok(Some(n)) => length = Some(n),
                Ok(None) => {}
                Err(why) => {
                    problem.get_or_insert(why);
                }
            }
        }
        Ok(Some(match (problem, length) {
            (Some(why), _) => {
                // The body's length is known: skip it, to read on at the next message.
                if let Some(n) = length {
                    self.skip(n)?;
                }
                Err(why)
            }
            (None, Some(n)) => Ok(n),
            (None, None) => Err("a message without a Content-Length header".into()),
        }))
    }

    /// One line without its `\n` (and `\r`), keeping at most
    /// [`MAX_HEADER_LINE`] bytes of it.
    fn line(&mut self) -> io::Result<Line> {
        let mut text = std::mem::take(&mut self.carry);
        let mut too_long = false;
        loop {
            let buf = self.input.fill_buf()?;
            if buf.is_empty() {
                return Ok(Line::End);
            }
            let (part, done) = match buf.iter().position(|&b| b == b'\n') {
                Some(i) => (&buf[..i], i + 1),
                None => (buf, buf.len()),
            };
            let newline = done > part.len();
            if text.len() + part.len() > MAX_HEADER_LINE {
                too_long = true;
                text.clear();
            } else if !too_long {
                text.extend_from_slice(part);
            }
            self.input.consume(done);
            if newline {
                break;
            }
        }
        if too_long {
            return Ok(Line::TooLong);
        }
        if text.last() == Some(&b'\r') {
            text.pop();
        }
        Ok(Line::Text(text))
    }

    /// Skips `length` bytes without keeping them, stopping early before a
    /// [`RESYNC`] header (kept in `carry` for the next line).
    fn skip(&mut self, length: u64) -> io::Result<()> {
        let mut left = length;
        let mut matched = 0;
        while left > 0 {
            let buf = self.input.fill_buf()?;
            if buf.is_empty() {
                return Ok(());
            }
            let n = buf.len().min(usize::try_from(left).unwrap_or(usize::MAX));
            let mut used = n;
            for (i, &b) in buf[..n].iter().enumerate() {
                // `C` occurs once in the pattern: a mismatch restarts it.
                matched = if b == RESYNC[matched] { matched + 1 } else { usize::from(b == RESYNC[0]) };
                if matched == RESYNC.len() {
                    used = i + 1;
                    break;
                }
            }
            self.input.consume(used);
            left -= used as u64;
            if matched == RESYNC.len() {
                self.carry = RESYNC.to_vec();
                return Ok(());
            }
        }
        Ok(())
    }

    /// A body of `length` bytes, read a chunk at a time so that memory
    /// follows the bytes that arrive, not the length claimed; `None` if the
    /// stream ends first.
    fn body(&mut self, length: usize) -> io::Result<Option<Vec<u8>>> {
        let mut body: Vec<u8> = Vec::new();
        while body.len() < length {
            let buf = self.input.fill_buf()?;
            if buf.is_empty() {
                return Ok(None);
            }
            let n = buf.len().min(length - body.len());
            if body.capacity() - body.len() < n {
                // Doubling, but never past the claimed length.
                let want = (body.len() * 2).max(CHUNK).max(body.len() + n).min(length);
                body.reserve_exact(want - body.len());
            }
            body.extend_from_slice(&buf[..n]);
            self.input.consume(n);
        }
        Ok(Some(body))
    }
}

/// A number of bytes, in MiB when it is whole ones.
fn size(bytes: u64) -> String {
    if bytes & ((1 << 20) - 1) == 0 {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

/// A header line: `Some(length)` for `Content-Length`, `None` for another
/// header (`Content-Type`), or what is wrong with it.
fn header(line: &[u8]) -> Result<Option<u64>, String> {
    let text = std::str::from_utf8(line).map_err(|_| "a header line that is not UTF-8".to_string())?;
    let Some((name, value)) = text.split_once(':') else {
        return Err(format!("a header line without `:` ({} bytes)", line.len()));
    };
    if !name.trim().eq_ignore_ascii_case("Content-Length") {
        return Ok(None);
    }
    let value = value.trim();
    if value.is_empty() || !value.bytes().all(|b| b.is_ascii_digit()) {
        return Err(format!("Content-Length `{}` is not a number", value.chars().take(40).collect::<String>()));
    }
    // All digits: only too many of them fails; such a length is over any limit.
    Ok(Some(value.parse().unwrap_or(u64::MAX)))
}

/// A body as a message, or the error that answers it.
fn classify(body: &[u8]) -> Next {
    let value: Value = match serde_json::from_slice(body) {
        Ok(v) => v,
        Err(e) => return Next::Refused(refusal(Value::Null, ErrorCode::ParseError, format!("not JSON: {e}"))),
    };
    let message = shape(&value);
    match message {
        Some(m) => Next::Message(m),
        None => {
            let id = match value.get("id") {
                Some(id @ (Value::Number(_) | Value::String(_))) => id.clone(),
                _ => Value::Null,
            };
            let why = "not a request, notification or response".to_string();
            Next::Refused(refusal(id, ErrorCode::InvalidRequest, why))
        }
    }
}

/// The message a JSON value is, by its members, as JSON-RPC tells them
/// apart: with `method`, a request (with `id`) or a notification; else, with
/// `id` and `result` or `error`, a response. (Left to serde's untagged
/// enum, anything with an `id` would pass for a response, and an array for
/// a request.)
fn shape(value: &Value) -> Option<Message> {
    let object = value.as_object()?;
    let has = |k: &str| object.contains_key(k);
    if has("method") && has("id") {
        Request::deserialize(value).ok().map(Message::Request)
    } else if has("method") {
        Notification::deserialize(value).ok().map(Message::Notification)
    } else if has("id") && (has("result") || has("error")) {
        Response::deserialize(value).ok().map(Message::Response)
    } else {
        None
    }
}

/// A JSON-RPC error response (`id` may be null, which lsp-server's
/// `Response` cannot say).
fn refusal(id: Value, code: ErrorCode, message: String) -> Value {
    json!({ "jsonrpc": "2.0", "id": id, "error": { "code": code as i32, "message": message } })
}

/// Writes one frame.
fn write_frame(out: &mut impl Write, body: &[u8]) -> io::Result<()> {
    write!(out, "Content-Length: {}\r\n\r\n", body.len())?;
    out.write_all(body)?;
    out.flush()
}

/// The threads serving a connection's bytes.
pub struct Io {
    writer: JoinHandle<io::Result<()>>,
}

impl Io {
    /// Waits until everything the server sent is written. The reader is
    /// not waited for: after `exit` it has stopped, and otherwise it may be
    /// blocked on an input that never ends.
    pub fn join(self) -> io::Result<()> {
        self.writer.join().unwrap_or_else(|_| Err(io::Error::other("the writer thread panicked")))
    }
}

/// A connection over `input` and `output`: a reader thread parses the
/// input within bounds (answering what it refuses itself), a writer thread
/// writes frames.
pub fn connect(input: impl Read + Send + 'static, output: impl Write + Send + 'static) -> (Connection, Io) {
    let (to_server, from_reader) = bounded::<Message>(16);
    let (to_writer, from_server) = bounded::<Message>(16);
    let (refuse, refused) = bounded::<Value>(16);
    std::thread::spawn(move || read_loop(Reader::new(BufReader::new(input), MAX_MESSAGE), &to_server, &refuse));
    let writer = std::thread::spawn(move || write_loop(output, &from_server, &refused));
    (Connection { sender: to_writer, receiver: from_reader }, Io { writer })
}

fn read_loop<R: BufRead>(mut reader: Reader<R>, to_server: &Sender<Message>, refuse: &Sender<Value>) {
    loop {
        match reader.next_message() {
            Ok(Next::Message(m)) => {
                let exit = matches!(&m, Message::Notification(n) if n.method == "exit");
                if to_server.send(m).is_err() || exit {
                    return;
                }
            }
            Ok(Next::Refused(v)) => {
                if refuse.send(v).is_err() {
                    return;
                }
            }
            Ok(Next::End) | Err(_) => return,
        }
    }
}

/// Writes the server's messages and the reader's refusals until the server
/// is done (then the refusals already made).
fn write_loop(mut out: impl Write, from_server: &Receiver<Message>, refused: &Receiver<Value>) -> io::Result<()> {
    let mut reader_open = true;
    loop {
        let refusals = if reader_open { refused.clone() } else { never() };
        select! {
            recv(from_server) -> m => match m {
                Ok(m) => m.write(&mut out)?,
                Err(_) => break,
            },
            recv(refusals) -> v => match v {
                Ok(v) => write_frame(&mut out, v.to_string().as_bytes())?,
                Err(_) => reader_open = false,
            },
        }
    }
    for v in refused.try_iter() {
        write_frame(&mut out, v.to_string().as_bytes())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Everything a reader with `limit` makes of `bytes`: each message's
    /// method or id, each refusal's code, id and message.
    fn read_all(bytes: &[u8], limit: u64) -> Vec<String> {
        let mut r = Reader::new(bytes, limit);
        let mut out = Vec::new();
        loop {
            match r.next_message().expect("read") {
                Next::Message(Message::Request(q)) => out.push(format!("request {} {}", q.id, q.method)),
                Next::Message(Message::Notification(n)) => out.push(format!("notification {}", n.method)),
                Next::Message(Message::Response(p)) => out.push(format!("response {}", p.id)),
                Next::Refused(v) => out.push(format!("{} {} {}", v["error"]["code"], v["id"], v["error"]["message"])),
                Next::End => return out,
            }
        }
    }

    fn frame(body: &str) -> String {
        format!("Content-Length: {}\r\n\r\n{body}", body.len())
    }

    const PING: &str = r#"{"jsonrpc":"2.0","id":7,"method":"ping"}"#;

    #[test]
    fn well_formed_messages_are_read_whatever_the_header_spelling() {
        let stream = format!(
            "{}\r\n\r\ncontent-length:{}\r\nContent-Type: application/vscode-jsonrpc; charset=utf-8\r\n\r\n{PING}{}",
            frame(r#"{"jsonrpc":"2.0","method":"initialized","params":{}}"#),
            PING.len(),
            frame(r#"{"jsonrpc":"2.0","id":"a","result":null}"#),
        );
        assert_eq!(
            read_all(stream.as_bytes(), MAX_MESSAGE),
            ["notification initialized", "request 7 ping", "response \"a\""]
        );
    }

    #[test]
    fn a_message_over_the_limit_is_refused_and_skipped_up_to_the_next_header() {
        let limit = 10;
        let at_limit = r#"{"id":1234}"#; // 11 bytes: one over
        let stream = format!("{}{}", frame(at_limit), frame("[1,2,3]"));
        assert_eq!(
            read_all(stream.as_bytes(), limit),
            [
                "-32600 null \"a message of 11 bytes is over the limit of 10 bytes\"",
                "-32600 null \"not a request, notification or response\"",
            ]
        );
        // A claimed length that never comes: the next header is found.
        let stream = format!("Content-Length: 100000000000\r\n\r\n{}", frame(PING));
        assert_eq!(
            read_all(stream.as_bytes(), MAX_MESSAGE),
            ["-32600 null \"a message of 100000000000 bytes is over the limit of 64 MiB\"", "request 7 ping"]
        );
        // More digits than any length: over the limit too.
        let stream = format!("Content-Length: {}\r\n\r\n{}", "9".repeat(40), frame(PING));
        assert_eq!(read_all(stream.as_bytes(), MAX_MESSAGE)[1], "request 7 ping");
    }

    #[test]
    fn malformed_headers_are_parse_errors_and_reading_goes_on() {
        let long = format!("X-Long: {}\r\nContent-Length: 2\r\n\r\n{{}}", "x".repeat(MAX_HEADER_LINE));
        let many = format!("{}Content-Length: 2\r\n\r\n{{}}", "X-A: b\r\n".repeat(MAX_HEADERS));
        let cases = [
            ("Content-Length: ten\r\n\r\n", "Content-Length `ten` is not a number"),
            ("Content-Type: text\r\n\r\n", "a message without a Content-Length header"),
            ("no colon here\r\nContent-Length: 2\r\n\r\n{}", "a header line without `:` (13 bytes)"),
            ("Content-Length: 2\r\nContent-Length: 3\r\n\r\n{}", "two different Content-Length headers"),
            (long.as_str(), "a header line is longer than 1024 bytes"),
            (many.as_str(), "more than 32 header lines"),
        ];
        for (bad, why) in cases {
            let stream = format!("{bad}{}", frame(PING));
            assert_eq!(
                read_all(stream.as_bytes(), MAX_MESSAGE),
                [format!("-32700 null \"{why}\""), "request 7 ping".into()]
            );
        }
    }

    #[test]
    fn bodies_that_are_not_json_or_not_messages_are_answered() {
        let stream = [frame("{\"id\": 3, "), frame(r#"{"id":4,"method":5}"#), frame("[]"), frame(PING)].concat();
        let got = read_all(stream.as_bytes(), MAX_MESSAGE);
        assert!(got[0].starts_with("-32700 null \"not JSON: EOF while parsing"), "{got:?}");
        assert_eq!(
            got[1..],
            [
                "-32600 4 \"not a request, notification or response\"".to_string(),
                "-32600 null \"not a request, notification or response\"".into(),
                "request 7 ping".into()
            ]
        );
    }

    #[test]
    fn a_body_cut_by_the_end_of_the_stream_is_dropped() {
        assert_eq!(read_all(b"Content-Length: 50\r\n\r\n{\"id\":", MAX_MESSAGE), Vec::<String>::new());
        assert_eq!(read_all(b"Content-Len", MAX_MESSAGE), Vec::<String>::new());
    }
}

//! Fuzz of the framing, through the real reader and the real server
//! (`linc_lsp::serve_io` over in-memory streams): 100,000 messages, of which
//! half are broken in ways whose answer is known (bad JSON, JSON of the
//! wrong shape, malformed headers, lengths far over the limit that never
//! come) and counted exactly, and half chaos (random bytes, messages cut
//! anywhere, huge and truncated lengths), all interleaved with valid
//! requests. Every valid request of the first half is answered, the open
//! document survives, the request after the chaos is answered, the server
//! ends as the protocol says, and the heap's peak (a counting allocator)
//! stays under 100 MB. The input is generated as it is read and the output
//! parsed as it is written, so the test itself holds neither.
//!
//! The stream is counted work, not timed; `LINC_FRAMING_FUZZ=N` changes the
//! number of messages (100,000 by default, a few seconds in debug).

use linc_lsp::Ending;
use linc_test_support::alloc::{peak_of, serial, Counting};
use linc_test_support::Rng;
use serde_json::{json, Value};
use std::collections::VecDeque;
use std::io::{Read, Write};
use std::sync::{Arc, Mutex};

#[global_allocator]
static A: Counting = Counting;

const URI: &str = "file:///fuzz/actions.stx";
const TEXT: &str = "ACTION Main\n  x := ABS(1);\nEND_ACTION\n";

fn cases() -> usize {
    std::env::var("LINC_FRAMING_FUZZ").ok().and_then(|v| v.parse().ok()).unwrap_or(100_000)
}

fn frame(body: &str) -> Vec<u8> {
    format!("Content-Length: {}\r\n\r\n{body}", body.len()).into_bytes()
}

fn request(id: u64, method: &str, params: Value) -> Vec<u8> {
    frame(&json!({ "jsonrpc": "2.0", "id": id, "method": method, "params": params }).to_string())
}

fn notification(method: &str, params: Value) -> Vec<u8> {
    frame(&json!({ "jsonrpc": "2.0", "method": method, "params": params }).to_string())
}

/// A hover on `ABS` in the open document.
fn hover(id: u64) -> Vec<u8> {
    request(
        id,
        "textDocument/hover",
        json!({ "textDocument": { "uri": URI }, "position": { "line": 1, "character": 8 } }),
    )
}

/// What the server is expected to answer, counted as the stream is made.
#[derive(Default, Debug, PartialEq, Eq, Clone)]
struct Tally {
    parse_errors: usize,
    invalid: usize,
    /// Requests that must be answered (with a result or MethodNotFound).
    answered: usize,
    hovers: usize,
}

/// The stream: a session's start, the known half, the chaos, the last
/// hover, `shutdown` and `exit`; each piece made when the reader needs it.
struct Stream {
    rng: Rng,
    left: usize,
    left_at_start: usize,
    chaos_from: usize,
    pending: VecDeque<u8>,
    expected: Tally,
    next_id: u64,
    after_huge: bool,
    finished: bool,
}

impl Stream {
    /// `n` pieces, known ones if `known`, else chaos.
    fn new(n: usize, known: bool) -> Stream {
        let mut pending: VecDeque<u8> = VecDeque::new();
        let init = json!({ "processId": null, "capabilities": {}, "initializationOptions": { "debounceMs": 0 } });
        pending.extend(request(1, "initialize", init));
        pending.extend(notification("initialized", json!({})));
        let doc = json!({ "textDocument": { "uri": URI, "languageId": "lin-st", "version": 1, "text": TEXT } });
        pending.extend(notification("textDocument/didOpen", doc));
        let expected = Tally { answered: 1, ..Tally::default() };
        Stream {
            rng: Rng::new(0x5eed_f4a3),
            left: n,
            left_at_start: n,
            chaos_from: if known { 0 } else { n },
            pending,
            expected,
            next_id: 10,
            after_huge: false,
            finished: false,
        }
    }

    fn id(&mut self) -> u64 {
        self.next_id += 1;
        self.next_id
    }

    /// One piece of the known half, its answer counted.
    fn known(&mut self) -> Vec<u8> {
        // After a huge length, only what starts with `Content-Length:`:
        // the skip of the length that never comes stops there.
        let choice = if self.after_huge { [0, 1, 2, 3, 5][self.rng.below(5)] } else { self.rng.below(7) };
        self.after_huge = false;
        match choice {
            0 => {
                let id = self.id();
                self.expected.answered += 1;
                if self.rng.one_in(20) {
                    self.expected.hovers += 1;
                    hover(id)
                } else {
                    request(id, "linc/unknown", json!({}))
                }
            }
            1 => {
                self.expected.parse_errors += 1;
                let bodies = ["{\"id\": 3, ", "not json", "{\"a\":1}}", "\u{1F600}", ""];
                frame(bodies[self.rng.below(bodies.len())])
            }
            2 => {
                self.expected.invalid += 1;
                let bodies = ["[]", "42", "\"text\"", "{}", "{\"id\":4,\"method\":5}", "{\"method\":[1]}", "null"];
                frame(bodies[self.rng.below(bodies.len())])
            }
            3 => {
                self.expected.parse_errors += 1;
                b"Content-Length: 12x\r\n\r\n".to_vec()
            }
            4 => {
                self.expected.parse_errors += 1;
                let mut b = b"a header without a colon\r\n".to_vec();
                b.extend(frame("{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"skipped\"}"));
                b
            }
            5 => {
                self.expected.invalid += 1;
                self.after_huge = true;
                let lengths = ["100000000000", "67108865", "18446744073709551615", "99999999999999999999999999"];
                format!("Content-Length: {}\r\n\r\n", lengths[self.rng.below(lengths.len())]).into_bytes()
            }
            // No Content-Length: the block ends, nothing else is taken.
            _ => {
                self.expected.parse_errors += 1;
                b"Content-Type: application/vscode-jsonrpc\r\n\r\n".to_vec()
            }
        }
    }

    /// One piece of chaos: its answers are not counted.
    fn chaos(&mut self) -> Vec<u8> {
        let rng = &mut self.rng;
        match rng.below(6) {
            0 => (0..rng.below(200)).map(|_| rng.below(256) as u8).collect(),
            1 => {
                let mut m = request(7, "textDocument/hover", json!({ "textDocument": { "uri": URI } }));
                m.truncate(rng.below(m.len()));
                m
            }
            2 => format!("Content-Length: {}\r\n\r\n{{\"id\":", rng.below(4096)).into_bytes(),
            3 => format!("Content-Length: {}\r\n\r\n", 1u64 << (27 + rng.below(37))).into_bytes(),
            4 => {
                let mut m =
                    notification("textDocument/didChange", json!({ "textDocument": { "uri": "file:///other.stx" } }));
                let i = rng.below(m.len());
                m[i] = rng.below(256) as u8;
                m
            }
            _ => hover(8),
        }
    }

    /// The end. After chaos, whatever it left half read is completed and
    /// refused first (a body of at most 4,096 bytes is filled by the
    /// spaces, a huge one's skip stops at the next header); then the last
    /// hover, `shutdown` and `exit`.
    fn finish(&mut self) -> Vec<u8> {
        let mut b = Vec::new();
        if self.chaos_from == self.left_at_start {
            b.extend(b"\r\n");
            b.extend([b' '; 5000]);
            b.extend(b"\r\n\r\n");
        }
        b.extend(hover(999_999));
        b.extend(request(1_000_000, "shutdown", Value::Null));
        b.extend(notification("exit", Value::Null));
        b
    }
}

impl Read for Stream {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        while self.pending.is_empty() {
            let piece = if self.left > self.chaos_from {
                self.known()
            } else if self.left > 0 {
                self.chaos()
            } else if !self.finished {
                self.finished = true;
                self.finish()
            } else {
                return Ok(0);
            };
            self.left = self.left.saturating_sub(1);
            self.pending.extend(piece);
        }
        let n = buf.len().min(self.pending.len());
        for (b, p) in buf.iter_mut().zip(self.pending.drain(..n)) {
            *b = p;
        }
        Ok(n)
    }
}

/// What the server wrote, parsed frame by frame as it comes.
#[derive(Default)]
struct Seen {
    bytes: Vec<u8>,
    known: Tally,
    /// The answer to the last hover.
    last_hover: Option<Value>,
    shutdown: bool,
    /// Answers are not counted (the chaos session).
    chaos: bool,
}

#[derive(Clone)]
struct Sink(Arc<Mutex<Seen>>);

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let mut seen = self.0.lock().expect("sink");
        seen.bytes.extend_from_slice(buf);
        while let Some((len, start)) = next_frame(&seen.bytes) {
            let body: Value = serde_json::from_slice(&seen.bytes[start..start + len]).expect("the server writes JSON");
            seen.bytes.drain(..start + len);
            seen.count(&body);
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// The body's length and start of the first complete frame.
fn next_frame(b: &[u8]) -> Option<(usize, usize)> {
    let end = b.windows(4).position(|w| w == b"\r\n\r\n")?;
    let head = std::str::from_utf8(&b[..end]).expect("header");
    let len: usize = head.strip_prefix("Content-Length: ").expect("one header").parse().expect("length");
    (b.len() >= end + 4 + len).then_some((len, end + 4))
}

impl Seen {
    fn count(&mut self, m: &Value) {
        if m.get("method").is_some() {
            return; // diagnostics
        }
        let code = m["error"]["code"].as_i64();
        match (&m["id"], code) {
            (Value::Number(n), _) if n.as_u64() == Some(999_999) => self.last_hover = Some(m["result"].clone()),
            (Value::Number(n), _) if n.as_u64() == Some(1_000_000) => self.shutdown = m["result"].is_null(),
            _ if self.chaos => {}
            (_, Some(-32700)) => self.known.parse_errors += 1,
            (Value::Null, Some(-32600)) => self.known.invalid += 1,
            (Value::Number(n), Some(-32600)) if n.as_u64() == Some(4) => self.known.invalid += 1,
            (Value::Number(_), Some(-32601)) => self.known.answered += 1,
            (Value::Number(_), None) => {
                self.known.answered += 1;
                if m["result"]["contents"].is_object() {
                    self.known.hovers += 1;
                }
            }
            _ => panic!("unexpected answer {m}"),
        }
    }
}

/// Runs a session over `stream`: how it ended, what was answered, and the
/// heap's peak while it ran.
fn run(stream: Stream, chaos: bool) -> (Ending, Seen, usize) {
    let seen = Arc::new(Mutex::new(Seen { chaos, ..Seen::default() }));
    let sink = Sink(seen.clone());
    let mut ending = None;
    let peak = peak_of(|| ending = Some(linc_lsp::serve_io(stream, sink).expect("served")));
    let seen = std::mem::take(&mut *seen.lock().expect("seen"));
    (ending.expect("ended"), seen, peak)
}

/// The answer to a hover on `ABS` in the open document.
fn abs_hover(v: &Option<Value>) -> &str {
    v.as_ref().and_then(|v| v["contents"]["value"].as_str()).unwrap_or("no hover")
}

#[test]
fn broken_messages_are_each_answered_and_the_session_goes_on() {
    let _serial = serial();
    let stream = Stream::new(cases() / 2, true);
    let (ending, seen, peak) = run(stream, false);
    let expected = {
        // The same stream, made again to count what it holds.
        let mut s = Stream::new(cases() / 2, true);
        std::io::copy(&mut s, &mut std::io::sink()).expect("made");
        s.expected
    };
    assert_eq!(seen.known, expected, "every broken message answered once, every request answered");
    assert!(expected.parse_errors > cases() / 20 && expected.invalid > cases() / 20, "{expected:?}");
    assert!(abs_hover(&seen.last_hover).contains("ABS"), "{:?}", seen.last_hover);
    assert!(seen.shutdown);
    assert_eq!(ending, Ending::Shutdown);
    assert!(peak < 100 << 20, "peak heap {peak} bytes");
}

#[test]
fn chaos_leaves_the_server_answering() {
    let _serial = serial();
    let (ending, seen, peak) = run(Stream::new(cases() / 2, false), true);
    assert!(abs_hover(&seen.last_hover).contains("ABS"), "{:?}", seen.last_hover);
    assert!(seen.shutdown);
    assert_eq!(ending, Ending::Shutdown);
    assert!(peak < 100 << 20, "peak heap {peak} bytes");
}

/// A length just under the limit, of which one byte comes: memory follows
/// the bytes that came, not the length claimed.
#[test]
fn a_claimed_length_costs_nothing_until_its_bytes_come() {
    let _serial = serial();
    let mut head = request(1, "initialize", json!({ "capabilities": {} }));
    head.extend(notification("initialized", json!({})));
    head.extend(format!("Content-Length: {}\r\n\r\n{{", linc_lsp::MAX_MESSAGE).into_bytes());
    let seen = Arc::new(Mutex::new(Seen::default()));
    let mut ending = None;
    let peak = peak_of(|| ending = Some(linc_lsp::serve_io(std::io::Cursor::new(head), Sink(seen.clone()))));
    assert_eq!(ending.expect("ended"), Ok(Ending::NoShutdown), "the input ended without shutdown");
    assert!(peak < 4 << 20, "peak heap {peak} bytes for a claimed {} bytes", linc_lsp::MAX_MESSAGE);
}

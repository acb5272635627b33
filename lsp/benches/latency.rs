//! What an editor waits for (issue 18): diagnostics for a 5,000-line
//! action file after a change, hover and completion in it, beside a
//! native baseline in the same run (a byte scan of the same text, the
//! least any answer must do).

#[path = "../../compiler/tests/workload.rs"]
mod workload;

use criterion::{criterion_group, criterion_main, Criterion};
use linc_lsp::Server;
use lsp_server::{Notification, Request, RequestId};
use serde_json::json;
use std::hint::black_box;
use std::time::{Duration, Instant};

/// About 5,000 lines of realistic actions, cut after an action.
fn five_thousand_lines() -> String {
    let text = workload::actions(400_000);
    let mut out = String::new();
    for (i, line) in text.lines().enumerate() {
        out.push_str(line);
        out.push('\n');
        if i >= 4_990 && line.starts_with("END_ACTION") {
            break;
        }
    }
    out
}

fn server(dir: &std::path::Path) -> Server {
    std::fs::write(dir.join("plant.db.json"), include_str!("../../examples/guide/plant.db.json")).expect("db");
    let uri = lsp_types::Url::from_file_path(dir).expect("uri");
    let params: lsp_types::InitializeParams = serde_json::from_value(json!({
        "processId": null, "rootUri": uri, "capabilities": {},
        "initializationOptions": { "database": "plant.db.json", "debounceMs": 0 }
    }))
    .expect("params");
    linc_lsp::server_for(&params)
}

fn bench(c: &mut Criterion) {
    let dir = linc_test_support::temp_dir("lsp-bench");
    let mut s = server(&dir);
    let text = five_thousand_lines();
    let lines = text.lines().count();
    let uri = lsp_types::Url::from_file_path(dir.join("big.stx")).expect("uri").to_string();
    let open = json!({ "textDocument": { "uri": uri, "languageId": "lin-st", "version": 1, "text": text } });
    s.notification(Notification::new("textDocument/didOpen".into(), open));
    let first = s.due_diagnostics(Instant::now() + Duration::from_secs(3600));
    let lsp_server::Message::Notification(n) = &first[0] else { panic!("diagnostics") };
    assert_eq!(n.params["diagnostics"], json!([]), "the workload checks clean");
    // The cursor on a field reference in the middle of the file.
    let mid = text.len() / 2 + text[text.len() / 2..].find("TIC_100.SL").expect("a reference");
    let line = text[..mid].matches('\n').count();
    let col = mid - text[..mid].rfind('\n').map_or(0, |i| i + 1);
    let at = json!({ "textDocument": { "uri": uri }, "position": { "line": line, "character": col + 9 } });

    let hover = s.request(Request::new(RequestId::from(-1), "textDocument/hover".into(), at.clone()));
    let shown = hover.result.as_ref().and_then(|r| r["contents"]["value"].as_str().map(str::to_string));
    assert!(shown.as_deref().is_some_and(|v| v.starts_with("**TIC_100.SL**")), "{hover:?}");
    let done = s.request(Request::new(RequestId::from(-2), "textDocument/completion".into(), at.clone()));
    assert!(done.result.as_ref().is_some_and(|r| r.to_string().contains("\"TrimSP\"")), "{done:?}");

    let mut g = c.benchmark_group(format!("editor, {lines} lines"));
    g.sample_size(20);
    g.bench_function("baseline: count the dots of the text (native)", |b| {
        b.iter(|| black_box(&text).bytes().filter(|&b| b == b'.').count())
    });
    let mut version = 1;
    g.bench_function("diagnostics after a change", |b| {
        b.iter(|| {
            version += 1;
            let change = json!({ "textDocument": { "uri": uri, "version": version },
                "contentChanges": [{ "range": { "start": { "line": 3, "character": 0 }, "end": { "line": 3, "character": 0 } },
                                     "text": if version % 2 == 0 { " " } else { "" } }] });
            s.notification(Notification::new("textDocument/didChange".into(), change));
            s.due_diagnostics(Instant::now() + Duration::from_secs(3600)).len()
        })
    });
    let mut id = 0;
    for method in ["textDocument/hover", "textDocument/completion"] {
        g.bench_function(method.trim_start_matches("textDocument/"), |b| {
            b.iter(|| {
                id += 1;
                s.request(Request::new(RequestId::from(id), method.into(), at.clone())).result.is_some()
            })
        });
    }
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, bench);
criterion_main!(benches);

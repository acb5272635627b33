//! Loader and I/O errors go through the one renderer, in every format.
mod common;

/// Exit status and standard error.
fn linc(args: &[&str]) -> (Option<i32>, String) {
    let o = common::linc(args);
    (o.status.code(), common::stderr(&o))
}

#[test]
fn a_damaged_object_is_a_file_level_diagnostic() {
    let dir = common::temp_dir("report");
    let bad = dir.join("bad.sto");
    std::fs::write(&bad, b"LINCSTO\x1a\x02\x00").expect("write");
    let bad = bad.to_string_lossy().into_owned();
    let (code, err) = linc(&["disasm", &bad]);
    assert_eq!(code, Some(2));
    assert_eq!(err, format!("error[E0703]: the object file is truncated in its header\n = in {bad}\n\n"));
    let (_, err) = linc(&["disasm", &bad, "--message-format", "short"]);
    assert_eq!(err, format!("{bad}:1:1: error[E0703]: the object file is truncated in its header\n"));
    let (_, err) = linc(&["run", &bad, "--db", "examples/guide/plant.db.json", "--message-format", "json"]);
    let v: serde_json::Value = serde_json::from_str(err.trim()).expect("one JSON object");
    assert_eq!((v["code"].as_str(), v["file"].as_str()), (Some("E0703"), Some(bad.as_str())));
}

#[test]
fn eval_reports_runtime_errors_in_the_chosen_format() {
    let (code, err) = linc(&["eval", "1 / (1 - 1)", "--message-format", "short"]);
    assert_eq!((code, err.as_str()), (Some(1), "<expr>:1:1: error[R0001]: in `eval`: division by zero\n"));
    let (code, err) = linc(&["eval", "1 +", "--message-format", "short"]);
    assert_eq!(code, Some(2));
    assert!(err.starts_with("<expr>:1:4: error[E0011]"), "{err}");
}

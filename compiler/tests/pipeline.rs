//! Long texts are parsed on a second thread while the checker works on what
//! was read before (`parser::parse_actions_pipelined`), and a long file of
//! actions in parts on two threads at once (ADR 0024). The sink must see
//! exactly what the plain parse hands it, in the same order, with the same
//! errors, whatever the text: clean, full of errors, past the error limit,
//! a file without headers (one item per statement), and whatever stands at
//! the headers where the parts start: errors in the part before or the last
//! part only, a comment or string left open across a header (the comment
//! left open to the end: `st::split`'s tests), an action left open,
//! statements before the first header.

mod workload;

use linc_compiler::st::parser::{parse_actions, parse_actions_pipelined, PIPELINE_MIN};

/// Everything a parse produces, as text to compare.
fn parse_with(pipelined: bool, src: &str) -> (Vec<String>, bool, String) {
    let mut items = Vec::new();
    let mut sink = |item| items.push(format!("{item:?}"));
    let (ok, errors) = if pipelined { parse_actions_pipelined(src, &mut sink) } else { parse_actions(src, &mut sink) };
    (items, ok, format!("{errors:?}"))
}

fn assert_same(what: &str, src: &str) {
    assert!(src.len() >= PIPELINE_MIN, "{what}: {} bytes does not take the pipelined path", src.len());
    let plain = parse_with(false, src);
    let piped = parse_with(true, src);
    assert!(!plain.0.is_empty(), "{what}: nothing parsed");
    assert_eq!(plain.0.len(), piped.0.len(), "{what}: item counts differ");
    for (i, (a, b)) in plain.0.iter().zip(&piped.0).enumerate() {
        assert_eq!(a, b, "{what}: item {i} differs");
    }
    assert_eq!(plain.1, piped.1, "{what}: outcome differs");
    assert_eq!(plain.2, piped.2, "{what}: errors differ");
}

#[test]
fn a_clean_file_parses_the_same_on_two_threads() {
    assert_same("clean", &workload::actions(PIPELINE_MIN * 3));
}

#[test]
fn a_file_with_errors_parses_the_same_on_two_threads() {
    // Every 40th statement broken in a different way.
    let src = workload::actions(PIPELINE_MIN * 2);
    let breakers = [" := ;", " ) + ;", " THEN ;", " :=: 1;"];
    let mut out = String::new();
    for (i, part) in src.split_inclusive(";\n").enumerate() {
        out.push_str(part);
        if i % 40 == 7 {
            out.push_str(&format!("Recipe.A0{}\n", breakers[i / 40 % breakers.len()]));
        }
    }
    let (_, _, errors) = parse_with(false, &out);
    assert!(errors.contains("Unexpected"), "the broken statements must be errors");
    assert_same("errors", &out);
}

#[test]
fn a_file_past_the_error_limit_stops_at_the_same_place() {
    assert_same("many errors", &"xx := ;\n".repeat(PIPELINE_MIN / 4));
}

#[test]
fn lexical_errors_and_the_error_limit_are_the_same_on_two_threads() {
    // The parser thread reads ahead of the sink; where the parse stops, and
    // which lexical errors it reports and counts as omitted, must not change.
    let src = "xx := @ ;\nyy := 1 $ 2;\n".repeat(PIPELINE_MIN / 20);
    let (_, _, errors) = parse_with(false, &src);
    assert!(errors.contains("Stopped"), "the parse must stop at the error limit");
    assert!(errors.contains("UnexpectedChar"), "there must be lexical errors");
    assert_same("lexical errors past the stop", &src);
}

#[test]
fn a_file_without_headers_hands_over_the_same_statements() {
    let src =
        "Recipe.A0 := Recipe.A1 * 2 + 1;\nIF Dig_A.Out.Bit0 THEN Recipe.N0 := 1; END_IF;\n".repeat(PIPELINE_MIN / 60);
    assert_same("statements", &src);
}

#[test]
fn random_token_soup_parses_the_same_on_two_threads() {
    // Fragments that make every kind of error: unclosed brackets and
    // comments, stray keywords, bad characters, deep nesting, headers.
    const PARTS: [&str; 24] = [
        "ACTION a\n",
        "END_ACTION\n",
        "IF ",
        " THEN ",
        "END_IF;\n",
        "x.y := ",
        "1 + ",
        "(",
        ")",
        "{",
        "}",
        ";\n",
        "NOT ",
        "- ",
        "FOR i := 1 TO 3 DO ",
        "END_FOR;",
        "@",
        "(* c *)",
        "\"s\"",
        "T#1s",
        "ABS(",
        ",",
        "Block_5.Val1",
        "WHILE ",
    ];
    for seed in [1u64, 7, 1234] {
        let mut state = seed;
        let mut src = String::new();
        while src.len() < PIPELINE_MIN + 4096 {
            // xorshift64: deterministic, no dependency.
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            src.push_str(PARTS[(state % PARTS.len() as u64) as usize]);
        }
        assert_same(&format!("soup {seed}"), &src);
    }
}

/// A clean file of about 40 parts with `fragment` put before every `ACTION`
/// header between `from` and `to` (fractions of its length), so that some
/// header where a part starts has it.
fn with_fragment(fragment: &str, from: f64, to: f64) -> String {
    let src = workload::actions(PIPELINE_MIN * 10);
    let (from, to) = ((src.len() as f64 * from) as usize, (src.len() as f64 * to) as usize);
    let mut out = String::with_capacity(src.len() * 2);
    for (i, action) in src.split_inclusive("END_ACTION\n\n").enumerate() {
        if i > 0 && (from..to).contains(&out.len()) {
            out.push_str(fragment);
        }
        out.push_str(action);
    }
    out
}

#[test]
fn an_error_before_a_header_in_the_middle_parses_the_same_in_parts() {
    assert_same("error mid-file", &with_fragment("Recipe.A0 := ;\n", 0.45, 0.55));
}

#[test]
fn an_error_in_any_one_part_parses_the_same_in_parts() {
    // Parts are parsed by either thread (the calling one takes one in
    // four). A part is about 2.5% of the file: windows that far apart put
    // the error in four parts in a row, twice.
    for at in [0.2, 0.225, 0.25, 0.275, 0.5, 0.525, 0.55, 0.575] {
        assert_same(&format!("error at {at}"), &with_fragment("Recipe.A0 := ;\n", at, at + 0.01));
    }
}

#[test]
fn an_error_in_the_last_parts_parses_the_same_in_parts() {
    assert_same("errors near the end", &with_fragment("Recipe.A0 := ;\n", 0.99, 1.0));
    let last = format!("{}Recipe.A0 := ;\n", workload::actions(PIPELINE_MIN * 10));
    assert_same("error after the last action", &last);
}

#[test]
fn a_comment_over_a_header_parses_the_same_in_parts() {
    // The header's line ends the comment (`(* generated action *)`): the
    // header is inside it, and the action's statements stand outside any.
    assert_same("comment over a header", &with_fragment("(* over the next header\n", 0.45, 0.55));
}

#[test]
fn a_string_left_open_before_a_header_parses_the_same_in_parts() {
    assert_same("string left open", &with_fragment("Recipe.A0 := 'open\n", 0.45, 0.55));
}

#[test]
fn an_action_left_open_before_a_header_parses_the_same_in_parts() {
    let src = workload::actions(PIPELINE_MIN * 10);
    let middle = src.len() / 2;
    let end = middle + src[middle..].find("END_ACTION").unwrap();
    // Every action of the middle tenth loses its END_ACTION.
    let cut = src[end..end + src.len() / 10].replace("END_ACTION\n", "");
    assert_same("action left open", &format!("{}{cut}{}", &src[..end], &src[end + src.len() / 10..]));
}

#[test]
fn errors_past_the_limit_after_clean_parts_stop_at_the_same_place() {
    assert_same("many errors mid-file", &with_fragment(&"xx := ;\n".repeat(300), 0.45, 0.55));
}

#[test]
fn statements_before_the_first_header_parse_the_same_in_parts() {
    let src = format!("Recipe.A0 := 1;\n{}", workload::actions(PIPELINE_MIN * 10));
    let (_, _, errors) = parse_with(false, &src);
    assert!(errors.contains("StatementOutsideAction"), "the statement must be E0016");
    assert_same("statement before the headers", &src);
}

#[test]
fn headers_that_are_not_headers_parse_the_same_in_parts() {
    // A header in lower case, and a name that starts like a header, at the
    // start of lines where a part could start.
    let src = with_fragment("action Lower\nACTION_1 := 2;\nEND_ACTION\n\n", 0.2, 0.8);
    assert_same("not headers", &src);
}

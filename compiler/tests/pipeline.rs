//! Long texts are parsed on a second thread while the checker works on what
//! was read before (`parser::parse_actions_pipelined`). The sink must see
//! exactly what the plain parse hands it, in the same order, with the same
//! errors, whatever the text: clean, full of errors, past the error limit,
//! or a file without headers (one item per statement).

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

//! Comments are skipped by finding their end: a long one, even one full of
//! `*`, neither overflows the stack (in a debug build logos's matcher for
//! the regular expression used before recursed once per star) nor changes
//! what a comment is: it ends at the first `*)`, and `(*` without one is
//! an unclosed comment.

use linc_compiler::{check_source, Context};

fn codes(src: &str) -> Vec<String> {
    let r = check_source(src, "a.st", Context::of(None));
    r.diagnostics.iter().map(|d| d.code.as_str().to_string()).collect()
}

#[test]
fn a_long_comment_full_of_stars_is_skipped() {
    for body in ["*x".repeat(150_000), "*".repeat(300_000), "(* ".repeat(100_000), "ab\n".repeat(100_000)] {
        let src = format!("ACTION A\nRecipe.N0 := 1; (* {body} *)\nRecipe.N1 := 2;\nEND_ACTION\n");
        assert_eq!(codes(&src), Vec::<String>::new(), "{}", &body[..10]);
    }
}

#[test]
fn a_comment_ends_at_its_first_close() {
    // `(**)` and `(* ** *)` are comments; after the first `*)` the text is
    // code again, so a second `*)` is two stray tokens.
    assert_eq!(codes("ACTION A\n(**) Recipe.N0 := 1; (* ** *)\nEND_ACTION\n"), Vec::<String>::new());
    let once = codes("ACTION A\n(* a *) Recipe.N0 := 1;\nEND_ACTION\n");
    let twice = codes("ACTION A\n(* a *) *) Recipe.N0 := 1;\nEND_ACTION\n");
    assert!(once.is_empty() && !twice.is_empty(), "{once:?} {twice:?}");
}

#[test]
fn an_unclosed_comment_is_one_error_at_its_start() {
    let long = format!("ACTION A\nRecipe.N0 := 1; (* {}\nEND_ACTION\n", "*x".repeat(150_000));
    let short = "ACTION A\nRecipe.N0 := 1; (*)\nEND_ACTION\n";
    let (a, b) = (codes(&long), codes(short));
    assert_eq!(a, b);
    assert!(a.iter().any(|c| c == "E0003"), "an unclosed comment is reported: {a:?}");
}

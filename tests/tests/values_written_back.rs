//! No value that can't be written back: infinity or NaN never reaches an
//! INT, an offset or a REAL field; each raises R0005 at its statement
//! (docs/semantics.md), also when the compiler could fold the expression.
use linc_conformance::exec::run;

fn fault(src: &str) -> (Option<&'static str>, u32) {
    let r = run(src);
    (r.code(), r.error.as_ref().map_or(0, |e| e.line))
}

#[test]
fn infinity_to_int_is_r0005_folded_or_not() {
    assert_eq!(fault("Recipe.N1 := 2;\nRecipe.N1 := 1.0E38 * 10.0;\n"), (Some("R0005"), 2));
    assert_eq!(fault("Recipe.A0 := 3.0E38;\nRecipe.N1 := Recipe.A0 * 10.0;\n"), (Some("R0005"), 2));
    let r = run("Recipe.N1 := 2;\nRecipe.N1 := 1.0E38 * 10.0;\n");
    assert_eq!(r.get("Recipe.N1"), "2", "nothing was stored");
}

#[test]
fn infinity_as_an_offset_is_r0005_not_an_offset_error() {
    assert_eq!(fault("Block_5.Val1{1.0E38 * 10.0} := 1.0;\n"), (Some("R0005"), 1));
    assert_eq!(fault("Recipe.A0 := 3.0E38;\nBlock_5.Val1{Recipe.A0 * 10.0} := 1.0;\n"), (Some("R0005"), 2));
}

#[test]
fn nan_to_int_and_infinity_to_real_are_r0005() {
    let nan = "Recipe.A0 := 3.0E38;\nRecipe.N0 := (Recipe.A0 * 10.0) - (Recipe.A0 * 10.0);\n";
    assert_eq!(fault(nan), (Some("R0005"), 2));
    assert_eq!(fault("Recipe.A1 := 1.0E38 * 10.0;\n"), (Some("R0005"), 1));
    let r = run("Recipe.A1 := 1.5;\nRecipe.A1 := -1.0E38 * 10.0;\n");
    assert_eq!((r.code(), r.get("Recipe.A1").as_str()), (Some("R0005"), "1.5"));
}

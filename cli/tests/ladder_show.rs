//! `linc ladder show`: rungs drawn between the rails.
mod common;
use common::{linc, stderr, stdout, temp_dir};

#[test]
fn the_guide_rungs_are_drawn() {
    let o = linc(&["ladder", "show", "examples/ladder/interlock.ld"]);
    assert_eq!(o.status.code(), Some(0));
    insta::assert_snapshot!("ladder_show_interlock", stdout(&o));
}

#[test]
fn nested_branches_and_boxes_are_drawn() {
    let f = temp_dir("ladder-show").join("nested.ld");
    std::fs::write(
        &f,
        "A: ([a.x] | ([b.y] [/c.z] | [d.w > 1.0]) | [e.v]) [f.u] -> (g.t);\n\
         OR([a.x], AND([b.y], [c.z]), NOT([d.w])) -> JUMP L;\nL: -> x.y := 1;\n",
    )
    .expect("write");
    let o = linc(&["ladder", "show", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0));
    insta::assert_snapshot!("ladder_show_nested", stdout(&o));
    std::fs::write(&f, "[a.x -> (b.y);\n").expect("write");
    let o = linc(&["ladder", "show", f.to_str().unwrap(), "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(stderr(&o).contains("error[E03"), "{}", stderr(&o));
}

#[test]
fn values_draw_powered_elements_after_a_run() {
    let o = linc(&[
        "ladder",
        "show",
        "examples/ladder/interlock.ld",
        "--values",
        "--db",
        "examples/ladder/plant.json",
        "--set",
        "Dig_1a.In=1",
        "--set",
        "Dig_3a.In=1",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let drawn = stdout(&o);
    assert!(drawn.contains("  |==[ Dig_1a.In ]====( Dig_1b.Out )--"), "{drawn}");
    assert!(drawn.contains("  |--[ Dig_2a.In ]--==[/Dig_2b.In]====(/Dig_2c.Out)--"), "{drawn}");
    insta::assert_snapshot!("ladder_show_values", drawn);
    let o = linc(&["ladder", "show", "examples/ladder/interlock.ld", "--values"]);
    assert_eq!(o.status.code(), Some(2), "--values needs --db");
}

/// The rungs a taken jump skipped did not run: none of their contacts is
/// drawn passing power (`==`), whatever it reads now, and each says so.
/// Here the rung after the label clears the jump's contact, so the values
/// alone would say the jump was not taken.
#[test]
fn values_tell_the_rungs_a_taken_jump_skipped() {
    let f = temp_dir("ladder-show").join("skip.ld");
    std::fs::write(&f, "[Dig_1b.Out] -> JUMP Over;\n[Dig_2a.In] -> (Dig_2c.Out);\nOver: -> (R Dig_1b.Out);\n")
        .expect("write");
    let db = "examples/ladder/plant.json";
    let args = ["ladder", "show", f.to_str().unwrap(), "--values", "--db", db, "--set", "Dig_1b.Out=TRUE"];
    let o = linc(&[&args[..], &["--set", "Dig_2a.In=TRUE"]].concat());
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let drawn = stdout(&o);
    assert!(drawn.contains("  |--[ Dig_2a.In ]----( Dig_2c.Out )--"), "{drawn}");
    assert_eq!(drawn.matches("(not run: a jump skipped it)").count(), 1, "{drawn}");
    assert!(drawn.contains("  |--[ Dig_2a.In ]----( Dig_2c.Out )--|\n  |  (not run: a jump skipped it)\n"), "{drawn}");
}

/// A rung of 3,900 contacts is 66,000 characters wide: `format!` pads to
/// at most 65,535 and panicked on it. Every rung check accepts is drawn.
#[test]
fn a_rung_wider_than_format_can_pad_is_drawn() {
    let f = temp_dir("ladder-show").join("wide.ld");
    let src = format!("{}-> (Dig_1b.Out);\n[Dig_1a.In] -> (Dig_1b.Out);\n", "[Dig_1a.In] ".repeat(3_900));
    std::fs::write(&f, &src).expect("write");
    let o = linc(&["ladder", "show", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", common::stderr(&o));
    let drawn = stdout(&o);
    let lines: Vec<&str> = drawn.lines().collect();
    let wide = format!("  |{}--( Dig_1b.Out )--|", "--[ Dig_1a.In ]--".repeat(3_900));
    assert!(lines[1] == wide, "the wide rung is drawn whole ({} characters)", lines[1].len());
    // The short rung keeps the right rail of short rungs.
    assert_eq!(lines[3], "  |--[ Dig_1a.In ]----( Dig_1b.Out )--|");
    let o = linc(&["check", "--db", "examples/ladder/plant.json", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

/// A drawing is as wide as its widest branch on every row: 2,000 branches
/// beside a series of 600 contacts would be 2,000 rows of 10,000
/// characters. Such a rung is refused, located, and nothing is drawn.
#[test]
fn a_rung_too_large_to_draw_is_refused_at_the_rung() {
    let f = temp_dir("ladder-show").join("large.ld");
    let branch = "[Dig_1a.In] ".repeat(600);
    let rung = format!("({branch}{}) -> (Dig_1b.Out);\n", "| [Dig_2a.In] ".repeat(2_000));
    let src = format!("[Dig_1a.In] -> (Dig_1b.Out);\n{rung}");
    std::fs::write(&f, &src).expect("write");
    let o = linc(&["ladder", "show", f.to_str().unwrap(), "--message-format", "short"]);
    assert_eq!(o.status.code(), Some(1));
    let text = common::stderr(&o);
    assert!(text.starts_with(&format!("{}:2:1: error[E0314]", f.display())), "{text}");
    assert!(stdout(&o).is_empty(), "nothing is drawn: {}", stdout(&o));
    let o = linc(&["check", "--db", "examples/ladder/plant.json", f.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stdout(&o));
}

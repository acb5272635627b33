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

//! `--trace` of `linc run`: printed as writes happen, or collected in a file.
mod common;

#[test]
fn one_action_traces_to_stdout_or_to_a_file() {
    let dir = common::temp_dir("trace");
    let src = dir.join("t.st");
    std::fs::write(&src, "Recipe.N0 := Recipe.N0 + 1;\n").expect("write");
    let file = dir.join("trace.txt");
    let run = |extra: &[&str]| {
        let mut args = vec!["run", src.to_str().unwrap(), "--db", common::DB, "--cycles", "2"];
        args.extend_from_slice(extra);
        common::linc(&args)
    };
    let expected = "cycle 1: Recipe.N0 = 1\ncycle 2: Recipe.N0 = 2\n";
    let o = run(&["--trace"]);
    assert_eq!(String::from_utf8_lossy(&o.stdout), expected);
    let o = run(&["--trace", file.to_str().unwrap()]);
    assert_eq!((o.status.code(), String::from_utf8_lossy(&o.stdout).as_ref()), (Some(0), ""));
    assert_eq!(std::fs::read_to_string(&file).expect("trace file"), expected);
    // The trace file may not be an input.
    let o = run(&["--trace", src.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(std::fs::read_to_string(&src).expect("source"), "Recipe.N0 := Recipe.N0 + 1;\n");
}

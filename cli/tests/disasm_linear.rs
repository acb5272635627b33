//! `linc disasm` is linear in the object's size (it walked the whole line
//! table once per instruction: 194k statements took 45 s).
use std::process::Command;
use std::time::{Duration, Instant};

fn linc(args: &[&str]) -> (bool, Duration) {
    let t = Instant::now();
    let o = Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run linc");
    (o.status.success(), t.elapsed())
}

/// Compiles `n` statements into an object and times its listing.
fn disasm_time(n: usize) -> Duration {
    let dir = linc_test_support::temp_dir(&format!("disasm-{n}"));
    let src = dir.join("big.st");
    let sto = dir.join("big.sto");
    std::fs::write(&src, "Recipe.N0 := Recipe.N0 + 1;\nRecipe.A0 := Recipe.A0 * 0.5;\n".repeat(n / 2)).expect("write");
    let (src, sto) = (src.to_string_lossy().into_owned(), sto.to_string_lossy().into_owned());
    assert!(linc(&["compile", &src, "-o", &sto, "--db", "examples/guide/plant.db.json"]).0);
    // The best of three, to keep a busy machine from deciding the ratio.
    (0..3)
        .map(|_| {
            let (ok, t) = linc(&["disasm", &sto]);
            assert!(ok);
            t
        })
        .min()
        .unwrap_or_default()
}

#[test]
fn disasm_time_grows_linearly() {
    let small = disasm_time(12_000);
    let large = disasm_time(48_000);
    // Four times the statements: linear is about 4x, the old quadratic walk 16x.
    let ratio = large.as_secs_f64() / small.as_secs_f64().max(1e-3);
    assert!(ratio < 8.0, "12k statements {small:?}, 48k {large:?}: ratio {ratio:.1}");
}

/// A string constant is listed whole once, in the strings table, and by
/// its number where it is pushed; source lines are cut. A 1 MiB constant
/// pushed 4,000 times made 4.3 GB of listing.
#[test]
fn a_long_constant_is_listed_once() {
    let dir = linc_test_support::temp_dir("disasm-const");
    let (src, sto) = (dir.join("const.st"), dir.join("const.sto"));
    let long = "x".repeat(100_000);
    std::fs::write(&src, format!("Recipe.N0 := LEN('{long}');\n").repeat(30)).expect("write");
    let (src, sto) = (src.to_string_lossy().into_owned(), sto.to_string_lossy().into_owned());
    assert!(linc(&["compile", &src, "-o", &sto, "--db", "examples/guide/plant.db.json"]).0);
    let o = Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(["disasm", &sto])
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run linc");
    assert!(o.status.success());
    let listing = String::from_utf8_lossy(&o.stdout);
    let object = std::fs::metadata(&sto).expect("object").len() as usize;
    assert_eq!(listing.matches(&long).count(), 1, "the constant is listed once");
    let use_line = format!("PushS        $0 '{}…' (100000 bytes)", "x".repeat(32));
    assert_eq!(listing.matches(&use_line).count(), 30, "each push names the constant");
    assert!(listing.contains(&format!("; 1:1  Recipe.N0 := LEN('{}…\n", "x".repeat(102))), "source lines are cut");
    assert!(listing.len() < object + 20_000, "{} bytes of listing for a {object}-byte object", listing.len());
}

//! `linc disasm` is linear in the object's size (it walked the whole line
//! table once per instruction: 194k statements took 45 s).
use std::process::Command;

fn linc(args: &[&str]) -> bool {
    let o = Command::new(env!("CARGO_BIN_EXE_linc"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
        .output()
        .expect("run linc");
    o.status.success()
}

/// An object of `n` statements, compiled by `linc compile`, loaded.
fn object(n: usize) -> linc_format::ObjectFile {
    let dir = linc_test_support::temp_dir(&format!("disasm-{n}"));
    let src = dir.join("big.st");
    let sto = dir.join("big.sto");
    std::fs::write(&src, "Recipe.N0 := Recipe.N0 + 1;\nRecipe.A0 := Recipe.A0 * 0.5;\n".repeat(n / 2)).expect("write");
    let (src_name, sto_name) = (src.to_string_lossy().into_owned(), sto.to_string_lossy().into_owned());
    assert!(linc(&["compile", &src_name, "-o", &sto_name, "--db", "examples/guide/plant.db.json"]));
    linc_driver::disasm::load(&sto).expect("the object loads").object().clone()
}

#[test]
fn disasm_time_grows_linearly() {
    let (small, large) = (object(12_000), object(48_000));
    // The listing's work on this thread, in processor time: how busy the
    // machine is does not count.
    let ratio = linc_test_support::work::growth(|big| {
        let obj = if big { &large } else { &small };
        let listed = linc_test_support::work::thread_cpu(|| linc_driver::disasm::listing(obj, &mut std::io::sink()));
        listed.0.expect("listed");
        listed.1
    });
    // Four times the statements: linear is about 4x, the old quadratic walk 16x.
    assert!(ratio < 8.0, "12k → 48k statements: {ratio:.1}x the work");
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
    assert!(linc(&["compile", &src, "-o", &sto, "--db", "examples/guide/plant.db.json"]));
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

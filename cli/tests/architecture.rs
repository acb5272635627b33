//! The shape of the code, checked (docs/architecture.md): only the `linc`
//! binary prints or exits — every library returns what it made and what
//! it ran into as data — and the language server links no runtime.
mod common;

use std::path::Path;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/..");

/// The library crates: every member of the workspace but the binary and
/// the test-only crates.
const LIBRARIES: &[&str] =
    &["stdlib", "format", "runtime", "engines", "compiler", "driver", "draw", "comms", "serve", "lsp"];

/// What prints or ends the process.
const FORBIDDEN: &[&str] = &["eprintln!", "println!", "eprint!(", "print!(", "process::exit", "dbg!("];

/// The lines of a source that print or exit (1-based), with what they
/// call; unit tests (after `#[cfg(test)]`) and comments are left out.
fn prints(text: &str) -> Vec<(usize, &'static str)> {
    let code = text.split("#[cfg(test)]").next().unwrap_or_default();
    code.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with("//"))
        .filter_map(|(i, l)| FORBIDDEN.iter().find(|f| l.contains(*f)).map(|f| (i + 1, *f)))
        .collect()
}

#[test]
fn nothing_below_the_command_line_prints_or_exits() {
    let mut files = Vec::new();
    for krate in LIBRARIES {
        common::rust_sources(&Path::new(ROOT).join(krate).join("src"), &mut files);
    }
    assert!(files.len() > 100, "the sources were found: {}", files.len());
    let found: Vec<String> = files
        .iter()
        .flat_map(|path| {
            let text = std::fs::read_to_string(path).expect("source");
            prints(&text).into_iter().map(|(line, f)| format!("{}:{line}: {f}", path.display())).collect::<Vec<_>>()
        })
        .collect();
    assert!(found.is_empty(), "libraries that print or exit:\n{}", found.join("\n"));
}

#[test]
fn the_scan_finds_prints_and_exits_but_not_in_comments_or_unit_tests() {
    let text = "fn a() {\n    // println!(\"no\")\n    eprintln!(\"{x}\");\n    std::process::exit(2);\n}\n\
                #[cfg(test)]\nmod tests { fn t() { println!(\"ok\"); } }\n";
    assert_eq!(prints(text), [(3, "eprintln!"), (4, "process::exit")]);
}

/// `cargo tree` of a package's normal dependencies, one crate a line.
fn tree(package: &str, depth: Option<u32>) -> Vec<String> {
    let mut cmd = std::process::Command::new(env!("CARGO"));
    cmd.args(["tree", "--offline", "-p", package, "-e", "normal", "--prefix", "none"]).current_dir(ROOT);
    if let Some(d) = depth {
        cmd.args(["--depth", &d.to_string()]);
    }
    let o = cmd.output().expect("cargo tree");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).lines().map(|l| l.split_whitespace().next().unwrap_or("").to_string()).collect()
}

#[test]
fn the_language_server_links_no_runtime_engines_or_compiling_tier() {
    let all = tree("linc-lsp", None);
    assert!(all.iter().any(|c| c == "linc-compiler"), "{all:?}");
    let runs: Vec<&String> =
        all.iter().filter(|c| c.starts_with("cranelift") || *c == "linc-runtime" || *c == "linc-engines").collect();
    assert!(runs.is_empty(), "linc-lsp links {runs:?}");
    let linc: Vec<String> = tree("linc-lsp", Some(1)).into_iter().filter(|c| c.starts_with("linc-")).collect();
    assert_eq!(linc, ["linc-lsp", "linc-compiler", "linc-format"], "its own crates are the compiler and the format");
}

//! Generates the LALR parser from `src/grammar.lalrpop`.
fn main() {
    if let Err(e) = lalrpop::Configuration::new().use_cargo_dir_conventions().process() {
        panic!("lalrpop failed: {e}");
    }
}

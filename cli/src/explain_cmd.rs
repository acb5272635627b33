//! `linc explain CODE`: print a code's explanation page.

use linc_compiler::codes::{lookup, CODES};

pub fn run(code: Option<&str>, list: bool) -> u8 {
    match code {
        Some(c) if !list => match lookup(c) {
            Some(entry) => {
                print!("{}", entry.explanation);
                if !entry.explanation.ends_with('\n') {
                    println!();
                }
                0
            }
            None => {
                eprintln!("error: `{c}` is not a linc diagnostic code (see `linc explain --list`)");
                2
            }
        },
        _ => {
            for c in CODES {
                println!("{}  {}", c.code, c.title);
            }
            0
        }
    }
}

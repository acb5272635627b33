// The integer loop in plain Rust, as linc's kernel runs it (32-bit
// wrapping arithmetic); the count comes from the command line so that the
// optimiser cannot fold the loop away.
fn main() {
    let n: i32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000_000);
    let mut acc: i32 = 0;
    for i in 1..=n {
        if i % 3 == 0 {
            acc = acc.wrapping_add(i);
        } else {
            acc = acc.wrapping_sub(1);
        }
    }
    println!("{acc}");
}

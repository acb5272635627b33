// The shift register in plain Rust: an [f32; 8] with checked indexing (the
// index comes through a variable, as the ST loop's does).
fn main() {
    let n: i32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000_000);
    let top: usize = std::env::args().nth(2).and_then(|a| a.parse().ok()).unwrap_or(7);
    let mut v = [0.0f32; 8];
    for _ in 0..n {
        let mut i = top;
        while i >= 1 {
            v[i] = v[i - 1];
            i -= 1;
        }
        v[0] = v[7] * 0.5 + 1.0;
    }
    println!("{}", v[0]);
}

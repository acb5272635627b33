// The shift register in plain Rust: an [f32; 8] with checked indexing (the
// index comes through a variable, as the ST loop's does), every value
// stored checked to be finite, as LIN stores a REAL (a non-finite one is a
// runtime fault: without the check the optimiser turns the inner loop
// into one block move, work the ST loop must do value by value).
fn main() {
    let n: i32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000_000);
    let top: usize = std::env::args().nth(2).and_then(|a| a.parse().ok()).unwrap_or(7);
    let mut v = [0.0f32; 8];
    for _ in 0..n {
        let mut i = top;
        while i >= 1 {
            let x = v[i - 1];
            if !x.is_finite() {
                std::process::exit(2);
            }
            v[i] = x;
            i -= 1;
        }
        let x = v[7] * 0.5 + 1.0;
        if !x.is_finite() {
            std::process::exit(2);
        }
        v[0] = x;
    }
    println!("{}", v[0]);
}

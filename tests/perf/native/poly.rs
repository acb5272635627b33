// The REAL polynomial in plain Rust: Horner's rule in f32. Every value
// stored is checked to be finite, as LIN stores a REAL (a non-finite one
// is a runtime fault); without the check the optimiser drops every value
// of `y` but the last and the loop measures only the additions to `x`.
fn main() {
    let n: i32 = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(10_000_000);
    let (mut x, mut y) = (0.0f32, 0.0f32);
    for _ in 0..n {
        y = (((1.5 * x - 2.0) * x + 0.5) * x + 3.0) * x - 1.0;
        if !y.is_finite() {
            std::process::exit(2);
        }
        x += 0.001;
        if !x.is_finite() {
            std::process::exit(2);
        }
    }
    println!("{y} {x}");
}

// String building in plain Rust: owned byte strings with LIN's rules (LEFT
// and RIGHT of more than the length give the null string, an empty
// string is allowed, a result over 65,535 bytes is cut there), 100,000
// rounds a run, 50 runs.
const CAP: usize = 65_535;

fn concat(a: &[u8], b: &[u8]) -> Vec<u8> {
    let mut out = Vec::with_capacity((a.len() + b.len()).min(CAP));
    out.extend_from_slice(a);
    out.extend_from_slice(&b[..b.len().min(CAP - a.len().min(CAP))]);
    out
}

fn main() {
    let runs: usize = std::env::args().nth(1).and_then(|a| a.parse().ok()).unwrap_or(50);
    let mut u: Vec<u8> = b"[M01G0DI*01C5E5$R".to_vec();
    let mut total: i64 = 0;
    for _ in 0..runs {
        let mut n: i32 = 0;
        for _ in 0..100_000 {
            let t = concat(u.get(..4).unwrap_or(b""), b"ab");
            u = concat(&t, t.len().checked_sub(2).map_or(&b""[..], |s| &t[s..]));
            n = n.wrapping_add(u.len() as i32);
        }
        total += i64::from(n);
    }
    println!("{total}");
}

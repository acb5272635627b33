//! Times `linc check`'s front end on a file (for profiling; see README Figures).
use linc_compiler::session::{CheckOptions, Session};
use linc_compiler::Context;
use linc_runtime::Database;
fn main() {
    let args: Vec<String> = std::env::args().collect();
    let src = std::fs::read_to_string(&args[1]).expect("file");
    let db = Database::from_json(include_str!("../../examples/guide/plant.db.json")).expect("db");
    let ctx = Context::of(Some(&db));
    let n: usize = args.get(2).and_then(|a| a.parse().ok()).unwrap_or(5);
    let mut best = f64::MAX;
    if std::env::var("PARSE_ONLY").is_ok() {
        for _ in 0..n {
            best = best.min(parse_only(&src));
        }
        println!("parse best {:.1} ms", best * 1e3);
        return;
    }
    for _ in 0..n {
        let t = std::time::Instant::now();
        let mut s = Session::new(ctx);
        let id = s.add("bench.st", src.as_bytes().to_vec());
        let d = s.check(id, CheckOptions::default()).diagnostics.len();
        assert_eq!(d, 0);
        best = best.min(t.elapsed().as_secs_f64());
    }
    println!("best {:.1} ms, {:.1} MiB/s", best * 1e3, src.len() as f64 / 1048576.0 / best);
}
fn parse_only(src: &str) -> f64 {
    let t = std::time::Instant::now();
    let mut n = 0usize;
    let (ok, _) = linc_compiler::st::parser::parse_actions(src, &mut |_| n += 1);
    assert!(ok);
    t.elapsed().as_secs_f64()
}

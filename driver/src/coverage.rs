//! Coverage reports (ADR 0020, docs/testing.md): the counts a run
//! collected, per source file, written as lcov (which `genhtml` reads),
//! Cobertura XML (which CI systems show) or a summary table in the style
//! of `cargo llvm-cov`; and lcov files added together (`--merge-coverage`),
//! so shards merge into exactly what one run gives.
//!
//! Everything is kept sorted and the reports carry no time or machine, so
//! equal counts give equal bytes.

use linc_compiler::diag::{Diagnostic, Problems, Span};
use linc_format::xml::{escape, Whitespace};
use linc_format::Code;
use std::collections::BTreeMap;

/// What `linc test --coverage` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// An lcov tracefile (`genhtml` reads it).
    Lcov,
    /// Cobertura XML (CI systems show it).
    Cobertura,
    /// A table per file, in the style of `cargo llvm-cov`.
    Summary,
}

impl Format {
    /// `lcov`, `cobertura` or `summary`.
    pub fn parse(text: &str) -> Result<Format, String> {
        match text {
            "lcov" => Ok(Format::Lcov),
            "cobertura" => Ok(Format::Cobertura),
            "summary" => Ok(Format::Summary),
            _ => Err(format!("`{text}` is not a coverage format: lcov, cobertura or summary")),
        }
    }
}

/// One source file's counts.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FileCoverage {
    /// Hits by line.
    pub lines: BTreeMap<u32, u64>,
    /// Times taken by (line, block, branch); `None` when the decision was
    /// never evaluated (lcov's `-`).
    pub branches: BTreeMap<(u32, u32, u32), Option<u64>>,
    /// Hits and line of each function (an action, a step, a rung), by name.
    pub functions: BTreeMap<String, (u32, u64)>,
}

/// Counts for every file of a run.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Coverage {
    pub files: BTreeMap<String, FileCoverage>,
}

/// Two counts added; `None` (never reached) only when both are.
pub(crate) fn add_opt(a: Option<u64>, b: Option<u64>) -> Option<u64> {
    match (a, b) {
        (None, None) => None,
        (a, b) => Some(a.unwrap_or(0).saturating_add(b.unwrap_or(0))),
    }
}

impl Coverage {
    /// Adds another run's counts to these.
    pub fn merge(&mut self, other: &Coverage) {
        for (path, f) in &other.files {
            let mine = self.files.entry(path.clone()).or_default();
            for (&l, &h) in &f.lines {
                let e = mine.lines.entry(l).or_default();
                *e = e.saturating_add(h);
            }
            for (&k, &t) in &f.branches {
                let e = mine.branches.entry(k).or_insert(None);
                *e = add_opt(*e, t);
            }
            for (name, &(line, h)) in &f.functions {
                let e = mine.functions.entry(name.clone()).or_insert((line, 0));
                e.1 = e.1.saturating_add(h);
            }
        }
    }

    /// The lcov tracefile; E0912 for a source or function name lcov can't
    /// hold (a line break in one would start a forged record).
    pub fn to_lcov(&self) -> Result<String, Problems> {
        let names = self.files.iter().flat_map(|(path, f)| std::iter::once(path).chain(f.functions.keys()));
        if let Some(bad) = names.into_iter().find(|n| n.chars().any(char::is_control)) {
            let why =
                format!("{bad:?} holds a line break or another control character, which an lcov record can't hold");
            return Err(Problems::finding(Diagnostic::command(Code::E0912, why)));
        }
        let mut out = String::new();
        for (path, f) in &self.files {
            out.push_str(&format!("TN:\nSF:{path}\n"));
            for (name, (line, _)) in &f.functions {
                out.push_str(&format!("FN:{line},{name}\n"));
            }
            for (name, (_, hits)) in &f.functions {
                out.push_str(&format!("FNDA:{hits},{name}\n"));
            }
            let fnh = f.functions.values().filter(|(_, h)| *h > 0).count();
            out.push_str(&format!("FNF:{}\nFNH:{fnh}\n", f.functions.len()));
            for ((line, block, branch), taken) in &f.branches {
                let t = taken.map_or("-".to_string(), |t| t.to_string());
                out.push_str(&format!("BRDA:{line},{block},{branch},{t}\n"));
            }
            let brh = f.branches.values().filter(|t| t.is_some_and(|t| t > 0)).count();
            out.push_str(&format!("BRF:{}\nBRH:{brh}\n", f.branches.len()));
            for (line, hits) in &f.lines {
                out.push_str(&format!("DA:{line},{hits}\n"));
            }
            let lh = f.lines.values().filter(|h| **h > 0).count();
            out.push_str(&format!("LF:{}\nLH:{lh}\nend_of_record\n", f.lines.len()));
        }
        Ok(out)
    }

    /// Reads an lcov tracefile (one linc wrote, or any with the same
    /// records); `Err` names the line that is not one.
    pub fn from_lcov(text: &str) -> Result<Coverage, (usize, String)> {
        let mut cov = Coverage::default();
        let mut current: Option<String> = None;
        let mut fn_lines: BTreeMap<String, u32> = BTreeMap::new();
        for (i, line) in text.lines().enumerate() {
            let bad = |why: &str| (i + 1, format!("{why}: `{line}`"));
            let (tag, rest) = line.split_once(':').unwrap_or((line, ""));
            let num = |s: &str| s.trim().parse::<u64>().map_err(|_| bad("not a number"));
            // Lines count from 1; blocks and branches from 0; each fits
            // the 32 bits linc keeps (never cut into another line's).
            let line_no = |s: &str| match s.trim().parse::<u32>() {
                Ok(n) if n > 0 => Ok(n),
                _ => Err(bad("not a line number from 1 to 4294967295")),
            };
            let index = |s: &str| s.trim().parse::<u32>().map_err(|_| bad("not a number from 0 to 4294967295"));
            let file = |cov: &mut Coverage, current: &Option<String>| -> Result<FileCoverage, (usize, String)> {
                let path = current.as_ref().ok_or_else(|| bad("a record before SF"))?;
                Ok(cov.files.remove(path).unwrap_or_default())
            };
            match tag {
                "TN" | "FNF" | "FNH" | "BRF" | "BRH" | "LF" | "LH" | "" => {}
                "SF" if rest.is_empty() => return Err(bad("SF needs the source's name")),
                "SF" => current = Some(rest.to_string()),
                "end_of_record" => current = None,
                "FN" => {
                    let (l, name) = rest.split_once(',').ok_or_else(|| bad("FN needs line,name"))?;
                    fn_lines.insert(name.to_string(), line_no(l)?);
                }
                "FNDA" | "DA" | "BRDA" => {
                    let mut f = file(&mut cov, &current)?;
                    let parts: Vec<&str> = rest.split(',').collect();
                    match (tag, parts.as_slice()) {
                        ("FNDA", [h, name]) => {
                            let line = fn_lines.get(*name).copied().unwrap_or(0);
                            let e = f.functions.entry(name.to_string()).or_insert((line, 0));
                            e.1 = e.1.saturating_add(num(h)?);
                        }
                        ("DA", [l, h, ..]) => {
                            let e = f.lines.entry(line_no(l)?).or_default();
                            *e = e.saturating_add(num(h)?);
                        }
                        ("BRDA", [l, b, br, t]) => {
                            let key = (line_no(l)?, index(b)?, index(br)?);
                            let t = if *t == "-" { None } else { Some(num(t)?) };
                            let e = f.branches.entry(key).or_insert(None);
                            *e = add_opt(*e, t);
                        }
                        _ => return Err(bad("malformed record")),
                    }
                    if let Some(p) = &current {
                        cov.files.insert(p.clone(), f);
                    }
                }
                _ => return Err(bad("not an lcov record")),
            }
        }
        Ok(cov)
    }

    /// Line and branch totals: (lines hit, lines, branches taken, branches).
    fn totals(f: &FileCoverage) -> (usize, usize, usize, usize) {
        let lh = f.lines.values().filter(|h| **h > 0).count();
        let bh = f.branches.values().filter(|t| t.is_some_and(|t| t > 0)).count();
        (lh, f.lines.len(), bh, f.branches.len())
    }

    /// Cobertura XML (coverage-04.dtd), every file a class of one package
    /// with its functions (actions, steps, transitions) as methods.
    /// The timestamp is 0, so equal counts give equal bytes.
    pub fn to_cobertura(&self) -> String {
        let rate = |hit: usize, all: usize| if all == 0 { 1.0 } else { hit as f64 / all as f64 };
        let [_, (lh, lf), (bh, bf)] = self.sums();
        let sum = (lh, lf, bh, bf);
        let mut out = String::from("<?xml version=\"1.0\" ?>\n<!DOCTYPE coverage SYSTEM \"http://cobertura.sourceforge.net/xml/coverage-04.dtd\">\n");
        out.push_str(&format!(
            "<coverage line-rate=\"{:.4}\" branch-rate=\"{:.4}\" lines-covered=\"{}\" lines-valid=\"{}\" branches-covered=\"{}\" branches-valid=\"{}\" complexity=\"0\" version=\"linc\" timestamp=\"0\">\n  <sources>\n    <source>.</source>\n  </sources>\n  <packages>\n",
            rate(sum.0, sum.1), rate(sum.2, sum.3), sum.0, sum.1, sum.2, sum.3
        ));
        out.push_str(&format!(
            "    <package name=\"linc\" line-rate=\"{:.4}\" branch-rate=\"{:.4}\" complexity=\"0\">\n      <classes>\n",
            rate(sum.0, sum.1),
            rate(sum.2, sum.3)
        ));
        for (path, f) in &self.files {
            let (lh, lf, bh, bf) = Coverage::totals(f);
            let p = escape(path, Whitespace::Keep);
            out.push_str(&format!(
                "        <class name=\"{p}\" filename=\"{p}\" line-rate=\"{:.4}\" branch-rate=\"{:.4}\" complexity=\"0\">\n",
                rate(lh, lf), rate(bh, bf)
            ));
            out.push_str(&methods(f));
            out.push_str("          <lines>\n");
            for (line, hits) in &f.lines {
                let branches: Vec<&Option<u64>> =
                    f.branches.range((*line, 0, 0)..=(*line, u32::MAX, u32::MAX)).map(|(_, t)| t).collect();
                if branches.is_empty() {
                    out.push_str(&format!("            <line number=\"{line}\" hits=\"{hits}\" branch=\"false\"/>\n"));
                } else {
                    let taken = branches.iter().filter(|t| t.is_some_and(|t| t > 0)).count();
                    let pct = taken * 100 / branches.len();
                    out.push_str(&format!(
                        "            <line number=\"{line}\" hits=\"{hits}\" branch=\"true\" condition-coverage=\"{pct}% ({taken}/{})\"/>\n",
                        branches.len()
                    ));
                }
            }
            out.push_str("          </lines>\n        </class>\n");
        }
        out.push_str("      </classes>\n    </package>\n  </packages>\n</coverage>\n");
        out
    }

    /// A table per file in the style of `cargo llvm-cov`: functions
    /// (actions, steps, transitions), lines and branches, each with its
    /// missed count and the share covered, then the totals.
    pub fn summary(&self) -> String {
        let pct = |hit: usize, all: usize| {
            if all == 0 {
                "-".to_string()
            } else {
                format!("{:.2}%", hit as f64 * 100.0 / all as f64)
            }
        };
        let width = self.files.keys().map(|k| k.len()).max().unwrap_or(0).max("Filename".len()).max("TOTAL".len());
        let columns = |name: &str, cells: [String; 9]| {
            let [a, b, c, d, e, f, g, h, i] = cells;
            format!("{name:<width$}  {a:>9}  {b:>7}  {c:>8}  {d:>7}  {e:>7}  {f:>7}  {g:>8}  {h:>7}  {i:>7}\n")
        };
        let row = |name: &str, t: [usize; 6]| {
            let [fh, ff, lh, lf, bh, bf] = t;
            let n = |v: usize| v.to_string();
            columns(
                name,
                [n(ff), n(ff - fh), pct(fh, ff), n(lf), n(lf - lh), pct(lh, lf), n(bf), n(bf - bh), pct(bh, bf)],
            )
        };
        let heads = ["Functions", "Missed", "Executed", "Lines", "Missed", "Cover", "Branches", "Missed", "Cover"];
        let mut out = columns("Filename", heads.map(String::from));
        let rule = "-".repeat(out.trim_end().len());
        out.push_str(&rule);
        out.push('\n');
        let mut total = [0; 6];
        for (path, f) in &self.files {
            let (lh, lf, bh, bf) = Coverage::totals(f);
            let fh = f.functions.values().filter(|(_, h)| *h > 0).count();
            let t = [fh, f.functions.len(), lh, lf, bh, bf];
            total.iter_mut().zip(t).for_each(|(a, b)| *a += b);
            out.push_str(&row(path, t));
        }
        out.push_str(&rule);
        out.push('\n');
        out.push_str(&row("TOTAL", total));
        out
    }
}

/// The shares `linc test --fail-under-functions`, `--fail-under-lines` and
/// `--fail-under-branches` ask for, in percent, as `cargo llvm-cov` takes
/// them.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Gate {
    pub functions: Option<f64>,
    pub lines: Option<f64>,
    pub branches: Option<f64>,
}

impl Gate {
    /// A share from the command line: a number from 0 to 100.
    pub fn parse_percent(text: &str) -> Result<f64, String> {
        match text.trim_end_matches('%').parse::<f64>() {
            Ok(p) if (0.0..=100.0).contains(&p) => Ok(p),
            _ => Err(format!("`{text}` is not a share from 0 to 100 (percent)")),
        }
    }

    pub fn is_set(&self) -> bool {
        self.functions.is_some() || self.lines.is_some() || self.branches.is_some()
    }
}

impl Coverage {
    /// Hit and found counts of functions, lines and branches over all files.
    pub fn sums(&self) -> [(usize, usize); 3] {
        let mut sums = [(0, 0); 3];
        for f in self.files.values() {
            let (lh, lf, bh, bf) = Coverage::totals(f);
            let fh = f.functions.values().filter(|(_, h)| *h > 0).count();
            for (sum, (hit, all)) in sums.iter_mut().zip([(fh, f.functions.len()), (lh, lf), (bh, bf)]) {
                *sum = (sum.0 + hit, sum.1 + all);
            }
        }
        sums
    }

    /// Each kind whose share is under what `gate` asks: its name, its share
    /// and the threshold, all in percent. A kind with nothing to cover
    /// (no branches at all) is wholly covered, so it never fails a gate.
    pub fn short_of(&self, gate: &Gate) -> Vec<(&'static str, f64, f64)> {
        let kinds = [("functions", gate.functions), ("lines", gate.lines), ("branches", gate.branches)];
        let mut out = Vec::new();
        for ((name, want), (hit, all)) in kinds.into_iter().zip(self.sums()) {
            let share = if all == 0 { 100.0 } else { hit as f64 * 100.0 / all as f64 };
            if let Some(want) = want.filter(|w| share < *w) {
                out.push((name, share, want));
            }
        }
        out
    }
}

/// A file's functions (actions, steps, transitions) as Cobertura methods,
/// each with its line and hits.
fn methods(f: &FileCoverage) -> String {
    if f.functions.is_empty() {
        return "          <methods/>\n".to_string();
    }
    let mut out = String::from("          <methods>\n");
    for (name, (line, hits)) in &f.functions {
        let rate = if *hits > 0 { "1.0000" } else { "0.0000" };
        out.push_str(&format!(
            "            <method name=\"{}\" signature=\"\" line-rate=\"{rate}\" branch-rate=\"1.0000\">\n              <lines>\n                <line number=\"{line}\" hits=\"{hits}\"/>\n              </lines>\n            </method>\n",
            escape(name, Whitespace::Keep)
        ));
    }
    out.push_str("          </methods>\n");
    out
}

/// Reads and adds lcov files (`linc test --merge-coverage`); a file that
/// can't be read (E0900) or is not lcov (E0912, at its line) is a refused
/// request.
pub fn merge_files(paths: &[std::path::PathBuf]) -> Result<Coverage, Problems> {
    let mut all = Coverage::default();
    for path in paths {
        let text = crate::files::read_input_text(path).map_err(|e| Problems::unreadable(path, &e))?;
        match Coverage::from_lcov(&text) {
            Ok(c) => all.merge(&c),
            Err((line, why)) => {
                let start: usize = text.split_inclusive('\n').take(line - 1).map(str::len).sum();
                let end = start + text[start..].find('\n').unwrap_or(text.len() - start);
                let mut p = Problems::new();
                let id = p.add_file(path.display().to_string(), text);
                p.push(Diagnostic::error(Code::E0912, why, Span::new(start, end)).label("here").in_file(id));
                return Err(p.refused());
            }
        }
    }
    Ok(all)
}

/// Each kind of coverage under what `--fail-under-*` asks, as E0913
/// errors (findings: the run happened, its coverage falls short).
pub fn gate_problems(coverage: &Coverage, gate: &Gate) -> Problems {
    let mut p = Problems::new();
    for (kind, share, want) in coverage.short_of(gate) {
        let why = format!("{share:.2}% of {kind} covered, under the {want}% --fail-under-{kind} asks for");
        p.push(Diagnostic::command(Code::E0913, why));
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample() -> Coverage {
        let mut f = FileCoverage::default();
        f.lines.extend([(1, 3), (2, 0), (4, 3)]);
        f.branches.extend([((1, 0, 0), Some(2)), ((1, 0, 1), Some(0)), ((4, 0, 0), None), ((4, 0, 1), None)]);
        f.functions.insert("Tank".into(), (1, 3));
        let mut c = Coverage::default();
        c.files.insert("plant/sim.stx".into(), f);
        c
    }

    #[test]
    fn lcov_is_read_back_by_an_independent_parser_and_by_ours() {
        let text = sample().to_lcov().expect("lcov");
        let report = lcov::Report::from_reader(lcov::Reader::new(text.as_bytes())).expect("an lcov parser reads it");
        let (key, file) = report.sections.iter().next().expect("one section");
        assert_eq!(key.source_file, std::path::PathBuf::from("plant/sim.stx"));
        assert_eq!(file.lines.len(), 3);
        assert_eq!(file.branches.len(), 4);
        assert_eq!(file.functions.len(), 1);
        assert_eq!(Coverage::from_lcov(&text), Ok(sample()));
        assert!(Coverage::from_lcov("DA:1,2\n").is_err(), "a record before SF");
        assert_eq!(Coverage::from_lcov("SF:a\nXX:1\n").unwrap_err().0, 2);
    }

    #[test]
    fn merging_adds_counts_in_any_order_to_the_same_bytes() {
        let (a, mut b) = (sample(), sample());
        b.files.get_mut("plant/sim.stx").unwrap().branches.insert((4, 0, 0), Some(5));
        let mut ab = a.clone();
        ab.merge(&b);
        let mut ba = b.clone();
        ba.merge(&a);
        assert_eq!(ab.to_lcov().expect("lcov"), ba.to_lcov().expect("lcov"));
        let f = &ab.files["plant/sim.stx"];
        assert_eq!((f.lines[&1], f.branches[&(4, 0, 0)], f.branches[&(4, 0, 1)]), (6, Some(5), None));
        assert_eq!(f.functions["Tank"], (1, 6));
    }

    #[test]
    fn numbers_that_do_not_fit_are_refused_not_cut_into_other_lines() {
        // 2^32 + 1 would be line 1 cut to 32 bits.
        for bad in ["DA:4294967297,5", "DA:0,1", "DA:-1,1", "BRDA:1,4294967296,0,1", "FN:4294967297,Tank"] {
            let text = format!("SF:a.st\n{bad}\nend_of_record\n");
            let (line, why) = Coverage::from_lcov(&text).expect_err(bad);
            assert_eq!(line, 2, "{bad}: {why}");
        }
        let max = Coverage::from_lcov("SF:a.st\nDA:4294967295,7\nend_of_record\n").expect("the largest line");
        assert_eq!(max.files["a.st"].lines[&u32::MAX], 7);
        assert!(Coverage::from_lcov("SF:\nDA:1,1\n").is_err(), "a nameless source");
    }

    #[test]
    fn a_name_that_would_forge_a_record_is_not_written() {
        let mut c = sample();
        let f = c.files.remove("plant/sim.stx").unwrap();
        c.files.insert("evil.st\nSF:forged.st\nDA:1,999".into(), f);
        let p = c.to_lcov().expect_err("refused");
        assert_eq!(p.diagnostics()[0].code, Code::E0912);
        let mut c = sample();
        let f = c.files.get_mut("plant/sim.stx").unwrap();
        f.functions.insert("T\rX".into(), (1, 1));
        assert!(c.to_lcov().is_err(), "a function's name too");
    }

    #[test]
    fn cobertura_and_the_summary_count_the_same() {
        let x = sample().to_cobertura();
        assert!(x.contains("lines-covered=\"2\" lines-valid=\"3\" branches-covered=\"1\" branches-valid=\"4\""), "{x}");
        assert!(x.contains("<line number=\"1\" hits=\"3\" branch=\"true\" condition-coverage=\"50% (1/2)\"/>"), "{x}");
        assert!(x.contains("<line number=\"2\" hits=\"0\" branch=\"false\"/>"), "{x}");
        let s = sample().summary();
        assert!(s.contains("plant/sim.stx") && s.contains("66.67%") && s.contains("25.00%"), "{s}");
        assert!(s.lines().last().unwrap().starts_with("TOTAL"), "{s}");
    }
}

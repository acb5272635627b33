//! `linc test`'s files: a JUnit XML report and VCD traces (GTKWave) of the
//! fields each scenario names. Both are deterministic: no wall-clock times.

use crate::scenarios::Outcome;
use linc_compiler::diag::Problems;
use linc_format::Code;
use std::path::{Path, PathBuf};

/// Text escaped for the report, tab and newline kept.
fn xml(text: &str) -> String {
    linc_format::xml::escape(text, linc_format::xml::Whitespace::Keep)
}

/// The JUnit report: one suite, one test case per scenario; a failed
/// scenario's case holds a `<failure>` with its first message and all its
/// details. Simulated time, not wall time, goes in `system-out`.
pub fn junit(outcomes: &[Outcome]) -> String {
    let failures = outcomes.iter().filter(|o| !o.passed).count();
    let n = outcomes.len();
    let mut out = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    out.push_str(&format!("<testsuites name=\"linc test\" tests=\"{n}\" failures=\"{failures}\" errors=\"0\">\n"));
    out.push_str(&format!(
        "  <testsuite name=\"linc scenarios\" tests=\"{n}\" failures=\"{failures}\" errors=\"0\" skipped=\"0\">\n"
    ));
    for o in outcomes {
        let classname =
            Path::new(&o.name).parent().map(|p| p.display().to_string().replace('/', ".")).unwrap_or_default();
        out.push_str(&format!("    <testcase name=\"{}\" classname=\"{}\"", xml(&o.name), xml(&classname)));
        let simulated = linc_engines::scenario::time(o.report.end_us);
        let summary = format!("simulated {simulated}, {} scans", o.report.scans);
        if o.passed {
            out.push_str(&format!(">\n      <system-out>{}</system-out>\n    </testcase>\n", xml(&summary)));
            continue;
        }
        let first = o.report.failures.first().map(|f| f.message.clone()).unwrap_or_else(|| o.details.clone());
        let first = first.lines().next().unwrap_or("").to_string();
        out.push_str(&format!(
            ">\n      <failure message=\"{}\" type=\"scenario\">{}</failure>\n      <system-out>{}</system-out>\n    </testcase>\n",
            xml(&first),
            xml(&o.details),
            xml(&summary)
        ));
    }
    out.push_str("  </testsuite>\n</testsuites>\n");
    out
}

/// How a sampled field is drawn.
#[derive(Clone, Copy, PartialEq)]
enum Shape {
    Bit,
    Integer,
    Real,
    Text,
}

fn shape_of(first: &str) -> Shape {
    match first {
        "TRUE" | "FALSE" => Shape::Bit,
        v if v.parse::<i64>().is_ok() => Shape::Integer,
        v if v.parse::<f64>().is_ok() => Shape::Real,
        _ => Shape::Text,
    }
}

/// One scenario's samples as VCD text (timescale 1 µs, scope `linc`).
pub fn vcd(o: &Outcome) -> std::io::Result<Vec<u8>> {
    use vcd::{ScopeType, TimescaleUnit, Value, VarType};
    let s = &o.report.samples;
    let mut w = vcd::Writer::new(Vec::new());
    w.timescale(1, TimescaleUnit::US)?;
    w.comment(&format!("linc test {}", o.name))?;
    w.add_module("linc")?;
    let mut vars = Vec::new();
    for (i, name) in s.names.iter().enumerate() {
        let first = s.changes.iter().find(|(_, v, _)| *v == i).map(|(_, _, x)| x.as_str()).unwrap_or("0");
        let shape = shape_of(first);
        let (ty, width) = match shape {
            Shape::Bit => (VarType::Wire, 1),
            Shape::Integer => (VarType::Integer, 32),
            Shape::Real => (VarType::Real, 64),
            Shape::Text => (VarType::String, 1),
        };
        let reference: String = name.chars().map(|c| if c.is_whitespace() { '_' } else { c }).collect();
        vars.push((w.add_var(ty, width, &reference, None)?, shape));
    }
    w.upscope()?;
    w.enddefinitions()?;
    let mut last_time = None;
    for (t, var, value) in &s.changes {
        if last_time != Some(*t) {
            w.timestamp(*t)?;
            last_time = Some(*t);
        }
        let (id, shape) = vars[*var];
        match shape {
            Shape::Bit => w.change_scalar(id, if value == "TRUE" { Value::V1 } else { Value::V0 })?,
            Shape::Integer => {
                let n = value.parse::<i64>().unwrap_or(0) as u32;
                w.change_vector(id, (0..32).rev().map(|b| if n >> b & 1 == 1 { Value::V1 } else { Value::V0 }))?
            }
            Shape::Real => w.change_real(id, value.parse::<f64>().unwrap_or(0.0))?,
            Shape::Text => w.change_string(id, &value.replace(char::is_whitespace, "_"))?,
        }
    }
    let _ = ScopeType::Module;
    Ok(w.writer().clone())
}

/// The VCD file of each scenario: `path` itself for one scenario; for
/// several, `NAME.vcd` in the directory `path`, numbered where two
/// scenarios share a file name.
pub fn vcd_targets(path: &Path, scenarios: &[PathBuf]) -> Vec<PathBuf> {
    if scenarios.len() == 1 {
        return vec![path.to_path_buf()];
    }
    let mut names: Vec<String> = Vec::new();
    scenarios
        .iter()
        .map(|file| {
            let stem = file.file_stem().map_or("scenario".into(), |s| s.to_string_lossy().into_owned());
            let mut name = stem.clone();
            let mut k = 2;
            while names.contains(&name) {
                name = format!("{stem}-{k}");
                k += 1;
            }
            names.push(name.clone());
            path.join(format!("{name}.vcd"))
        })
        .collect()
}

/// `--vcd PATH`: the file itself for one scenario; for several, a
/// directory of `NAME.vcd` files (made if missing).
pub fn write_vcds(path: &Path, outcomes: &[Outcome]) -> Result<(), Problems> {
    let fail =
        |e: &dyn std::fmt::Display| Problems::usage(Code::E0900, format!("can't write `{}`: {e}", path.display()));
    if outcomes.len() > 1 {
        std::fs::create_dir_all(path).map_err(|e| fail(&e))?;
    }
    let names: Vec<PathBuf> = outcomes.iter().map(|o| PathBuf::from(&o.name)).collect();
    for (o, target) in outcomes.iter().zip(vcd_targets(path, &names)) {
        let bytes = vcd(o).map_err(|e| fail(&e))?;
        // A refused output keeps its own code (E0901, E0902).
        crate::files::write_atomic(&target, &bytes)?;
    }
    Ok(())
}

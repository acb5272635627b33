//! `linc sfc …`: generic sequences (guide §9.1), through the driver; and
//! how `--resources` prints what a sequence uses.

use crate::report::Reporter;
use linc_compiler::diag::{Format, Problems};
use linc_driver::sfc::{Direction, Resources};
use std::path::Path;

/// `linc sfc specialise|generalise FILE --map MAP -o OUT`.
pub fn rewrite(dir: Direction, file: &Path, map: &Path, out: &Path, r: &Reporter) -> u8 {
    r.done(linc_driver::sfc::rewrite(dir, file, map, out).map(|()| Problems::new()))
}

/// `linc sfc map-template FILE [--db DB]`: prints a map with every generic
/// name and an empty target.
pub fn map_template(file: &Path, db: Option<&Path>, r: &Reporter) -> u8 {
    match linc_driver::sfc::map_template(file, db) {
        Ok(map) => {
            crate::out::print(&map);
            0
        }
        Err(p) => r.report(&p),
    }
}

/// `--resources`: the table of what the sequence uses (or one JSON line).
pub fn print_resources(used: &Resources, format: Format) {
    let Resources { file: name, instrument, uses } = used;
    if format == Format::Json {
        let fields: Vec<String> =
            uses.iter().map(|u| format!("{:?}:{{\"used\":{},\"limit\":{}}}", u.resource, u.used, u.limit)).collect();
        crate::out::line(&format!(
            "{{\"resources\":{{\"file\":{},\"instrument\":\"{instrument}\",{}}}}}",
            serde_json::Value::String(name.to_string()),
            fields.join(",")
        ));
        return;
    }
    crate::out::line(&format!("resources of {name} ({instrument} instrument):"));
    for u in uses {
        let mark = if u.used > u.limit { "  over the limit" } else { "" };
        crate::out::line(&format!("  {:<13}{:>5} of {}{mark}", u.resource, u.used, u.limit));
    }
}

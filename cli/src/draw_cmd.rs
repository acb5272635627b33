//! `linc draw`: a sequence, ladder file, FST table or trace as SVG
//! (docs/pictures.md), to standard output or atomically to `-o FILE`.

use crate::report::Reporter;
use linc_driver::draw::Options;
use std::path::{Path, PathBuf};

pub fn run(o: &Options, out: Option<&Path>, r: &Reporter) -> u8 {
    let inputs: Vec<&Path> =
        [Some(o.file.as_path()), o.db.as_deref(), o.state.as_deref()].into_iter().flatten().collect();
    crate::out::print_or_write(out, &inputs, r, || linc_driver::draw::picture(o).map(|p| (p.svg, p.problems)))
}

/// `linc draw`'s options.
#[derive(clap::Args)]
pub struct DrawArgs {
    /// A sequence (.sfc), ladder file (.ld), FST table (.csv) or a `--trace` file (.jsonl).
    pub file: PathBuf,
    /// Write the SVG here (atomically) instead of standard output.
    #[arg(short, long)]
    pub out: Option<PathBuf>,
    /// The database to check names against and to run in (with --for or --cycles).
    #[arg(long)]
    pub db: Option<PathBuf>,
    /// Run the sequence or FST table this long first and draw the state it leaves.
    #[arg(long = "for", value_name = "DURATION", allow_hyphen_values = true)]
    pub duration: Option<String>,
    /// Run a ladder file's actions this many times first and draw power flow.
    #[arg(long, value_name = "N")]
    pub cycles: Option<u32>,
    /// The SFC_CON or FST block that runs the file (default: the only one).
    #[arg(long)]
    pub block: Option<String>,
    /// Seconds per scan of the sequence or table (default: its task's period).
    #[arg(long, value_name = "SECS", allow_hyphen_values = true, value_parser = crate::period)]
    pub period: Option<f64>,
    /// Set a field before the run: BLOCK.FIELD=VALUE (repeatable).
    #[arg(long)]
    pub set: Vec<String>,
    /// Start the run warm from this retentive state file (only read).
    #[arg(long, value_name = "FILE")]
    pub state: Option<PathBuf>,
    /// Fix the clock: YYYY-MM-DDTHH:MM:SS (UTC).
    #[arg(long, value_name = "YYYY-MM-DDTHH:MM:SS", value_parser = crate::now)]
    pub now: Option<i64>,
    #[arg(long)]
    pub seed: Option<u64>,
    /// A field of a trace to draw: BLOCK.FIELD (repeatable).
    #[arg(long, value_name = "BLOCK.FIELD")]
    pub field: Vec<String>,
    /// Draw the trace from this time after its start (10m, 1h).
    #[arg(long, value_name = "TIME")]
    pub from: Option<String>,
    /// Draw the trace up to this time after its start.
    #[arg(long, value_name = "TIME")]
    pub to: Option<String>,
}

impl DrawArgs {
    pub fn options(self) -> (Options, Option<PathBuf>) {
        let o = Options {
            file: self.file,
            db: self.db,
            duration: self.duration,
            cycles: self.cycles,
            block: self.block,
            period: self.period,
            set: self.set,
            state: self.state,
            now: self.now,
            seed: self.seed,
            fields: self.field,
            from: self.from,
            to: self.to,
        };
        (o, self.out)
    }
}

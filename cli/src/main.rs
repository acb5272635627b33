//! `linc`: check, compile and run LIN Structured Text from the command line.
//!
//! Exit status: 0 clean, 1 errors found in the input, 2 usage or I/O problem.

mod alloc;
mod check_cmd;
mod compile_cmd;
mod console_cmd;
mod disasm_cmd;
mod draw_cmd;
mod eval_cmd;
mod explain_cmd;
mod fmt_cmd;
mod fst_cmd;
mod ladder_cmd;
mod line_args;
mod out;
mod report;
mod roc_cmd;
mod run_cmd;
mod serve_cmd;
mod sfc_cmd;
mod test_cmd;

use clap::{Parser, Subcommand, ValueEnum};
use linc_driver::plant::{PlantSpec, Program, StateFile};
use linc_format::Code;
use report::Reporter;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "linc",
    version,
    about = "A toolchain for control logic — LIN ST actions, sequences and ladder, ROC FST tables: check, compile, run and test strategies headless"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// How to print diagnostics (errors and warnings, on standard error).
    #[arg(long, value_enum, default_value = "human", global = true)]
    message_format: MessageFormat,
}

#[derive(Clone, Copy, ValueEnum)]
enum TierArg {
    Auto,
    Compiled,
    Interpreter,
}

impl From<TierArg> for linc_driver::plant::Tier {
    fn from(t: TierArg) -> Self {
        match t {
            TierArg::Auto => Self::Auto,
            TierArg::Compiled => Self::Compiled,
            TierArg::Interpreter => Self::Interpreter,
        }
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum MessageFormat {
    Human,
    Short,
    Json,
}

// Parsed once per process: the size of the largest variant does not matter.
#[allow(clippy::large_enum_variant)]
#[derive(Subcommand)]
enum Command {
    /// Check action (.st/.stx), sequence (.sfc), ladder (.ld) and FST table (.csv) files.
    Check {
        /// Files to check.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Database (JSON) to resolve block, field and alias names against.
        #[arg(long)]
        db: Option<PathBuf>,
        /// Print the syntax tree of each file.
        #[arg(long)]
        tree: bool,
        /// Each file is one transition expression (§12.11), checked in sequence context.
        #[arg(long)]
        transition: bool,
        /// Check actions as sequence actions, where step.X and step.T exist.
        #[arg(long)]
        sequence: bool,
        /// Map file (JSON) turning a generic sequence's names into database names.
        #[arg(long)]
        map: Option<PathBuf>,
        /// With --map: a generic name the map lacks is a warning, not an error.
        #[arg(long, requires = "map")]
        allow_unmapped: bool,
        /// Print the steps, transitions, actions, associations and SFCs each sequence uses.
        #[arg(long)]
        resources: bool,
        /// The instrument whose limits --resources compares against.
        #[arg(long, value_enum, default_value = "small", requires = "resources")]
        instrument: InstrumentSize,
    },
    /// Compile action files (or one sequence or FST table) into a .sto object file.
    Compile {
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// The object file to write.
        #[arg(short, long)]
        out: PathBuf,
        /// Database giving the types of the blocks the actions use.
        #[arg(long)]
        db: Option<PathBuf>,
        /// Map file (JSON) for a generic sequence: every generic name needs a target.
        #[arg(long)]
        map: Option<PathBuf>,
    },
    /// Generic sequences: specialise, generalise and list generic names (guide §9.1).
    Sfc {
        #[command(subcommand)]
        command: SfcCommand,
    },
    /// ROC Function Sequence Tables (.csv): list a table as the FST Editor shows it.
    Fst {
        #[command(subcommand)]
        command: FstCommand,
    },
    /// Draw a sequence, ladder file or FST table as SVG (after a run with --db and --for/--cycles: its
    /// state), or trends of a --trace file (docs/pictures.md).
    Draw(Box<draw_cmd::DrawArgs>),
    /// Run a strategy in real time behind a live monitor page and a JSON API (docs/serve.md).
    Serve(Box<serve_cmd::ServeArgs>),
    /// The ROC host: poll a ROC or ROC Plus device with a command list, as the communication module does.
    Roc {
        #[command(subcommand)]
        command: roc_cmd::RocCommand,
    },
    /// Ladder files (.ld): print the ST a ladder compiles as.
    Ladder {
        #[command(subcommand)]
        command: ladder_cmd::LadderCommand,
    },
    /// Run a strategy (PLANT.json --for DURATION), one sequence or FST table (FILE --db DB.json --for DURATION),
    /// or one action once per cycle (FILE --db DB.json).
    Run(Box<RunArgs>),
    /// Run scenario tests (.ltest files; a directory is searched) and report like `cargo test`.
    Test {
        /// Scenario files or directories (default: the current directory).
        paths: Vec<PathBuf>,
        /// Scenarios run at once (default: one per core); reports are the same for any number.
        #[arg(long, value_name = "N")]
        jobs: Option<usize>,
        /// Write a JUnit XML report here.
        #[arg(long, value_name = "FILE")]
        junit: Option<PathBuf>,
        /// Write a VCD trace of the fields the scenario names (a directory of NAME.vcd for several scenarios).
        #[arg(long, value_name = "PATH")]
        vcd: Option<PathBuf>,
        /// Run only shard K of N: the scenarios split by a stable hash of their paths (for CI matrices).
        #[arg(long, value_name = "K/N", value_parser = linc_driver::scenarios::Shard::parse)]
        shard: Option<linc_driver::scenarios::Shard>,
        /// List the scenario files that would run (this shard's, with --shard) and run none.
        #[arg(long)]
        list: bool,
        /// Count what the scenarios ran (ST statements and branches, steps, transitions, rungs, FST
        /// steps and branches) and write it to -o FILE as lcov or Cobertura XML, or print a summary.
        #[arg(long, value_name = "FORMAT", conflicts_with = "list", value_parser = linc_driver::coverage::Format::parse)]
        coverage: Option<linc_driver::coverage::Format>,
        /// Add lcov coverage files (the shards of a CI matrix) into -o OUT, and run nothing.
        #[arg(long, value_name = "FILE", num_args = 1.., conflicts_with_all = ["paths", "junit", "vcd", "shard", "list", "coverage"])]
        merge_coverage: Vec<PathBuf>,
        /// Where --coverage writes its report, or --merge-coverage the sum.
        #[arg(short, long, value_name = "FILE")]
        out: Option<PathBuf>,
        /// Fail (E0913, exit 1) when under this share of functions (actions, steps, transitions) ran.
        #[arg(long, value_name = "PERCENT", value_parser = linc_driver::coverage::Gate::parse_percent)]
        fail_under_functions: Option<f64>,
        /// Fail (E0913, exit 1) when under this share of lines ran.
        #[arg(long, value_name = "PERCENT", value_parser = linc_driver::coverage::Gate::parse_percent)]
        fail_under_lines: Option<f64>,
        /// Fail (E0913, exit 1) when under this share of branch outcomes was taken.
        #[arg(long, value_name = "PERCENT", value_parser = linc_driver::coverage::Gate::parse_percent)]
        fail_under_branches: Option<f64>,
    },
    /// A command console over a running strategy: display, modify and force fields, start and stop
    /// programs, control sequences, move the simulated clock (docs/console.md).
    Console {
        /// The strategy's database (.json).
        file: PathBuf,
        /// Run the commands of this file (default: standard input; a terminal gets a `linc>` prompt).
        #[arg(long, value_name = "FILE")]
        script: Option<PathBuf>,
        /// Set a field before the start: BLOCK.FIELD=VALUE (repeatable).
        #[arg(long)]
        set: Vec<String>,
        /// Trace field writes (and the console's own changes) to FILE as JSON lines.
        #[arg(long, value_name = "FILE")]
        trace: Option<PathBuf>,
        /// Fix the clock: YYYY-MM-DDTHH:MM:SS (UTC).
        #[arg(long, value_name = "YYYY-MM-DDTHH:MM:SS", value_parser = now)]
        now: Option<i64>,
        /// Seed of RANDOM, for repeatable runs.
        #[arg(long)]
        seed: Option<u64>,
        /// Restore the retentive state from FILE at the start (a warm start) and save it there on SAVE and at the end.
        #[arg(long, value_name = "FILE")]
        state: Option<PathBuf>,
        /// With --state: ignore the state file and start cold (it is still saved).
        #[arg(long, requires = "state")]
        cold: bool,
    },
    /// Evaluate one ST expression and print its value.
    Eval {
        /// The expression; it may start with `-`.
        #[arg(allow_hyphen_values = true)]
        expr: String,
        #[arg(long)]
        db: Option<PathBuf>,
        /// Fix the clock: YYYY-MM-DDTHH:MM:SS (UTC).
        #[arg(long, value_name = "YYYY-MM-DDTHH:MM:SS", value_parser = now)]
        now: Option<i64>,
        #[arg(long)]
        seed: Option<u64>,
    },
    /// Print a readable listing of an object file.
    Disasm { file: PathBuf },
    /// A language server over standard input and output, for editors (docs/editors.md).
    Lsp,
    /// Format action, sequence, ladder and FST table files in place (docs/style.md).
    Fmt {
        /// Files or directories; none: the files of the strategies in the current directory.
        files: Vec<PathBuf>,
        /// Change nothing: list the files that would change and exit 1 if any would.
        #[arg(long)]
        check: bool,
    },
    /// Explain a diagnostic code, e.g. `linc explain E0104`.
    Explain {
        /// The code; omit it (or use --list) to list all codes.
        code: Option<String>,
        /// List every code with its title.
        #[arg(long)]
        list: bool,
    },
}

/// `linc run`'s options (boxed: the largest command by far).
#[derive(clap::Args)]
struct RunArgs {
    /// A strategy's database (.json), or an action file (.st/.stx, compiled first) or object file (.sto).
    file: PathBuf,
    /// The database to run one action against (not with a strategy).
    #[arg(long)]
    db: Option<PathBuf>,
    /// Run the strategy for this much simulated time: 10m, 1h30m, T#2.5s.
    #[arg(long = "for", value_name = "DURATION", allow_hyphen_values = true)]
    duration: Option<String>,
    /// The action to run (default: the first in the file).
    #[arg(long)]
    action: Option<String>,
    /// The block running an `ACTION name : TYPE` action (default: the only block of that type).
    #[arg(long)]
    block: Option<String>,
    /// Cycles to run; 0 links the action and applies --set, --show and --out without running it.
    #[arg(long, value_name = "N", allow_negative_numbers = true, value_parser = cycles)]
    cycles: Option<u32>,
    /// Seconds of simulated time per cycle (default 1), or per scan of a sequence (default: its task's period).
    #[arg(long, value_name = "SECS", allow_hyphen_values = true, value_parser = period)]
    period: Option<f64>,
    /// Hold a step of the sequence being run (repeatable).
    #[arg(long, value_name = "STEP")]
    hold_step: Vec<String>,
    /// Force a transition of the sequence being run: NAME=hold|continue|normal (repeatable).
    #[arg(long, value_name = "NAME=HOW")]
    force: Vec<String>,
    /// Set a field before the run: BLOCK.FIELD=VALUE (repeatable).
    #[arg(long)]
    set: Vec<String>,
    /// Print BLOCK.FIELD = VALUE after the run (repeatable).
    #[arg(long)]
    show: Vec<String>,
    /// Trace field writes: to FILE as JSON lines for a strategy, or printed as they happen.
    #[arg(long, value_name = "FILE", num_args = 0..=1, default_missing_value = "-")]
    trace: Option<PathBuf>,
    /// Write the database, with its values after the run, here (atomically).
    #[arg(long)]
    out: Option<PathBuf>,
    /// A strategy's retentive state: restored at the start when the file exists (a warm start), saved at the end.
    #[arg(long, value_name = "FILE")]
    state: Option<PathBuf>,
    /// Start cold: ignore the --state file (it is still written at the end).
    #[arg(long)]
    cold: bool,
    /// Fix the clock: YYYY-MM-DDTHH:MM:SS (UTC).
    #[arg(long, value_name = "YYYY-MM-DDTHH:MM:SS", value_parser = now)]
    now: Option<i64>,
    /// Seed of RANDOM, for repeatable runs.
    #[arg(long)]
    seed: Option<u64>,
    /// Instruction budget of one run before the watchdog stops it (at least 1).
    #[arg(
        long,
        default_value_t = linc_driver::plant::DEFAULT_WATCHDOG,
        value_name = "N",
        allow_negative_numbers = true,
        value_parser = watchdog
    )]
    watchdog: u64,
    /// Which tier runs the code: `auto` compiles loops at once and other code once it has run long,
    /// in the background while the interpreter runs it (ADR 0011, 0023); `compiled` compiles every
    /// block before its first run; `interpreter` never compiles.
    #[arg(long, value_enum, default_value = "auto")]
    tier: TierArg,
}

#[derive(Subcommand)]
enum FstCommand {
    /// Print the table aligned, with each step's instruction offset (IP) when --db lets it compile.
    List {
        file: PathBuf,
        /// The ROC point database the table's points live in.
        #[arg(long)]
        db: Option<PathBuf>,
    },
    /// Translate a table without waits to the ST action that does what one cycle of it does
    /// (docs/fst-translation.md); a step that cannot be translated faithfully is a located error.
    ToSt {
        file: PathBuf,
        /// The ROC point database the table's points live in.
        #[arg(long)]
        db: PathBuf,
        /// The FST block that runs the table (needed when the database has several).
        #[arg(long)]
        block: Option<String>,
        /// Write the action here instead of standard output.
        #[arg(short, long)]
        out: Option<PathBuf>,
    },
    /// Translate a table to a sequence: a step where each cycle can start (step 0, after each WT), its
    /// P action the cycle from there, transitions where the table goes on (docs/fst-translation.md).
    ToSfc {
        file: PathBuf,
        /// The ROC point database the table's points live in.
        #[arg(long)]
        db: PathBuf,
        /// The FST block that runs the table (needed when the database has several).
        #[arg(long)]
        block: Option<String>,
        /// A numeric field nothing else uses (BLOCK.FIELD), where a step that can go on in several ways notes which.
        #[arg(long, value_name = "BLOCK.FIELD")]
        exit: Option<String>,
        /// Write the sequence here instead of standard output.
        #[arg(short, long)]
        out: Option<PathBuf>,
    },
}

#[derive(Clone, Copy, ValueEnum)]
enum InstrumentSize {
    Small,
    Large,
}

#[derive(Subcommand)]
enum SfcCommand {
    /// Write the specific sequence: generic names replaced by their map targets.
    Specialise {
        file: PathBuf,
        #[arg(long)]
        map: PathBuf,
        /// The sequence to write.
        #[arg(short, long)]
        out: PathBuf,
    },
    /// Write the generic sequence: database names a map entry targets replaced by its generic name.
    Generalise {
        file: PathBuf,
        #[arg(long)]
        map: PathBuf,
        #[arg(short, long)]
        out: PathBuf,
    },
    /// Print a map (JSON) with every generic name of a sequence and an empty target.
    MapTemplate {
        file: PathBuf,
        /// The database whose blocks and aliases are not generic names.
        #[arg(long)]
        db: Option<PathBuf>,
    },
}

// Value parsers: a bad option value is a usage error (E0903, exit 2) whose
// message says what is accepted, before any file is read; clap's errors
// reach the user through the reporter like every other error.

/// `--period`: simulated seconds per cycle. Zero or less would stop or
/// reverse the clock, NaN or infinity would poison every timer, and less
/// than the clock's microsecond would not move it at all.
fn period(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if (1e-6..=366.0 * 86_400.0).contains(&x) => Ok(x),
        _ => Err("the period must be a number of seconds from 0.000001 (the clock's microsecond) to 366 days, such as 0.5 or 10".into()),
    }
}

/// `--cycles`: 0 is allowed (link, --set, --show and --out without a run).
fn cycles(s: &str) -> Result<u32, String> {
    s.trim().parse::<u32>().map_err(|_| format!("the number of cycles must be a whole number from 0 to {}", u32::MAX))
}

/// `--watchdog`: a budget of 0 instructions would stop every action before
/// its first instruction.
fn watchdog(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err("the watchdog budget must be a whole number of instructions, at least 1".into()),
    }
}

/// `--now`: a real date and time (no 29 February 2023, no 24:00:00), in
/// POSIX seconds.
fn now(s: &str) -> Result<i64, String> {
    match linc_driver::database::timestamp(s) {
        Some(t) => Ok(t),
        None => Err("not a real date and time; write YYYY-MM-DDTHH:MM:SS (UTC), such as 2024-02-29T13:45:07".into()),
    }
}

fn format(m: MessageFormat) -> linc_compiler::diag::render::Format {
    match m {
        MessageFormat::Human => linc_compiler::diag::render::Format::Human,
        MessageFormat::Short => linc_compiler::diag::render::Format::Short,
        MessageFormat::Json => linc_compiler::diag::render::Format::Json,
    }
}

fn sfc(command: SfcCommand, r: &Reporter) -> u8 {
    use linc_driver::sfc::Direction;
    match command {
        SfcCommand::Specialise { file, map, out } => sfc_cmd::rewrite(Direction::Specialise, &file, &map, &out, r),
        SfcCommand::Generalise { file, map, out } => sfc_cmd::rewrite(Direction::Generalise, &file, &map, &out, r),
        SfcCommand::MapTemplate { file, db } => sfc_cmd::map_template(&file, db.as_deref(), r),
    }
}

/// The message format asked for on a command line clap refused, so that
/// even that error comes in the format the caller reads.
fn format_in_args() -> linc_compiler::diag::render::Format {
    let args: Vec<String> = std::env::args().collect();
    let value = args.iter().enumerate().find_map(|(i, a)| match a.strip_prefix("--message-format") {
        Some("") => args.get(i + 1).cloned(),
        Some(v) => v.strip_prefix('=').map(str::to_string),
        None => None,
    });
    match value.as_deref() {
        Some("json") => linc_compiler::diag::render::Format::Json,
        Some("short") => linc_compiler::diag::render::Format::Short,
        _ => linc_compiler::diag::render::Format::Human,
    }
}

/// A command line clap refused, as E0903 through the reporter (help and
/// version requests print as clap prints them).
fn refused_arguments(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion)
        || e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    {
        let _ = e.print();
        return ExitCode::from(if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand { 2 } else { 0 });
    }
    // clap's first line is the message; its tips and usage line are help.
    let text = e.render().to_string();
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let first = lines.next().unwrap_or_default();
    let mut d = linc_compiler::Diagnostic::command(Code::E0903, first.strip_prefix("error: ").unwrap_or(first));
    for line in lines {
        d = d.help(line.strip_prefix("tip: ").unwrap_or(line));
    }
    let r = Reporter::new(format_in_args());
    ExitCode::from(r.report(&linc_driver::Problems::refusal(d)))
}

/// See cli/Cargo.toml: frees from another thread without a lock.
#[global_allocator]
static ALLOCATOR: alloc::Allocator = alloc::Allocator;

fn main() -> ExitCode {
    quiet_broken_pipe();
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return refused_arguments(e),
    };
    let r = Reporter::new(format(cli.message_format));
    ExitCode::from(dispatch(cli.command, &r))
}

/// A reader that stops reading (`linc explain --list | head -1`) ends
/// `linc` quietly, as it ends any Unix tool, instead of a panic in `println!`.
fn quiet_broken_pipe() {
    #[cfg(unix)]
    // SAFETY: restoring the default action of SIGPIPE, before any thread
    // is started, is what every C program starts with.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

fn dispatch(command: Command, r: &Reporter) -> u8 {
    match command {
        Command::Compile { files, out, db, map } => compile_cmd::run(&files, &out, db.as_deref(), map.as_deref(), r),
        Command::Sfc { command } => sfc(command, r),
        Command::Fst { command: FstCommand::List { file, db } } => fst_cmd::list(&file, db.as_deref(), r),
        Command::Fst { command: FstCommand::ToSt { file, db, block, out } } => {
            fst_cmd::translate(&file, &db, out.as_deref(), r, || linc_driver::fst::to_st(&file, &db, block.as_deref()))
        }
        Command::Fst { command: FstCommand::ToSfc { file, db, block, exit, out } } => {
            fst_cmd::translate(&file, &db, out.as_deref(), r, || {
                linc_driver::fst::to_sfc(&file, &db, block.as_deref(), exit.as_deref())
            })
        }
        Command::Ladder { command } => ladder_cmd::run(command, r),
        Command::Serve(args) => serve_cmd::run(*args, r),
        Command::Roc { command } => roc_cmd::run(command, r),
        Command::Draw(args) => {
            let (o, out) = args.options();
            draw_cmd::run(&o, out.as_deref(), r)
        }
        Command::Console { file, script, set, trace, now, seed, state, cold } => {
            let state = state.map(|path| StateFile { path, cold });
            let spec = PlantSpec { set, now, seed, state, ..PlantSpec::strategy(file) };
            console_cmd::run(console_cmd::Options { spec, script, trace }, r)
        }
        Command::Run(run) => run_command(*run, r),
        Command::Eval { expr, db, now, seed } => eval_cmd::run(&expr, db.as_deref(), now, seed, r),
        Command::Test {
            paths,
            jobs,
            junit,
            vcd,
            shard,
            list,
            coverage,
            merge_coverage,
            out,
            fail_under_functions,
            fail_under_lines,
            fail_under_branches,
        } => {
            let gate = linc_driver::coverage::Gate {
                functions: fail_under_functions,
                lines: fail_under_lines,
                branches: fail_under_branches,
            };
            test_cmd::run(
                &test_cmd::Options { paths, jobs, junit, vcd, shard, list, coverage, merge_coverage, out, gate },
                r,
            )
        }
        Command::Disasm { file } => disasm_cmd::run(&file, r),
        Command::Check { files, db, tree, transition, sequence, map, allow_unmapped, resources, instrument } => {
            check_cmd::run(
                &linc_driver::check::CheckRequest {
                    files,
                    db,
                    tree,
                    transition,
                    sequence,
                    map,
                    allow_unmapped,
                    resources: resources.then_some(match instrument {
                        InstrumentSize::Small => linc_compiler::sfc::resources::Instrument::Small,
                        InstrumentSize::Large => linc_compiler::sfc::resources::Instrument::Large,
                    }),
                },
                r,
            )
        }
        Command::Explain { code, list } => explain_cmd::run(code.as_deref(), list, r),
        Command::Fmt { files, check } => fmt_cmd::run(&files, check, r),
        Command::Lsp => match linc_lsp::run_stdio() {
            Ok(ending) => ending.status(),
            Err(e) => report::usage(r, format!("the language server stopped: {e}")),
        },
    }
}

/// The options of `linc run` that only one form takes: refused (E0903)
/// where they would be ignored.
fn misuse(a: &RunArgs) -> Option<String> {
    let strategy = a.db.is_none();
    let single = a.db.is_some() && a.duration.is_some();
    let action = a.db.is_some() && a.duration.is_none();
    let only = |flag: &str, given: bool, ok: bool, form: &str| (given && !ok).then(|| format!("{flag} {form}"));
    [
        only("--cold", a.cold && a.state.is_none(), false, "ignores a --state file: give --state FILE too"),
        only("--state", a.state.is_some(), a.duration.is_some(), "keeps a strategy's state: give --for DURATION"),
        only("--cycles", a.cycles.is_some(), action, "runs one action: a strategy or sequence runs --for DURATION"),
        only("--action", a.action.is_some(), action, "chooses the action of an action file run with --db"),
        only("--block", a.block.is_some(), !strategy, "chooses the block of one program run with --db"),
        only("--period", a.period.is_some(), !strategy, "sets one program's period: a strategy's tasks set theirs"),
        only("--hold-step", !a.hold_step.is_empty(), single, "holds a step of a sequence run with --db and --for"),
        only("--force", !a.force.is_empty(), single, "forces a transition of a sequence run with --db and --for"),
    ]
    .into_iter()
    .flatten()
    .next()
}

fn run_command(a: RunArgs, r: &Reporter) -> u8 {
    if let Some(why) = misuse(&a) {
        return report::usage(r, why);
    }
    let common = run_cmd::Common {
        set: a.set,
        show: a.show,
        trace: a.trace,
        out: a.out,
        now: a.now,
        seed: a.seed,
        watchdog: a.watchdog,
        tier: a.tier.into(),
        state: a.state.map(|path| StateFile { path, cold: a.cold }),
    };
    let file = a.file;
    let controls = linc_driver::run::Controls { hold_steps: a.hold_step, force: a.force };
    match (a.db, a.duration) {
        (None, Some(duration)) => {
            run_cmd::run(file, run_cmd::Form::For { program: Program::Strategy, duration, controls }, common, r)
        }
        (Some(db), None) => {
            let (cycles, period) = (a.cycles.unwrap_or(1), a.period.unwrap_or(1.0));
            let program = run_cmd::action(file, a.action, a.block);
            run_cmd::run(db, run_cmd::Form::Cycles { program, cycles, period }, common, r)
        }
        (Some(db), Some(duration))
            if linc_driver::source::kind(&file).stands_alone() || linc_driver::source::is_object(&file) =>
        {
            let program = Program::One { file, block: a.block, period: a.period };
            run_cmd::run(db, run_cmd::Form::For { program, duration, controls }, common, r)
        }
        (Some(_), Some(_)) => report::usage(
            r,
            "--for runs a strategy (PLANT.json without --db), a sequence (FILE.sfc --db PLANT.json) \
             or an FST table (TABLE.csv --db ROC.json)",
        ),
        (None, None) => report::usage(r, "give --for DURATION to run a strategy, or --db DB.json to run one action"),
    }
}

//! `linc`: check, compile and run LIN Structured Text from the command line.
//!
//! Exit status: 0 clean, 1 errors found in the input, 2 usage or I/O problem.

mod check_cmd;
mod explain_cmd;

use clap::{Parser, Subcommand, ValueEnum};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "linc",
    version,
    about = "A toolchain for LIN Structured Text: check actions against a function-block database"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Clone, Copy, ValueEnum)]
enum MessageFormat {
    Human,
    Short,
    Json,
}

#[derive(Subcommand)]
enum Command {
    /// Check action files (.st/.stx) for syntax, names and types.
    Check {
        /// Files to check.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Database (JSON) to resolve block, field and alias names against.
        #[arg(long)]
        db: Option<PathBuf>,
        /// How to print diagnostics.
        #[arg(long, value_enum, default_value = "human")]
        message_format: MessageFormat,
        /// Print the syntax tree of each file.
        #[arg(long)]
        tree: bool,
        /// Each file is one transition expression (§12.11), checked in sequence context.
        #[arg(long)]
        transition: bool,
        /// Check actions as sequence actions, where step.X and step.T exist.
        #[arg(long)]
        sequence: bool,
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

fn main() -> ExitCode {
    let cli = Cli::parse();
    let status = match cli.command {
        Command::Check {
            files,
            db,
            message_format,
            tree,
            transition,
            sequence,
        } => {
            let format = match message_format {
                MessageFormat::Human => linc_compiler::render::Format::Human,
                MessageFormat::Short => linc_compiler::render::Format::Short,
                MessageFormat::Json => linc_compiler::render::Format::Json,
            };
            check_cmd::run(&check_cmd::Options {
                files,
                db,
                format,
                tree,
                transition,
                sequence,
            })
        }
        Command::Explain { code, list } => explain_cmd::run(code.as_deref(), list),
    };
    ExitCode::from(status)
}

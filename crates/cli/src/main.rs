//! The `gonio` command: parses flags, calls into the gonio crates and formats their results.
//! No physics lives here.

mod compare;
mod report;
mod plot;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// gonio: predict how a coated surface looks from its measured topography.
///
/// Units are SI inside; every flag and output column names its unit (`--sq-nm`, `--dx-um`,
/// `_deg`, `_per_sr`). Errors exit with status 2.
#[derive(Parser)]
#[command(name = "gonio", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Compare measured and computed in-plane curves (RMS of log reflectance, peaks, FWHM).
    Compare(compare::CompareArgs),
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result: anyhow::Result<()> = match cli.command {
        Command::Compare(args) => compare::run(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("error: {err:#}");
            ExitCode::from(2)
        }
    }
}

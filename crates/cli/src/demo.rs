//! `gonio demo`: the whole pipeline on embedded default data, written up as one HTML report
//! (`out/report.html`) by [`gonio_report::demo`]. Here only the flags, the steps printed as
//! they begin, the progress bars and the closing line.

use anyhow::Result;
use clap::Args;
use gonio_io::Progress;
use gonio_report::demo::{DemoPlan, DemoProgress};
use std::path::PathBuf;

#[derive(Args)]
pub struct DemoArgs {
    /// Directory for the report and everything it shows (created if missing).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
    /// A small, fast run (128 × 128 maps, two samples, one wavelength), as the tests use.
    #[arg(long)]
    quick: bool,
}

pub fn run(args: DemoArgs) -> Result<()> {
    let plan = DemoPlan {
        output: args.output,
        quick: args.quick,
    };
    let progress = DemoProgress {
        steps: Progress::new(|r| eprintln!("[{}/{}] {}", r.done + 1, r.total, r.stage)),
        work: crate::progress::successive(),
    };
    let outcome = gonio_report::demo::run(&plan, &progress)?;
    eprintln!(
        "done in {:.0} s: the report is {}",
        outcome.seconds,
        outcome.report.display()
    );
    Ok(())
}

//! Progress on a terminal: bars and spinners on stderr (indicatif draws nothing when stderr is
//! not a terminal, so pipes and scripts stay quiet), and the bridge from the libraries'
//! [`Progress`] reports to a bar. Only the command line draws; the libraries only report.

use gonio_io::Progress;
use indicatif::{ProgressBar, ProgressFinish, ProgressStyle};
use std::time::Duration;

/// A bar of `len` steps: `████░░ 3/8 message 12s`, cleared from the terminal when it is
/// finished or when its last handle (a [`reporting`] callback holds one) is dropped.
pub fn bar(len: u64) -> ProgressBar {
    let bar = ProgressBar::new(len).with_finish(ProgressFinish::AndClear);
    if let Ok(style) = ProgressStyle::with_template("{bar:30} {pos}/{len} {msg} {elapsed}") {
        bar.set_style(style);
    }
    bar
}

/// A spinner with `message`, for work that reports no steps.
pub fn spinner(message: &str) -> ProgressBar {
    let bar = ProgressBar::new_spinner().with_message(message.to_string());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
        bar.set_style(style);
    }
    bar.enable_steady_tick(Duration::from_millis(120));
    bar
}

/// Reports into `bar`: the stage as its message (when one is given), the total as its length,
/// the count as its position (the largest seen, as parallel steps may report out of order).
pub fn reporting(bar: &ProgressBar) -> Progress {
    let bar = bar.clone();
    Progress::new(move |r| {
        if !r.stage.is_empty() {
            bar.set_message(r.stage.to_string());
        }
        if r.total > 0 {
            bar.set_length(r.total);
        }
        if r.done > bar.position() {
            bar.set_position(r.done);
        }
    })
}

/// Reports that each advance `bar` by one step, whatever their count: for several computations
/// that share one bar.
pub fn ticking(bar: &ProgressBar) -> Progress {
    let bar = bar.clone();
    Progress::new(move |_| bar.inc(1))
}

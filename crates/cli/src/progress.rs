//! Progress of long computations on stderr, and the bridge from the libraries' [`Progress`]
//! reports to it. Only the command line writes; the libraries only report.
//!
//! On a terminal: bars and spinners (indicatif). When stderr is not a terminal (a pipe, a log
//! file, a batch job), where indicatif draws nothing: a plain line every [`interval`] seconds
//! (10 by default), `brdf compute: 34% done, 1m 02s elapsed, about 2m 01s left`. In both, once a
//! computation has run for a fifth of the interval (the pilot), the time it will take in all,
//! extrapolated from the share of the work done so far, is printed once, unless it is shorter
//! than the interval: fast computations stay quiet. The libraries weigh their reports by the
//! expected cost of each step (e.g. `Kirchhoff::hemisphere_cost`), so the share done is a share
//! of the time.

use gonio_io::Progress;
use indicatif::{ProgressBar, ProgressFinish, ProgressStyle};
use std::io::IsTerminal;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// The environment variable that sets the interval of the progress lines, in seconds (for tests
/// and batch logs; default 10). 0 writes a line at every report and the estimate at the first.
pub const INTERVAL_VARIABLE: &str = "GONIO_PROGRESS_SECONDS";

/// Seconds between two progress lines on a stderr that is not a terminal: [`INTERVAL_VARIABLE`]
/// when it holds a number of seconds (0 or more), else 10.
pub fn interval() -> Duration {
    std::env::var(INTERVAL_VARIABLE)
        .ok()
        .and_then(|s| s.trim().parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s >= 0.0)
        .map_or(Duration::from_secs(10), Duration::from_secs_f64)
}

/// A bar of `len` steps: `████░░  37% message 12s, about 20s left`, cleared from the terminal
/// when it is finished or when its last handle (a [`reporting`] callback holds one) is dropped.
pub fn bar(len: u64) -> ProgressBar {
    let bar = ProgressBar::new(len).with_finish(ProgressFinish::AndClear);
    if let Ok(style) =
        ProgressStyle::with_template("{bar:30} {percent:>3}% {msg} {elapsed}, about {eta} left")
    {
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
/// the count as its position (the largest seen, as parallel steps may report out of order);
/// and the estimate and the progress lines of [`Log`].
pub fn reporting(bar: &ProgressBar) -> Progress {
    let bar = bar.clone();
    let log = Log::new(bar.clone());
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
        log.update();
    })
}

/// Reports that each advance `bar` by one step, whatever their count: for several computations
/// that share one bar.
pub fn ticking(bar: &ProgressBar) -> Progress {
    let bar = bar.clone();
    let log = Log::new(bar.clone());
    Progress::new(move |_| {
        bar.inc(1);
        log.update();
    })
}

/// Reports of computations that run one after another (the demo's study, renders and texture
/// pictures), each on a bar of its own: a report that counts fewer steps than the one before,
/// or of another total, begins the next computation (each counts its own steps from the
/// start), so the last bar is finished and a new one drawn.
pub fn successive() -> Progress {
    let current: Mutex<Option<(ProgressBar, Progress, u64, u64)>> = Mutex::new(None);
    Progress::new(move |r| {
        let Ok(mut current) = current.lock() else {
            return;
        };
        let next = match current.as_ref() {
            Some((_, _, done, total)) => r.done < *done || r.total != *total,
            None => true,
        };
        if next {
            if let Some((bar, ..)) = current.take() {
                bar.finish_and_clear();
            }
            let bar = bar(0);
            let progress = reporting(&bar);
            *current = Some((bar, progress, 0, r.total));
        }
        if let Some((_, progress, done, _)) = current.as_mut() {
            *done = (*done).max(r.done);
            progress.report(r.stage, r.done, r.total);
        }
    })
}

/// The estimate and the plain progress lines of one bar (see the module's documentation).
#[derive(Clone)]
struct Log {
    bar: ProgressBar,
    interval: Duration,
    /// Lines go to stderr (not a terminal) rather than above the bar.
    plain: bool,
    state: Arc<Mutex<LogState>>,
}

struct LogState {
    /// When the bar was made: the elapsed time shown counts from here.
    start: Instant,
    /// When the work began: the first report, if it counted no step (a computation that plans
    /// its steps first reports `0` of them when it starts), else the start. The rate of the
    /// work, and so the time left, counts from here.
    work_start: Instant,
    reported: bool,
    last_line: Instant,
    estimated: bool,
}

impl Log {
    fn new(bar: ProgressBar) -> Log {
        let now = Instant::now();
        Log {
            bar,
            interval: interval(),
            plain: !std::io::stderr().is_terminal(),
            state: Arc::new(Mutex::new(LogState {
                start: now,
                work_start: now,
                reported: false,
                last_line: now,
                estimated: false,
            })),
        }
    }

    /// After a report: the estimate once the pilot has run, a line when one is due.
    fn update(&self) {
        let (done, total) = (self.bar.position(), self.bar.length().unwrap_or(0));
        let Ok(mut state) = self.state.lock() else {
            return;
        };
        let now = Instant::now();
        if !state.reported {
            state.reported = true;
            if done == 0 {
                state.work_start = now;
            }
        }
        if done == 0 || total == 0 {
            return;
        }
        let (elapsed, working) = (now - state.start, now - state.work_start);
        let fraction = (done as f64 / total as f64).min(1.0);
        let remaining = working.as_secs_f64() * (1.0 / fraction - 1.0);
        let what = match self.bar.message() {
            m if m.is_empty() => "working".to_string(),
            m => m,
        };
        if !state.estimated && working >= self.interval / 5 {
            state.estimated = true;
            let projected = elapsed.as_secs_f64() + remaining;
            if projected >= self.interval.as_secs_f64() {
                self.write(format!(
                    "{what}: estimated time about {} in all ({:.0}% done in {})",
                    duration(projected),
                    100.0 * fraction,
                    duration(elapsed.as_secs_f64())
                ));
            }
        }
        if self.plain && now - state.last_line >= self.interval {
            state.last_line = now;
            self.write(format!(
                "{what}: {:.0}% done, {} elapsed, about {} left",
                100.0 * fraction,
                duration(elapsed.as_secs_f64()),
                duration(remaining)
            ));
        }
    }

    fn write(&self, line: String) {
        if self.plain {
            eprintln!("{line}");
        } else {
            self.bar.println(line);
        }
    }
}

/// `42s`, `3m 05s`, `1h 02m`: a duration as a person reads it.
fn duration(seconds: f64) -> String {
    let s = seconds.max(0.0).round() as u64;
    match s {
        0..60 => format!("{s}s"),
        60..3600 => format!("{}m {:02}s", s / 60, s % 60),
        _ => format!("{}h {:02}m", s / 3600, s % 3600 / 60),
    }
}

#[cfg(test)]
mod tests {
    use super::duration;

    #[test]
    fn durations_read_as_written() {
        assert_eq!(duration(0.4), "0s");
        assert_eq!(duration(42.0), "42s");
        assert_eq!(duration(185.0), "3m 05s");
        assert_eq!(duration(3720.0), "1h 02m");
    }
}

//! How a long computation tells its caller how far it has come. The libraries (tables and
//! in-plane curves by the ray method and Kirchhoff, studies, the isotropy check, the renderer)
//! take one [`Progress`] and report through it; only the command line turns the reports into
//! bars on a terminal, so a library never writes to the terminal and a script or the Python
//! package can follow a computation its own way.

use std::sync::Arc;

/// One report: what is being done and how far the computation has come.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Report<'a> {
    /// What is being done now, in words ("30°: curves of the turned map"); empty when the
    /// report only counts a step.
    pub stage: &'a str,
    /// Steps finished. Steps that run in parallel are counted as they finish, so two reports
    /// may arrive in the other order: a display keeps the largest count it has seen. A
    /// computation whose steps differ in cost may count each by its expected cost (the
    /// Kirchhoff tables count nanoseconds of a calibrated cost model), so that `done/total` is
    /// the share of the time and a display can tell the time left; one that plans its steps
    /// first reports `0` of them when the work begins.
    pub done: u64,
    /// All the steps, as far as known when reporting (it may grow).
    pub total: u64,
}

/// The caller's callback, called from whichever thread finishes a step.
type Callback = dyn Fn(Report<'_>) + Send + Sync;

/// A handle on the caller's progress callback, cheap to clone and shareable between threads;
/// the default reports nowhere.
#[derive(Clone, Default)]
pub struct Progress(Option<Arc<Callback>>);

impl Progress {
    /// Reports go to `f`, from whichever thread finishes a step.
    pub fn new(f: impl Fn(Report<'_>) + Send + Sync + 'static) -> Progress {
        Progress(Some(Arc::new(f)))
    }

    /// A handle that reports nowhere.
    pub fn silent() -> Progress {
        Progress(None)
    }

    /// Report `done` of `total` steps finished, now doing `stage`.
    pub fn report(&self, stage: &str, done: u64, total: u64) {
        if let Some(f) = &self.0 {
            f(Report { stage, done, total });
        }
    }
}

impl std::fmt::Debug for Progress {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.0.is_some() {
            "Progress(callback)"
        } else {
            "Progress(silent)"
        })
    }
}

/// Two handles are equal when both are silent or both call the same callback.
impl PartialEq for Progress {
    fn eq(&self, other: &Progress) -> bool {
        match (&self.0, &other.0) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    #[test]
    fn reports_reach_the_callback_from_any_thread_and_silence_reaches_nothing() {
        let seen = Arc::new(Mutex::new(vec![]));
        let sink = seen.clone();
        let progress = Progress::new(move |r| {
            sink.lock()
                .unwrap()
                .push((r.stage.to_owned(), r.done, r.total))
        });
        let copy = progress.clone();
        std::thread::spawn(move || copy.report("", 1, 2))
            .join()
            .unwrap();
        progress.report("second", 2, 2);
        assert_eq!(
            *seen.lock().unwrap(),
            [("".to_owned(), 1, 2), ("second".to_owned(), 2, 2)]
        );
        Progress::silent().report("nothing", 1, 1);
        assert_eq!(progress, progress.clone());
        assert_ne!(progress, Progress::silent());
        assert_eq!(Progress::default(), Progress::silent());
    }
}

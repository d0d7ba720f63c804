//! How a front end follows and stops a long formulation computation (a match, a sensitivity
//! run) while it runs: the lab's page shows the readings made and the best objective so far, and
//! its Cancel button raises the flag. A [`Watch`] holds a [`Cancel`] flag, checked before every
//! reading (a stopped computation returns `InstrumentError::Cancelled`, never a partial result),
//! and a function told after every reading. The default watches nothing and stops never: the
//! command line's and Python's calls are unchanged.

use crate::error::Result;
use gonio_instrument::InstrumentError;
use gonio_io::Cancel;

/// What a computation has done so far.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Progress {
    /// Readings made so far.
    pub readings: usize,
    /// Readings the computation makes in all, when known before it ends (a sensitivity run's
    /// design; a match's search stops when it converges, so it has none).
    pub total: Option<usize>,
    /// The lowest objective so far (a match's; none for a sensitivity run).
    pub best: Option<f64>,
}

/// How a caller follows and stops a computation.
#[derive(Clone, Copy, Default)]
pub struct Watch<'a> {
    /// Raised, the computation stops before its next reading.
    pub cancel: Option<&'a Cancel>,
    /// Told after every reading (from any thread).
    pub progress: Option<&'a (dyn Fn(Progress) + Sync)>,
}

impl Watch<'_> {
    /// `Err(Cancelled)` once the flag is raised.
    pub fn check(&self) -> Result<()> {
        match self.cancel {
            Some(c) if c.is_cancelled() => Err(InstrumentError::Cancelled.into()),
            _ => Ok(()),
        }
    }

    /// Tell the caller about `progress`.
    pub fn report(&self, progress: Progress) {
        if let Some(f) = self.progress {
            f(progress);
        }
    }
}

//! How a caller stops a long computation it no longer needs: the lab drops the readings and the
//! picture of a formulation as soon as a newer one arrives, so that moving a slider never
//! queues work. The caller keeps a [`Cancel`] and calls [`Cancel::cancel`]; the computation,
//! given a clone, checks [`Cancel::is_cancelled`] between steps short enough (a table cell's
//! walks, a tile of pixels) that it stops within milliseconds, and returns its crate's
//! `Cancelled` error: never a partial result that could be taken for a finished one.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// A shared flag, cheap to clone; the default is never cancelled (and costs nothing to check).
#[derive(Clone, Default, Debug)]
pub struct Cancel(Option<Arc<AtomicBool>>);

impl Cancel {
    /// A flag not yet raised, that [`Cancel::cancel`] raises for every clone.
    pub fn new() -> Cancel {
        Cancel(Some(Arc::new(AtomicBool::new(false))))
    }

    /// Ask every computation holding a clone to stop.
    pub fn cancel(&self) {
        if let Some(flag) = &self.0 {
            flag.store(true, Ordering::Relaxed);
        }
    }

    /// Whether [`Cancel::cancel`] has been called on this flag or a clone.
    pub fn is_cancelled(&self) -> bool {
        self.0.as_ref().is_some_and(|f| f.load(Ordering::Relaxed))
    }
}

/// Two handles are equal when both are never cancelled or both share one flag.
impl PartialEq for Cancel {
    fn eq(&self, other: &Cancel) -> bool {
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

    /// Raising the flag reaches every clone, on any thread; the default is never raised.
    #[test]
    fn a_raised_flag_reaches_every_clone() {
        let c = Cancel::new();
        let d = c.clone();
        assert!(!d.is_cancelled());
        std::thread::spawn(move || c.cancel()).join().unwrap();
        assert!(d.is_cancelled());
        let never = Cancel::default();
        never.cancel();
        assert!(!never.is_cancelled());
    }
}

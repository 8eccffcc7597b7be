//! The limits a host sets on every solve, and the helpers that keep them in every loop.

use std::time::{Duration, Instant};

use super::SolverOutcome;
use crate::error::{require_setting, try_copy, Fc3dError};

/// The limits every family honours. Their defaults depend on the family (Siconos' defaults):
/// [`crate::SolverConfig::new`] fills them in.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Tolerance on the relative natural-map error of the returned `(r, u)`.
    pub tolerance: f64,
    /// Iteration limit: sweeps (NSGS, SOCLCP), Newton steps (NSN), outer iterations (TFP, PFP,
    /// ACLMFP, PROX), projection steps (VI), ADMM iterations.
    pub max_iter: usize,
    /// Wall-clock budget: `None` (default) runs until convergence or the iteration limit.
    pub time_budget: Option<Duration>,
}

impl Limits {
    /// Checks the limits against their documented ranges: a finite tolerance >= 0, a positive
    /// budget when there is one (any iteration limit is valid).
    pub fn validate(&self) -> Result<(), Fc3dError> {
        let t = self.tolerance;
        require_setting(t >= 0.0 && t.is_finite(), "tolerance", t, "finite and >= 0")?;
        if let Some(b) = self.time_budget {
            require_setting(
                !b.is_zero(),
                "time_budget",
                format!("{b:?}"),
                "positive (None: no budget)",
            )?;
        }
        Ok(())
    }

    /// Starts a run: the deadline is fixed now.
    pub(crate) fn start(&self) -> Run {
        Run {
            tolerance: self.tolerance,
            max_iter: self.max_iter,
            deadline: self.time_budget.and_then(|b| Instant::now().checked_add(b)),
        }
    }
}

/// One run of a family's main loop against its [`Limits`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct Run {
    pub tolerance: f64,
    pub max_iter: usize,
    deadline: Option<Instant>,
}

impl Run {
    /// A run of an inner solve with its own tolerance and iteration limit under the same
    /// deadline.
    pub fn inner(&self, tolerance: f64, max_iter: usize) -> Run {
        Run {
            tolerance,
            max_iter,
            deadline: self.deadline,
        }
    }

    /// The instant the budget runs out, if there is a budget.
    pub fn deadline(&self) -> Option<Instant> {
        self.deadline
    }

    pub fn out_of_time(&self) -> bool {
        deadline_passed(self.deadline)
    }

    /// Whether a step expected to take `duration` would end past the deadline. For loops whose
    /// one step cannot be interrupted (a sparse factorization of seconds at 10^4 contacts): such
    /// a step is not started, so the budget holds up to the error of the estimate.
    pub fn cannot_afford(&self, duration: Duration) -> bool {
        self.deadline.is_some_and(|d| {
            Instant::now()
                .checked_add(duration)
                .is_none_or(|end| end > d)
        })
    }

    /// The end-of-iteration test every main loop runs after iteration `iteration`: stop when
    /// converged, else when the budget is spent; `None` goes on.
    pub fn end_of_iteration(&self, iteration: usize, converged: bool) -> Option<SolverOutcome> {
        if converged {
            Some(SolverOutcome::stopped(iteration, false))
        } else if self.out_of_time() {
            Some(SolverOutcome::stopped(iteration, true))
        } else {
            None
        }
    }

    /// The outcome of a loop that used all its iterations.
    pub fn exhausted(&self) -> SolverOutcome {
        SolverOutcome::stopped(self.max_iter, false)
    }
}

/// Whether `deadline` has passed (for loops whose iteration costs a sweep or more).
#[inline]
pub fn deadline_passed(deadline: Option<Instant>) -> bool {
    deadline.is_some_and(|d| Instant::now() >= d)
}

/// Every this many iterations a tight loop reads the clock (a local solve's iteration costs far
/// less than a clock read).
const CLOCK_PERIOD: usize = 64;

/// Whether `deadline` has passed, read once every [`CLOCK_PERIOD`] iterations of a tight loop
/// (its `iteration` counter): the budget holds in loops whose length an option controls
/// (`INT_MAX` local iterations or line-search trials) at the cost of one clock read per period.
#[inline]
pub fn past_deadline(deadline: Option<Instant>, iteration: usize) -> bool {
    match deadline {
        Some(d) => iteration % CLOCK_PERIOD == CLOCK_PERIOD - 1 && Instant::now() >= d,
        None => false,
    }
}

/// The best iterate seen by its error (allocated once, before the loop), for the families that
/// return the best iterate rather than the last one when they stop short.
pub(crate) struct BestIterate {
    r: Vec<f64>,
    error: f64,
}

impl BestIterate {
    /// Starts from `r` with its `error` (use infinity when it was not measured).
    pub fn try_new(r: &[f64], error: f64) -> Result<Self, Fc3dError> {
        Ok(BestIterate {
            r: try_copy(r, "the best iterate")?,
            error,
        })
    }

    /// Keeps `r` if its error is below the best so far.
    pub fn offer(&mut self, r: &[f64], error: f64) {
        if error < self.error {
            self.error = error;
            self.r.copy_from_slice(r);
        }
    }

    /// Writes the best iterate into `r`.
    pub fn restore(&self, r: &mut [f64]) {
        r.copy_from_slice(&self.r);
    }

    /// Writes the best iterate into `r` when it beats `current_error` (or that is not finite);
    /// returns whether it did.
    pub fn restore_if_better(&self, r: &mut [f64], current_error: f64) -> bool {
        let better = self.error < current_error || !current_error.is_finite();
        if better {
            self.restore(r);
        }
        better
    }
}

//! The outer loop of the fixed-point families (TFP, PFP, ACLMFP): an inner problem solved to an
//! inner tolerance, then the Coulomb error measured, the iterate guarded, the observer told.

use super::{IterationEvent, Observer, Run, SolverOutcome};
use crate::error::{require_setting, try_copy, Fc3dError};
use crate::matrix::BlockRows;
use crate::measure::natural_map_error_by_rows;
use crate::problem::FrictionProblem;

/// How the tolerance of an inner solve is chosen (Siconos iparam[2]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InnerTolerance {
    /// `current outer error / ratio`, floored at `tolerance / ratio` (Siconos' adaptive strategy,
    /// default ratio 10 = dparam[2]).
    Adaptive { ratio: f64 },
    /// A fixed inner tolerance (the internal solver's dparam[0]).
    Given(f64),
}

impl InnerTolerance {
    pub(crate) fn value(self, outer_error: f64, tolerance: f64) -> f64 {
        match self {
            InnerTolerance::Adaptive { ratio } => {
                (outer_error / ratio).max(tolerance / ratio).min(1e-1)
            }
            InnerTolerance::Given(t) => t,
        }
    }

    pub(crate) fn validate(self) -> Result<(), Fc3dError> {
        match self {
            InnerTolerance::Adaptive { ratio } => require_setting(
                ratio > 0.0 && ratio.is_finite(),
                "inner_tolerance.ratio",
                ratio,
                "finite and > 0",
            ),
            InnerTolerance::Given(t) => require_setting(
                t >= 0.0 && t.is_finite(),
                "inner_tolerance",
                t,
                "finite and >= 0",
            ),
        }
    }
}

/// Deadline, finite-iterate guard and observer calls of an outer fixed-point loop.
pub(crate) struct OuterLoop {
    run: Run,
    /// The last iterate known finite (allocated once).
    previous: Vec<f64>,
}

impl OuterLoop {
    pub fn new(run: Run, r: &[f64]) -> Result<Self, Fc3dError> {
        Ok(OuterLoop {
            run,
            previous: try_copy(r, "the previous iterate")?,
        })
    }

    /// Restores the previous iterate if `r` is not finite (returns false then); otherwise
    /// records `r` as the new previous iterate.
    fn accept(&mut self, r: &mut [f64]) -> bool {
        if r.iter().all(|v| v.is_finite()) {
            self.previous.copy_from_slice(r);
            true
        } else {
            r.copy_from_slice(&self.previous);
            false
        }
    }

    /// Ends outer iteration `iteration`: guards `r`, measures the Coulomb error (returned), tells
    /// the observer, and gives the outcome when the loop must stop: converged, a non-finite step
    /// (r is back to the last finite iterate), or time spent.
    pub fn end_iteration(
        &mut self,
        iteration: usize,
        problem: &FrictionProblem<'_>,
        rows: &BlockRows,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> (f64, Option<SolverOutcome>) {
        self.end_iteration_measured(iteration, r, observer, |r| {
            natural_map_error_by_rows(problem, rows, r, u)
        })
    }

    /// [`OuterLoop::end_iteration`] with the error measured by `measure` (the global
    /// problem's outer loops).
    pub fn end_iteration_measured(
        &mut self,
        iteration: usize,
        r: &mut [f64],
        observer: &mut Observer<'_>,
        measure: impl FnOnce(&[f64]) -> f64,
    ) -> (f64, Option<SolverOutcome>) {
        let finite = self.accept(r);
        let error = measure(r);
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        let converged = error <= self.run.tolerance;
        // A non-finite step stops the loop as a failure that is not out of time.
        let outcome = if !finite && !converged {
            Some(SolverOutcome::stopped(iteration, false))
        } else {
            self.run.end_of_iteration(iteration, converged)
        };
        (error, outcome)
    }

    /// The outcome of a loop that used all its iterations.
    pub fn exhausted(&self) -> SolverOutcome {
        self.run.exhausted()
    }
}

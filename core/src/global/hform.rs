//! fc3d's global method 691 (`NSGS_HFORM`): NSGS swept in the velocity form on H and a
//! block-diagonal M (the sweep: [`crate::solvers::nsgs::HFormSweeper`]), W never formed.
//!
//! The stopping test follows the NSGS schedule of the options (by default Siconos' cheap
//! increment test, confirmed by the full error) with the global error ([`global_error`]) as
//! the full error: before each measurement `v` is computed again from `r`
//! (`M v = q + H r`), so the triple measured (and returned) is consistent whatever round-off
//! the incremental updates of `v` gathered, and the sweeps go on from the exact `v`.

use crate::contract::{
    BestIterate, ErrorEvaluation, ErrorSchedule, IterationEvent, Limits, Observer, SolverOutcome,
};
use crate::error::{require_setting, Fc3dError};
use crate::matrix::HForm;
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;
use crate::solvers::nsgs::{
    Acceleration, ContactOrder, Decomposition, HFormSweeper, LocalTolerance, NsgsOptions,
};

/// The NSGS options the velocity-form sweep runs: the local solver, relaxation, the error
/// schedule, the sequential or coloured decomposition.
pub(super) fn validate(options: &NsgsOptions) -> Result<(), Fc3dError> {
    options.validate()?;
    let why = "the H-form sweep runs the sequential or coloured decomposition in natural order, \
               without freezing, acceleration, adaptive local tolerance or Dumont's criterion";
    require_setting(
        options.decomposition != Decomposition::Islands,
        "nsgs_hform.decomposition",
        format!("{:?}", options.decomposition),
        why,
    )?;
    let supported = options.order == ContactOrder::Natural
        && options.freezing.is_none_or(|k| k == 0)
        && options.acceleration == Acceleration::None
        && options.local_tolerance == LocalTolerance::Given
        && options.error_evaluation != ErrorEvaluation::DumontCriterion;
    require_setting(supported, "nsgs_hform", "these options", why)
}

/// Runs the sweep from the reaction in `r`; `u` and `v` receive the triple last measured.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &NsgsOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    // The budget covers the sweep's set-up (each contact's W_cc and M^-1 H_c: a pass over H
    // that takes seconds at 10^5 contacts on a loaded machine).
    let run = limits.start();
    let Some(mut sweeper) = HFormSweeper::new(operator, options, run.deadline())? else {
        return Ok(SolverOutcome::stopped(0, true));
    };
    let mut work = ErrorWork::new(problem.ndof());
    sweeper.set_deadline(run.deadline());
    let mut schedule = ErrorSchedule::new(
        options.error_evaluation,
        run.tolerance,
        options.evaluation_frequency,
        run.max_iter,
    );
    // Under a time budget the run may be cut at any sweep: every iterate is measured and the
    // best one returned, as NSGS does (its copy allocated once, here).
    let mut best = match run.deadline() {
        Some(_) => Some(BestIterate::try_new(r, f64::INFINITY)?),
        None => None,
    };
    operator.global_velocity(problem.q(), r, v);
    for iteration in 1..=run.max_iter {
        let increment_sq = sweeper.sweep(problem.b(), problem.mu(), r, v);
        let test = schedule.test(iteration, increment_sq, r, |_| {
            operator.global_velocity(problem.q(), r, v);
            global_error_with(problem, ContactLaw::Coulomb, r, u, v, None, &mut work)
        });
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error: test.error,
        });
        let measured = test.full.then_some(test.error);
        if let Some(b) = best.as_mut() {
            let e = match measured {
                Some(e) => e,
                None => {
                    operator.global_velocity(problem.q(), r, v);
                    global_error_with(problem, ContactLaw::Coulomb, r, u, v, None, &mut work)
                }
            };
            b.offer(r, e);
        }
        if test.stalled {
            return Ok(SolverOutcome::stopped(iteration, false).with_final_error(measured));
        }
        if let Some(outcome) = run.end_of_iteration(iteration, test.converged) {
            return Ok(if outcome.out_of_time {
                // v and u are recomputed from the iterate returned (the solve's finish).
                if let Some(b) = &best {
                    b.restore(r);
                }
                outcome
            } else {
                outcome.with_final_error(measured)
            });
        }
    }
    Ok(run.exhausted())
}

/// The velocity-form sweep of a global problem prepared once, for benchmarks and hosts that
/// drive their own loop (the solver is [`GlobalMethod::HForm`](super::GlobalMethod::HForm)).
pub struct HFormSweep {
    operator: HForm,
    sweeper: HFormSweeper,
}

impl HFormSweep {
    /// M factored, the contacts' data and (for a coloured decomposition) the colouring
    /// prepared; `options` as [`GlobalMethod::HForm`](super::GlobalMethod::HForm) takes them.
    pub fn new(problem: &GlobalProblem<'_>, options: &NsgsOptions) -> Result<Self, Fc3dError> {
        validate(options)?;
        let operator = problem.operator()?;
        let sweeper = HFormSweeper::new(&operator, options, None)?
            .ok_or_else(|| Fc3dError::Unsupported("no deadline: always prepared".into()))?;
        Ok(HFormSweep { operator, sweeper })
    }

    /// `v = M^-1 (q + H r)`: the velocity a sweep starts from.
    pub fn global_velocity(&mut self, problem: &GlobalProblem<'_>, r: &[f64], v: &mut [f64]) {
        self.operator.global_velocity(problem.q(), r, v);
    }

    /// One sweep, `r` and `v` updated in place (`v` must be `M^-1 (q + H r)`); returns the
    /// squared increment of r.
    pub fn sweep(&mut self, problem: &GlobalProblem<'_>, r: &mut [f64], v: &mut [f64]) -> f64 {
        self.sweeper.sweep(problem.b(), problem.mu(), r, v)
    }

    /// Bytes a sweep reads of the contacts' own data (indices, `H_c^T`, `M^-1 H_c`, `W_cc`),
    /// and bytes of v it reads and writes.
    pub fn bytes_per_sweep(&self) -> (usize, usize) {
        self.sweeper.contacts().bytes_per_sweep()
    }

    /// `(colours, units)` of a coloured sweep.
    pub fn colouring(&self) -> Option<(usize, usize)> {
        self.sweeper.colouring_size()
    }

    /// Contact c's diagonal block `W_cc = H_c^T M^-1 H_c` (rows).
    pub fn diagonal(&self, c: usize) -> [[f64; 3]; 3] {
        *self.sweeper.contacts().diagonal(c)
    }
}

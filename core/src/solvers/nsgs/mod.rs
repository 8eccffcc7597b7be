//! Nonsmooth Gauss-Seidel (NSGS, Algorithm 7): sweep over contacts, solve each one-contact problem
//! FC(W_cc, q_c + sum_{b != c} W_cb r_b, mu_c) with the chosen local solver, and write its
//! reaction back (relaxed by omega when asked) before moving to the next contact.
//!
//! Sweep options, all off by default: over-relaxation (PSOR), shuffled contact order, freezing of
//! contacts that stopped moving, adaptive local tolerance, a stopping test every k sweeps, and
//! Dumont's criterion (37) as the stopping test. A frictionless contact (mu = 0) is solved as the
//! scalar problem it is: `r_N = max(0, -q_N / W_NN)`, `r_T = 0`, from the normal row only.

mod anderson;
mod coloured;
mod hform;
mod islands;
mod parallel;
mod settings;
mod step;
mod sweeper;

pub(crate) use coloured::Colouring;
pub(crate) use hform::HFormSweeper;
pub use parallel::{resolve_threads, NUM_THREADS_ENV};
pub use settings::{
    Acceleration, ContactOrder, Decomposition, F32Sweeps, LocalTolerance, NsgsOptions,
    DEFAULT_F32_SWITCH_ERROR,
};
pub use step::{update_contact, ContactStep, LocalStep};
pub use sweeper::{GaussSeidel, SweepOptions, Sweeper};

use crate::contract::{
    BestIterate, ErrorEvaluation, ErrorSchedule, Family, IterationEvent, Limits, Measure, Observer,
    SolverOutcome,
};
use crate::error::Fc3dError;
use crate::measure::SweptProblem;
use crate::problem::FrictionProblem;

/// History of the `NSGS-AA` presets (measured on generated piles, docs/scale.md).
pub const DEFAULT_ANDERSON_MEMORY: usize = 5;

impl Family for NsgsOptions {
    /// Siconos' NSGS first (the default of id 500), then the parallel decompositions, each also
    /// with the full error (133) tested after every sweep (`-FULL`: on problems where Siconos'
    /// cheap increment test stops far later than the error passes the tolerance).
    fn presets() -> Vec<Self> {
        let mut presets = Vec::new();
        for error_evaluation in [ErrorEvaluation::LightWithFullFinal, ErrorEvaluation::Full] {
            for decomposition in [
                Decomposition::Sequential,
                Decomposition::Coloured,
                Decomposition::Islands,
            ] {
                presets.push(NsgsOptions {
                    decomposition,
                    error_evaluation,
                    ..Default::default()
                });
            }
        }
        // Anderson-accelerated sweeps (full error every sweep: the cheap increment test means
        // little once points are extrapolated).
        for decomposition in [Decomposition::Sequential, Decomposition::Coloured] {
            presets.push(NsgsOptions {
                decomposition,
                error_evaluation: ErrorEvaluation::Full,
                acceleration: Acceleration::Anderson {
                    memory: DEFAULT_ANDERSON_MEMORY,
                },
                ..Default::default()
            });
        }
        presets
    }

    fn name(&self) -> &'static str {
        let full = self.error_evaluation == ErrorEvaluation::Full;
        if let Acceleration::Anderson { .. } = self.acceleration {
            return match self.decomposition {
                Decomposition::Coloured => "NSGS-COLOURED-AA",
                _ => "NSGS-AA",
            };
        }
        match (self.decomposition, full) {
            (Decomposition::Sequential, false) => "NSGS",
            (Decomposition::Coloured, false) => "NSGS-COLOURED",
            (Decomposition::Islands, false) => "NSGS-ISLANDS",
            (Decomposition::Sequential, true) => "NSGS-FULL",
            (Decomposition::Coloured, true) => "NSGS-COLOURED-FULL",
            (Decomposition::Islands, true) => "NSGS-ISLANDS-FULL",
        }
    }

    fn label(&self) -> String {
        format!("{}/{}", self.name(), self.local.kind.siconos_id())
    }

    fn siconos_id(&self) -> i32 {
        500
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 1000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        NsgsOptions::validate(self)
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        nsgs(problem, self, limits, r, u, observer)
    }
}

/// Runs NSGS from the reaction in `r`. `u` is used as work space; the caller recomputes
/// `u = W r + q` and the final error.
pub(crate) fn nsgs(
    problem: &FrictionProblem<'_>,
    options: &NsgsOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    // Everything that can fail happens before r is touched (the options are checked below).
    let rows = problem.w().block_rows()?;
    let prepared = PreparedSweep {
        rows,
        colouring: None,
    };
    nsgs_on_rows(problem, options, limits, prepared, r, u, observer).0
}

/// [`Delassus::check_finite`](crate::matrix::Delassus::check_finite) on the threads an NSGS run
/// with `options` sweeps on (one for the sequential sweep): the blocks cut in one range per
/// thread, the first failing range's error returned, so the block named does not depend on the
/// thread count. A check before the run that reads all of W once costs about what a
/// multithreaded sweep costs only when it is shared out too.
pub(crate) fn check_finite_on_threads(
    w: &crate::matrix::Delassus<'_>,
    options: &NsgsOptions,
) -> Result<(), Fc3dError> {
    let threads = match options.decomposition {
        Decomposition::Sequential => 1,
        Decomposition::Coloured | Decomposition::Islands => resolve_threads(options.threads),
    };
    let Some(pool) = parallel::Pool::shared(threads)? else {
        return w.check_finite();
    };
    let parts = pool.threads();
    let results: Vec<std::sync::Mutex<Result<(), Fc3dError>>> =
        (0..parts).map(|_| std::sync::Mutex::new(Ok(()))).collect();
    pool.broadcast(&|part| {
        let result = w.check_finite_part(part, parts);
        *results[part].lock().unwrap_or_else(|e| e.into_inner()) = result;
    });
    results
        .into_iter()
        .map(|m| m.into_inner().unwrap_or_else(|e| e.into_inner()))
        .collect()
}

/// What a Gauss-Seidel run prepares from W's block pattern and a workspace keeps from one time
/// step to the next while the pattern holds: the block rows and, once a coloured sweep ran, its
/// colouring.
pub(crate) struct PreparedSweep<'a> {
    pub rows: crate::matrix::BlockRows<'a>,
    pub colouring: Option<Colouring>,
}

/// [`nsgs`] over block rows of `problem`'s W prepared earlier (with the colouring of their
/// pattern, when known): they are moved into the sweeper and handed back with the outcome, so
/// that a workspace keeps them for the next step.
pub(crate) fn nsgs_on_rows<'a>(
    problem: &FrictionProblem<'a>,
    options: &NsgsOptions,
    limits: &Limits,
    prepared: PreparedSweep<'a>,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> (Result<SolverOutcome, Fc3dError>, Option<PreparedSweep<'a>>) {
    if let Err(e) = options.validate() {
        return (Err(e), Some(prepared));
    }
    let PreparedSweep { rows, colouring } = prepared;
    // A colouring this run does not use is handed back as it came.
    let (colouring, unused) = if options.decomposition == Decomposition::Coloured {
        (colouring, None)
    } else {
        (None, colouring)
    };
    let mut sweeper = match Sweeper::with_rows(rows, options, limits.tolerance, colouring) {
        Ok(s) => s,
        Err(e) => return (Err(e), None),
    };
    let schedule = SweepSchedule {
        error_evaluation: options.error_evaluation,
        evaluation_frequency: options.evaluation_frequency,
        local_tolerance: options.local_tolerance,
        stop_when_stalled: true,
        acceleration: options.acceleration,
    };
    let outcome = if options.decomposition == Decomposition::Islands {
        islands::run_islands(problem, &mut sweeper, options, limits, r, u, observer)
    } else {
        run_sweeps(problem, &mut sweeper, &schedule, limits, r, u, observer)
    };
    let (rows, colouring) = sweeper.into_prepared();
    let colouring = colouring.or(unused);
    (outcome, Some(PreparedSweep { rows, colouring }))
}

/// How a Gauss-Seidel run tests for convergence and tunes its local tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SweepSchedule {
    pub error_evaluation: ErrorEvaluation,
    pub evaluation_frequency: usize,
    pub local_tolerance: LocalTolerance,
    /// Stop when a light-with-full-final test finds the cheap tolerance driven to 0 (the sweep
    /// left r unchanged while the full error is above the tolerance): Siconos' 3D NSGS does,
    /// its 2D NSGS sweeps on.
    pub stop_when_stalled: bool,
    /// Acceleration across sweeps.
    pub acceleration: Acceleration,
}

/// The Gauss-Seidel main loop over contacts of any dimension: sweep, test on the schedule,
/// adapt the local tolerance, keep the best iterate under a time budget. The prepared `sweeper`
/// has been checked, so nothing fails once `r` is touched.
pub(crate) fn run_sweeps<const D: usize, P: SweptProblem<D>, S: ContactStep<D>>(
    problem: &P,
    sweeper: &mut GaussSeidel<'_, D, S>,
    options: &SweepSchedule,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let (q, mu) = (problem.q(), problem.mu());
    let nc = problem.n_contacts().max(1) as f64;
    let run = limits.start();
    sweeper.set_deadline(run.deadline());
    let tol = run.tolerance;
    let mut schedule = ErrorSchedule::new(
        options.error_evaluation,
        tol,
        options.evaluation_frequency,
        run.max_iter,
    );
    // Under a time budget the run may be cut at any sweep: the best iterate measured is kept
    // (its copy allocated once, here).
    let mut best = match run.deadline() {
        Some(_) => Some(BestIterate::try_new(r, f64::INFINITY)?),
        None => None,
    };

    let mut anderson = match options.acceleration {
        Acceleration::None => None,
        Acceleration::Anderson { memory } => Some(anderson::Anderson::new(r.len(), memory)?),
    };

    let mut last_measured = None;
    let mut dumont = None;
    let outcome = 'run: {
        for iteration in 1..=run.max_iter {
            if let Some(a) = anderson.as_mut() {
                a.before_sweep(r);
            }
            let increment_sq = sweeper.sweep(q, mu, r);
            let test = schedule.test(iteration, increment_sq, r, |measure| match measure {
                Measure::NaturalMap => sweeper.tested_error(problem, r, u),
                Measure::DumontCriterion => {
                    let e = sweeper.dumont_criterion(problem, r, u);
                    dumont = Some(e);
                    e
                }
            });
            let (error, full) = (test.error, test.full);
            // A mixed-precision run leaving its f32 copy starts the cheap test afresh: the
            // ratio of cheap to full error learnt on f32 sweeps says nothing of f64 ones.
            let switched = test.tested && sweeper.f32_switch(&test, tol, q, r, u);
            if switched {
                schedule.restart_light();
            }
            let mut converged = test.converged;
            if converged && !full && sweeper.any_frozen() {
                // A cheap test cannot see frozen contacts (they did not move because they were not
                // visited): visit everything again before believing it.
                sweeper.thaw();
                converged = false;
            }
            if test.tested {
                match options.local_tolerance {
                    LocalTolerance::Given => {}
                    LocalTolerance::Adaptive { ratio } => {
                        sweeper.set_local_tolerance((error / ratio).max(tol / nc))
                    }
                    LocalTolerance::AdaptivePerContact { ratio } => {
                        sweeper.set_local_tolerance(error / (ratio * nc))
                    }
                }
            }
            if let Some(b) = best.as_mut() {
                // Measure every iterate so the one returned is the best seen, not merely the last
                // one measured.
                let e = if full {
                    error
                } else {
                    sweeper.natural_map_error(problem, r, u)
                };
                b.offer(r, e);
            }
            observer(&IterationEvent {
                iteration,
                reaction: r,
                error,
            });
            let measured = full.then_some(error);
            if test.tested {
                last_measured = measured;
            }
            if options.stop_when_stalled && test.stalled && !switched && !sweeper.any_frozen() {
                break 'run SolverOutcome::stopped(iteration, false).with_final_error(measured);
            }
            if let Some(outcome) = run.end_of_iteration(iteration, converged) {
                break 'run if outcome.out_of_time {
                    if let Some(b) = &best {
                        // b holds the best measured iterate, the current one included.
                        b.restore(r);
                    }
                    outcome
                } else {
                    outcome.with_final_error(measured)
                };
            }
            if let Some(a) = anderson.as_mut().filter(|_| iteration < run.max_iter) {
                // Only now, with r tested and the run going on: the next sweep may start from an
                // extrapolated point. Not after the last sweep: the run returns the iterate it
                // measured, not an extrapolation nobody measured.
                a.after_sweep(r);
            }
        }
        run.exhausted().with_final_error(last_measured)
    };
    // The final error of a run whose last iterate was not measured is left to the solve's
    // single-threaded measurement, except for a coloured sweep: its threads measure it, as they
    // measure its tests (the same bits for any number of threads).
    let outcome = match outcome.final_error {
        None if sweeper.is_coloured() => {
            let error = sweeper.tested_error(problem, r, u);
            outcome.with_final_error(Some(error))
        }
        _ => outcome,
    };
    Ok(SolverOutcome {
        dumont_criterion: dumont,
        f32_sweeps: sweeper.f32_sweeps(),
        ..outcome
    })
}

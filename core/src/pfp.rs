//! Panagiotopoulos alternating fixed point (PFP, Siconos id 522, Algorithm 10 of
//! Acary-Brémond-Huber): a two-block Gauss-Seidel between
//! * the normal problem (128) for frozen tangent reactions, the LCP
//!   `0 <= W_NN r_N + q_N + W_NT r_T ⟂ r_N >= 0`, solved by projected Gauss-Seidel (PGS), and
//! * the tangent problem (130) for the new normal reactions, the Tresca problem on the disks of
//!   radius `mu_c r_N,c`, solved by FP-VI-UPK, projected gradient (Algorithm 9) or Gauss-Seidel
//!   (see [`TrescaInnerSolver`]),
//!
//! until the Coulomb natural-map error is below the tolerance.

use std::time::Duration;

use crate::error::Fc3dError;
use crate::matrix::BlockRows;
use crate::measure::cheap_error;
use crate::problem::FrictionProblem;
use crate::solver::{IterationEvent, SolverOutcome};
use crate::tresca::{
    coulomb_error, InnerTolerance, OuterLoop, TrescaInnerSolver, TrescaMode, TrescaWorkspace,
};

/// Options of the Panagiotopoulos fixed point (PFP, Siconos id 522).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PfpOptions {
    /// Maximum outer (normal + tangent) iterations (default 1000, iparam[0]).
    pub max_iter: usize,
    /// Tolerance on the Coulomb natural-map error (default 1e-4, dparam[0]).
    pub tolerance: f64,
    /// Solver of the tangent (Tresca-on-disks) problem (default FP-VI-UPK).
    pub tangent: TrescaInnerSolver,
    /// Maximum iterations of each inner solve, PGS sweeps or tangent iterations (default 1000).
    pub inner_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
    /// Wall-clock budget (default none): stop after the current outer iteration when spent.
    pub time_budget: Option<Duration>,
}

impl Default for PfpOptions {
    fn default() -> Self {
        PfpOptions {
            max_iter: 1000,
            tolerance: 1e-4,
            tangent: TrescaInnerSolver::FixedPointViUpk,
            inner_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
            time_budget: None,
        }
    }
}

/// Projected Gauss-Seidel on the normal LCP with the tangent reactions frozen; returns the sweeps
/// done. Contacts with `W_NN <= 0` keep their normal reaction (no pivot).
pub(crate) fn normal_pgs(
    rows: &BlockRows,
    q: &[f64],
    tol: f64,
    max_iter: usize,
    r: &mut [f64],
) -> usize {
    for it in 1..=max_iter {
        let mut increment_sq = 0.0;
        for c in 0..rows.n_contacts() {
            let w = rows.diagonal(c);
            if w[0][0].is_nan() || w[0][0] <= 0.0 {
                continue;
            }
            let lq = rows.local_q(c, q, r);
            let s = 3 * c;
            let un = lq[0] + w[0][0] * r[s] + w[0][1] * r[s + 1] + w[0][2] * r[s + 2];
            let new = (r[s] - un / w[0][0]).max(0.0);
            if new.is_finite() {
                increment_sq += (new - r[s]).powi(2);
                r[s] = new;
            }
        }
        if cheap_error(increment_sq, r) <= tol {
            return it;
        }
    }
    max_iter
}

/// Runs PFP from the reaction in `r`. `u` is work space.
pub(crate) fn pfp(
    problem: &FrictionProblem<'_>,
    options: &PfpOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolverOutcome, Fc3dError> {
    options.inner_tolerance.validate()?;
    let mut work = TrescaWorkspace::new(problem)?;
    let (q, mu) = (problem.q(), problem.mu());
    let tol = options.tolerance;
    let mut outer = OuterLoop::new(options.time_budget, r);
    let mut error = coulomb_error(problem, &work.rows, r, u);
    for iteration in 1..=options.max_iter {
        let inner_tol = options.inner_tolerance.value(error, tol);
        normal_pgs(&work.rows, q, inner_tol, options.inner_max_iter, r);
        for (c, radius) in work.radius.iter_mut().enumerate() {
            *radius = mu[c] * r[3 * c];
        }
        work.solve(
            options.tangent,
            TrescaMode::TangentOnly,
            q,
            inner_tol,
            options.inner_max_iter,
            r,
        );
        let (e, stop) = outer.end_iteration(iteration, problem, &work.rows, r, u, tol, observer);
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome);
        }
    }
    Ok(OuterLoop::iterations_exhausted(options.max_iter))
}

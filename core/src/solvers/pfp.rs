//! Panagiotopoulos alternating fixed point (PFP, Siconos id 522, Algorithm 10 of
//! Acary-Brémond-Huber): a two-block Gauss-Seidel between
//! * the normal problem (128) for frozen tangent reactions, the LCP
//!   `0 <= W_NN r_N + q_N + W_NT r_T ⟂ r_N >= 0`, solved by projected Gauss-Seidel (PGS), and
//! * the tangent problem (130) for the new normal reactions, the Tresca problem on the disks of
//!   radius `mu_c r_N,c`, solved by FP-VI-UPK, projected gradient (Algorithm 9) or Gauss-Seidel
//!   (see [`TrescaInnerSolver`]),
//!
//! until the Coulomb natural-map error is below the tolerance.

use std::time::Instant;

use crate::contract::{
    deadline_passed, Family, InnerTolerance, Limits, Observer, OuterLoop, SolverOutcome,
};
use crate::error::Fc3dError;
use crate::matrix::BlockRows;
use crate::measure::{cheap_error, natural_map_error_by_rows};
use crate::problem::FrictionProblem;
use crate::solvers::tresca::subproblem::{TrescaMode, TrescaWorkspace};
use crate::solvers::tresca::TrescaInnerSolver;

/// Settings of the Panagiotopoulos fixed point (PFP, Siconos id 522). Its limits default to 1000
/// outer (normal + tangent) iterations and a tolerance of 1e-4 on the Coulomb error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PfpOptions {
    /// Solver of the tangent (Tresca-on-disks) problem (default FP-VI-UPK).
    pub tangent: TrescaInnerSolver,
    /// Maximum iterations of each tangent solve (default 1000; Siconos' tangent internal solver,
    /// `internalSolvers[1]`, iparam[0]).
    pub inner_max_iter: usize,
    /// Maximum PGS sweeps of each normal solve (default 1000; Siconos' normal internal solver,
    /// `internalSolvers[0]`, iparam[0]).
    pub normal_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
}

impl Default for PfpOptions {
    fn default() -> Self {
        PfpOptions {
            tangent: TrescaInnerSolver::FixedPointViUpk,
            inner_max_iter: 1000,
            normal_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
        }
    }
}

impl Family for PfpOptions {
    fn name(&self) -> &'static str {
        "PFP"
    }

    fn label(&self) -> String {
        format!("PFP/{}", self.tangent.siconos_id())
    }

    fn siconos_id(&self) -> i32 {
        522
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 1000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        self.inner_tolerance.validate()
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        pfp(problem, self, limits, r, u, observer)
    }
}

/// Projected Gauss-Seidel on the normal LCP with the tangent reactions frozen; returns the sweeps
/// done. Contacts with `W_NN <= 0` keep their normal reaction (no pivot).
pub(crate) fn normal_pgs(
    rows: &BlockRows,
    q: &[f64],
    tol: f64,
    max_iter: usize,
    deadline: Option<Instant>,
    r: &mut [f64],
) -> usize {
    for it in 1..=max_iter {
        if deadline_passed(deadline) {
            return it - 1;
        }
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
fn pfp(
    problem: &FrictionProblem<'_>,
    options: &PfpOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.inner_tolerance.validate()?;
    let mut work = TrescaWorkspace::new(problem)?;
    let (q, mu) = (problem.q(), problem.mu());
    let run = limits.start();
    work.deadline = run.deadline();
    let tol = run.tolerance;
    let mut outer = OuterLoop::new(run, r)?;
    let mut error = natural_map_error_by_rows(problem, &work.rows, r, u);
    for iteration in 1..=run.max_iter {
        let inner_tol = options.inner_tolerance.value(error, tol);
        normal_pgs(
            &work.rows,
            q,
            inner_tol,
            options.normal_max_iter,
            run.deadline(),
            r,
        );
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
        let (e, stop) = outer.end_iteration(iteration, problem, &work.rows, r, u, observer);
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome);
        }
    }
    Ok(outer.exhausted())
}

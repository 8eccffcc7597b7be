//! The ACLM fixed point (ACLMFP, Siconos id 516, Algorithm 12 of Acary-Brémond-Huber): the shift
//! `s_c = (mu_c ||u_T,c||, 0, 0)` of the current velocity, then the SOCLCP
//! `K* ∋ W r + q + s ⟂ r ∈ K` with that `s`, until the Coulomb error is below the tolerance. At a
//! fixed point `W r + q + s` is De Saxcé's modified velocity. The SOCLCP is solved by the
//! Gauss-Seidel sweep of [`crate::solvers::soclcp`].

use crate::contract::{Family, InnerTolerance, Limits, Observer, OuterLoop, SolverOutcome};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::norm2;
use crate::measure::{cheap_error, natural_map_error_by_rows};
use crate::problem::FrictionProblem;
use crate::solvers::soclcp::soclcp_sweep;

/// Settings of the ACLM fixed point (Siconos id 516). Its limits default to 1000 outer (threshold
/// update) iterations and a tolerance of 1e-4 on the Coulomb error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AclmOptions {
    /// Maximum Gauss-Seidel sweeps of each inner SOCLCP solve (default 1000).
    pub inner_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
}

impl Default for AclmOptions {
    fn default() -> Self {
        AclmOptions {
            inner_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
        }
    }
}

impl Family for AclmOptions {
    fn name(&self) -> &'static str {
        "ACLMFP"
    }

    fn label(&self) -> String {
        "ACLMFP".to_string()
    }

    fn siconos_id(&self) -> i32 {
        516
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
        aclmfp(problem, self, limits, r, u, observer)
    }
}

/// Runs ACLMFP from the reaction in `r`; `u` is work space.
fn aclmfp(
    problem: &FrictionProblem<'_>,
    options: &AclmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.inner_tolerance.validate()?;
    let rows = problem.w().block_rows()?;
    let (q, mu) = (problem.q(), problem.mu());
    let run = limits.start();
    let tol = run.tolerance;
    let mut shift = try_vec(rows.n_contacts(), 0.0, "the ACLM shifts")?;
    let mut outer = OuterLoop::new(run, r)?;
    let mut error = natural_map_error_by_rows(problem, &rows, r, u);
    for iteration in 1..=run.max_iter {
        // u = W r + q is current here (coulomb_error computed it).
        for (c, s) in shift.iter_mut().enumerate() {
            *s = mu[c] * norm2(u[3 * c + 1], u[3 * c + 2]);
        }
        let inner_tol = options.inner_tolerance.value(error, tol);
        for _ in 0..options.inner_max_iter {
            if run.out_of_time() {
                break;
            }
            let increment_sq = soclcp_sweep(&rows, q, mu, Some(&shift), 1.0, r);
            if cheap_error(increment_sq, r) <= inner_tol {
                break;
            }
        }
        let (e, stop) = outer.end_iteration(iteration, problem, &rows, r, u, observer);
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome);
        }
    }
    Ok(outer.exhausted())
}

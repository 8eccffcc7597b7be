//! Siconos' `GFC3D_NSGS` (id 605), which despite its name is a projected Jacobi iteration on
//! the reaction with the global velocity solved exactly at every step:
//!
//! `v = M^-1 (q + H r)`, `u = H^T v + b`, then for every contact at once
//! `r_c <- P_K(r_c - rho (u_c + mu_c ||u_{T,c}|| e_N))` (Siconos: `rho = 1`).
//!
//! It converges when `rho` is small against W (a unit step needs `||W|| < 2` roughly): on a
//! badly scaled M it does not, as in Siconos. The error is measured on the triple of the current
//! reaction (`v` and `u` computed from it) before the step, so that the triple returned is
//! consistent (`M v = q + H r`) and its error is the one tested; Siconos measures the new
//! reaction against the previous velocity and returns that velocity.

use crate::contract::{IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::{require_setting, Fc3dError};
use crate::math::cone::{modified_velocity, project_on_cone};
use crate::matrix::HForm;
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;

/// Settings of the projected Jacobi iteration (605).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JacobiOptions {
    /// Step of the projection (Siconos: 1; > 0).
    pub step: f64,
    /// The global error is measured every this many iterations (Siconos' `iparam[8]`; 1 =
    /// every iteration, the default; >= 1).
    pub error_frequency: usize,
}

impl Default for JacobiOptions {
    fn default() -> Self {
        JacobiOptions {
            step: 1.0,
            error_frequency: 1,
        }
    }
}

impl JacobiOptions {
    pub fn validate(&self) -> Result<(), Fc3dError> {
        require_setting(
            self.step > 0.0 && self.step.is_finite(),
            "global_jacobi.step",
            self.step,
            "finite and > 0",
        )?;
        require_setting(
            self.error_frequency >= 1,
            "global_jacobi.error_frequency",
            self.error_frequency,
            ">= 1",
        )
    }
}

/// Runs the iteration from the reaction in `r`.
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &JacobiOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let run = limits.start();
    let mut work = ErrorWork::new(problem.ndof());
    let mu = problem.mu();
    for iteration in 1..=run.max_iter {
        operator.global_velocity(problem.q(), r, v);
        let measured = iteration % options.error_frequency == 0;
        if measured {
            // Sets u = H^T v + b.
            let error = global_error_with(problem, ContactLaw::Coulomb, r, u, v, None, &mut work);
            observer(&IterationEvent {
                iteration,
                reaction: r,
                error,
            });
            if error <= run.tolerance {
                return Ok(SolverOutcome::stopped(iteration, false).with_final_error(Some(error)));
            }
            if !error.is_finite() {
                return Ok(SolverOutcome::diverged(iteration));
            }
        } else {
            u.copy_from_slice(problem.b());
            operator.ht_mul_add(v, u);
        }
        for (c, &m) in mu.iter().enumerate() {
            let uc = modified_velocity(&[u[3 * c], u[3 * c + 1], u[3 * c + 2]], m);
            let rc = &mut r[3 * c..3 * c + 3];
            let p = project_on_cone(
                &[
                    rc[0] - options.step * uc[0],
                    rc[1] - options.step * uc[1],
                    rc[2] - options.step * uc[2],
                ],
                m,
            );
            rc.copy_from_slice(&p);
        }
        if let Some(outcome) = run.end_of_iteration(iteration, false) {
            return Ok(outcome);
        }
    }
    Ok(run.exhausted())
}

//! Siconos' `GFC3D_ACLMFP` (id 612): the fixed point of Acary-Cadoux-Lemaréchal-Malick on De
//! Saxcé's term. Each outer iteration freezes `s_c = (mu_c ||u_{T,c}||, 0, 0)` at the current
//! velocity and solves the convex problem
//!
//! `min v^T M v / 2 - q^T v`  subject to  `H^T v + b + s ∈ K*`
//!
//! (its multiplier is the reaction) to an inner tolerance, by the global ADMM with s held
//! fixed (Siconos: its convex-QP ADMM, id 1203, on the same splitting); the factorization of
//! `M + rho H H^T` and rho are kept from one outer iteration to the next. The outer error is
//! the global error of the consistent triple of the reaction.

use crate::contract::{InnerTolerance, Limits, Observer, OuterLoop, SolverOutcome};
use crate::error::{require_setting, Fc3dError};
use crate::math::linalg::norm2;
use crate::matrix::HForm;
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;
use crate::solvers::admm::{AdmmOptions, AdmmRhoStrategy};

use super::admm::{GlobalAdmm, GlobalAdmmOptions};
use super::rescaling::GlobalRescaling;

/// Settings of ACLMFP (612), Siconos 4.4's defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobalAclmOptions {
    /// The inner tolerance (Siconos: adaptive, the outer error over `dparam[2] = 2`).
    pub inner_tolerance: InnerTolerance,
    /// ADMM iterations per inner solve (Siconos' internal solver 1203: 1000).
    pub inner_max_iter: usize,
    /// The inner ADMM (Siconos 1203's defaults: rho 1, residual balancing, accelerated with
    /// restart, eta 0.999, tau 2, phi 10); its De Saxcé term is the outer loop's.
    pub inner: AdmmOptions,
}

impl Default for GlobalAclmOptions {
    fn default() -> Self {
        GlobalAclmOptions {
            inner_tolerance: InnerTolerance::Adaptive { ratio: 2.0 },
            inner_max_iter: 1000,
            inner: AdmmOptions {
                rho: 1.0,
                rho_strategy: AdmmRhoStrategy::ResidualBalancing,
                balancing_phi: 10.0,
                ..AdmmOptions::default()
            },
        }
    }
}

impl GlobalAclmOptions {
    pub fn validate(&self) -> Result<(), Fc3dError> {
        self.inner_tolerance.validate()?;
        self.inner.validate()?;
        require_setting(
            self.inner_max_iter >= 1,
            "global_aclm.inner_max_iter",
            self.inner_max_iter,
            ">= 1",
        )
    }
}

/// Runs ACLMFP from the reaction in `r`.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &GlobalAclmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let run = limits.start();
    let inner_options = GlobalAdmmOptions {
        admm: options.inner,
        update_s: false,
        error_frequency: 1,
        rescaling: GlobalRescaling::None,
    };
    let Some(mut admm) = GlobalAdmm::new(problem, operator, &options.inner, run.deadline())? else {
        // Out of time before the set-up or the first factorization: r as it came.
        return Ok(SolverOutcome::stopped(0, true));
    };
    let mut work = ErrorWork::new(problem.ndof());
    let mut shift = vec![0.0; problem.size()];
    let mut outer = OuterLoop::new(run, r)?;
    operator.global_velocity(problem.q(), r, v);
    let mut error = global_error_with(problem, ContactLaw::Coulomb, r, u, v, None, &mut work);
    for iteration in 1..=run.max_iter {
        // u = H^T v + b of the current reaction (the error computed it).
        for (c, &mu) in problem.mu().iter().enumerate() {
            shift[3 * c] = mu * norm2(u[3 * c + 1], u[3 * c + 2]);
        }
        let inner_run = run.inner(
            options.inner_tolerance.value(error, run.tolerance),
            options.inner_max_iter,
        );
        admm.run(
            problem,
            operator,
            &inner_options,
            &inner_run,
            Some(&shift),
            r,
            u,
            v,
            &mut |_| {},
        )?;
        let (e, stop) = outer.end_iteration_measured(iteration, r, observer, |r| {
            operator.global_velocity(problem.q(), r, v);
            global_error_with(problem, ContactLaw::Coulomb, r, u, v, None, &mut work)
        });
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome.with_final_error(Some(error)));
        }
    }
    Ok(outer.exhausted().with_final_error(Some(error)))
}

//! The convex relaxation of the frictional contact problem and the fixed point built on it
//! (section 7.3-7.4 of Acary-Brémond-Huber):
//!
//! * SOCLCP (Siconos id 517): `K* ∋ W r + q + s ⟂ r ∈ K` with `s = 0`, the problem without the
//!   De Saxcé term `mu ||u_T||` (an associated friction law: sliding lifts the contact). Its
//!   solution is a Coulomb solution only when every contact sticks or separates, so the solver
//!   reports `SolveStatus::RelaxationNotCoulomb` when the relaxed problem converged but the
//!   Coulomb error (the one reported) is above the tolerance.
//!
//! The SOCLCP is solved by Gauss-Seidel over contacts with an exact one-contact SOCLCP solver
//! ([`solve_local_soclcp`]); the ACLM fixed point (`aclm`) solves its sub-problems with the same
//! sweep.

mod local;

pub use local::solve_local_soclcp;

use crate::contract::{
    ErrorEvaluation, ErrorSchedule, Family, IterationEvent, Limits, Observer, SolverOutcome,
};
use crate::error::{require_setting, Fc3dError};
use crate::math::cone::project_on_cone;
use crate::math::linalg::norm;
use crate::matrix::BlockRows;
use crate::problem::FrictionProblem;
use local::local_soclcp_projection;

/// Settings of the SOCLCP relaxation solved on its own (Siconos id 517). Its limits default to 1000
/// Gauss-Seidel sweeps and a tolerance of 1e-4, on the SOCLCP natural-map error for the relaxed
/// convergence test and on the Coulomb error for `Converged`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoclcpOptions {
    /// Over-relaxation of the Gauss-Seidel update, in (0, 2) (default 1, dparam[8]).
    pub relaxation: f64,
}

impl Default for SoclcpOptions {
    fn default() -> Self {
        SoclcpOptions { relaxation: 1.0 }
    }
}

impl SoclcpOptions {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        let w = self.relaxation;
        require_setting(w > 0.0 && w < 2.0, "soclcp.relaxation", w, "in (0, 2)")
    }
}

impl Family for SoclcpOptions {
    fn name(&self) -> &'static str {
        "SOCLCP"
    }

    fn label(&self) -> String {
        "SOCLCP".to_string()
    }

    fn siconos_id(&self) -> i32 {
        517
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 1000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        SoclcpOptions::validate(self)
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        soclcp(problem, self, limits, r, u, observer)
    }
}

/// One Gauss-Seidel sweep of `K* ∋ W r + q + shift ⟂ r ∈ K`, where `shift_c` is added to the
/// normal component of contact c; returns `sum_c ||r_c^new - r_c^old||^2`.
pub(crate) fn soclcp_sweep(
    rows: &BlockRows,
    q: &[f64],
    mu: &[f64],
    shift: Option<&[f64]>,
    omega: f64,
    r: &mut [f64],
) -> f64 {
    let mut increment_sq = 0.0;
    for c in 0..rows.n_contacts() {
        let mut lq = rows.local_q(c, q, r);
        if let Some(s) = shift {
            lq[0] += s[c];
        }
        let w = &rows.diagonal(c);
        let old = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
        let hint = (old[1] != 0.0 || old[2] != 0.0).then(|| old[2].atan2(old[1]));
        let mut new = solve_local_soclcp(w, &lq, mu[c], hint)
            .unwrap_or_else(|| local_soclcp_projection(w, &lq, mu[c], &old));
        if omega != 1.0 {
            new = project_on_cone(
                &[
                    omega * new[0] + (1.0 - omega) * old[0],
                    omega * new[1] + (1.0 - omega) * old[1],
                    omega * new[2] + (1.0 - omega) * old[2],
                ],
                mu[c],
            );
        }
        if !new.iter().all(|v| v.is_finite()) {
            new = old;
        }
        increment_sq +=
            (new[0] - old[0]).powi(2) + (new[1] - old[1]).powi(2) + (new[2] - old[2]).powi(2);
        r[3 * c..3 * c + 3].copy_from_slice(&new);
    }
    increment_sq
}

/// Relative natural-map error of the SOCLCP, `sqrt(sum_c ||r_c - P_K(r_c - u_c)||^2) /
/// max(||q||, ||r||, ||u||)` with `u = W r + q` (no De Saxcé term); `u` is overwritten.
pub(crate) fn soclcp_error(
    rows: &BlockRows,
    q: &[f64],
    mu: &[f64],
    r: &[f64],
    u: &mut [f64],
) -> f64 {
    rows.velocity(q, r, u);
    let mut sum = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        let s = 3 * c;
        let x = [r[s] - u[s], r[s + 1] - u[s + 1], r[s + 2] - u[s + 2]];
        let p = project_on_cone(&x, m);
        sum += (r[s] - p[0]).powi(2) + (r[s + 1] - p[1]).powi(2) + (r[s + 2] - p[2]).powi(2);
    }
    let scale = norm(q).max(norm(r)).max(norm(u));
    sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// Runs the SOCLCP solver from the reaction in `r`; `u` is work space. The outcome says whether
/// the relaxed problem converged (its own error below the tolerance).
fn soclcp(
    problem: &FrictionProblem<'_>,
    options: &SoclcpOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let rows = problem.w().block_rows()?;
    let (q, mu) = (problem.q(), problem.mu());
    let run = limits.start();
    // The cheap increment error each sweep, confirmed by the relaxed problem's own natural-map
    // error (Siconos' light-with-full-final schedule).
    let mut schedule = ErrorSchedule::new(
        ErrorEvaluation::LightWithFullFinal,
        run.tolerance,
        1,
        run.max_iter,
    );
    for iteration in 1..=run.max_iter {
        let increment_sq = soclcp_sweep(&rows, q, mu, None, options.relaxation, r);
        let test = schedule.test(iteration, increment_sq, r, |_| {
            soclcp_error(&rows, q, mu, r, u)
        });
        let (error, relaxed_converged) = (test.error, test.converged);
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        if let Some(outcome) = run.end_of_iteration(iteration, relaxed_converged) {
            return Ok(SolverOutcome {
                relaxation_converged: relaxed_converged,
                ..outcome
            });
        }
    }
    Ok(run.exhausted())
}

//! Nonsmooth Gauss-Seidel (NSGS, Algorithm 7 with omega = 1): sweep over contacts, solve each
//! one-contact problem FC(W_cc, q_c + sum_{b != c} W_cb r_b, mu_c) with the chosen local solver,
//! and write its reaction back before moving to the next contact.

use crate::error::Fc3dError;
use crate::local::{AnyLocalSolver, LocalProblem, LocalSolver};
use crate::measure::{cheap_error, natural_map_error};
use crate::options::{ErrorEvaluation, NsgsOptions};
use crate::problem::FrictionProblem;
use crate::solver::IterationEvent;

/// Runs NSGS from the reaction in `r`. Returns the number of sweeps done. `u` is used as work
/// space; the caller recomputes `u = W r + q` and the final error.
pub(crate) fn nsgs(
    problem: &FrictionProblem<'_>,
    options: &NsgsOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<usize, Fc3dError> {
    // Everything that can fail happens before r is touched.
    let rows = problem.w().block_rows()?;
    let mut local = AnyLocalSolver::new(&options.local);
    let (q, mu) = (problem.q(), problem.mu());
    let tol = options.tolerance;
    let mut light_tol = tol;

    for iteration in 1..=options.max_iter {
        let increment_sq = sweep(&rows, q, mu, &mut local, r);

        let (error, converged) = match options.error_evaluation {
            ErrorEvaluation::Full => {
                let e = natural_map_error(problem, r, u);
                (e, e <= tol)
            }
            ErrorEvaluation::Light => {
                let e = cheap_error(increment_sq, r);
                (e, e <= tol)
            }
            ErrorEvaluation::LightWithFullFinal => {
                let light = cheap_error(increment_sq, r);
                if light <= light_tol {
                    let full = natural_map_error(problem, r, u);
                    if full <= tol {
                        (full, true)
                    } else {
                        // Assume full/light stays roughly proportional and ask the cheap error
                        // for what the full one still lacks.
                        light_tol = light * tol / full;
                        (full, false)
                    }
                } else {
                    (light, false)
                }
            }
        };
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        if converged {
            return Ok(iteration);
        }
    }
    Ok(options.max_iter)
}

/// One Gauss-Seidel sweep in contact order; returns `sum_c ||r_c^new - r_c^old||^2`.
/// A local solution that is not finite is discarded (the contact keeps its previous reaction).
fn sweep(
    rows: &crate::matrix::BlockRows,
    q: &[f64],
    mu: &[f64],
    local: &mut AnyLocalSolver,
    r: &mut [f64],
) -> f64 {
    let mut increment_sq = 0.0;
    for c in 0..rows.n_contacts() {
        let p = LocalProblem {
            w: rows.diagonal(c),
            q: rows.local_q(c, q, r),
            mu: mu[c],
        };
        let old = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
        let mut rc = old;
        local.solve(&p, &mut rc);
        if !rc.iter().all(|v| v.is_finite()) {
            rc = old;
        }
        let d = [rc[0] - old[0], rc[1] - old[1], rc[2] - old[2]];
        increment_sq += d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        r[3 * c..3 * c + 3].copy_from_slice(&rc);
    }
    increment_sq
}

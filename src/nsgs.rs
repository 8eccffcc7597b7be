//! Nonsmooth Gauss-Seidel (NSGS, Algorithm 7 with omega = 1): sweep over contacts, solve each
//! one-contact problem FC(W_cc, q_c + sum_{b != c} W_cb r_b, mu_c) with the chosen local solver,
//! and write its reaction back before moving to the next contact.

use std::time::Instant;

use crate::error::Fc3dError;
use crate::local::{AnyLocalSolver, LocalProblem, LocalSolver};
use crate::matrix::BlockRows;
use crate::measure::{cheap_error, natural_map_error};
use crate::options::{ErrorEvaluation, NsgsOptions};
use crate::problem::FrictionProblem;
use crate::solver::{IterationEvent, SolverOutcome};

/// The best iterate by full natural-map error, kept only when a time budget may cut the run
/// short (the copy is allocated once, before the loop).
struct BestIterate {
    r: Vec<f64>,
    error: f64,
}

/// One Gauss-Seidel sweep's state, prepared once per problem: the block-row view of W and the
/// local solver. Public so that benchmarks and hosts that drive their own loop can sweep
/// without re-preparing; a sweep allocates nothing.
pub struct Sweeper {
    rows: BlockRows,
    local: AnyLocalSolver,
    /// Each contact's penalty parameters for the local solver (they depend on W_cc only).
    rho: Vec<(f64, f64)>,
}

impl Sweeper {
    pub fn new(
        problem: &FrictionProblem<'_>,
        local: &crate::options::LocalSolverOptions,
    ) -> Result<Self, Fc3dError> {
        let rows = problem.w().block_rows()?;
        let local = AnyLocalSolver::new(local);
        let rho = (0..rows.n_contacts())
            .map(|c| local.rho(rows.diagonal(c)))
            .collect();
        Ok(Sweeper { rows, local, rho })
    }

    /// One sweep over all contacts in order, updating `r` in place; returns
    /// `sum_c ||r_c^new - r_c^old||^2`.
    pub fn sweep(&mut self, q: &[f64], mu: &[f64], r: &mut [f64]) -> f64 {
        sweep(&self.rows, &self.rho, q, mu, &mut self.local, r)
    }

    /// The relative natural-map error of `r`, with `u = W r + q` computed through the prepared
    /// blocks (cheaper than the host's storage when W is dense but sparsely coupled).
    pub fn natural_map_error(
        &self,
        problem: &FrictionProblem<'_>,
        r: &[f64],
        u: &mut [f64],
    ) -> f64 {
        self.rows.velocity(problem.q(), r, u);
        crate::measure::natural_map_error_of(problem, r, u)
    }
}

/// Runs NSGS from the reaction in `r`. `u` is used as work space; the caller recomputes
/// `u = W r + q` and the final error.
pub(crate) fn nsgs(
    problem: &FrictionProblem<'_>,
    options: &NsgsOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolverOutcome, Fc3dError> {
    // Everything that can fail happens before r is touched.
    let mut sweeper = Sweeper::new(problem, &options.local)?;
    let (q, mu) = (problem.q(), problem.mu());
    let tol = options.tolerance;
    let mut light_tol = tol;
    let deadline = options.time_budget.map(|b| Instant::now() + b);
    let mut best = deadline.map(|_| BestIterate {
        r: r.to_vec(),
        error: f64::INFINITY,
    });

    let mut last_measured = None;
    for iteration in 1..=options.max_iter {
        let increment_sq = sweeper.sweep(q, mu, r);

        // (error tested this sweep, whether it is the full error, converged)
        let (error, full, converged) = match options.error_evaluation {
            ErrorEvaluation::Full => {
                let e = natural_map_error(problem, r, u);
                (e, true, e <= tol)
            }
            ErrorEvaluation::Light => {
                let e = cheap_error(increment_sq, r);
                (e, false, e <= tol)
            }
            ErrorEvaluation::LightWithFullFinal => {
                let light = cheap_error(increment_sq, r);
                if light <= light_tol {
                    let full = natural_map_error(problem, r, u);
                    if full > tol {
                        // Assume full/light stays roughly proportional and ask the cheap error
                        // for what the full one still lacks.
                        light_tol = light * tol / full;
                    }
                    (full, true, full <= tol)
                } else {
                    (light, false, false)
                }
            }
        };
        if let Some(b) = best.as_mut() {
            // Under a time budget the run may be cut at any sweep: measure every iterate so the
            // one returned is the best seen, not merely the last one measured.
            let e = if full {
                error
            } else {
                sweeper.natural_map_error(problem, r, u)
            };
            if e < b.error {
                b.error = e;
                b.r.copy_from_slice(r);
            }
        }
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        let measured = full.then_some(error);
        last_measured = measured;
        if converged {
            return Ok(SolverOutcome {
                iterations: iteration,
                out_of_time: false,
                final_error: measured,
            });
        }
        if deadline.is_some_and(|d| Instant::now() >= d) {
            if let Some(b) = best {
                // b holds the best measured iterate, the current one included.
                r.copy_from_slice(&b.r);
            }
            return Ok(SolverOutcome {
                iterations: iteration,
                out_of_time: true,
                final_error: None,
            });
        }
    }
    Ok(SolverOutcome {
        iterations: options.max_iter,
        out_of_time: false,
        final_error: last_measured,
    })
}

/// One Gauss-Seidel sweep in contact order; returns `sum_c ||r_c^new - r_c^old||^2`.
/// A local solution that is not finite is discarded (the contact keeps its previous reaction).
fn sweep(
    rows: &BlockRows,
    rho: &[(f64, f64)],
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
        local.solve_with_rho(&p, rho[c], &mut rc);
        if !rc.iter().all(|v| v.is_finite()) {
            rc = old;
        }
        let d = [rc[0] - old[0], rc[1] - old[1], rc[2] - old[2]];
        increment_sq += d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        r[3 * c..3 * c + 3].copy_from_slice(&rc);
    }
    increment_sq
}

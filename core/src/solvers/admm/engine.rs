//! The ADMM iteration shared by the local formulation (split `r = z`, `z ∈ K`) and the global
//! one (split `H^T v + b_s = z`, `z ∈ K*`): with a primal step giving the split image `a`,
//!
//! * `a = A x` with `x` from the linear step at `(ẑ, ξ̂)` (the splitting's own system);
//! * `z = P(a + ξ̂)`;
//! * `ξ = ξ̂ + a - z`;
//!
//! the primal residual `||a - z||`, the dual residual `rho ||B (z - ẑ)||`, Nesterov's
//! extrapolation with restart (Goldstein-O'Donoghue-Setzer-Baraniuk) and residual balancing of
//! rho (Boyd et al. §3.4.1) are the same for both; a [`Splitting`] supplies the rest.

use std::time::Instant;

use super::settings::{AdmmAcceleration, AdmmOptions, AdmmRhoStrategy};
use crate::contract::{Observer, Run, SolverOutcome};
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::math::linalg::norm;

/// What an ADMM formulation supplies to [`iterate`].
pub(crate) trait Splitting {
    /// Size of the split variable z (and of a, ξ).
    fn split_size(&self) -> usize;
    /// Whether a factorization for a new rho, started now, is predicted to end by `deadline`.
    fn factor_ends_by(&self, deadline: Option<Instant>) -> bool;
    /// Factors the linear step's matrix for `rho`; false when it is singular.
    fn factor(&mut self, rho: f64) -> bool;
    /// The linear step at `(ẑ, ξ̂)`: solves for the primal unknown and writes its split image
    /// into `a`; false when the result is not bounded (diverging, or the factors lost all
    /// accuracy), the previous iterate then kept.
    fn linear_step(&mut self, rho: f64, z_hat: &[f64], xi_hat: &[f64], a: &mut [f64]) -> bool;
    /// `z = P(w)`, the projection on the split variable's set.
    fn project(&self, w: &[f64], z: &mut [f64]);
    /// `||B (z - ẑ)||` (the dual residual is rho times it).
    fn dual_residual(&mut self, z: &[f64], z_hat: &[f64]) -> f64;
    /// The scales of the scaled residual balancing: the primal one (from a and z) and
    /// `||B ξ||`.
    fn balancing_scales(&mut self, a: &[f64], z: &[f64], xi: &[f64]) -> (f64, f64);
    /// After the updates of an iteration: the error of the current iterate when it is
    /// measured this iteration (and the observer called), `None` otherwise. `residuals` are the
    /// primal and dual residuals of the iteration.
    fn measure(
        &mut self,
        iteration: usize,
        rho: f64,
        xi: &[f64],
        residuals: (f64, f64),
        observer: &mut Observer<'_>,
    ) -> Option<f64>;
}

/// Work vectors of [`iterate`], allocated once.
struct Vectors {
    a: Vec<f64>,
    z: Vec<f64>,
    xi: Vec<f64>,
    z_prev: Vec<f64>,
    xi_prev: Vec<f64>,
    z_hat: Vec<f64>,
    xi_hat: Vec<f64>,
    w: Vec<f64>,
}

/// Runs ADMM from `(ẑ, ξ̂) = (z0, xi0)` with the splitting factored for `rho` (its work
/// arrays allocated fallibly, before the loop). `scale` divides
/// the dual residual (Siconos' scalar rescaling of the local formulation; 1 otherwise).
#[allow(clippy::too_many_arguments)]
pub(crate) fn iterate<S: Splitting>(
    splitting: &mut S,
    options: &AdmmOptions,
    run: &Run,
    mut rho: f64,
    scale: f64,
    z0: &[f64],
    xi0: &[f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let n = splitting.split_size();
    let what = "the ADMM work arrays";
    let mut v = Vectors {
        a: try_vec(n, 0.0, what)?,
        z: try_vec(n, 0.0, what)?,
        xi: try_vec(n, 0.0, what)?,
        z_prev: try_copy(z0, what)?,
        xi_prev: try_copy(xi0, what)?,
        z_hat: try_copy(z0, what)?,
        xi_hat: try_copy(xi0, what)?,
        w: try_vec(n, 0.0, what)?,
    };
    let mut alpha = 1.0_f64;
    let mut combined_prev = f64::INFINITY;

    for iteration in 1..=run.max_iter {
        if !splitting.linear_step(rho, &v.z_hat, &v.xi_hat, &mut v.a) {
            return Ok(SolverOutcome::diverged(iteration));
        }
        // z- and dual updates.
        for i in 0..n {
            v.w[i] = v.a[i] + v.xi_hat[i];
        }
        splitting.project(&v.w, &mut v.z);
        for i in 0..n {
            v.xi[i] = v.xi_hat[i] + v.a[i] - v.z[i];
        }
        let primal = crate::math::linalg::distance_sq(&v.a, &v.z).sqrt();
        let dual = rho / scale * splitting.dual_residual(&v.z, &v.z_hat);
        let error = splitting.measure(iteration, rho, &v.xi, (primal, dual), observer);
        let converged = error.is_some_and(|e| e <= run.tolerance);
        if let Some(outcome) = run.end_of_iteration(iteration, converged) {
            return Ok(outcome);
        }

        // Next extrapolation point.
        let combined = primal * primal + dual * dual;
        match options.acceleration {
            AdmmAcceleration::None => {
                v.z_hat.copy_from_slice(&v.z);
                v.xi_hat.copy_from_slice(&v.xi);
            }
            AdmmAcceleration::Accelerated if combined < options.restart_eta * combined_prev => {
                let alpha_next = 0.5 * (1.0 + (1.0 + 4.0 * alpha * alpha).sqrt());
                let beta = (alpha - 1.0) / alpha_next;
                for i in 0..n {
                    v.z_hat[i] = v.z[i] + beta * (v.z[i] - v.z_prev[i]);
                    v.xi_hat[i] = v.xi[i] + beta * (v.xi[i] - v.xi_prev[i]);
                }
                alpha = alpha_next;
                combined_prev = combined;
            }
            AdmmAcceleration::Accelerated => {
                // Restart from the previous iterate.
                alpha = 1.0;
                v.z_hat.copy_from_slice(&v.z_prev);
                v.xi_hat.copy_from_slice(&v.xi_prev);
                combined_prev /= options.restart_eta;
            }
        }
        v.z_prev.copy_from_slice(&v.z);
        v.xi_prev.copy_from_slice(&v.xi);

        // Penalty update (residual balancing); the scaled dual follows rho so that rho ξ is kept.
        let (p, d) = match options.rho_strategy {
            AdmmRhoStrategy::Constant => continue,
            AdmmRhoStrategy::ResidualBalancing => (primal, dual),
            AdmmRhoStrategy::ScaledResidualBalancing => {
                let (scale_p, xi_norm) = splitting.balancing_scales(&v.a, &v.z, &v.xi);
                let scale_d = rho / scale * xi_norm;
                (
                    if scale_p > 0.0 {
                        primal / scale_p
                    } else {
                        primal
                    },
                    if scale_d > 0.0 { dual / scale_d } else { dual },
                )
            }
        };
        let factor = if p > options.balancing_phi * d {
            options.balancing_tau
        } else if d > options.balancing_phi * p {
            1.0 / options.balancing_tau
        } else {
            continue;
        };
        let new_rho = rho * factor;
        if !(new_rho.is_finite() && new_rho > 0.0 && splitting.factor_ends_by(run.deadline())) {
            // Keep the current factorization (valid for rho).
            continue;
        }
        if !splitting.factor(new_rho) {
            splitting.factor(rho);
            continue;
        }
        rho = new_rho;
        // Siconos rescales the scaled duals and keeps the extrapolation and its momentum.
        for x in [&mut v.xi, &mut v.xi_hat, &mut v.xi_prev] {
            x.iter_mut().for_each(|e| *e /= factor);
        }
    }
    Ok(run.exhausted())
}

/// `max(||a||, ||z||)`: the primal scale of the local formulation.
pub(crate) fn primal_scale(a: &[f64], z: &[f64]) -> f64 {
    norm(a).max(norm(z))
}

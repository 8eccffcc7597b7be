//! Variants of the projection local solvers: proximal regularization (554), diagonal metric
//! (555), the cone step computed in velocity space (558) and iterated cylinder steps (564).

use super::{local_rho, LocalOutcome, LocalProblem, LocalSolver};
use crate::cone::{modified_velocity, project_on_cone, project_on_cylinder, project_on_dual_cone};
use crate::linalg::{norm3, sub3, Mat3, Vec3};
use crate::options::{LocalSolverOptions, RhoRule};

/// `1 / W_NN` with the degenerate-block fallback of [`local_rho`].
#[inline]
fn inverse_normal(w: &Mat3) -> f64 {
    local_rho(w, RhoRule::SplitSpectralNorm).0
}

/// Moves a one-step solver to `next`; converged when the step left `r` unchanged, or when
/// the step is not finite (then `r` is kept).
#[inline]
fn take_step(r: &mut Vec3, next: Vec3) -> LocalOutcome {
    if !next.iter().all(|x| x.is_finite()) {
        return LocalOutcome {
            converged: false,
            iterations: 1,
        };
    }
    let converged = next == *r;
    *r = next;
    LocalOutcome {
        converged,
        iterations: 1,
    }
}

/// [554] One step of the proximal point iteration on the contact: the problem with
/// `w + eps I` and `q - eps r_old` has, at `r_old`, the same velocity as the original one, so
/// its 552 step is `r <- P_K(r - ũ(r) / (W_NN + eps))`: the regularization shortens the step.
pub struct ProjectionOnConeWithRegularization {
    regularization: f64,
}

impl ProjectionOnConeWithRegularization {
    pub fn new(options: &LocalSolverOptions) -> Self {
        ProjectionOnConeWithRegularization {
            regularization: options.regularization,
        }
    }
}

impl LocalSolver for ProjectionOnConeWithRegularization {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        let rho = 1.0 / (1.0 / inverse_normal(w) + self.regularization);
        (rho, rho)
    }

    #[inline]
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let rho = rho.0;
        let ut = modified_velocity(&p.velocity(r), p.mu);
        let next = project_on_cone(
            &[r[0] - rho * ut[0], r[1] - rho * ut[1], r[2] - rho * ut[2]],
            p.mu,
        );
        take_step(r, next)
    }
}

/// [555] One separated step with the diagonal of `w` as metric:
/// `r_N <- (r_N - u_N / W_NN)_+` (the exact normal solve with `r_T` frozen), then
/// `r_T <- P_{B(0, mu r_N)}(r_T - u_T ./ (W_T1T1, W_T2T2))`. The normal and tangential
/// projection is separate from the normal one, so the normal fixed point is exact; the
/// tangential one is `D u_T ∥ -r_T` with `D = diag(1/W_T1T1, 1/W_T2T2)`, the Coulomb law only
/// when `W_T1T1 = W_T2T2`: otherwise NSGS stalls at a non-zero error (Siconos 4.4 stalls at the
/// same error, e.g. 1.955e-2 on FrictionContact3D_RR_1c). This is Siconos' step, kept as such.
pub struct ProjectionOnConeWithDiagonalization;

impl LocalSolver for ProjectionOnConeWithDiagonalization {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        (inverse_normal(w), 1.0)
    }

    #[inline]
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let u = p.velocity(r);
        let step = |d: f64| {
            if d > 0.0 && d.is_finite() {
                1.0 / d
            } else {
                rho.0
            }
        };
        let tau = [
            r[0] - rho.0 * u[0],
            r[1] - step(p.w[1][1]) * u[1],
            r[2] - step(p.w[2][2]) * u[2],
        ];
        take_step(r, project_on_cylinder(&tau, p.mu * tau[0].max(0.0)))
    }
}

/// [558] The cone step of 552 written in velocity space: by Moreau's decomposition
/// `x = P_K(x) - P_{K*}(-x)`, `P_K(r - rho ũ) = r - rho ũ + P_{K*}(rho ũ - r)`. Same fixed
/// points and, up to rounding, the same iterates as 552; the velocity-side projection is the
/// one used when the dual (velocity) variable is the primary unknown.
pub struct ProjectionOnConeVelocity;

impl LocalSolver for ProjectionOnConeVelocity {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        let rho = inverse_normal(w);
        (rho, rho)
    }

    #[inline]
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let rho = rho.0;
        let ut = modified_velocity(&p.velocity(r), p.mu);
        let y = [rho * ut[0] - r[0], rho * ut[1] - r[1], rho * ut[2] - r[2]];
        let py = project_on_dual_cone(&y, p.mu);
        let mut next = [py[0] - y[0], py[1] - y[1], py[2] - y[2]];
        // Rounding in the difference can leave the result a hair outside K.
        next = project_on_cone(&next, p.mu);
        take_step(r, next)
    }
}

/// [564] Augmented-Lagrangian (557) steps until the natural-map residual is below the local
/// tolerance, with the self-adaptive rho of 553 (shrink by `NU` when
/// `rho ||u(r+) - u(r)|| > L ||r+ - r||`, grow when below `LMIN`). Its fixed points are those of
/// the Jean-Moreau function (58), i.e. the Coulomb law.
pub struct ProjectionOnCylinderWithLocalIteration {
    tolerance: f64,
    max_iter: usize,
}

const NU: f64 = 2.0 / 3.0;
const L: f64 = 0.9;
const LMIN: f64 = 0.3;

impl ProjectionOnCylinderWithLocalIteration {
    pub fn new(options: &LocalSolverOptions) -> Self {
        ProjectionOnCylinderWithLocalIteration {
            tolerance: options.tolerance,
            max_iter: options.max_iter,
        }
    }
}

#[inline]
fn cylinder_step(r: &Vec3, u: &Vec3, rho: f64, mu: f64) -> Vec3 {
    let tau = [r[0] - rho * u[0], r[1] - rho * u[1], r[2] - rho * u[2]];
    project_on_cylinder(&tau, mu * tau[0].max(0.0))
}

impl LocalSolver for ProjectionOnCylinderWithLocalIteration {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        let rho = inverse_normal(w);
        (rho, rho)
    }

    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let mut rho = rho.0;
        let mut u = p.velocity(r);
        for it in 0..self.max_iter {
            let next = cylinder_step(r, &u, rho, p.mu);
            let step = norm3(&sub3(&next, r));
            if step == 0.0 || !step.is_finite() {
                return LocalOutcome {
                    converged: step == 0.0,
                    iterations: it,
                };
            }
            let u_next = p.velocity(&next);
            let ratio = rho * norm3(&sub3(&u_next, &u)) / step;
            if ratio > L && rho > f64::MIN_POSITIVE {
                rho *= NU;
                continue;
            }
            *r = next;
            u = u_next;
            if ratio < LMIN {
                rho /= NU;
            }
            if p.residual(r) <= self.tolerance * p.scale(r) {
                return LocalOutcome {
                    converged: true,
                    iterations: it + 1,
                };
            }
        }
        LocalOutcome {
            converged: p.residual(r) <= self.tolerance * p.scale(r),
            iterations: self.max_iter,
        }
    }
}

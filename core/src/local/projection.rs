//! Projection-type local solvers: one step on the cone (SBP / FP-DS-One), iterated steps with a
//! self-adaptive rho, and one augmented-Lagrangian step on the cylinder (SAL).

use super::{local_rho, LocalOutcome, LocalProblem, LocalSolver};
use crate::cone::{modified_velocity, project_on_cone, project_on_cylinder};
use crate::linalg::{norm3, sub3, Mat3, Vec3};
use crate::options::{LocalSolverOptions, RhoRule};

/// `rho = 1 / W_NN` for every component (with the degenerate-block fallback of [`local_rho`]).
#[inline]
fn normal_rho(w: &Mat3) -> (f64, f64) {
    let rho = local_rho(w, RhoRule::SplitSpectralNorm).0;
    (rho, rho)
}

/// One step `r <- P_K(r - rho ũ(r))`, with ũ the De Saxcé velocity.
#[inline]
fn cone_step(p: &LocalProblem<'_>, r: &Vec3, rho: f64) -> Vec3 {
    let ut = modified_velocity(&p.velocity(r), p.mu);
    project_on_cone(
        &[r[0] - rho * ut[0], r[1] - rho * ut[1], r[2] - rho * ut[2]],
        p.mu,
    )
}

/// Moves a one-step solver to `next`; it has converged when the step left `r` unchanged.
#[inline]
fn take_step(r: &mut Vec3, next: Vec3) -> LocalOutcome {
    let converged = next == *r;
    *r = next;
    LocalOutcome {
        converged,
        iterations: 1,
    }
}

/// [552] Dumont's SBP: a single projection step on the Coulomb cone along the De Saxcé
/// direction, rho = 1 / W_NN. Reports convergence when the step left r unchanged.
pub struct ProjectionOnCone;

impl LocalSolver for ProjectionOnCone {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        normal_rho(w)
    }

    #[inline]
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        take_step(r, cone_step(p, r, rho.0))
    }
}

/// [557] Dumont's SAL: one augmented-Lagrangian step,
/// `r_N <- (r_N - rho u_N)_+`, `r_T <- P_{B(0, mu r_N)}(r_T - rho u_T)` with the new `r_N`.
pub struct ProjectionOnCylinder;

impl LocalSolver for ProjectionOnCylinder {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        normal_rho(w)
    }

    #[inline]
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let rho = rho.0;
        let u = p.velocity(r);
        let tau = [r[0] - rho * u[0], r[1] - rho * u[1], r[2] - rho * u[2]];
        take_step(r, project_on_cylinder(&tau, p.mu * tau[0].max(0.0)))
    }
}

/// [553] Projection steps on the cone until the natural-map residual of the contact is below
/// the local tolerance, with a self-adaptive rho (the UPK-type rule of the VI solvers:
/// shrink by `NU` when `rho ||ũ(r+) - ũ(r)|| > L ||r+ - r||`, grow when below `LMIN`).
pub struct ProjectionOnConeWithLocalIteration {
    tolerance: f64,
    max_iter: usize,
}

const NU: f64 = 2.0 / 3.0;
const L: f64 = 0.9;
const LMIN: f64 = 0.3;

impl ProjectionOnConeWithLocalIteration {
    pub fn new(options: &LocalSolverOptions) -> Self {
        ProjectionOnConeWithLocalIteration {
            tolerance: options.tolerance,
            max_iter: options.max_iter,
        }
    }
}

impl LocalSolver for ProjectionOnConeWithLocalIteration {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        normal_rho(w)
    }

    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let mut rho = rho.0;
        let mut ut = modified_velocity(&p.velocity(r), p.mu);
        for it in 0..self.max_iter {
            let next = project_on_cone(
                &[r[0] - rho * ut[0], r[1] - rho * ut[1], r[2] - rho * ut[2]],
                p.mu,
            );
            let step = norm3(&sub3(&next, r));
            if step == 0.0 {
                return LocalOutcome {
                    converged: true,
                    iterations: it,
                };
            }
            let ut_next = modified_velocity(&p.velocity(&next), p.mu);
            let ratio = rho * norm3(&sub3(&ut_next, &ut)) / step;
            if ratio > L && rho > f64::MIN_POSITIVE {
                rho *= NU;
                continue;
            }
            *r = next;
            ut = ut_next;
            if ratio < LMIN {
                rho /= NU;
            }
            let res = {
                let pr = project_on_cone(&[r[0] - ut[0], r[1] - ut[1], r[2] - ut[2]], p.mu);
                norm3(&sub3(r, &pr))
            };
            if res <= self.tolerance * p.scale(r) {
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

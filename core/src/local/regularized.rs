//! Variants of the projection local solvers: proximal regularization (554), diagonal metric
//! (555), the cone step computed in velocity space (558) and iterated cylinder steps (564).

use std::time::Instant;

use super::adaptive::self_adaptive_projection;
use super::adaptive::ProjectionStep;
use super::projection::{ConeStep, CylinderStep};
use super::{local_rho, take_step, LocalOutcome, LocalProblem, LocalSolver};
use crate::local::{LocalSolverOptions, RhoRule};
use crate::math::cone::{
    modified_velocity, project_on_cone, project_on_cylinder, project_on_dual_cone,
};
use crate::math::linalg::{Mat3, Vec3};

/// `1 / W_NN` with the degenerate-block fallback of [`local_rho`].
#[inline]
fn inverse_normal(w: &Mat3) -> f64 {
    local_rho(w, RhoRule::SplitSpectralNorm).0
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
        take_step(r, ConeStep.step(p, r, &ConeStep.field(p, r), rho.0))
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

impl ProjectionOnConeWithDiagonalization {
    pub fn new(_: &LocalSolverOptions) -> Self {
        ProjectionOnConeWithDiagonalization
    }
}

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

impl ProjectionOnConeVelocity {
    pub fn new(_: &LocalSolverOptions) -> Self {
        ProjectionOnConeVelocity
    }
}

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
/// tolerance, with the self-adaptive rho of [`super::adaptive`] from `1 / W_NN`. Its fixed points
/// are those of the Jean-Moreau function (58), i.e. the Coulomb law.
pub struct ProjectionOnCylinderWithLocalIteration {
    tolerance: f64,
    max_iter: usize,
    deadline: Option<Instant>,
}

impl ProjectionOnCylinderWithLocalIteration {
    pub fn new(options: &LocalSolverOptions) -> Self {
        ProjectionOnCylinderWithLocalIteration {
            tolerance: options.tolerance,
            max_iter: options.max_iter,
            deadline: None,
        }
    }
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
        self_adaptive_projection(
            &CylinderStep,
            p,
            rho.0,
            self.tolerance,
            self.max_iter,
            self.deadline,
            r,
        )
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
    }
}

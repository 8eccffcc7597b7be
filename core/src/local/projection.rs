//! Projection-type local solvers: one step on the cone (SBP / FP-DS-One), iterated steps with a
//! self-adaptive rho, and one augmented-Lagrangian step on the cylinder (SAL).

use std::time::Instant;

use super::adaptive::{self_adaptive_projection, siconos_cone_iteration, ProjectionStep};
use super::{local_rho, take_step, LocalOutcome, LocalProblem, LocalSolver};
use crate::local::{AlgorithmVariant, LocalSolverOptions, RhoRule};
use crate::math::cone::{modified_velocity, project_on_cone, project_on_cylinder};
use crate::math::linalg::{norm3, sub3, Mat3, Vec3};

/// `rho = 1 / W_NN` for every component (with the degenerate-block fallback of [`local_rho`]).
#[inline]
pub(super) fn normal_rho(w: &Mat3) -> (f64, f64) {
    let rho = local_rho(w, RhoRule::SplitSpectralNorm).0;
    (rho, rho)
}

/// Steps on the Coulomb cone along the De Saxcé velocity ũ: `P_K(r - rho ũ(r))`.
pub(super) struct ConeStep;

impl ProjectionStep for ConeStep {
    #[inline]
    fn field(&self, p: &LocalProblem<'_>, r: &Vec3) -> Vec3 {
        modified_velocity(&p.velocity(r), p.mu)
    }

    #[inline]
    fn step(&self, p: &LocalProblem<'_>, r: &Vec3, ut: &Vec3, rho: f64) -> Vec3 {
        project_on_cone(
            &[r[0] - rho * ut[0], r[1] - rho * ut[1], r[2] - rho * ut[2]],
            p.mu,
        )
    }

    #[inline]
    fn residual(&self, p: &LocalProblem<'_>, r: &Vec3, ut: &Vec3) -> f64 {
        norm3(&sub3(r, &self.step(p, r, ut, 1.0)))
    }
}

/// Augmented-Lagrangian steps on the cylinder `R+ x B(0, mu r_N)` along the velocity:
/// `r_N <- (r_N - rho u_N)_+`, `r_T <- P_{B(0, mu r_N)}(r_T - rho u_T)` with the new `r_N`.
pub(super) struct CylinderStep;

impl ProjectionStep for CylinderStep {
    #[inline]
    fn field(&self, p: &LocalProblem<'_>, r: &Vec3) -> Vec3 {
        p.velocity(r)
    }

    #[inline]
    fn step(&self, p: &LocalProblem<'_>, r: &Vec3, u: &Vec3, rho: f64) -> Vec3 {
        let tau = [r[0] - rho * u[0], r[1] - rho * u[1], r[2] - rho * u[2]];
        project_on_cylinder(&tau, p.mu * tau[0].max(0.0))
    }

    #[inline]
    fn residual(&self, p: &LocalProblem<'_>, r: &Vec3, u: &Vec3) -> f64 {
        crate::measure::contact_residual_sq(r, u, p.mu).sqrt()
    }
}

/// [552] Dumont's SBP: a single projection step on the Coulomb cone along the De Saxcé
/// direction, rho = 1 / W_NN. Reports convergence when the step left r unchanged.
pub struct ProjectionOnCone;

impl ProjectionOnCone {
    pub fn new(_: &LocalSolverOptions) -> Self {
        ProjectionOnCone
    }
}

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
        take_step(r, ConeStep.step(p, r, &ConeStep.field(p, r), rho.0))
    }
}

/// [557] Dumont's SAL: one augmented-Lagrangian step ([`CylinderStep`]).
pub struct ProjectionOnCylinder;

impl ProjectionOnCylinder {
    pub fn new(_: &LocalSolverOptions) -> Self {
        ProjectionOnCylinder
    }
}

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
        take_step(r, CylinderStep.step(p, r, &CylinderStep.field(p, r), rho.0))
    }
}

/// [553] Projection steps on the cone until the local error is below the local tolerance.
/// [`AlgorithmVariant::Siconos`] (default): Siconos 4.4's iteration
/// ([`siconos_cone_iteration`]), whose step length each contact keeps from one sweep to the
/// next. [`AlgorithmVariant::Fc3d`]: the self-adaptive rho of [`super::adaptive`] from `1 / W_NN`
/// at every solve, to a relative residual.
pub struct ProjectionOnConeWithLocalIteration {
    tolerance: f64,
    max_iter: usize,
    variant: AlgorithmVariant,
    deadline: Option<Instant>,
}

impl ProjectionOnConeWithLocalIteration {
    pub fn new(options: &LocalSolverOptions) -> Self {
        ProjectionOnConeWithLocalIteration {
            tolerance: options.tolerance,
            max_iter: options.max_iter,
            variant: options.variant,
            deadline: None,
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
        let mut step = 1.0;
        self.solve_in_sweep(p, rho, &mut step, r)
    }

    fn solve_in_sweep(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        step: &mut f64,
        r: &mut Vec3,
    ) -> LocalOutcome {
        match self.variant {
            AlgorithmVariant::Siconos => {
                siconos_cone_iteration(p, step, self.tolerance, self.max_iter, self.deadline, r)
            }
            AlgorithmVariant::Fc3d => self_adaptive_projection(
                &ConeStep,
                p,
                rho.0,
                self.tolerance,
                self.max_iter,
                self.deadline,
                r,
            ),
        }
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
    }
}

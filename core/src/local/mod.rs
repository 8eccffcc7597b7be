//! One-contact solvers: FC(w, q, mu) with a 3x3 `w`, behind one trait so that the Gauss-Seidel
//! sweep does not know which one it drives; and the exact 2x2 solve of a 2D contact (`planar`).

mod adaptive;
pub(crate) mod dumont;
mod fischer_burmeister;
mod newton;
mod planar;
mod projection;
mod quartic;
mod registry;
mod regularized;
pub mod rolling;
mod settings;
mod vi_upk;

pub use dumont::EnhancedBipotential;
pub use fischer_burmeister::{fischer_burmeister_function, FischerBurmeisterNewton};
pub use newton::{alart_curnier_function, jean_moreau_function, AlartCurnierNewton};
pub use planar::{solve_planar_contact, PlanarBranch, PlanarSolution};
pub use projection::{ProjectionOnCone, ProjectionOnConeWithLocalIteration, ProjectionOnCylinder};
pub use quartic::Quartic;
pub use registry::{AnyLocalSolver, LocalSolverKind};
pub use regularized::{
    ProjectionOnConeVelocity, ProjectionOnConeWithDiagonalization,
    ProjectionOnConeWithRegularization, ProjectionOnCylinderWithLocalIteration,
};
pub use settings::{AlgorithmVariant, LocalSolverOptions, NewtonFormulation, RhoRule};
pub use vi_upk::FpViUpk;

use crate::math::linalg::{lambda_max_sym2, lambda_min_sym2, Mat3, Vec3};
use crate::measure::contact_residual_sq;

/// One contact's problem: `u = w r + q`, `K* ∋ ũ ⟂ r ∈ K(mu)`.
#[derive(Debug, Clone, Copy)]
pub struct LocalProblem<'a> {
    pub w: &'a Mat3,
    pub q: Vec3,
    pub mu: f64,
}

impl LocalProblem<'_> {
    #[inline]
    pub fn velocity(&self, r: &Vec3) -> Vec3 {
        crate::math::linalg::mat3_vec_add(self.w, r, &self.q)
    }

    /// Natural-map residual `||r - P_K(r - ũ)||` of this contact at `r`.
    #[inline]
    pub fn residual(&self, r: &Vec3) -> f64 {
        contact_residual_sq(r, &self.velocity(r), self.mu).sqrt()
    }

    /// Scale against which local residuals are compared: `max(||r||, ||q||, tiny)`.
    #[inline]
    pub fn scale(&self, r: &Vec3) -> f64 {
        crate::math::linalg::norm3(r)
            .max(crate::math::linalg::norm3(&self.q))
            .max(f64::MIN_POSITIVE)
    }
}

/// What a local solve did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalOutcome {
    pub converged: bool,
    pub iterations: usize,
}

/// A one-contact solver. `solve` starts from the value in `r` and leaves its answer there.
/// Implementations allocate nothing.
pub trait LocalSolver {
    /// The penalty parameters `(rho_N, rho_T)` this solver uses for a contact whose diagonal
    /// block is `w`. They depend on `w` only, so a sweep computes them once per contact.
    fn rho(&self, w: &Mat3) -> (f64, f64);

    /// Solves with penalty parameters `rho` obtained from [`LocalSolver::rho`] for `p.w`.
    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome;

    /// The instant after which iterating solvers stop early and return their best point
    /// (`None`: no limit). One-step solvers ignore it.
    fn set_deadline(&mut self, _deadline: Option<std::time::Instant>) {}

    /// Solves one contact of a sweep. `memory` is the contact's own state, kept by the sweep from
    /// one visit to the next and set to 1 before the first (Siconos' 553 keeps its step length
    /// there). Solvers without such state ignore it.
    #[inline]
    fn solve_in_sweep(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        _memory: &mut f64,
        r: &mut Vec3,
    ) -> LocalOutcome {
        self.solve_with_rho(p, rho, r)
    }

    /// Solves, computing rho from `p.w`.
    #[inline]
    fn solve(&mut self, p: &LocalProblem<'_>, r: &mut Vec3) -> LocalOutcome {
        let rho = self.rho(p.w);
        self.solve_with_rho(p, rho, r)
    }
}

/// Penalty parameters `(rho_N, rho_T)` of a contact from its diagonal block, by `rule`.
/// A non-positive or non-finite estimate (a degenerate block) falls back to the inverse of the
/// largest diagonal entry, or to 1 for a zero block.
pub fn local_rho(w: &Mat3, rule: RhoRule) -> (f64, f64) {
    local_rho_of_variant(w, rule, AlgorithmVariant::Fc3d)
}

/// [`local_rho`] as `variant` computes it. Siconos 4.4's split rules take the spread of the
/// tangent block from `s^2 - 4 (s - W_ST + W_TS)` with `s = W_TT + W_SS` (where the
/// eigenvalues of `W_T` would use `s^2 - 4 det W_T`): `rho_T = 2 / (s + d)` and
/// `2 (s - d) / (s + d)^2` with `d` the square root of that value (0 when negative). fc3d's
/// rules use the eigenvalues of the symmetric part of `W_T`. For the spectral rule Siconos takes
/// `W_NN` as the largest eigenvalue of a block whose upper triangle is zero.
pub fn local_rho_of_variant(w: &Mat3, rule: RhoRule, variant: AlgorithmVariant) -> (f64, f64) {
    let wnn = w[0][0];
    let siconos_spread = || {
        let s = w[1][1] + w[2][2];
        let disc = s * s - 4.0 * (s - w[2][1] + w[1][2]);
        (s, if disc > 0.0 { disc.sqrt() } else { 0.0 })
    };
    let lt_max = lambda_max_sym2(w[1][1], w[1][2], w[2][1], w[2][2]);
    let (rn, rt) = match (rule, variant) {
        (RhoRule::SplitSpectralNorm, AlgorithmVariant::Siconos) => {
            let (s, d) = siconos_spread();
            (1.0 / wnn, 2.0 / (s + d))
        }
        // Siconos takes W_NN for the largest eigenvalue of a block whose upper triangle is
        // zero.
        (RhoRule::SpectralNorm, AlgorithmVariant::Siconos)
            if w[0][1] == 0.0 && w[0][2] == 0.0 && w[1][2] == 0.0 =>
        {
            (1.0 / wnn, 1.0 / wnn)
        }
        (RhoRule::SplitSpectralNormCond, AlgorithmVariant::Siconos) => {
            let (s, d) = siconos_spread();
            (1.0 / wnn, 2.0 * (s - d) / ((s + d) * (s + d)))
        }
        (rule, _) => match rule {
            RhoRule::Constant(rho) => (rho, rho),
            RhoRule::SpectralNorm => {
                let l = lambda_max_sym3(w);
                (1.0 / l, 1.0 / l)
            }
            RhoRule::SplitSpectralNorm => (1.0 / wnn, 1.0 / lt_max),
            RhoRule::SplitSpectralNormCond => {
                let lt_min = lambda_min_sym2(w[1][1], w[1][2], w[2][1], w[2][2]);
                (1.0 / wnn, lt_min / (lt_max * lt_max))
            }
            RhoRule::Dumont(alpha) => (alpha / wnn, alpha / wnn),
        },
    };
    let fallback = {
        let d = w[0][0].abs().max(w[1][1].abs()).max(w[2][2].abs());
        if d > 0.0 && d.is_finite() {
            1.0 / d
        } else {
            1.0
        }
    };
    let fix = |x: f64| {
        if x > 0.0 && x.is_finite() {
            x
        } else {
            fallback
        }
    };
    (fix(rn), fix(rt))
}

/// Largest eigenvalue of the symmetric part of a 3x3 matrix (closed form, trigonometric).
pub fn lambda_max_sym3(w: &Mat3) -> f64 {
    let a = |i: usize, j: usize| 0.5 * (w[i][j] + w[j][i]);
    let p1 = a(0, 1).powi(2) + a(0, 2).powi(2) + a(1, 2).powi(2);
    let tr = a(0, 0) + a(1, 1) + a(2, 2);
    if p1 == 0.0 {
        return a(0, 0).max(a(1, 1)).max(a(2, 2));
    }
    let qm = tr / 3.0;
    let p2 = (a(0, 0) - qm).powi(2) + (a(1, 1) - qm).powi(2) + (a(2, 2) - qm).powi(2) + 2.0 * p1;
    let p = (p2 / 6.0).sqrt();
    let b = |i: usize, j: usize| (a(i, j) - if i == j { qm } else { 0.0 }) / p;
    let det = b(0, 0) * (b(1, 1) * b(2, 2) - b(1, 2) * b(2, 1))
        - b(0, 1) * (b(1, 0) * b(2, 2) - b(1, 2) * b(2, 0))
        + b(0, 2) * (b(1, 0) * b(2, 1) - b(1, 1) * b(2, 0));
    let phi = (det / 2.0).clamp(-1.0, 1.0).acos() / 3.0;
    qm + 2.0 * p * phi.cos()
}

/// Moves a one-step solver to `next`; converged when the step left `r` unchanged. A step that
/// is not finite leaves `r` as it was.
#[inline]
pub(crate) fn take_step(r: &mut Vec3, next: Vec3) -> LocalOutcome {
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

#[cfg(test)]
mod tests;

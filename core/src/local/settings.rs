//! Typed options of the one-contact solvers, with Siconos' defaults (the defaults that depend on
//! the solver are in its row of the registry, `registry.rs`).

use super::LocalSolverKind;
use crate::error::{require_setting, Fc3dError};

/// The nonsmooth function a local Newton solver (550, 551, 565) zeroes (Siconos iparam[10]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum NewtonFormulation {
    /// Alart-Curnier (61): disk radius `mu (r_N - rho_N u_N)_+` (Siconos' default, 0).
    #[default]
    AlartCurnier,
    /// Jean-Moreau (59), "NSN-JM" of Table 3: disk radius `mu (r_N)_+` (Siconos 1).
    JeanMoreau,
}

/// Which of two variants of the same one-contact algorithm runs (550, 551, 565 and 553; the
/// other local solvers have one variant).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum AlgorithmVariant {
    /// Siconos 4.4's algorithm, step for step (default): a contact with `q_N >= -eps` takes off
    /// at once; Newton stops when `||F||^2 / (2 ||q||) < tolerance` after a step and takes the
    /// last trial of a failed Goldstein-Price search; 565 keeps a new point only when its local
    /// error `||r - P_K(r - ũ)|| / ||q||` did not grow; 553 keeps each contact's rho from one
    /// sweep to the next (starting at 1), stops when the squared absolute residual is below the
    /// tolerance and takes the tenth trial of a failed step search.
    #[default]
    Siconos,
    /// fc3d's refinements (fc3d 0.2's behaviour): Newton stops when `||F|| <= tolerance *
    /// max(||r||, rho_N ||q||)` before a step, a failed search keeps the best decrease, 565
    /// keeps the best point of all rounds; 553 starts every solve at `rho = 1 / W_NN` and stops
    /// on the relative residual `||r - P_K(r - ũ)|| <= tolerance * max(||r||, ||q||)`.
    Fc3d,
}

/// How the penalty parameters rho (rho_N, rho_T) of a local solver are taken from the diagonal
/// block `W_cc` of the contact (section 5.4 of Acary-Brémond-Huber).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RhoRule {
    /// A fixed value for both.
    Constant(f64),
    /// (110): `rho_N = rho_T = 1 / lambda_max(W_cc)`.
    SpectralNorm,
    /// (111): `rho_N = 1 / W_NN`, `rho_T = 1 / lambda_max(W_TT)`.
    SplitSpectralNorm,
    /// (112), corrected: `rho_N = 1 / W_NN`, `rho_T = lambda_min(W_TT) / lambda_max(W_TT)^2`
    /// (the paper prints `lambda_min(W_NN)`, a scalar, which cannot measure the conditioning of W_TT).
    SplitSpectralNormCond,
    /// Dumont's rule: `rho_N = rho_T = alpha * rho_bar` with `rho_bar = 1 / W_NN`, the reduced
    /// mass `m_i m_j / (m_i + m_j)` of the two bodies at the contact when `W = H^T M^-1 H` (Dumont
    /// writes `rho_bar = m_i m_j / (m_i + m_j) / dt` for forces; impulses drop the `dt`).
    /// Dumont finds alpha in [1, 2] best for EBP.
    Dumont(f64),
}

/// Options of a local solver. Defaults per kind are Siconos 4.4's (`solver_options_create(id)`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalSolverOptions {
    pub kind: LocalSolverKind,
    /// Local tolerance on the local residual, relative to the local scale.
    pub tolerance: f64,
    /// Maximum local iterations.
    pub max_iter: usize,
    /// Rule for rho (Newton solvers; projection solvers use `1 / W_NN`).
    pub rho_rule: RhoRule,
    /// Maximum trial steps of the Goldstein-Price line search.
    pub line_search_max_iter: usize,
    /// Hybrid solver: number of (projection, Newton) rounds after the first Newton.
    pub hybrid_max_loop: usize,
    /// Hybrid solver: maximum projection iterations per round.
    pub hybrid_max_iter: usize,
    /// Newton solvers 550/551/565: which function Newton zeroes (default Alart-Curnier).
    pub formulation: NewtonFormulation,
    /// 554: the proximal regularization `eps` added to W_NN in the step (default 0, Siconos'
    /// dparam[3]).
    pub regularization: f64,
    /// 550/551/565/553: Siconos 4.4's algorithm (default) or fc3d's refinements (the default
    /// of fc3d's own ids 570-572, which reuse these iterations).
    pub variant: AlgorithmVariant,
}

impl LocalSolverOptions {
    /// Siconos' defaults for the given local solver (fc3d's for its own ids 570-572).
    pub fn new(kind: LocalSolverKind) -> Self {
        let (tolerance, max_iter, rho_rule) = kind.default_tolerance_iterations_rho();
        LocalSolverOptions {
            kind,
            tolerance,
            max_iter,
            rho_rule,
            line_search_max_iter: 10,
            hybrid_max_loop: 1,
            hybrid_max_iter: 100,
            formulation: NewtonFormulation::AlartCurnier,
            regularization: 0.0,
            // fc3d's own solvers (570-572) keep fc3d's iteration where they share code with
            // Siconos' ids.
            variant: if kind.siconos_id() >= 570 {
                AlgorithmVariant::Fc3d
            } else {
                AlgorithmVariant::Siconos
            },
        }
    }
}

impl Default for LocalSolverOptions {
    fn default() -> Self {
        LocalSolverOptions::new(LocalSolverKind::NewtonHybrid)
    }
}

impl LocalSolverOptions {
    /// Checks the ranges of the local solver's settings.
    pub fn validate(&self) -> Result<(), Fc3dError> {
        let t = self.tolerance;
        require_setting(
            t >= 0.0 && t.is_finite(),
            "local.tolerance",
            t,
            "finite and >= 0",
        )?;
        match self.rho_rule {
            RhoRule::Constant(rho) => require_setting(
                rho > 0.0 && rho.is_finite(),
                "local.rho",
                rho,
                "finite and > 0",
            )?,
            RhoRule::Dumont(alpha) => require_setting(
                alpha > 0.0 && alpha.is_finite(),
                "local.rho",
                alpha,
                "finite and > 0 (Dumont's alpha)",
            )?,
            _ => {}
        }
        let eps = self.regularization;
        require_setting(
            eps >= 0.0 && eps.is_finite(),
            "local.regularization",
            eps,
            "finite and >= 0",
        )
    }
}

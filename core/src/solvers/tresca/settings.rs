//! Settings of the Tresca successive approximation (TFP) and of the Tresca sub-problem solvers
//! it shares with PFP, with Siconos' defaults.

use crate::contract::InnerTolerance;
use crate::solvers::accelerated::{ApgdSettings, FirstOrderMethod, SpgSettings};

/// Solver of the Tresca sub-problems (Siconos internal solver id in brackets; the accelerated
/// solvers are fc3d's own and have none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrescaInnerSolver {
    /// Gauss-Seidel over contacts with an exact one-contact Tresca solve [500, NSGS on the
    /// Tresca cylinder].
    GaussSeidel,
    /// Projection fixed point with self-adaptive rho (FP-VI-UPK) [566 VI_FPP_Cylinder].
    FixedPointViUpk,
    /// Projected gradient with Armijo line search, Algorithm 9 [567 CONVEXQP_PG_CYLINDER].
    ProjectedGradient,
    /// Nesterov's accelerated projected gradient with adaptive restart (fc3d's; see
    /// [`ApgdSettings`]): one product with W an iteration.
    Apgd(ApgdSettings),
    /// Spectral projected gradient with a non-monotone line search (fc3d's; see
    /// [`SpgSettings`]): one product with W an iteration.
    Spg(SpgSettings),
}

impl TrescaInnerSolver {
    /// APGD with its default settings.
    pub fn apgd() -> Self {
        TrescaInnerSolver::Apgd(ApgdSettings::default())
    }

    /// SPG with its default settings.
    pub fn spg() -> Self {
        TrescaInnerSolver::Spg(SpgSettings::default())
    }

    /// Siconos' id of the internal solver; `None` for fc3d's own.
    pub fn siconos_id(self) -> Option<i32> {
        match self {
            TrescaInnerSolver::GaussSeidel => Some(500),
            TrescaInnerSolver::FixedPointViUpk => Some(566),
            TrescaInnerSolver::ProjectedGradient => Some(567),
            TrescaInnerSolver::Apgd(_) | TrescaInnerSolver::Spg(_) => None,
        }
    }

    /// The id, or fc3d's name, in labels: `500`, `566`, `567`, `APGD`, `SPG`.
    pub fn short_name(self) -> String {
        match self {
            TrescaInnerSolver::Apgd(_) => "APGD".to_string(),
            TrescaInnerSolver::Spg(_) => "SPG".to_string(),
            other => other.siconos_id().unwrap_or_default().to_string(),
        }
    }

    /// The accelerated first-order method this solver is, if it is one.
    pub(crate) fn first_order(self) -> Option<FirstOrderMethod> {
        match self {
            TrescaInnerSolver::Apgd(s) => Some(FirstOrderMethod::Apgd(s)),
            TrescaInnerSolver::Spg(s) => Some(FirstOrderMethod::Spg(s)),
            _ => None,
        }
    }

    pub(crate) fn validate(self) -> Result<(), crate::error::Fc3dError> {
        self.first_order().map_or(Ok(()), |m| m.validate())
    }

    pub fn from_siconos_id(id: i32) -> Option<Self> {
        Some(match id {
            500 => TrescaInnerSolver::GaussSeidel,
            566 => TrescaInnerSolver::FixedPointViUpk,
            567 => TrescaInnerSolver::ProjectedGradient,
            _ => return None,
        })
    }
}

/// Settings of the Tresca successive approximation (TFP, Siconos id 503). Its limits default to
/// 1000 outer (threshold update) iterations and a tolerance of 1e-4 on the Coulomb error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrescaOptions {
    /// Tresca sub-problem solver (default Gauss-Seidel = Siconos' internal NSGS, id 500).
    pub inner: TrescaInnerSolver,
    /// Maximum iterations of one inner solve (default 1000, the internal solver's iparam[0]).
    pub inner_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
}

impl Default for TrescaOptions {
    fn default() -> Self {
        TrescaOptions {
            inner: TrescaInnerSolver::GaussSeidel,
            inner_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
        }
    }
}

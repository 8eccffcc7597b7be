//! Settings of the Tresca successive approximation (TFP) and of the Tresca sub-problem solvers
//! it shares with PFP, with Siconos' defaults.

use crate::contract::InnerTolerance;

/// Solver of the Tresca sub-problems (Siconos internal solver id in brackets).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrescaInnerSolver {
    /// Gauss-Seidel over contacts with an exact one-contact Tresca solve [500, NSGS on the
    /// Tresca cylinder].
    GaussSeidel,
    /// Projection fixed point with self-adaptive rho (FP-VI-UPK) [566 VI_FPP_Cylinder].
    FixedPointViUpk,
    /// Projected gradient with Armijo line search, Algorithm 9 [567 CONVEXQP_PG_CYLINDER].
    ProjectedGradient,
}

impl TrescaInnerSolver {
    pub fn siconos_id(self) -> i32 {
        match self {
            TrescaInnerSolver::GaussSeidel => 500,
            TrescaInnerSolver::FixedPointViUpk => 566,
            TrescaInnerSolver::ProjectedGradient => 567,
        }
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

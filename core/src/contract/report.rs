//! What a solve returns.

/// Why a solver stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolveStatus {
    /// The natural-map error of the returned `(r, u)` is at or below the tolerance.
    Converged,
    /// The iteration limit was reached first; the returned error is above the tolerance.
    MaxIterationsReached,
    /// The wall-clock budget ran out first; the returned iterate is the best one seen (by its
    /// natural-map error) and its error is above the tolerance.
    TimeBudgetExhausted,
    /// A solver of a relaxed problem (SOCLCP, Siconos id 517) solved its relaxation to the
    /// tolerance, but the returned `(r, u)` is not a Coulomb solution: its natural-map error (the
    /// one reported) is above the tolerance. Happens when some contact slides.
    RelaxationNotCoulomb,
    /// The reaction grew without bound, and the solver stopped: either its iterates diverged
    /// (a step too large for W), or the relative error fell below the tolerance only because
    /// `||r||` grew along a direction `d` with `W d = 0` into which q pushes (`q·d < 0`): then the
    /// problem has no solution (a singular W that cannot balance the contacts q pushes in).
    Unbounded,
}

impl SolveStatus {
    /// Short name for tables and CSV files (`converged`, `max-iter`, `out-of-time`,
    /// `relaxed-not-coulomb`, `unbounded`).
    pub fn name(self) -> &'static str {
        match self {
            SolveStatus::Converged => "converged",
            SolveStatus::MaxIterationsReached => "max-iter",
            SolveStatus::TimeBudgetExhausted => "out-of-time",
            SolveStatus::RelaxationNotCoulomb => "relaxed-not-coulomb",
            SolveStatus::Unbounded => "unbounded",
        }
    }

    /// Siconos' `info`: 0 converged, 1 not; fc3d adds 2 for an exhausted time budget, 3
    /// (`FC3D_RELAXED_NOT_COULOMB`) for a relaxed solution that is not a Coulomb solution and 4
    /// (`FC3D_UNBOUNDED`) for a reaction that grew without bound.
    pub fn info_code(self) -> i32 {
        match self {
            SolveStatus::Converged => 0,
            SolveStatus::MaxIterationsReached => 1,
            SolveStatus::TimeBudgetExhausted => 2,
            SolveStatus::RelaxationNotCoulomb => 3,
            SolveStatus::Unbounded => 4,
        }
    }
}

/// Outcome of a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolveReport {
    pub status: SolveStatus,
    /// Iterations (sweeps for NSGS) done.
    pub iterations: usize,
    /// Relative natural-map error of the returned `(r, u)`, recomputed after the solver stopped.
    pub error: f64,
    /// Dumont's global criterion (37) at the last sweep, when NSGS ran with
    /// [`ErrorEvaluation::DumontCriterion`](crate::ErrorEvaluation::DumontCriterion); reported beside
    /// `error`, never instead of it.
    pub dumont_criterion: Option<f64>,
    /// The self-adaptive rho the run ended with, for VI_FPP (506) and VI_EG (507): Siconos'
    /// generic VI solvers hand it back in `dparam[3]` (as `-rho`, "self-adaptive from rho"), so
    /// that a host reusing its options starts the next solve from it; `fc3d_driver` does the
    /// same. `None` for the other solvers, and when the solve ran rescaled.
    pub final_rho: Option<f64>,
    /// The stages AUTO (`Method::Auto`, `FC3D_AUTO`) took, in order; `None` for the other
    /// solvers.
    pub stages: Option<super::StageLog>,
}

impl SolveReport {
    pub fn converged(&self) -> bool {
        self.status == SolveStatus::Converged
    }
}

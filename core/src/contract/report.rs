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
    /// The size of the sparse LU factors, for the families that factorize a matrix: NSN (the
    /// Newton matrix, also inside PROX and AUTO), ADMM and rolling ADMM (`W + rho I`). `None` for
    /// the others (they factorize nothing; 2D Lemke and enumeration work on a dense LCP matrix).
    pub fill: Option<Fill>,
    /// The work of the run in products with W (a Gauss-Seidel sweep, which reads W once,
    /// counts as one; the measures of the error the run made included, the final one of the
    /// solve not), for the families that count it: TFP, PFP and ACLMFP with every inner solver.
    /// `None` for the others.
    pub products: Option<usize>,
    /// The sweeps NSGS did on its f32 copy of W's coupling blocks, when it ran with
    /// [`NsgsOptions::f32_sweeps`](crate::NsgsOptions) (the others, `iterations` minus these,
    /// read W's f64 blocks); `None` for every other run, and when the copy could not hold W.
    pub f32_sweeps: Option<usize>,
}

/// The fill of a sparse LU factorization `P A Q = L U`: how many entries the factors hold
/// against the factorized matrix. Counted structurally on the first factorization of the solve
/// (of the first solve, when a [`crate::Workspace`] keeps NSN's Newton matrix across solves)
/// from the pattern and the permutations chosen (fill-reducing column order, partial pivoting):
/// see [`crate::math::lu_fill`]. Within AUTO, the largest of its stages' fills.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Fill {
    /// Stored entries of the factorized matrix `A` (its pattern, structural zeros included).
    pub matrix_nnz: usize,
    /// `nnz(L) + nnz(U)`, L's unit diagonal not counted: equal to `matrix_nnz` when elimination
    /// creates no new entry.
    pub factor_nnz: usize,
}

impl Fill {
    /// `factor_nnz / matrix_nnz` (1 without fill).
    pub fn ratio(&self) -> f64 {
        self.factor_nnz as f64 / self.matrix_nnz.max(1) as f64
    }

    /// The larger of two fills (by factor size).
    pub fn largest(a: Option<Fill>, b: Option<Fill>) -> Option<Fill> {
        match (a, b) {
            (Some(x), Some(y)) => Some(if y.factor_nnz > x.factor_nnz { y } else { x }),
            (x, y) => x.or(y),
        }
    }
}

impl SolveReport {
    pub fn converged(&self) -> bool {
        self.status == SolveStatus::Converged
    }
}

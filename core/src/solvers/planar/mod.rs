//! 2D friction (Siconos' `fc2d` family): FC(W, q, mu) with contacts of dimension 2, `r_c = (r_N,
//! r_T)` and the cone `|r_T| <= mu r_N`. Four solvers, under Siconos' ids:
//!
//! * 400 NSGS: the Gauss-Seidel sweep shared with 3D ([`GaussSeidel`] over 2x2 blocks) with the
//!   exact one-contact solve of [`crate::local::solve_planar_contact`];
//! * 402 CPG: Siconos' conjugate projected gradient on the contact statuses ([`cpg`]);
//! * 404 LEMKE and 405 ENUM: the linear complementarity reformulation of the 2D law (three
//!   complementarity pairs per contact, [`lcp`]) solved by lexicographic Lemke or by enumeration.

pub mod cpg;
pub mod lcp;
mod nsgs;

pub use nsgs::PlanarStep;

use crate::contract::{Limits, Observer, SolverOutcome};
use crate::problem::FrictionProblem;

use crate::contract::ErrorEvaluation;
use crate::error::{require_setting, Fc3dError};
use crate::solvers::nsgs::{ContactOrder, SweepOptions};

#[cfg(doc)]
use crate::solvers::nsgs::GaussSeidel;

/// Settings of the 2D NSGS (Siconos id 400) beyond the limits (default 1000 sweeps, tolerance
/// 1e-4). The one-contact solve is exact, so there is no local solver to choose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarNsgsOptions {
    /// Error evaluation strategy (default [`ErrorEvaluation::LightWithFullFinal`], Siconos'
    /// default; Dumont's criterion is not offered in 2D).
    pub error_evaluation: ErrorEvaluation,
    /// The stopping test runs every `evaluation_frequency` sweeps (default 1).
    pub evaluation_frequency: usize,
    /// Contact visiting order (default [`ContactOrder::Natural`]).
    pub order: ContactOrder,
    /// Over-relaxation factor in (0, 2), `None` (default): plain Gauss-Seidel.
    pub relaxation: Option<f64>,
    /// Sweeps a contact that stopped moving is skipped (default `None`: never).
    pub freezing: Option<usize>,
}

impl Default for PlanarNsgsOptions {
    fn default() -> Self {
        PlanarNsgsOptions {
            error_evaluation: ErrorEvaluation::LightWithFullFinal,
            evaluation_frequency: 1,
            order: ContactOrder::Natural,
            relaxation: None,
            freezing: None,
        }
    }
}

impl PlanarNsgsOptions {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        if let Some(omega) = self.relaxation {
            require_setting(
                omega > 0.0 && omega < 2.0,
                "nsgs.relaxation",
                omega,
                "in (0, 2)",
            )?;
        }
        if self.error_evaluation == ErrorEvaluation::DumontCriterion {
            return Err(Fc3dError::Unsupported(
                "Dumont's criterion is a 3D NSGS error evaluation (2D NSGS: full, light, light \
                 with full final)"
                    .into(),
            ));
        }
        Ok(())
    }

    fn sweep_options(&self) -> SweepOptions {
        SweepOptions {
            relaxation: self.relaxation,
            order: self.order,
            freezing: self.freezing,
            track_solved_velocity: false,
        }
    }
}

/// A 2D solver and its own settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PlanarMethod {
    /// Nonsmooth Gauss-Seidel (Siconos 400).
    Nsgs(PlanarNsgsOptions),
    /// Conjugate projected gradient (Siconos 402).
    Cpg,
    /// Lexicographic Lemke on the LCP reformulation (Siconos 404).
    Lemke,
    /// Enumeration of the LCP reformulation's complementary bases (Siconos 405) in Siconos'
    /// order, from case `seed` (Siconos' `iparam[9]`, default 0), under the iteration limit
    /// (cases tried) and the time budget.
    Enumeration { seed: u64 },
}

impl PlanarMethod {
    /// Siconos' default `(tolerance, iteration limit)` of the id: 1e-4 and 1000 for NSGS and
    /// CPG, 1e-6 and 10000 pivots for Lemke, 1e-6 and 0 for enumeration, whose limit counts
    /// cases (0: every case, which a problem of more than 10 contacts must bound with a limit or
    /// a time budget).
    pub fn default_limits(&self) -> (f64, usize) {
        match self {
            PlanarMethod::Nsgs(_) | PlanarMethod::Cpg => (1e-4, 1000),
            PlanarMethod::Lemke => (1e-6, 10000),
            PlanarMethod::Enumeration { .. } => (1e-6, 0),
        }
    }

    /// Siconos' id.
    pub fn siconos_id(&self) -> i32 {
        match self {
            PlanarMethod::Nsgs(_) => 400,
            PlanarMethod::Cpg => 402,
            PlanarMethod::Lemke => 404,
            PlanarMethod::Enumeration { .. } => 405,
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        match self {
            PlanarMethod::Nsgs(o) => o.validate(),
            _ => Ok(()),
        }
    }
}

/// Runs `method` on `problem` from the reaction in `r` (CPG, Lemke and enumeration start from
/// zero, as Siconos' do).
pub(crate) fn run(
    method: &PlanarMethod,
    problem: &FrictionProblem<'_, 2>,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    match method {
        PlanarMethod::Nsgs(o) => nsgs::nsgs(problem, o, limits, r, u, observer),
        PlanarMethod::Cpg => cpg::cpg(problem, limits, r, u, observer),
        PlanarMethod::Lemke => lcp::solve_by_lcp(problem, false, limits, 0, r, u),
        PlanarMethod::Enumeration { seed } => lcp::solve_by_lcp(problem, true, limits, *seed, r, u),
    }
}

//! Rolling friction (Siconos' `rolling_fc3d` and `rolling_fc2d` families): contacts of dimension
//! `D` = 5 (normal, two tangential, two rolling components) or 3 (normal, tangential, rolling),
//! each with the rolling cone `||r_T|| <= mu r_N, ||r_R|| <= mu_r r_N`
//! ([`crate::math::rolling`]). NSGS (Siconos 3000 / 4000) is the Gauss-Seidel sweep and main
//! loop shared with 3D and 2D friction ([`GaussSeidel`], `run_sweeps`) with a one-contact step of
//! the rolling law ([`RollingStep`]): the projected step (3001 / 4001) or the self-adaptive
//! projection iteration (3002 / 4002) of [`crate::local::rolling`]. ADMM (Siconos 3003) is the
//! 3D friction ADMM ([`crate::solvers::admm`]) with the rolling cone.

use std::time::Instant;

use crate::contract::{ErrorEvaluation, Limits, Observer, SolverOutcome};
use crate::error::{require_setting, Fc3dError};
use crate::local::rolling::{
    rolling_projection_step, RollingLocalProblem, RollingProjectionIteration,
};
use crate::math::linalg::Block;
use crate::math::rolling::project_on_rolling_cone;
use crate::matrix::BlockRows;
use crate::problem::RollingProblem;
use crate::solvers::admm::AdmmOptions;
use crate::solvers::nsgs::{
    run_sweeps, ContactOrder, ContactStep, GaussSeidel, LocalTolerance, SweepOptions, SweepSchedule,
};

/// The one-contact solver of the rolling NSGS.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RollingLocalSolver {
    /// One projected step per visit (Siconos 3001 / 4001), of length `min_i 1 / W_ii`, or 1
    /// when `unit_step` is set (the step of Siconos' 2D rolling NSGS).
    Projection { unit_step: bool },
    /// Self-adaptive projection steps until the local tolerance (Siconos 3002 / 4002, default).
    ProjectionWithLocalIteration(RollingProjectionIteration),
}

impl Default for RollingLocalSolver {
    fn default() -> Self {
        RollingLocalSolver::ProjectionWithLocalIteration(RollingProjectionIteration::default())
    }
}

/// Settings of the rolling NSGS (Siconos 3000 and 4000) beyond the limits (default 1000 sweeps,
/// tolerance 1e-4), with Siconos' defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingNsgsOptions {
    /// Error evaluation strategy (default [`ErrorEvaluation::LightWithFullFinal`]).
    pub error_evaluation: ErrorEvaluation,
    /// The stopping test runs every `evaluation_frequency` sweeps (default 1).
    pub evaluation_frequency: usize,
    /// How the local tolerance evolves (default [`LocalTolerance::Given`]).
    pub local_tolerance: LocalTolerance,
    /// Over-relaxation factor in (0, 2) (default `None`).
    pub relaxation: Option<f64>,
    /// Contact visiting order (default [`ContactOrder::Natural`]).
    pub order: ContactOrder,
    /// Sweeps a contact that stopped moving is skipped (default `None`: never).
    pub freezing: Option<usize>,
    /// Keep a contact's previous reaction when its local iteration ends with a step longer than
    /// 1 or not finite (Siconos' "filter local solution", default false).
    pub filter_local_solution: bool,
    pub local: RollingLocalSolver,
}

impl Default for RollingNsgsOptions {
    fn default() -> Self {
        RollingNsgsOptions {
            error_evaluation: ErrorEvaluation::LightWithFullFinal,
            evaluation_frequency: 1,
            local_tolerance: LocalTolerance::Given,
            relaxation: None,
            order: ContactOrder::Natural,
            freezing: None,
            filter_local_solution: false,
            local: RollingLocalSolver::default(),
        }
    }
}

impl RollingNsgsOptions {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        if let Some(omega) = self.relaxation {
            require_setting(
                omega > 0.0 && omega < 2.0,
                "nsgs.relaxation",
                omega,
                "in (0, 2)",
            )?;
        }
        if let LocalTolerance::Adaptive { ratio } | LocalTolerance::AdaptivePerContact { ratio } =
            self.local_tolerance
        {
            require_setting(
                ratio > 0.0 && ratio.is_finite(),
                "nsgs.local_tolerance.ratio",
                ratio,
                "finite and > 0",
            )?;
        }
        if let RollingLocalSolver::ProjectionWithLocalIteration(it) = self.local {
            require_setting(
                it.tolerance >= 0.0 && it.tolerance.is_finite(),
                "local.tolerance",
                it.tolerance,
                "finite and >= 0",
            )?;
        }
        Ok(())
    }

    fn sweep_options(&self) -> SweepOptions {
        SweepOptions {
            relaxation: self.relaxation,
            order: self.order,
            freezing: self.freezing,
            track_solved_velocity: self.error_evaluation == ErrorEvaluation::DumontCriterion,
        }
    }
}

/// A rolling solver and its settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RollingMethod {
    /// Nonsmooth Gauss-Seidel (Siconos 3000 in 3D, 4000 in 2D).
    Nsgs(RollingNsgsOptions),
    /// ADMM on the local formulation (Siconos 3003), the 3D friction ADMM with the rolling cone.
    /// Siconos' rolling ADMM has no rescaling: `scalar_rescaling` must be false.
    Admm(AdmmOptions),
}

impl RollingMethod {
    /// Siconos' default `(tolerance, iteration limit)`: 1e-4 and 1000 sweeps for NSGS, 1e-6
    /// and 20000 iterations for ADMM.
    pub fn default_limits(&self) -> (f64, usize) {
        match self {
            RollingMethod::Nsgs(_) => (1e-4, 1000),
            RollingMethod::Admm(_) => (1e-6, 20000),
        }
    }

    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        match self {
            RollingMethod::Nsgs(o) => o.validate(),
            RollingMethod::Admm(o) => {
                if o.scalar_rescaling {
                    return Err(Fc3dError::Unsupported(
                        "rescaling in the rolling ADMM (Siconos 4.4 has none either)".into(),
                    ));
                }
                o.validate()
            }
        }
    }
}

/// The rolling one-contact step: the configured local solver with each contact's rolling
/// coefficient and step length (carried from sweep to sweep).
pub struct RollingStep<'p> {
    local: RollingLocalSolver,
    filter: bool,
    mu_r: &'p [f64],
    deadline: Option<Instant>,
}

impl<'p> RollingStep<'p> {
    fn new(options: &RollingNsgsOptions, mu_r: &'p [f64]) -> Result<Self, Fc3dError> {
        Ok(RollingStep {
            local: options.local,
            filter: options.filter_local_solution,
            mu_r,
            deadline: None,
        })
    }
}

impl<const D: usize> ContactStep<D> for RollingStep<'_> {
    /// The local solvers keep no state of their own: a contact's step length lives in the
    /// sweep's per-contact memory.
    type Worker = ();

    fn worker(&self) {}

    /// `memory` is the contact's step length (local solver 3002), carried from sweep to sweep.
    #[inline]
    fn solve(
        &self,
        _worker: &mut (),
        c: usize,
        w: &Block<D>,
        q: &[f64; D],
        mu: f64,
        memory: &mut f64,
        r: &mut [f64; D],
    ) {
        let p = RollingLocalProblem {
            w,
            q: *q,
            mu,
            mu_r: self.mu_r[c],
        };
        let old = *r;
        let local_error = match &self.local {
            RollingLocalSolver::Projection { unit_step } => {
                rolling_projection_step(&p, *unit_step, r);
                0.0
            }
            RollingLocalSolver::ProjectionWithLocalIteration(it) => {
                it.solve(&p, memory, r, self.deadline)
            }
        };
        let rejected = self.filter && !(local_error <= 1.0);
        if rejected || !r.iter().all(|v| v.is_finite()) {
            *r = old;
        }
    }

    fn set_tolerance(&mut self, tolerance: f64) {
        if let RollingLocalSolver::ProjectionWithLocalIteration(it) = &mut self.local {
            if tolerance.is_finite() && tolerance >= 0.0 {
                it.tolerance = tolerance;
            }
        }
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
    }

    fn normal_only(&self, c: usize, mu: f64) -> bool {
        mu == 0.0 && self.mu_r[c] == 0.0
    }

    fn project(&self, c: usize, r: &[f64; D], mu: f64) -> [f64; D] {
        project_on_rolling_cone(r, mu, self.mu_r[c])
    }
}

/// Runs `method` on `problem` from the reaction in `r`.
pub(crate) fn run<const D: usize>(
    method: &RollingMethod,
    problem: &RollingProblem<'_, D>,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    match method {
        RollingMethod::Nsgs(o) => nsgs(problem, o, limits, r, u, observer),
        RollingMethod::Admm(o) => crate::solvers::admm::admm(problem, o, limits, r, u, observer),
    }
}

fn nsgs<const D: usize>(
    problem: &RollingProblem<'_, D>,
    options: &RollingNsgsOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let rows = BlockRows::<D>::from_delassus(problem.w())?;
    let step = RollingStep::new(options, problem.mu_r())?;
    let mut sweeper =
        GaussSeidel::from_parts(rows, step, &options.sweep_options(), limits.tolerance)?;
    let schedule = SweepSchedule {
        error_evaluation: options.error_evaluation,
        evaluation_frequency: options.evaluation_frequency,
        local_tolerance: options.local_tolerance,
        // Siconos' rolling NSGS sweeps on when a sweep leaves r unchanged above the tolerance.
        stop_when_stalled: false,
        acceleration: Default::default(),
    };
    run_sweeps(problem, &mut sweeper, &schedule, limits, r, u, observer)
}

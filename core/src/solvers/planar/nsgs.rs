//! The 2D NSGS: the generic Gauss-Seidel sweep over 2x2 blocks with the exact one-contact solve.

use crate::contract::{Limits, Observer, SolverOutcome};
use crate::error::Fc3dError;
use crate::local::solve_planar_contact;
use crate::math::linalg::Block;
use crate::matrix::BlockRows;
use crate::problem::FrictionProblem;
use crate::solvers::nsgs::{run_sweeps, ContactStep, GaussSeidel, LocalTolerance, SweepSchedule};

use super::PlanarNsgsOptions;

/// The 2D one-contact step: the exact 2x2 solve (every branch of the law in closed form). A
/// contact whose block admits no finite candidate (a singular `W_cc`) keeps its reaction.
#[derive(Debug, Clone, Copy, Default)]
pub struct PlanarStep;

impl ContactStep<2> for PlanarStep {
    type Worker = ();

    fn worker(&self) {}

    #[inline]
    fn solve(
        &self,
        _worker: &mut (),
        _c: usize,
        w: &Block<2>,
        q: &[f64; 2],
        mu: f64,
        _memory: &mut f64,
        r: &mut [f64; 2],
    ) {
        if let Some(s) = solve_planar_contact(w, q, mu) {
            *r = s.r;
        }
    }
}

/// Siconos 400 on `problem`, from the reaction in `r`.
pub(crate) fn nsgs(
    problem: &FrictionProblem<'_, 2>,
    options: &PlanarNsgsOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let rows = BlockRows::<2>::from_delassus(problem.w())?;
    let mut sweeper =
        GaussSeidel::from_parts(rows, PlanarStep, &options.sweep_options(), limits.tolerance)?;
    let schedule = SweepSchedule {
        error_evaluation: options.error_evaluation,
        evaluation_frequency: options.evaluation_frequency,
        local_tolerance: LocalTolerance::Given,
        stop_when_stalled: false,
        acceleration: Default::default(),
    };
    run_sweeps(problem, &mut sweeper, &schedule, limits, r, u, observer)
}

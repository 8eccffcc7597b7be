//! The solver contract: the bottom floor every solver family builds on and that imports no
//! family. What a family receives ([`Limits`]), what it tells the observer ([`IterationEvent`]),
//! what it returns ([`SolverOutcome`]), and the loop helpers they share: the end-of-iteration test
//! ([`Run`]), the best iterate kept under a time budget ([`BestIterate`]), the error-evaluation
//! schedule of the sweeping families ([`ErrorSchedule`]) and the outer loop of the fixed-point
//! families ([`OuterLoop`]).

mod family;
mod limits;
mod outer;
mod report;
mod schedule;
mod stages;

pub(crate) use family::Family;
pub use limits::Limits;
pub use limits::{deadline_passed, past_deadline};
pub(crate) use limits::{BestIterate, Run};
pub use outer::InnerTolerance;
pub(crate) use outer::OuterLoop;
pub use report::{Fill, SolveReport, SolveStatus};
pub use schedule::ErrorEvaluation;
pub use schedule::{ErrorSchedule, Measure, Test};
pub use stages::{Stage, StageEnd, StageKind, StageLog, MAX_STAGES};

/// Progress of an iterative solver, handed to an observer after every iteration.
#[derive(Debug, Clone, Copy)]
pub struct IterationEvent<'a> {
    pub iteration: usize,
    pub reaction: &'a [f64],
    /// The error the solver tested at this iteration (cheap or full, as configured).
    pub error: f64,
}

/// What a solve reports after every iteration (the C `Callback`).
pub type Observer<'o> = dyn FnMut(&IterationEvent<'_>) + 'o;

/// How a solver family's run ended. The caller ([`crate::solve`]) then measures the error of the
/// returned `(r, u)` and sets the status from it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SolverOutcome {
    /// Iterations done (sweeps for NSGS, Newton steps for NSN, outer iterations, ...).
    pub iterations: usize,
    /// The run stopped because its time budget was spent.
    pub out_of_time: bool,
    /// The natural-map error of the returned reaction when the family's last step measured it
    /// with [`crate::measure::natural_map_error`] on the host's storage, leaving `u = W r + q`;
    /// `None` when the caller must measure it (always safe).
    pub final_error: Option<f64>,
    /// Dumont's criterion (37) at the last test, when NSGS stopped on it.
    pub dumont_criterion: Option<f64>,
    /// A solver of a relaxed problem (SOCLCP) solved its relaxation to the tolerance: whether the
    /// result is a Coulomb solution is then decided by the Coulomb error.
    pub relaxation_converged: bool,
    /// The run stopped because its iterates grew without bound.
    pub diverged: bool,
    /// The step size a self-adaptive run ends with, for the families whose Siconos solver hands
    /// it back to the host (see [`SolveReport::final_rho`](crate::SolveReport)).
    pub final_rho: Option<f64>,
    /// The stages a composite solver (AUTO) took.
    pub stages: Option<StageLog>,
    /// The fill of the factorization a factorizing family made.
    pub fill: Option<Fill>,
    /// The products with W the run did, for the families that count them.
    pub products: Option<usize>,
    /// The sweeps a mixed-precision NSGS run did on its f32 copy of W's coupling blocks.
    pub f32_sweeps: Option<usize>,
}

impl SolverOutcome {
    /// A run that did `iterations` and stopped, out of time or not, with nothing measured.
    pub fn stopped(iterations: usize, out_of_time: bool) -> Self {
        SolverOutcome {
            iterations,
            out_of_time,
            final_error: None,
            dumont_criterion: None,
            relaxation_converged: false,
            diverged: false,
            final_rho: None,
            stages: None,
            fill: None,
            products: None,
            f32_sweeps: None,
        }
    }

    /// A run that stopped after `iterations` because its iterates grew without bound.
    pub fn diverged(iterations: usize) -> Self {
        SolverOutcome {
            diverged: true,
            ..SolverOutcome::stopped(iterations, false)
        }
    }

    /// The same outcome with the step size the run ends with.
    pub fn with_final_rho(self, final_rho: Option<f64>) -> Self {
        SolverOutcome { final_rho, ..self }
    }

    /// The same outcome with the fill of the factorization the run made.
    pub fn with_fill(self, fill: Option<Fill>) -> Self {
        SolverOutcome { fill, ..self }
    }

    /// The same outcome with the products with W the run did.
    pub fn with_products(self, products: usize) -> Self {
        SolverOutcome {
            products: Some(products),
            ..self
        }
    }

    /// The same outcome with the final error the family measured on the returned `(r, u)`.
    pub fn with_final_error(self, final_error: Option<f64>) -> Self {
        SolverOutcome {
            final_error,
            ..self
        }
    }
}

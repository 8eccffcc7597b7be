//! Successive approximation by Tresca problems (TFP, Siconos id 503, Algorithm 11 of
//! Acary-Brémond-Huber): freeze the friction threshold `s_c = r_N,c` of the current iterate, solve
//! the Tresca problem on the cylinders `C_c = { r_N >= 0, ||r_T|| <= mu_c s_c }`,
//!
//! `-(W r + q) ∈ N_C(r)`,
//!
//! and repeat until the Coulomb (natural-map) error is below the tolerance. At a fixed point
//! `s = r_N` the Tresca conditions are the disjunctive form of Coulomb's law.
//!
//! The Tresca sub-problem solvers (`subproblem`) are shared with the Panagiotopoulos solver
//! (`pfp`), whose tangent problem is the same cylinder with the normal reaction frozen:
//! * [`TrescaInnerSolver::GaussSeidel`]: Gauss-Seidel over contacts with an exact one-contact
//!   Tresca solver (closed-form stick cases, a safeguarded Newton on the multiplier for sliding);
//! * [`TrescaInnerSolver::FixedPointViUpk`]: the projection fixed point on the cylinders with
//!   the self-adaptive rho of Algorithm 1 (nu = 2/3, L = 0.9, Lmin = 0.3);
//! * [`TrescaInnerSolver::ProjectedGradient`]: Algorithm 9 (Armijo backtracking on the quadratic
//!   `1/2 r.W r + r.q`).

mod local;
mod settings;
pub(crate) mod subproblem;

pub use local::{solve_disk_problem, solve_local_tresca};
pub use settings::{TrescaInnerSolver, TrescaOptions};

use crate::contract::{Family, Limits, Observer, OuterLoop, SolverOutcome};
use crate::error::Fc3dError;
use crate::measure::natural_map_error_by_rows;
use crate::problem::FrictionProblem;
use subproblem::{TrescaMode, TrescaWorkspace};

impl Family for TrescaOptions {
    fn name(&self) -> &'static str {
        "TFP"
    }

    fn label(&self) -> String {
        format!("TFP/{}", self.inner.siconos_id())
    }

    fn siconos_id(&self) -> i32 {
        503
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 1000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        self.inner_tolerance.validate()
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        tfp(problem, self, limits, r, u, observer)
    }
}

/// Runs TFP from the reaction in `r`. `u` is work space.
fn tfp(
    problem: &FrictionProblem<'_>,
    options: &TrescaOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.inner_tolerance.validate()?;
    let mut work = TrescaWorkspace::new(problem)?;
    let (q, mu) = (problem.q(), problem.mu());
    let run = limits.start();
    work.deadline = run.deadline();
    let tol = run.tolerance;
    let mut outer = OuterLoop::new(run, r)?;
    let mut error = natural_map_error_by_rows(problem, &work.rows, r, u);
    for iteration in 1..=run.max_iter {
        for (c, radius) in work.radius.iter_mut().enumerate() {
            *radius = mu[c] * r[3 * c].max(0.0);
        }
        let inner_tol = options.inner_tolerance.value(error, tol);
        work.solve(
            options.inner,
            TrescaMode::Full,
            q,
            inner_tol,
            options.inner_max_iter,
            r,
        );
        let (e, stop) = outer.end_iteration(iteration, problem, &work.rows, r, u, observer);
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome);
        }
    }
    Ok(outer.exhausted())
}

//! The ACLM fixed point (ACLMFP, Siconos id 516, Algorithm 12 of Acary-Brémond-Huber): the shift
//! `s_c = (mu_c ||u_T,c||, 0, 0)` of the current velocity, then the SOCLCP
//! `K* ∋ W r + q + s ⟂ r ∈ K` with that `s`, until the Coulomb error is below the tolerance. At a
//! fixed point `W r + q + s` is De Saxcé's modified velocity. The SOCLCP, for symmetric W the
//! convex QP `min 1/2 r.W r + (q + s).r` over the cones, is solved by the Gauss-Seidel sweep of
//! [`crate::solvers::soclcp`] (Siconos' choice) or by an accelerated first-order method of
//! [`crate::solvers::accelerated`] ([`AclmInnerSolver`]).

use crate::contract::{Family, InnerTolerance, Limits, Observer, OuterLoop, SolverOutcome};
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::math::cone::project_on_cone;
use crate::math::linalg::{norm, norm2};
use crate::measure::{cheap_error, natural_map_error_by_rows};
use crate::problem::FrictionProblem;
use crate::solvers::accelerated::{
    ApgdSettings, ConvexSet, ConvexSubproblem, FirstOrderMethod, FirstOrderWork, SpgSettings,
};
use crate::solvers::soclcp::soclcp_sweep;

/// Solver of ACLMFP's SOCLCP sub-problems.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum AclmInnerSolver {
    /// Gauss-Seidel over contacts with an exact one-cone solve (Siconos' 1100 SOCLCP NSGS).
    GaussSeidel,
    /// Nesterov's accelerated projected gradient with adaptive restart (fc3d's).
    Apgd(ApgdSettings),
    /// Spectral projected gradient with a non-monotone line search (fc3d's).
    Spg(SpgSettings),
}

impl AclmInnerSolver {
    fn first_order(self) -> Option<FirstOrderMethod> {
        match self {
            AclmInnerSolver::GaussSeidel => None,
            AclmInnerSolver::Apgd(s) => Some(FirstOrderMethod::Apgd(s)),
            AclmInnerSolver::Spg(s) => Some(FirstOrderMethod::Spg(s)),
        }
    }
}

/// Settings of the ACLM fixed point (Siconos id 516). Its limits default to 1000 outer (threshold
/// update) iterations and a tolerance of 1e-4 on the Coulomb error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AclmOptions {
    /// Solver of the SOCLCP sub-problems (default Gauss-Seidel, Siconos' 1100).
    pub inner: AclmInnerSolver,
    /// Maximum iterations of each inner SOCLCP solve: Gauss-Seidel sweeps, or products with W of
    /// the accelerated solvers (default 1000).
    pub inner_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
}

impl Default for AclmOptions {
    fn default() -> Self {
        AclmOptions {
            inner: AclmInnerSolver::GaussSeidel,
            inner_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
        }
    }
}

/// The Coulomb cones `K_mu`.
struct Cones<'m> {
    mu: &'m [f64],
}

impl ConvexSet for Cones<'_> {
    fn project(&self, x: &mut [f64]) {
        for (c, &m) in self.mu.iter().enumerate() {
            let s = 3 * c;
            let p = project_on_cone(&[x[s], x[s + 1], x[s + 2]], m);
            x[s..s + 3].copy_from_slice(&p);
        }
    }
}

impl Family for AclmOptions {
    fn presets() -> Vec<Self> {
        [
            AclmInnerSolver::GaussSeidel,
            AclmInnerSolver::Apgd(ApgdSettings::default()),
            AclmInnerSolver::Spg(SpgSettings::default()),
        ]
        .map(|inner| AclmOptions {
            inner,
            ..Default::default()
        })
        .to_vec()
    }

    fn name(&self) -> &'static str {
        match self.inner {
            AclmInnerSolver::GaussSeidel => "ACLMFP",
            AclmInnerSolver::Apgd(_) => "ACLMFP-APGD",
            AclmInnerSolver::Spg(_) => "ACLMFP-SPG",
        }
    }

    fn label(&self) -> String {
        self.name().to_string()
    }

    fn siconos_id(&self) -> i32 {
        516
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 1000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        if let Some(m) = self.inner.first_order() {
            m.validate()?;
        }
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
        aclmfp(problem, self, limits, r, u, observer)
    }
}

/// Runs ACLMFP from the reaction in `r`; `u` is work space.
fn aclmfp(
    problem: &FrictionProblem<'_>,
    options: &AclmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let rows = problem.w().block_rows()?;
    let (q, mu) = (problem.q(), problem.mu());
    let run = limits.start();
    let tol = run.tolerance;
    let mut shift = try_vec(rows.n_contacts(), 0.0, "the ACLM shifts")?;
    let first_order = options.inner.first_order();
    // The accelerated solvers take the shift in their linear term q + s.
    let mut shifted_q = if first_order.is_some() {
        try_copy(q, "the ACLM shifted q")?
    } else {
        Vec::new()
    };
    let mut work = first_order
        .map(|m| FirstOrderWork::new(problem.size(), m))
        .transpose()?;
    let norm_q = norm(q);
    let mut products = 1;
    let mut outer = OuterLoop::new(run, r)?;
    let mut error = natural_map_error_by_rows(problem, &rows, r, u);
    for iteration in 1..=run.max_iter {
        // u = W r + q is current here (coulomb_error computed it).
        for (c, s) in shift.iter_mut().enumerate() {
            *s = mu[c] * norm2(u[3 * c + 1], u[3 * c + 2]);
        }
        let inner_tol = options.inner_tolerance.value(error, tol);
        match work.as_mut() {
            None => {
                for _ in 0..options.inner_max_iter {
                    if run.out_of_time() {
                        break;
                    }
                    products += 1;
                    let increment_sq = soclcp_sweep(&rows, q, mu, Some(&shift), 1.0, r);
                    if cheap_error(increment_sq, r) <= inner_tol {
                        break;
                    }
                }
            }
            Some(work) => {
                for (c, s) in shift.iter().enumerate() {
                    shifted_q[3 * c] = q[3 * c] + s;
                }
                let sub = ConvexSubproblem {
                    rows: &rows,
                    linear: &shifted_q,
                    set: &Cones { mu },
                    norm_q,
                };
                let before = work.products;
                work.solve(&sub, inner_tol, options.inner_max_iter, run.deadline(), r);
                products += work.products - before;
            }
        }
        products += 1;
        let (e, stop) = outer.end_iteration(iteration, problem, &rows, r, u, observer);
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome.with_products(products));
        }
    }
    Ok(outer.exhausted().with_products(products))
}

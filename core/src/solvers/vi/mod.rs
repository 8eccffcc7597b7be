//! Projection methods on the variational-inequality form of FC(W, q, mu) (section 4 and Table 1
//! of Acary-Brémond-Huber): with De Saxcé's map
//!
//! `F(r) = W r + q + g(W r + q)`, `g(u)_c = (mu_c ||u_{T,c}||, 0, 0)`,
//!
//! r solves the problem iff `r = P_K(r - rho F(r))` for any `rho > 0` (K the product of the
//! Coulomb cones). Three iterations are built on that map:
//!
//! * fixed point (Algorithm 1, rule (95)): `r_{k+1} = P_K(r_k - rho_k F(r_k))`;
//! * extragradient: the prediction `r̄ = P_K(r_k - rho_k F(r_k))`, then a correction
//!   ([`ExtraGradientCorrection`]: Siconos' `P_K(r̄ - rho_k F(r̄))` or the paper's (96)
//!   `P_K(r_k - rho_k F(r̄))`);
//! * hyperplane projection (Siconos' HP 508, after Solodov-Svaiter): the prediction, a search
//!   along `[r_k, r̄]` for a point w whose velocity separates `r_k` from `r̄`, and a projection
//!   step along that velocity ([`HyperplaneSearch`]);
//!
//! with a fixed `rho` or the self-adaptive Armijo-type rule of Algorithm 3, whose ratio is
//! Khobotov's (98) (UPK) or Solodov-Tseng's (99) (UPTS).
//!
//! Siconos exposes six ids over these: DSFP 505 (fixed point, fixed rho: "FP-DS"), VI_FPP 506
//! and VI_EG 507 (through its generic VI solvers), HP 508, FPP 511 and EG 512 (written directly
//! on the friction problem). Each id follows its Siconos code in the details that change
//! iteration counts (see [`Lineage`]); they share this one implementation, and [`ViSolver`]
//! keeps the id for defaults, labels and the C layer.

mod hyperplane;
mod projection;
mod settings;

pub use settings::{
    ExtraGradientCorrection, HyperplaneSearch, SelfAdaptiveStep, StepRatio, StepSize, TrialStart,
    ViIteration, ViOptions, ViSolver,
};

pub(crate) use projection::run as run_projection;
pub(crate) use settings::Lineage;

use crate::contract::{Family, Limits, Observer, SolverOutcome};
use crate::error::Fc3dError;
use crate::math::cone::{modified_velocity, project_on_cone};
use crate::measure::{absolute_natural_map_residual, natural_map_error_of};
use crate::problem::FrictionProblem;

impl Family for ViOptions {
    fn presets() -> Vec<Self> {
        ViSolver::ALL.into_iter().map(ViOptions::new).collect()
    }

    fn name(&self) -> &'static str {
        self.solver.short_name()
    }

    fn label(&self) -> String {
        self.solver.short_name().to_string()
    }

    fn siconos_id(&self) -> i32 {
        self.solver.siconos_id()
    }

    fn default_limits(&self) -> (f64, usize) {
        self.solver.default_limits()
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        ViOptions::validate(self)
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        self.validate()?;
        match self.solver.iteration() {
            ViIteration::FixedPoint | ViIteration::ExtraGradient => {
                let map = LocalVi::new(problem);
                projection::run(&map, self, limits, r, u, observer)
            }
            ViIteration::HyperplaneProjection => {
                hyperplane::run(problem, self, limits, r, u, observer)
            }
        }
    }
}

/// A variational inequality `x ∈ X, F(x)·(y - x) >= 0 for all y ∈ X` with X a product of
/// Coulomb cones (on the reaction part of x) and free unknowns: what the fixed point and the
/// extragradient iterate on. FC(W, q, mu) in r ([`LocalVi`]), or the global problem in (v, r)
/// (`crate::global`).
pub(crate) trait ViMap {
    /// The unknowns x.
    fn size(&self) -> usize;
    /// The contact velocity `u` computed with F (what the host gets beside r).
    fn velocity_size(&self) -> usize;
    /// `u` and `f = F(x)`.
    fn evaluate(&self, x: &[f64], u: &mut [f64], f: &mut [f64]);
    /// `out = P_X(base - rho f)`.
    fn project_step(&self, base: &[f64], f: &[f64], rho: f64, out: &mut [f64]);
    /// `x <- P_X(x - rho f)`.
    fn project_step_in_place(&self, x: &mut [f64], f: &[f64], rho: f64);
    /// The error the lineage stops on at `x` (`u` and `f = F(x)` computed there).
    fn stopping_error(&self, lineage: Lineage, x: &[f64], u: &[f64], f: &[f64]) -> f64;
    /// The reaction part of x (what an observer is shown).
    fn reaction<'x>(&self, x: &'x [f64]) -> &'x [f64];
}

/// FC(W, q, mu) as a VI in r: `F(r) = W r + q + g(W r + q)`, X the cones.
pub(crate) struct LocalVi<'p, 'a> {
    problem: &'p FrictionProblem<'a>,
    norm_q: f64,
}

impl<'p, 'a> LocalVi<'p, 'a> {
    pub fn new(problem: &'p FrictionProblem<'a>) -> Self {
        LocalVi {
            problem,
            norm_q: crate::math::linalg::norm(problem.q()),
        }
    }
}

impl ViMap for LocalVi<'_, '_> {
    fn size(&self) -> usize {
        self.problem.size()
    }
    fn velocity_size(&self) -> usize {
        self.problem.size()
    }
    fn evaluate(&self, x: &[f64], u: &mut [f64], f: &mut [f64]) {
        evaluate(self.problem, x, u, f);
    }
    fn project_step(&self, base: &[f64], f: &[f64], rho: f64, out: &mut [f64]) {
        project_step(self.problem.mu(), base, f, rho, out);
    }
    fn project_step_in_place(&self, x: &mut [f64], f: &[f64], rho: f64) {
        project_step_in_place(self.problem.mu(), x, f, rho);
    }
    fn stopping_error(&self, lineage: Lineage, x: &[f64], u: &[f64], _f: &[f64]) -> f64 {
        stopping_error(lineage, self.problem, x, u, self.norm_q)
    }
    fn reaction<'x>(&self, x: &'x [f64]) -> &'x [f64] {
        x
    }
}

/// `u = W r + q` and `f = F(r) = u + g(u)`.
fn evaluate(problem: &FrictionProblem<'_>, r: &[f64], u: &mut [f64], f: &mut [f64]) {
    problem.velocity(r, u);
    de_saxce_map(problem.mu(), u, f);
}

/// `f = u + g(u)`, contact by contact.
pub(crate) fn de_saxce_map(mu: &[f64], u: &[f64], f: &mut [f64]) {
    for ((fc, uc), &m) in f.chunks_exact_mut(3).zip(u.chunks_exact(3)).zip(mu) {
        fc.copy_from_slice(&modified_velocity(&[uc[0], uc[1], uc[2]], m));
    }
}

/// `out = P_K(base - rho f)`, contact by contact.
pub(crate) fn project_step(mu: &[f64], base: &[f64], f: &[f64], rho: f64, out: &mut [f64]) {
    for (c, &m) in mu.iter().enumerate() {
        let k = 3 * c;
        let x = [
            base[k] - rho * f[k],
            base[k + 1] - rho * f[k + 1],
            base[k + 2] - rho * f[k + 2],
        ];
        out[k..k + 3].copy_from_slice(&project_on_cone(&x, m));
    }
}

/// `x <- P_K(x - rho f)`, contact by contact.
pub(crate) fn project_step_in_place(mu: &[f64], x: &mut [f64], f: &[f64], rho: f64) {
    for (c, &m) in mu.iter().enumerate() {
        let k = 3 * c;
        let y = [
            x[k] - rho * f[k],
            x[k + 1] - rho * f[k + 1],
            x[k + 2] - rho * f[k + 2],
        ];
        x[k..k + 3].copy_from_slice(&project_on_cone(&y, m));
    }
}

/// The error an id stops on, for `(r, u = W r + q)`: Siconos' friction error (133) or, for the
/// VI lineage, the VI solvers' `||r - P_K(r - F(r))|| / ||q||` (see [`Lineage`]).
fn stopping_error(
    lineage: Lineage,
    problem: &FrictionProblem<'_>,
    r: &[f64],
    u: &[f64],
    norm_q: f64,
) -> f64 {
    match lineage {
        Lineage::Friction => natural_map_error_of(problem, r, u),
        Lineage::Vi => {
            let e = absolute_natural_map_residual(r, u, problem.mu());
            if norm_q > f64::EPSILON {
                e / norm_q
            } else {
                e
            }
        }
    }
}

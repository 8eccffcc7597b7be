//! Siconos' `GFC3D ADMM` (id 613): ADMM on the global problem as the convex program
//! `min v^T M v / 2 - q^T v` subject to `H^T v + b_s = z`, `z ∈ K*` (b_s = b plus De Saxcé's
//! term `(mu ||u_T||, 0, 0)` at the last velocity when `update_s`, Siconos' default), whose
//! multiplier is the reaction: with the scaled dual `ξ = -r / rho`, each iteration of the
//! shared engine (`solvers::admm::engine`, the local ADMM's) runs
//!
//! * `(M + rho H H^T) v = q + rho H (ẑ - b_s - ξ̂)`, `a = H^T v + b_s`;
//! * `z = P_{K*}(a + ξ̂)`, `ξ = ξ̂ + a - z`;
//!
//! with `M + rho H H^T` factored by faer's sparse LU (pattern and symbolic analysis once,
//! refactored when residual balancing changes rho). The reaction `r = -rho ξ` is measured as
//! Siconos does, when the ADMM residuals pass their test or every `error_frequency`
//! iterations, on the triple the solve returns (`v = M^-1 (q + H r)`): the global error, or
//! without `update_s` the error of the convex relaxation (then reported as such).

use std::time::Instant;

use crate::contract::{IterationEvent, Limits, Observer, Run, SolverOutcome};
use crate::error::{require_setting, try_vec, Fc3dError};
use crate::math::cone::{modified_velocity, project_on_dual_cone};
use crate::math::linalg::{bounded, norm};
use crate::math::sparse_lu::SparseLu;
use crate::matrix::{transpose_mul_add, HForm};
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;

use super::rescaling::GlobalRescaling;
use crate::solvers::admm::{iterate, AdmmInitialRho, AdmmOptions, Splitting};

/// Settings of the global ADMM (613), Siconos 4.4's defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobalAdmmOptions {
    /// The iteration's settings (rho and its strategy, acceleration, restart, balancing).
    /// Siconos 613's defaults: rho given, 0.1; constant; accelerated with restart, eta 0.999;
    /// tau 2, phi 10.
    pub admm: AdmmOptions,
    /// De Saxcé's term updated at every iteration (Siconos' `UPDATE_S = YES`, the default):
    /// the problem solved is Coulomb's. Without it, the convex relaxation (associated law).
    pub update_s: bool,
    /// The error is measured at least every this many iterations (Siconos' `iparam[8]`, 50;
    /// >= 1), and whenever the ADMM residuals pass their test.
    pub error_frequency: usize,
    /// The rescaling of the problem before the run (Siconos' `iparam[3]`; default none).
    pub rescaling: GlobalRescaling,
}

impl Default for GlobalAdmmOptions {
    fn default() -> Self {
        GlobalAdmmOptions {
            admm: AdmmOptions {
                rho: 0.1,
                balancing_phi: 10.0,
                ..AdmmOptions::default()
            },
            update_s: true,
            error_frequency: 50,
            rescaling: GlobalRescaling::None,
        }
    }
}

impl GlobalAdmmOptions {
    pub fn validate(&self) -> Result<(), Fc3dError> {
        self.admm.validate()?;
        require_setting(
            self.error_frequency >= 1,
            "global_admm.error_frequency",
            self.error_frequency,
            ">= 1",
        )
    }

    /// The law the run measures its iterate against.
    pub fn law(&self) -> ContactLaw {
        if self.update_s {
            ContactLaw::Coulomb
        } else {
            ContactLaw::Convex
        }
    }
}

/// `M + rho H H^T` on a fixed pattern.
struct ShiftedMass {
    lu: SparseLu,
    /// The rho of the last successful factorization.
    rho: f64,
    /// M's values and `H H^T`'s, slot by slot of the pattern.
    m_values: Vec<f64>,
    hht_values: Vec<f64>,
}

impl ShiftedMass {
    fn new(problem: &GlobalProblem<'_>) -> Result<Self, Fc3dError> {
        let n = problem.ndof();
        let mut positions = Vec::new();
        let mut values = Vec::new();
        problem.m().for_each_entry(|i, j, x| {
            positions.push((i, j));
            values.push((x, 0.0));
        });
        // H H^T = sum over the columns of H of their outer products.
        let ht = crate::matrix::transpose(problem.h())?;
        for j in 0..ht.nrows() {
            let range = ht.row_ptr()[j]..ht.row_ptr()[j + 1];
            let (rows, hv) = (&ht.col_idx()[range.clone()], &ht.values()[range]);
            for (&i, &a) in rows.iter().zip(hv) {
                for (&k, &b) in rows.iter().zip(hv) {
                    positions.push((i, k));
                    values.push((0.0, a * b));
                }
            }
        }
        // A structural diagonal: every shift has the same pattern.
        for i in 0..n {
            positions.push((i, i));
            values.push((0.0, 0.0));
        }
        let (lu, slots) = SparseLu::from_positions(n, &positions, "M + rho H H^T")?;
        let mut m_values = try_vec(lu.nnz(), 0.0, "M + rho H H^T")?;
        let mut hht_values = try_vec(lu.nnz(), 0.0, "M + rho H H^T")?;
        for (&s, &(m, h)) in slots.iter().zip(&values) {
            m_values[s] += m;
            hht_values[s] += h;
        }
        Ok(ShiftedMass {
            lu,
            rho: f64::NAN,
            m_values,
            hht_values,
        })
    }

    fn factor(&mut self, rho: f64) -> bool {
        let values = self.lu.values_mut();
        for ((x, m), h) in values.iter_mut().zip(&self.m_values).zip(&self.hht_values) {
            *x = m + rho * h;
        }
        let ok = self.lu.factor().is_ok();
        if ok {
            self.rho = rho;
        }
        ok
    }
}

/// The global splitting of the ADMM engine.
struct GlobalSplitting<'p, 'a, 'r> {
    problem: &'p GlobalProblem<'a>,
    operator: &'p mut HForm,
    options: GlobalAdmmOptions,
    system: &'p mut ShiftedMass,
    /// A De Saxcé term held fixed (the inner problems of ACLMFP, 612), measured with.
    fixed_s: Option<&'p [f64]>,
    /// `b_s`, the current v and work vectors of the sizes of v (`t`) and of z (`d`).
    b_s: Vec<f64>,
    v: Vec<f64>,
    t: Vec<f64>,
    d: Vec<f64>,
    /// The host's arrays: r (`-rho ξ`) at every iteration, u and v of the measured triple.
    r: &'r mut [f64],
    u: &'r mut [f64],
    v_out: &'r mut [f64],
    tolerance: f64,
    work: ErrorWork,
    /// The error last measured.
    last_error: f64,
    /// `max(||a||, ||b_s||)` of the last linear step: the scale of the primal residual test.
    primal_scale: f64,
}

impl GlobalSplitting<'_, '_, '_> {
    /// `b_s = b + s(H^T v + b)` (De Saxcé's term at the current v), `b + s` for a fixed s, or
    /// b.
    fn update_b_s(&mut self) {
        let p = self.problem;
        self.b_s.copy_from_slice(p.b());
        if let Some(s) = self.fixed_s {
            for (b, x) in self.b_s.iter_mut().zip(s) {
                *b += x;
            }
            return;
        }
        if !self.options.update_s {
            return;
        }
        transpose_mul_add(p.h(), &self.v, &mut self.b_s);
        for (c, &mu) in p.mu().iter().enumerate() {
            let k = 3 * c;
            let u = [self.b_s[k], self.b_s[k + 1], self.b_s[k + 2]];
            let s = modified_velocity(&u, mu)[0] - u[0];
            self.b_s[k] = p.b()[k] + s;
            self.b_s[k + 1] = p.b()[k + 1];
            self.b_s[k + 2] = p.b()[k + 2];
        }
    }
}

impl Splitting for GlobalSplitting<'_, '_, '_> {
    fn split_size(&self) -> usize {
        self.problem.size()
    }
    fn factor_ends_by(&self, deadline: Option<Instant>) -> bool {
        // Predicted before the first factorization when there is a deadline (the pattern is
        // fixed: every refactorization costs what the first one did).
        self.system.lu.predicted_cost().is_none_or(|cost| {
            cost.ends_by_at(crate::math::lu_cost::GLOBAL_LU_FLOPS_PER_SECOND, deadline)
        })
    }
    fn factor(&mut self, rho: f64) -> bool {
        self.system.factor(rho)
    }
    fn linear_step(&mut self, rho: f64, z_hat: &[f64], xi_hat: &[f64], a: &mut [f64]) -> bool {
        let p = self.problem;
        self.update_b_s();
        for k in 0..self.d.len() {
            self.d[k] = rho * (z_hat[k] - self.b_s[k] - xi_hat[k]);
        }
        self.t.copy_from_slice(p.q());
        p.h().mul_add(&self.d, &mut self.t);
        self.system.lu.solve_in_place(&mut self.t);
        if !bounded(&self.t) {
            return false;
        }
        self.v.copy_from_slice(&self.t);
        a.copy_from_slice(&self.b_s);
        transpose_mul_add(p.h(), &self.v, a);
        self.primal_scale = norm(a).max(norm(&self.b_s));
        true
    }
    fn project(&self, w: &[f64], z: &mut [f64]) {
        for (c, &mu) in self.problem.mu().iter().enumerate() {
            let k = 3 * c;
            z[k..k + 3].copy_from_slice(&project_on_dual_cone(&[w[k], w[k + 1], w[k + 2]], mu));
        }
    }
    fn dual_residual(&mut self, z: &[f64], z_hat: &[f64]) -> f64 {
        for ((d, a), b) in self.d.iter_mut().zip(z).zip(z_hat) {
            *d = a - b;
        }
        self.t.iter_mut().for_each(|x| *x = 0.0);
        self.problem.h().mul_add(&self.d, &mut self.t);
        norm(&self.t)
    }
    fn balancing_scales(&mut self, a: &[f64], z: &[f64], xi: &[f64]) -> (f64, f64) {
        let primal = norm(a).max(norm(z)).max(norm(&self.b_s));
        self.t.iter_mut().for_each(|x| *x = 0.0);
        self.problem.h().mul_add(xi, &mut self.t);
        (primal, norm(&self.t))
    }
    fn measure(
        &mut self,
        iteration: usize,
        rho: f64,
        xi: &[f64],
        (primal, dual): (f64, f64),
        observer: &mut Observer<'_>,
    ) -> Option<f64> {
        for (r, x) in self.r.iter_mut().zip(xi) {
            *r = -rho * x;
        }
        // Siconos' ADMM test: primal <= tol (max(||H^T v + b_s||, ||b_s||) + sqrt(m)) and
        // dual <= tol (||rho H ξ|| + sqrt(ndof)), or the iteration of the periodic check.
        let (m, n) = (self.problem.size() as f64, self.problem.ndof() as f64);
        let scheduled = iteration % self.options.error_frequency == 0;
        let passed = !scheduled && primal <= self.tolerance * (self.primal_scale + m.sqrt()) && {
            self.t.iter_mut().for_each(|x| *x = 0.0);
            self.problem.h().mul_add(xi, &mut self.t);
            dual <= self.tolerance * (rho * norm(&self.t) + n.sqrt())
        };
        if !passed && !scheduled {
            return None;
        }
        self.operator
            .global_velocity(self.problem.q(), self.r, self.v_out);
        let error = global_error_with(
            self.problem,
            self.options.law(),
            self.r,
            self.u,
            self.v_out,
            self.fixed_s,
            &mut self.work,
        );
        self.last_error = error;
        observer(&IterationEvent {
            iteration,
            reaction: self.r,
            error,
        });
        Some(error)
    }
}

/// The first rho: given, `||M||_1 / ||H||_1`, or `sqrt(lambda_max lambda_min)` of M.
fn initial_rho(problem: &GlobalProblem<'_>, operator: &mut HForm, options: &AdmmOptions) -> f64 {
    let column_norm = |a: &crate::matrix::CsrMatrix| {
        let mut sums = vec![0.0_f64; a.ncols()];
        a.for_each_entry(|_, j, x| sums[j] += x.abs());
        sums.iter().fold(0.0_f64, |m, &s| m.max(s))
    };
    let rho = match options.initial_rho {
        AdmmInitialRho::Given => options.rho,
        AdmmInitialRho::NormInf => column_norm(problem.m()) / column_norm(problem.h()),
        AdmmInitialRho::Eigenvalues => {
            let n = problem.ndof();
            let mut x = vec![1.0 / (n as f64).sqrt(); n];
            let mut y = vec![0.0; n];
            let mut power = |apply: &mut dyn FnMut(&[f64], &mut [f64])| {
                x.iter_mut().for_each(|v| *v = 1.0 / (n as f64).sqrt());
                let mut lambda = 0.0;
                for _ in 0..100 {
                    apply(&x, &mut y);
                    let ny = norm(&y);
                    if !(ny > 0.0 && ny.is_finite()) {
                        return ny;
                    }
                    x.iter_mut().zip(&y).for_each(|(a, b)| *a = b / ny);
                    let done = (ny - lambda).abs() <= 1e-8 * ny;
                    lambda = ny;
                    if done {
                        break;
                    }
                }
                lambda
            };
            let lambda_max = power(&mut |a, b| {
                b.iter_mut().for_each(|v| *v = 0.0);
                problem.m().mul_add(a, b);
            });
            let inverse_max = power(&mut |a, b| {
                b.copy_from_slice(a);
                operator.solve_mass(b);
            });
            (lambda_max / inverse_max).sqrt()
        }
    };
    if rho > 0.0 && rho.is_finite() {
        rho
    } else {
        1.0
    }
}

/// The global ADMM's factorization and current rho, kept from run to run (ACLMFP's outer
/// iterations solve a sequence of problems with the same M and H).
pub(super) struct GlobalAdmm {
    system: ShiftedMass,
}

impl GlobalAdmm {
    /// Builds `M + rho H H^T` (pattern, symbolic analysis) and factors it for the first rho;
    /// `None` (nothing done that cannot be interrupted past `deadline`) when the set-up
    /// ([`crate::math::lu_cost::assembly_ends_by`]) or the factorization
    /// ([`SparseLu::factor_ends_by`]) is predicted to end past `deadline`.
    pub fn new(
        problem: &GlobalProblem<'_>,
        operator: &mut HForm,
        options: &AdmmOptions,
        deadline: Option<Instant>,
    ) -> Result<Option<Self>, Fc3dError> {
        // The positions of M, of each column of H's outer product (k touched unknowns a row of
        // H^T, 3 rows a contact) and of the diagonal.
        let entries = super::set_up_entries(problem, |k| 3.0 * k * k, problem.ndof());
        if !crate::math::lu_cost::assembly_ends_by(entries, deadline) {
            return Ok(None);
        }
        let rho = initial_rho(problem, operator, options);
        let mut system = ShiftedMass::new(problem)?;
        if !system
            .lu
            .factor_ends_by(deadline, "global ADMM: M + rho H H^T")?
        {
            return Ok(None);
        }
        if !system.factor(rho) {
            return Err(Fc3dError::Unsupported(format!(
                "global ADMM: M + rho H H^T is singular for rho = {rho}"
            )));
        }
        Ok(Some(GlobalAdmm { system }))
    }

    /// Runs ADMM from the reaction in `r` with the current rho; `fixed_s`: a De Saxcé term
    /// held fixed (and measured with: the convex error of the problem with `b + s`). Returns
    /// the outcome and the error measured last (in that measure).
    #[allow(clippy::too_many_arguments)]
    pub fn run(
        &mut self,
        problem: &GlobalProblem<'_>,
        operator: &mut HForm,
        options: &GlobalAdmmOptions,
        run: &Run,
        fixed_s: Option<&[f64]>,
        r: &mut [f64],
        u: &mut [f64],
        v: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<(SolverOutcome, f64), Fc3dError> {
        let (n, m) = (problem.ndof(), problem.size());
        let rho = self.system.rho;
        // Siconos starts from u = 0 and the given reaction as the multiplier.
        let z0 = vec![0.0; m];
        let xi0: Vec<f64> = r.iter().map(|x| -x / rho).collect();
        let mut v0 = try_vec(n, 0.0, "the global ADMM velocity")?;
        operator.global_velocity(problem.q(), r, &mut v0);
        let mut splitting = GlobalSplitting {
            problem,
            operator,
            options: *options,
            system: &mut self.system,
            fixed_s,
            b_s: vec![0.0; m],
            v: v0,
            t: vec![0.0; n],
            d: vec![0.0; m],
            r,
            u,
            v_out: v,
            tolerance: run.tolerance,
            work: ErrorWork::new(n),
            last_error: f64::INFINITY,
            primal_scale: 0.0,
        };
        let outcome = iterate(
            &mut splitting,
            &options.admm,
            run,
            rho,
            1.0,
            &z0,
            &xi0,
            observer,
        )?;
        Ok((outcome, splitting.last_error))
    }
}

/// Runs the global ADMM (613) from the reaction in `r`.
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &GlobalAdmmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let run = limits.start();
    let Some(mut admm) = GlobalAdmm::new(problem, operator, &options.admm, run.deadline())? else {
        // Out of time before the set-up or the first factorization: r as it came.
        return Ok(SolverOutcome::stopped(0, true));
    };
    let (outcome, last_error) =
        admm.run(problem, operator, options, &run, None, r, u, v, observer)?;
    let relaxation_converged = !options.update_s && last_error <= run.tolerance;
    // The solve measures the Coulomb error of the returned triple.
    Ok(SolverOutcome {
        relaxation_converged,
        ..outcome.with_final_error(None)
    })
}

//! ADMM on the local formulation (Siconos' `fc3d_admm`, id 523, and `rolling_fc3d_admm`, id
//! 3003: the same iteration with the rolling cone and its De Saxcé term, through
//! [`AdmmProblem`]).
//!
//! With De Saxcé's term `s(u)_c = (mu_c ||u_{T,c}||, 0, 0)` frozen at the last velocity, r solves
//! FC(W, q, mu) iff `0 ∈ W r + q + s + N_K(r)`. ADMM splits `r = z`, `z ∈ K` (scaled dual `ξ`);
//! each iteration, as Siconos 4.4's (its "symmetric" variant, the one its default options run):
//!
//! * `s = s(W x + q)` at the previous x (the starting reaction for the first iteration);
//! * `x = (W + rho I)^{-1} (rho (ẑ - ξ̂) - q - s)` (the resolvent of the affine part: valid for
//!   a non-symmetric W, which is never symmetrized);
//! * `z = P_K(x + ξ̂)`;
//! * `ξ = ξ̂ + x - z`;
//! * the iterate measured and returned is x (as Siconos'; x = z at a fixed point).
//!
//! At a fixed point `rho ξ = -(W z + q + s) ∈ N_K(z)`, which is the frictional contact law.
//! `(ẑ, ξ̂)` are the previous iterates, or their Nesterov extrapolation when accelerated (fast ADMM
//! of Goldstein-O'Donoghue-Setzer-Baraniuk, with the optional restart on the combined residual).
//! The penalty rho starts from a given value, `||W||_inf`, or `sqrt(lambda_max lambda_min)` of W,
//! and may follow residual balancing (Boyd et al. §3.4.1). `W + rho I` is factored with faer's
//! sparse LU once per rho value (symbolic analysis once per solve).
//!
//! One difference from Siconos, in the stopping test only: fc3d measures the natural-map error
//! of x at every iteration (free: `W x + q` is needed for the next De Saxcé term), where Siconos
//! measures it only once its primal and dual residuals pass; fc3d therefore stops at the first
//! iteration whose error is below the tolerance, never later than Siconos on the same iterates.

mod engine;
mod settings;

pub use settings::{AdmmAcceleration, AdmmInitialRho, AdmmOptions, AdmmRhoStrategy};

pub(crate) use engine::{iterate, Splitting};

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{CreationError, FaerError, SparseColMat, Triplet};
use faer::{Conj, MatMut, Par};

use std::time::Instant;

use crate::alloc::{reserve, try_push};
use crate::contract::{
    deadline_passed, Family, Fill, IterationEvent, Limits, Observer, SolverOutcome,
};
use crate::error::{try_copy, try_vec, Fc3dError};
use crate::math::cone::{modified_velocity, project_on_cone};
use crate::math::linalg::{bounded, contact_of, distance_sq, norm};
use crate::math::lu_cost::{checked_lu_cost, LuCost};
use crate::math::lu_fill::lu_factor_nnz;
use crate::math::rolling::{project_on_rolling_cone, rolling_modified_velocity};
use crate::matrix::Delassus;
use crate::measure::{natural_map_error_of, relative_rolling_error};
use crate::problem::{FrictionProblem, RollingProblem};

impl Family for AdmmOptions {
    fn name(&self) -> &'static str {
        "ADMM"
    }

    fn label(&self) -> String {
        "ADMM".to_string()
    }

    fn siconos_id(&self) -> i32 {
        523
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-6, 20000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        AdmmOptions::validate(self)
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        admm(problem, self, limits, r, u, observer)
    }
}

/// `W + rho I` in CSC with its LU; the diagonal positions let a new rho be set without rebuilding.
struct ShiftedSystem {
    matrix: SparseColMat<usize, f64>,
    diagonal_positions: Vec<usize>,
    shift: f64,
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    factor_scratch: MemBuffer,
    solve_scratch: MemBuffer,
    factored: bool,
    /// `nnz(L) + nnz(U)` of the first successful factorization.
    factor_nnz: Option<usize>,
    /// The predicted cost of one factorization (from the symbolic analysis).
    cost: LuCost,
}

impl ShiftedSystem {
    fn new(w: &Delassus<'_>) -> Result<Self, Fc3dError> {
        let n = w.nrows();
        let mut triplets = Vec::new();
        let mut stored = Ok(());
        w.for_each_entry(|i, j, v| {
            if v != 0.0 && stored.is_ok() {
                stored = try_push(&mut triplets, Triplet::new(i, j, v), "the ADMM matrix");
            }
        });
        stored?;
        // Structural diagonal, so that every shift has the same pattern.
        reserve(&mut triplets, n, "the ADMM matrix")?;
        triplets.extend((0..n).map(|i| Triplet::new(i, i, 0.0)));
        let matrix =
            SparseColMat::<usize, f64>::try_new_from_triplets(n, n, &triplets).map_err(|e| {
                let oom = matches!(e, CreationError::Generic(FaerError::OutOfMemory));
                faer_failure("ADMM: W + rho I", oom, e)
            })?;
        let sym = matrix.symbolic();
        let mut diagonal_positions = try_vec(n, 0, "the ADMM work arrays")?;
        for (j, pos) in diagonal_positions.iter_mut().enumerate() {
            let range = sym.col_ptr()[j]..sym.col_ptr()[j + 1];
            *pos = range
                .clone()
                .find(|&k| sym.row_idx()[k] == j)
                .expect("the diagonal was inserted");
        }
        let symbolic = factorize_symbolic_lu(sym, Default::default())
            .map_err(|e| faer_failure("ADMM: symbolic LU", e == FaerError::OutOfMemory, e))?;
        let cost = checked_lu_cost(sym, symbolic.col_perm(), "ADMM: LU factors of W + rho I")?;
        let factor_scratch = MemBuffer::try_new(
            symbolic.factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default()),
        )
        .map_err(|e| faer_failure("ADMM: LU scratch", true, e))?;
        let solve_scratch = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
            .map_err(|e| faer_failure("ADMM: LU scratch", true, e))?;
        Ok(ShiftedSystem {
            matrix,
            diagonal_positions,
            shift: 0.0,
            symbolic,
            numeric: NumericLu::new(),
            factor_scratch,
            solve_scratch,
            factored: false,
            factor_nnz: None,
            cost,
        })
    }

    /// Factors `W + shift I`; false when the LU fails (singular matrix).
    fn factor(&mut self, shift: f64) -> bool {
        let delta = shift - self.shift;
        let values = self.matrix.val_mut();
        for &p in &self.diagonal_positions {
            values[p] += delta;
        }
        self.shift = shift;
        self.factored = self
            .symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                self.matrix.as_ref(),
                Par::Seq,
                MemStack::new(&mut self.factor_scratch),
                Default::default(),
            )
            .is_ok();
        if self.factored && self.factor_nnz.is_none() {
            let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
            let pattern = self.matrix.symbolic();
            self.factor_nnz = lu_factor_nnz(
                pattern.nrows(),
                pattern.col_ptr(),
                pattern.row_idx(),
                lu.row_perm().arrays().1,
                lu.col_perm().arrays().0,
            );
        }
        self.factored
    }

    /// The fill of the first factorization, once one succeeded.
    fn fill(&self) -> Option<Fill> {
        self.factor_nnz.map(|factor_nnz| Fill {
            matrix_nnz: self.matrix.val().len(),
            factor_nnz,
        })
    }

    /// `x <- (W + shift I)^{-1} x`.
    fn solve_in_place(&mut self, x: &mut [f64]) {
        let n = x.len();
        let lu = LuRef::new_unchecked(&self.symbolic, &self.numeric);
        let rhs = MatMut::from_column_major_slice_mut(x, n, 1);
        lu.solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut self.solve_scratch),
        );
    }
}

/// Modulus of the dominant eigenvalue of `apply` by power iterations from `x` (overwritten).
fn power_iteration(
    x: &mut [f64],
    y: &mut [f64],
    deadline: Option<Instant>,
    mut apply: impl FnMut(&[f64], &mut [f64]),
) -> f64 {
    let n = x.len() as f64;
    x.iter_mut().for_each(|v| *v = 1.0 / n.sqrt());
    let mut lambda = 0.0;
    for k in 0..100 {
        if k > 0 && deadline_passed(deadline) {
            break;
        }
        apply(x, y);
        let ny = norm(y);
        if !(ny > 0.0 && ny.is_finite()) {
            return ny;
        }
        x.iter_mut().zip(y.iter()).for_each(|(a, b)| *a = b / ny);
        let converged = (ny - lambda).abs() <= 1e-8 * ny;
        lambda = ny;
        if converged {
            break;
        }
    }
    lambda
}

/// A failure of faer building the shifted system: [`Fc3dError::OutOfMemory`] when it could not
/// allocate, otherwise a structure it refused.
fn faer_failure(what: &str, out_of_memory: bool, detail: impl std::fmt::Debug) -> Fc3dError {
    if out_of_memory {
        Fc3dError::OutOfMemory {
            what: format!("{what} ({detail:?})"),
            bytes: 0,
        }
    } else {
        Fc3dError::InvalidStructure(format!("{what}: {detail:?}"))
    }
}

/// `||W||_inf`, the largest absolute row sum, when positive and finite.
fn norm_inf(w: &Delassus<'_>) -> Result<Option<f64>, Fc3dError> {
    let mut row_sums = try_vec(w.nrows(), 0.0, "the ADMM work arrays")?;
    w.for_each_entry(|i, _, v| row_sums[i] += v.abs());
    let norm_inf = row_sums.iter().fold(0.0_f64, |a, &b| a.max(b));
    Ok((norm_inf > 0.0 && norm_inf.is_finite()).then_some(norm_inf))
}

/// See [`AdmmInitialRho::Eigenvalues`].
const EIGENVALUE_RATIO_FLOOR: f64 = 1e-2;

fn initial_rho(
    w: &Delassus<'_>,
    options: &AdmmOptions,
    system: &mut ShiftedSystem,
    work: (&mut [f64], &mut [f64]),
    deadline: Option<Instant>,
) -> Result<f64, Fc3dError> {
    let (x, y) = work;
    Ok(match options.initial_rho {
        AdmmInitialRho::Given => options.rho,
        AdmmInitialRho::NormInf => norm_inf(w)?.unwrap_or(options.rho),
        AdmmInitialRho::Eigenvalues => {
            let lambda_max = power_iteration(x, y, deadline, |a, b| {
                b.iter_mut().for_each(|v| *v = 0.0);
                w.mul_add(a, b);
            });
            if !(lambda_max > 0.0 && lambda_max.is_finite()) {
                return Ok(options.rho);
            }
            let floor = EIGENVALUE_RATIO_FLOOR * lambda_max;
            let lambda_min = if system.cost.ends_by(deadline) && system.factor(0.0) {
                let inverse_max = power_iteration(x, y, deadline, |a, b| {
                    b.copy_from_slice(a);
                    system.solve_in_place(b);
                });
                if inverse_max.is_finite() && inverse_max > 0.0 {
                    (1.0 / inverse_max).max(floor)
                } else {
                    floor
                }
            } else {
                floor
            };
            (lambda_max * lambda_min).sqrt()
        }
    })
}

/// What ADMM needs of a problem beyond W and q: the De Saxcé term of its law and the projection
/// on its cones, and the error its results are judged by. The Coulomb problem (3D) and the
/// rolling problems (5D, 3D) share the iteration through it.
pub(crate) trait AdmmProblem {
    fn w(&self) -> &Delassus<'_>;
    fn q(&self) -> &[f64];
    /// `u = W r + q`.
    fn velocity(&self, r: &[f64], u: &mut [f64]);
    /// `s = ũ(u) - u`: the De Saxcé term, non-zero in the normal components only.
    fn de_saxce_term(&self, u: &[f64], s: &mut [f64]);
    /// `z_c = P_{K_c}(v_c)` for every contact.
    fn project(&self, v: &[f64], z: &mut [f64]);
    /// The relative natural-map error of `(r, u)`, `u = W r + q` given.
    fn error_of(&self, r: &[f64], u: &[f64]) -> f64;
}

impl AdmmProblem for FrictionProblem<'_> {
    fn w(&self) -> &Delassus<'_> {
        FrictionProblem::w(self)
    }
    fn q(&self) -> &[f64] {
        FrictionProblem::q(self)
    }
    fn velocity(&self, r: &[f64], u: &mut [f64]) {
        FrictionProblem::velocity(self, r, u)
    }
    /// `s_c = (mu_c ||u_{T,c}||, 0, 0)`.
    fn de_saxce_term(&self, u: &[f64], s: &mut [f64]) {
        for (c, &m) in self.mu().iter().enumerate() {
            let k = 3 * c;
            let ut = modified_velocity(&[u[k], u[k + 1], u[k + 2]], m);
            s[k] = ut[0] - u[k];
            s[k + 1] = 0.0;
            s[k + 2] = 0.0;
        }
    }
    fn project(&self, v: &[f64], z: &mut [f64]) {
        for (c, &m) in self.mu().iter().enumerate() {
            let k = 3 * c;
            z[k..k + 3].copy_from_slice(&project_on_cone(&[v[k], v[k + 1], v[k + 2]], m));
        }
    }
    fn error_of(&self, r: &[f64], u: &[f64]) -> f64 {
        natural_map_error_of(self, r, u)
    }
}

impl<const D: usize> AdmmProblem for RollingProblem<'_, D> {
    fn w(&self) -> &Delassus<'_> {
        RollingProblem::w(self)
    }
    fn q(&self) -> &[f64] {
        RollingProblem::q(self)
    }
    fn velocity(&self, r: &[f64], u: &mut [f64]) {
        RollingProblem::velocity(self, r, u)
    }
    /// `s_c = (mu_c ||u_{T,c}|| + mu_r,c ||u_{R,c}||, 0, ..., 0)`.
    fn de_saxce_term(&self, u: &[f64], s: &mut [f64]) {
        for (c, (&m, &mr)) in self.mu().iter().zip(self.mu_r()).enumerate() {
            let uc: [f64; D] = contact_of(u, c);
            let ut = rolling_modified_velocity(&uc, m, mr);
            let sc = &mut s[D * c..D * c + D];
            sc.iter_mut().for_each(|v| *v = 0.0);
            sc[0] = ut[0] - uc[0];
        }
    }
    fn project(&self, v: &[f64], z: &mut [f64]) {
        for (c, (&m, &mr)) in self.mu().iter().zip(self.mu_r()).enumerate() {
            let vc: [f64; D] = contact_of(v, c);
            z[D * c..D * c + D].copy_from_slice(&project_on_rolling_cone(&vc, m, mr));
        }
    }
    fn error_of(&self, r: &[f64], u: &[f64]) -> f64 {
        relative_rolling_error::<D>(r, u, self.mu(), self.mu_r(), norm(self.q()))
    }
}

/// Runs ADMM from the reaction in `r`; on return `r = z` and `u = W r + q`, and the outcome has
/// the fill of `W + rho I`'s first factorization.
pub(crate) fn admm<P: AdmmProblem>(
    problem: &P,
    options: &AdmmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let mut fill = None;
    let outcome = admm_iterations(problem, options, limits, r, u, observer, &mut fill)?;
    Ok(outcome.with_fill(fill))
}

/// [`admm`]'s iterations; `fill` is set once `W + rho I` was factored.
fn admm_iterations<P: AdmmProblem>(
    problem: &P,
    options: &AdmmOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
    fill: &mut Option<Fill>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let n = problem.w().nrows();
    let run = limits.start();
    // Neither the analysis nor a factorization can be interrupted: one predicted to end past
    // the deadline is not started, and the run stops out of time with r as it came.
    if let Some(stop) =
        super::stop_before_analysis(problem.w(), run.deadline(), || problem.velocity(r, u))
    {
        return Ok(stop);
    }
    let mut system = ShiftedSystem::new(problem.w())?;

    let mut x = try_vec(n, 0.0, "the ADMM work arrays")?;
    let mut scratch = try_vec(n, 0.0, "the ADMM work arrays")?;
    let mut rho = initial_rho(
        problem.w(),
        options,
        &mut system,
        (&mut x, &mut scratch),
        run.deadline(),
    )?;
    if !(rho > 0.0 && rho.is_finite()) {
        rho = 1.0;
    }
    // Siconos' scalar rescaling runs the iteration on (W / a, q / a), a = ||W||_inf, with the
    // rho chosen for W: the same iterates as rho a on (W, q), with the dual residual in the
    // rescaled units (rho ||z - ẑ||, divided by a).
    let scale = if options.scalar_rescaling {
        norm_inf(problem.w())?.unwrap_or(1.0)
    } else {
        1.0
    };
    rho *= scale;
    // A factorization cannot be interrupted: one predicted to end past the deadline is not
    // started, and the run stops out of time with r as it came.
    if !system.cost.ends_by(run.deadline()) {
        problem.velocity(r, u);
        return Ok(SolverOutcome::stopped(0, true));
    }
    if !system.factor(rho) {
        return Err(Fc3dError::InvalidStructure(format!(
            "ADMM: W + rho I is singular for rho = {rho}"
        )));
    }
    *fill = system.fill();

    // Siconos' iteration (its "symmetric" ADMM, the one its default options run): the iterate
    // is the solution x of the linear step, the De Saxcé term is taken at u = W x + q, and x is
    // what is measured and returned (z = P_K(x + ξ̂) is the feasible copy; x = z at a fixed
    // point). It starts from the given reaction as x, z and ẑ, with ξ = 0.
    problem.velocity(r, u);
    let z0 = try_copy(r, "the ADMM work arrays")?;
    let xi0 = try_vec(n, 0.0, "the ADMM work arrays")?;
    let mut splitting = LocalSplitting {
        problem,
        system,
        x,
        s: try_vec(n, 0.0, "the ADMM work arrays")?,
        r,
        u,
    };
    iterate(
        &mut splitting,
        options,
        &run,
        rho,
        scale,
        &z0,
        &xi0,
        observer,
    )
}

/// The local formulation's splitting: `r = z`, `z ∈ K`, the linear step
/// `(W + rho I) x = rho (ẑ - ξ̂) - q - s(W x_prev + q)`; the measured iterate is x, written to
/// the host's r (and `u = W r + q`) at every iteration.
struct LocalSplitting<'p, 'r, P: AdmmProblem> {
    problem: &'p P,
    system: ShiftedSystem,
    x: Vec<f64>,
    s: Vec<f64>,
    r: &'r mut [f64],
    u: &'r mut [f64],
}

impl<P: AdmmProblem> Splitting for LocalSplitting<'_, '_, P> {
    fn split_size(&self) -> usize {
        self.x.len()
    }
    fn factor_ends_by(&self, deadline: Option<Instant>) -> bool {
        self.system.cost.ends_by(deadline)
    }
    fn factor(&mut self, rho: f64) -> bool {
        self.system.factor(rho)
    }
    fn linear_step(&mut self, rho: f64, z_hat: &[f64], xi_hat: &[f64], a: &mut [f64]) -> bool {
        // x-update: (W + rho I) x = rho (ẑ - ξ̂) - q - s(W x_prev + q).
        let q = self.problem.q();
        self.problem.de_saxce_term(self.u, &mut self.s);
        for i in 0..self.x.len() {
            self.x[i] = rho * (z_hat[i] - xi_hat[i]) - q[i] - self.s[i];
        }
        self.system.solve_in_place(&mut self.x);
        if !bounded(&self.x) {
            // Diverging, or the factorization lost all accuracy: keep the last x (r and
            // u = W r + q are still those of the previous iteration) and stop.
            return false;
        }
        a.copy_from_slice(&self.x);
        true
    }
    fn project(&self, w: &[f64], z: &mut [f64]) {
        self.problem.project(w, z);
    }
    fn dual_residual(&mut self, z: &[f64], z_hat: &[f64]) -> f64 {
        distance_sq(z, z_hat).sqrt()
    }
    fn balancing_scales(&mut self, a: &[f64], z: &[f64], xi: &[f64]) -> (f64, f64) {
        (engine::primal_scale(a, z), norm(xi))
    }
    fn measure(
        &mut self,
        iteration: usize,
        _rho: f64,
        _xi: &[f64],
        _residuals: (f64, f64),
        observer: &mut Observer<'_>,
    ) -> Option<f64> {
        self.r.copy_from_slice(&self.x);
        self.problem.velocity(self.r, self.u);
        let error = self.problem.error_of(self.r, self.u);
        observer(&IterationEvent {
            iteration,
            reaction: self.r,
            error,
        });
        Some(error)
    }
}

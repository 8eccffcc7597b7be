//! fc3d's semismooth Newton augmented Lagrangian on the global problem (SSN-ALM, fc3d id 690,
//! not a Siconos id): the method of multipliers in the bodies' velocities with Newton steps on
//! matrices of M's size. No W is formed and nothing of W's size is factored.
//!
//! For a multiplier estimate r (the reaction) and a penalty rho, each outer iteration solves
//!
//! `F(v) = M v - q - H p(v) = 0`,  `p_c(v) = P_K(r_c - rho (u_c + mu ||u_T,c|| e_N))`,
//! `u = H^T v + b`,
//!
//! by semismooth Newton with an Armijo search on `||F||^2 / 2`, then sets `r = p(v)`. A fixed
//! point is a Coulomb solution: `r = P_K(r - rho (u + s(u)))` with De Saxcé's `s(u) = mu
//! ||u_T|| e_N`, and `M v = q + H r`. Without De Saxcé's term, F is the gradient of the
//! augmented Lagrangian of the convex program `min v^T M v / 2 - q^T v`, `H^T v + b ∈ K*`, and
//! the outer loop is the proximal point method on its dual.
//!
//! The Newton matrix is `M + rho H D (I + e_N g^T) H^T` (D the 3x3 Jacobian of the projection
//! on each contact's cone, g the gradient of De Saxcé's term): its symmetric part without g,
//! `(M + M^T)/2 + rho H D H^T`, is positive definite however many contacts there are (a
//! hyperstatic pile makes W singular, not this matrix) and is factored by a sparse Cholesky on
//! a pattern fixed for the run (AMD order and symbolic analysis once). Where no contact slides
//! and M is symmetric it is the Newton matrix; otherwise it preconditions GMRES on the true
//! one (products through H, D, g and M only).
//!
//! Between outer iterations the multiplier is extrapolated (Nesterov, restarted when the error
//! grows). What limits the method on tall piles is measured in docs/convergence.md: the outer
//! loop, not the linear algebra.

use crate::contract::{IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::{require_setting, try_copy, try_vec, Fc3dError};
use crate::math::cone::project_on_cone;
use crate::math::gmres::Gmres;
use crate::math::linalg::{norm, Mat3, Vec3};
use crate::math::sparse_cholesky::SparseCholesky;
use crate::matrix::{transpose, transpose_mul_add, CsrMatrix, HForm};
use crate::measure::{global_error_with, ContactLaw, ErrorWork};
use crate::problem::GlobalProblem;

/// Settings of the SSN-ALM (fc3d's own method, id 690); the defaults are fc3d's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GlobalAlmOptions {
    /// The penalty as a multiple of `trace(M) / ||H||_F^2` (about the inverse of W's mean
    /// diagonal entry): 1 makes `rho H H^T` of M's size. Default 100 (measured on generated
    /// sphere piles of 1k contacts: 30 and 300 take 321 and 290 Newton steps to 1e-4 against 248,
    /// and 1000 does not reach it: the larger rho, the more the Newton steps chatter across the kinks of the
    /// sticking contacts); > 0.
    pub rho_factor: f64,
    /// The factor rho grows by when an outer iteration did not divide the law's residual by at
    /// least [`GlobalAlmOptions::progress`]. Default 1 (rho fixed: growing it by 10 from a
    /// factor of 1 ended in the chattering regime); >= 1.
    pub rho_growth: f64,
    /// Largest rho, as a multiple of the first one. Default 100; >= 1.
    pub rho_max_factor: f64,
    /// The least factor the law's residual must fall by in an outer iteration for rho to stay.
    /// Default 0.25; in (0, 1].
    pub progress: f64,
    /// Newton's inner tolerance on `||grad phi||` relative to the balance's scale
    /// `max(||q||, ||M v||, ||H r||)`, as a multiple of the last outer error (with at most the
    /// outer tolerance times this ratio). Default 0.1; in (0, 1].
    pub inner_ratio: f64,
    /// Newton steps per outer iteration at most. Default 50; >= 1.
    pub inner_max_iter: usize,
    /// Trial steps of the Armijo search at most (halving). Default 40; >= 1.
    pub line_search_max_iter: usize,
    /// GMRES' relative tolerance on a Newton step where the Newton matrix is not the factored
    /// symmetric one (sliding contacts, a non-symmetric M). Default 1e-3; in (0, 1).
    pub linear_tolerance: f64,
    /// GMRES' products with the Newton matrix at most a step. Default 40; >= 1.
    pub linear_max_products: usize,
    /// Nesterov's extrapolation of the multiplier between outer iterations (Güler's
    /// accelerated proximal point), restarted when the error grows. Default true (on 1k-contact
    /// sphere piles: 207 Newton steps to 1e-4 against 248, 1.2e-6 against 3.7e-6 after 15 s).
    pub accelerate: bool,
}

/// GMRES' restart length (Krylov vectors kept: 20 vectors of M's size).
const GMRES_RESTART: usize = 20;

impl Default for GlobalAlmOptions {
    fn default() -> Self {
        GlobalAlmOptions {
            rho_factor: 100.0,
            rho_growth: 1.0,
            rho_max_factor: 100.0,
            progress: 0.25,
            inner_ratio: 0.1,
            inner_max_iter: 50,
            line_search_max_iter: 40,
            linear_tolerance: 1e-3,
            linear_max_products: 40,
            accelerate: true,
        }
    }
}

impl GlobalAlmOptions {
    pub fn validate(&self) -> Result<(), Fc3dError> {
        let positive = |x: f64| x > 0.0 && x.is_finite();
        require_setting(
            positive(self.rho_factor),
            "global_alm.rho_factor",
            self.rho_factor,
            "finite and > 0",
        )?;
        require_setting(
            self.rho_growth >= 1.0 && self.rho_growth.is_finite(),
            "global_alm.rho_growth",
            self.rho_growth,
            "finite and >= 1",
        )?;
        require_setting(
            self.rho_max_factor >= 1.0 && self.rho_max_factor.is_finite(),
            "global_alm.rho_max_factor",
            self.rho_max_factor,
            "finite and >= 1",
        )?;
        require_setting(
            self.progress > 0.0 && self.progress <= 1.0,
            "global_alm.progress",
            self.progress,
            "in (0, 1]",
        )?;
        require_setting(
            self.inner_ratio > 0.0 && self.inner_ratio <= 1.0,
            "global_alm.inner_ratio",
            self.inner_ratio,
            "in (0, 1]",
        )?;
        require_setting(
            self.inner_max_iter >= 1,
            "global_alm.inner_max_iter",
            self.inner_max_iter,
            ">= 1",
        )?;
        require_setting(
            self.line_search_max_iter >= 1,
            "global_alm.line_search_max_iter",
            self.line_search_max_iter,
            ">= 1",
        )?;
        require_setting(
            self.linear_tolerance > 0.0 && self.linear_tolerance < 1.0,
            "global_alm.linear_tolerance",
            self.linear_tolerance,
            "in (0, 1)",
        )?;
        require_setting(
            self.linear_max_products >= 1,
            "global_alm.linear_max_products",
            self.linear_max_products,
            ">= 1",
        )
    }
}

/// The projection on `K = {||x_T|| <= mu x_N}` and its Jacobian at x (symmetric, eigenvalues
/// in [0, 1]; at the kinks the one-sided choice: the identity on the cone's boundary, 0 at
/// its polar's).
fn project_with_jacobian(x: &Vec3, mu: f64) -> (Vec3, Mat3) {
    let t = x[1].hypot(x[2]);
    if t <= mu * x[0] {
        return (*x, [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
    }
    if mu * t <= -x[0] {
        return ([0.0; 3], [[0.0; 3]; 3]);
    }
    // Here t > 0: the projection lands on the cone's surface.
    let a = 1.0 / (1.0 + mu * mu);
    let normal = a * (x[0] + mu * t);
    let e = [x[1] / t, x[2] / t];
    let p = [normal, mu * normal * e[0], mu * normal * e[1]];
    let curvature = mu * normal / t;
    let mut d = [[0.0; 3]; 3];
    d[0][0] = a;
    for i in 0..2 {
        d[0][i + 1] = a * mu * e[i];
        d[i + 1][0] = a * mu * e[i];
        for j in 0..2 {
            let identity = if i == j { 1.0 } else { 0.0 };
            d[i + 1][j + 1] = a * mu * mu * e[i] * e[j] + curvature * (identity - e[i] * e[j]);
        }
    }
    (p, d)
}

/// The contacts' columns of H as small dense blocks, and the symmetric matrix
/// `(M + M^T) / 2 + rho sum_c H_c D_c H_c^T` (D_c the projection's Jacobian) on a fixed pattern,
/// Cholesky-factored: the Newton matrix without De Saxcé's derivative, the preconditioner of
/// the Newton step.
struct BodySystem {
    cholesky: SparseCholesky,
    /// The symmetric part of M's values, slot by slot of the lower triangle (zero elsewhere).
    m_values: Vec<f64>,
    /// Contact c's block of H is `h_blocks[3 offsets[c]..3 offsets[c + 1]]`, one row of 3 a
    /// touched unknown (in increasing order).
    offsets: Vec<usize>,
    h_blocks: Vec<f64>,
    /// The slots of the pairs `(a, b)`, `b <= a`, of contact c's unknowns, row by row, from
    /// `slot_offsets[c]`.
    slots: Vec<u32>,
    slot_offsets: Vec<usize>,
}

impl BodySystem {
    fn new(problem: &GlobalProblem<'_>, ht: &CsrMatrix) -> Result<Self, Fc3dError> {
        let (n, nc) = (problem.ndof(), problem.n_contacts());
        let mut offsets = try_vec(nc + 1, 0usize, "the SSN-ALM contact offsets")?;
        let mut dofs = Vec::new();
        let mut h_blocks = Vec::new();
        let mut row = Vec::new();
        for c in 0..nc {
            row.clear();
            for j in 3 * c..3 * c + 3 {
                row.extend_from_slice(&ht.col_idx()[ht.row_ptr()[j]..ht.row_ptr()[j + 1]]);
            }
            row.sort_unstable();
            row.dedup();
            dofs.try_reserve(row.len())
                .map_err(|_| oom("the SSN-ALM contact unknowns", row.len()))?;
            h_blocks
                .try_reserve(3 * row.len())
                .map_err(|_| oom("the SSN-ALM blocks of H", 3 * row.len()))?;
            for &i in &row {
                dofs.push(i);
                for j in 3 * c..3 * c + 3 {
                    h_blocks.push(ht.get(j, i));
                }
            }
            offsets[c + 1] = dofs.len();
        }
        let triangle = |k: usize| k * (k + 1) / 2;
        let pairs: usize = (0..nc).map(|c| triangle(offsets[c + 1] - offsets[c])).sum();
        let mut positions = Vec::new();
        positions
            .try_reserve(problem.m().nnz() + pairs + n)
            .map_err(|_| oom("the SSN-ALM pattern", pairs))?;
        problem.m().for_each_entry(|i, j, _| positions.push((i, j)));
        let m_entries = positions.len();
        for c in 0..nc {
            let d = &dofs[offsets[c]..offsets[c + 1]];
            for (a, &i) in d.iter().enumerate() {
                for &j in &d[..=a] {
                    positions.push((i, j));
                }
            }
        }
        // A structural diagonal: M's may have holes where an unknown has no mass of its own.
        for i in 0..n {
            positions.push((i, i));
        }
        let (cholesky, all_slots) =
            SparseCholesky::from_positions(n, &positions, "the SSN-ALM matrix M + rho H D H^T")?;
        if cholesky.nnz() > u32::MAX as usize {
            return Err(Fc3dError::Unsupported(format!(
                "the SSN-ALM matrix has {} entries, more than 2^32",
                cholesky.nnz()
            )));
        }
        let mut m_values = try_vec(cholesky.nnz(), 0.0, "the SSN-ALM matrix")?;
        let mut k = 0;
        problem.m().for_each_entry(|i, j, x| {
            // (i, j) and (j, i) share a slot: each brings half of the symmetric part.
            m_values[all_slots[k]] += if i == j { x } else { 0.5 * x };
            k += 1;
        });
        let mut slots = try_vec(pairs, 0u32, "the SSN-ALM slots")?;
        for (s, &a) in slots
            .iter_mut()
            .zip(&all_slots[m_entries..m_entries + pairs])
        {
            *s = a as u32;
        }
        let mut slot_offsets = try_vec(nc + 1, 0usize, "the SSN-ALM slot offsets")?;
        for c in 0..nc {
            slot_offsets[c + 1] = slot_offsets[c] + triangle(offsets[c + 1] - offsets[c]);
        }
        Ok(BodySystem {
            cholesky,
            m_values,
            offsets,
            h_blocks,
            slots,
            slot_offsets,
        })
    }

    /// Writes `(M + M^T) / 2 + rho sum_c H_c D_c H_c^T` (D_c symmetric) and factors it.
    fn factor(&mut self, rho: f64, jacobians: &[Mat3], active: &[bool]) -> bool {
        let values = self.cholesky.values_mut();
        values.copy_from_slice(&self.m_values);
        for (c, d) in jacobians.iter().enumerate() {
            if !active[c] {
                continue;
            }
            let rows = &self.h_blocks[3 * self.offsets[c]..3 * self.offsets[c + 1]];
            let k = self.offsets[c + 1] - self.offsets[c];
            let slots = &self.slots[self.slot_offsets[c]..self.slot_offsets[c + 1]];
            let mut slot = 0;
            for a in 0..k {
                let ha = [rows[3 * a], rows[3 * a + 1], rows[3 * a + 2]];
                // rho (H_a D), then its product with each row b <= a.
                let hd = [
                    rho * (ha[0] * d[0][0] + ha[1] * d[1][0] + ha[2] * d[2][0]),
                    rho * (ha[0] * d[0][1] + ha[1] * d[1][1] + ha[2] * d[2][1]),
                    rho * (ha[0] * d[0][2] + ha[1] * d[1][2] + ha[2] * d[2][2]),
                ];
                for b in 0..=a {
                    let hb = &rows[3 * b..3 * b + 3];
                    values[slots[slot] as usize] += hd[0] * hb[0] + hd[1] * hb[1] + hd[2] * hb[2];
                    slot += 1;
                }
            }
        }
        self.cholesky.factor().is_ok()
    }
}

/// Whether M is symmetric to round-off (`|m_ij - m_ji| <= 1e-14 max|m|`): then the Newton
/// matrix is the factored one wherever no contact slides.
fn is_symmetric(m: &CsrMatrix) -> bool {
    let scale = m.values().iter().fold(0.0_f64, |a, x| a.max(x.abs()));
    let mut symmetric = true;
    m.for_each_entry(|i, j, x| {
        if i != j && (x - m.get(j, i)).abs() > 1e-14 * scale {
            symmetric = false;
        }
    });
    symmetric
}

fn oom(what: &str, len: usize) -> Fc3dError {
    Fc3dError::OutOfMemory {
        what: what.to_string(),
        bytes: len.saturating_mul(8),
    }
}

/// The work vectors of a run (allocated once).
struct Work {
    /// `u = H^T v + b`, `H^T dv`, the contact map at v and at a trial point (contact size).
    u: Vec<f64>,
    h_dv: Vec<f64>,
    p: Vec<f64>,
    p_trial: Vec<f64>,
    /// The residual `F(v) = M v - q - H p(v)`, at a trial point, the step, `M v`, `M dv`
    /// (M's size).
    residual: Vec<f64>,
    residual_trial: Vec<f64>,
    dv: Vec<f64>,
    mv: Vec<f64>,
    m_dv: Vec<f64>,
    /// Each contact's projection Jacobian D, De Saxcé's gradient g (`dp/du = -rho D (I +
    /// e_N g^T)`), and whether D is non-zero.
    jacobians: Vec<Mat3>,
    gradients: Vec<[f64; 2]>,
    active: Vec<bool>,
    /// `H^T x` in the product with the true Newton matrix (contact size), the right-hand side
    /// of the step (M's size).
    t: Vec<f64>,
    rhs: Vec<f64>,
}

/// `y = M x + rho H D (I + e_N g^T) H^T x`: the product with the Newton matrix of F.
#[allow(clippy::too_many_arguments)]
fn newton_product(
    problem: &GlobalProblem<'_>,
    rho: f64,
    jacobians: &[Mat3],
    gradients: &[[f64; 2]],
    active: &[bool],
    t: &mut [f64],
    x: &[f64],
    y: &mut [f64],
) {
    t.iter_mut().for_each(|v| *v = 0.0);
    transpose_mul_add(problem.h(), x, t);
    for (c, d) in jacobians.iter().enumerate() {
        let k = 3 * c;
        if !active[c] {
            t[k..k + 3].copy_from_slice(&[0.0; 3]);
            continue;
        }
        let g = gradients[c];
        let a = [t[k] + g[0] * t[k + 1] + g[1] * t[k + 2], t[k + 1], t[k + 2]];
        for i in 0..3 {
            t[k + i] = rho * (d[i][0] * a[0] + d[i][1] * a[1] + d[i][2] * a[2]);
        }
    }
    y.iter_mut().for_each(|v| *v = 0.0);
    problem.m().mul_add(x, y);
    problem.h().mul_add(t, y);
}

/// The contact map `p = P_K(r - rho (u + s(u) e_N))`, `s(u) = mu ||u_T||` (De Saxcé's term
/// at u), and, when asked, the projection's Jacobian D at that point and the gradient
/// `g = ds/du = (0, mu u_T / ||u_T||)` (zero without sliding): `dp/du = -rho D (I + e_N g^T)`.
fn contact_map(
    r: &Vec3,
    u: &Vec3,
    mu: f64,
    rho: f64,
    derivatives: Option<(&mut Mat3, &mut [f64; 2])>,
) -> Vec3 {
    let tangent = u[1].hypot(u[2]);
    let x = [
        r[0] - rho * (u[0] + mu * tangent),
        r[1] - rho * u[1],
        r[2] - rho * u[2],
    ];
    let Some((jacobian, gradient)) = derivatives else {
        return project_on_cone(&x, mu);
    };
    let (p, d) = project_with_jacobian(&x, mu);
    *jacobian = d;
    *gradient = if tangent > 0.0 {
        [mu * u[1] / tangent, mu * u[2] / tangent]
    } else {
        [0.0; 2]
    };
    p
}

/// `F = M v + alpha M dv - q - H p` into `f` (with `mv` = M v, `m_dv` = M dv); returns
/// `||F||^2`.
fn residual_into(
    h: &CsrMatrix,
    q: &[f64],
    mv: &[f64],
    m_dv: &[f64],
    alpha: f64,
    p: &[f64],
    f: &mut [f64],
) -> f64 {
    f.copy_from_slice(q);
    h.mul_add(p, f);
    let mut sq = 0.0;
    for ((fi, &a), &d) in f.iter_mut().zip(mv).zip(m_dv) {
        *fi = a + alpha * d - *fi;
        sq += *fi * *fi;
    }
    sq
}

/// Runs the SSN-ALM from the reaction in `r`. Iterations are Newton steps (factorizations).
#[allow(clippy::too_many_arguments)]
pub(super) fn run(
    problem: &GlobalProblem<'_>,
    operator: &mut HForm,
    options: &GlobalAlmOptions,
    limits: &Limits,
    r: &mut [f64],
    u_out: &mut [f64],
    v: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let run = limits.start();
    let (n, m, nc) = (problem.ndof(), problem.size(), problem.n_contacts());
    let (q, b, mu, h) = (problem.q(), problem.b(), problem.mu(), problem.h());
    // The set-up (H^T, then the lower triangle of M and of each contact's square of the k
    // unknowns its rows touch, and the diagonal) and the first factorization are not started
    // when predicted to end past the deadline: r as it came, 0 iterations.
    let entries = super::set_up_entries(problem, |k| k * (k + 1.0) / 2.0, n);
    if !crate::math::lu_cost::assembly_ends_by(entries, run.deadline()) {
        return Ok(SolverOutcome::stopped(0, true));
    }
    let ht = transpose(h)?;
    let mut system = BodySystem::new(problem, &ht)?;
    let mut w = Work {
        u: try_vec(m, 0.0, "the SSN-ALM velocities")?,
        h_dv: try_vec(m, 0.0, "the SSN-ALM velocities")?,
        p: try_vec(m, 0.0, "the SSN-ALM contact map")?,
        p_trial: try_vec(m, 0.0, "the SSN-ALM contact map")?,
        residual: try_vec(n, 0.0, "the SSN-ALM residual")?,
        residual_trial: try_vec(n, 0.0, "the SSN-ALM residual")?,
        dv: try_vec(n, 0.0, "the SSN-ALM step")?,
        mv: try_vec(n, 0.0, "the SSN-ALM work")?,
        m_dv: try_vec(n, 0.0, "the SSN-ALM work")?,
        jacobians: try_vec(nc, [[0.0; 3]; 3], "the SSN-ALM Jacobians")?,
        gradients: try_vec(nc, [0.0; 2], "the SSN-ALM Jacobians")?,
        active: try_vec(nc, false, "the SSN-ALM active contacts")?,
        t: try_vec(m, 0.0, "the SSN-ALM work")?,
        rhs: try_vec(n, 0.0, "the SSN-ALM work")?,
    };
    let symmetric_m = is_symmetric(problem.m());
    let mut gmres = Gmres::new(n, options.linear_max_products.min(GMRES_RESTART))?;
    let mut error_work = ErrorWork::new(n);

    // rho H H^T of M's size: trace(M) / ||H||_F^2.
    let trace_m: f64 = (0..n).map(|i| problem.m().get(i, i).abs()).sum();
    let h_frobenius_sq: f64 = h.values().iter().map(|x| x * x).sum();
    let rho0 = if trace_m > 0.0 && h_frobenius_sq > 0.0 {
        options.rho_factor * trace_m / h_frobenius_sq
    } else {
        options.rho_factor
    };
    let rho_max = rho0 * options.rho_max_factor;
    let mut rho = rho0;

    // Start from the given reaction (projected on the cones) and v = M^-1 (q + H r).
    for c in 0..nc {
        let y = project_on_cone(&[r[3 * c], r[3 * c + 1], r[3 * c + 2]], mu[c]);
        r[3 * c..3 * c + 3].copy_from_slice(&y);
    }
    operator.global_velocity(q, r, v);
    let norm_q = norm(q);

    // The multiplier estimate of the contact maps (r extrapolated when accelerated).
    let mut y = try_copy(r, "the SSN-ALM multiplier")?;
    let mut v_exact = try_vec(n, 0.0, "the SSN-ALM velocity")?;

    let mut momentum_t = 1.0_f64;
    let mut iterations = 0;
    let mut inner_tolerance = f64::INFINITY;
    let inner_floor = options.inner_ratio * 1e-3 * run.tolerance;
    let mut last_error = f64::INFINITY;
    let mut last_law = f64::INFINITY;
    let mut outer = 0;
    // A factorization was refused for time: the outer iteration ends the run.
    let mut refused = false;
    loop {
        // Newton on F(v) = M v - q - H p(v) = 0 with (r, rho) fixed.
        // Inexact inner solves, tightened at least by half every outer iteration so that a
        // stagnating outer loop ends up with exact ones (the method of multipliers' condition).
        inner_tolerance = (options.inner_ratio * last_error.min(1.0))
            .min(0.5 * inner_tolerance)
            .max(inner_floor);
        let mut inner = 0;
        loop {
            w.u.copy_from_slice(b);
            transpose_mul_add(h, v, &mut w.u);
            for c in 0..nc {
                let k = 3 * c;
                let p = contact_map(
                    &[y[k], y[k + 1], y[k + 2]],
                    &[w.u[k], w.u[k + 1], w.u[k + 2]],
                    mu[c],
                    rho,
                    Some((&mut w.jacobians[c], &mut w.gradients[c])),
                );
                w.active[c] = p != [0.0; 3];
                w.p[k..k + 3].copy_from_slice(&p);
            }
            w.mv.iter_mut().for_each(|x| *x = 0.0);
            problem.m().mul_add(v, &mut w.mv);
            let f_sq = residual_into(h, q, &w.mv, &w.mv, 0.0, &w.p, &mut w.residual);
            let scale = norm_q.max(norm(&w.mv)).max(1e-300);
            let f_norm = f_sq.sqrt();
            if f_norm <= inner_tolerance * scale
                || inner >= options.inner_max_iter
                || iterations >= run.max_iter
                || run.out_of_time()
            {
                break;
            }
            // A factorization predicted to end past the deadline is not started.
            if !system
                .cholesky
                .factor_ends_by(run.deadline(), "the SSN-ALM matrix M + rho H D H^T")?
            {
                if iterations == 0 {
                    // r as it came (projected on the cones), 0 iterations.
                    return Ok(SolverOutcome::stopped(0, true));
                }
                refused = true;
                break;
            }
            // The Newton step: (M + rho H D' H^T) dv = -F.
            if !system.factor(rho, &w.jacobians, &w.active) {
                return Err(Fc3dError::Unsupported(
                    "SSN-ALM: M + rho H D H^T could not be factored (is M invertible?)".into(),
                ));
            }
            iterations += 1;
            inner += 1;
            for i in 0..n {
                w.rhs[i] = -w.residual[i];
            }
            // The symmetric part's step, then GMRES on the true matrix from it when De
            // Saxcé's derivative (or a non-symmetric M) makes them differ.
            w.dv.copy_from_slice(&w.rhs);
            system.cholesky.solve_in_place(&mut w.dv);
            let exact = symmetric_m && w.gradients.iter().all(|g| *g == [0.0; 2]);
            if !exact {
                let (jacobians, gradients, active, t) =
                    (&w.jacobians, &w.gradients, &w.active, &mut w.t);
                let cholesky = &mut system.cholesky;
                gmres.solve(
                    |x, y| newton_product(problem, rho, jacobians, gradients, active, t, x, y),
                    |z| cholesky.solve_in_place(z),
                    &w.rhs,
                    &mut w.dv,
                    options.linear_tolerance,
                    options.linear_max_products,
                );
            }
            if !w.dv.iter().all(|x| x.is_finite()) {
                return Ok(SolverOutcome::diverged(iterations));
            }
            // Armijo on ||F||^2 / 2 along dv (u and M v are linear in the step).
            w.h_dv.iter_mut().for_each(|x| *x = 0.0);
            transpose_mul_add(h, &w.dv, &mut w.h_dv);
            w.m_dv.iter_mut().for_each(|x| *x = 0.0);
            problem.m().mul_add(&w.dv, &mut w.m_dv);
            let mut alpha = 1.0;
            for trial in 0..options.line_search_max_iter {
                for c in 0..nc {
                    let k = 3 * c;
                    let u = [
                        w.u[k] + alpha * w.h_dv[k],
                        w.u[k + 1] + alpha * w.h_dv[k + 1],
                        w.u[k + 2] + alpha * w.h_dv[k + 2],
                    ];
                    let p = contact_map(&[y[k], y[k + 1], y[k + 2]], &u, mu[c], rho, None);
                    w.p_trial[k..k + 3].copy_from_slice(&p);
                }
                let trial_sq = residual_into(
                    h,
                    q,
                    &w.mv,
                    &w.m_dv,
                    alpha,
                    &w.p_trial,
                    &mut w.residual_trial,
                );
                if trial_sq <= (1.0 - 2e-4 * alpha) * f_sq
                    || trial + 1 == options.line_search_max_iter
                {
                    break;
                }
                alpha *= 0.5;
            }
            for i in 0..n {
                v[i] += alpha * w.dv[i];
            }
        }
        if inner == 0 {
            // An outer iteration without a Newton step still counts against the limit.
            iterations += 1;
        }
        // The multiplier update at the final velocity (w.p is the contact map there).
        let mut law_sq = 0.0;
        for k in 0..m {
            law_sq += (w.p[k] - y[k]).powi(2);
        }
        // y_next = r_new + beta (r_new - r_old) (Nesterov's extrapolation of the proximal
        // point iteration), projected on the cones.
        let t_next = 0.5 * (1.0 + (1.0 + 4.0 * momentum_t * momentum_t).sqrt());
        let beta = if options.accelerate {
            (momentum_t - 1.0) / t_next
        } else {
            0.0
        };
        momentum_t = t_next;
        for c in 0..nc {
            let k = 3 * c;
            let e = [
                w.p[k] + beta * (w.p[k] - r[k]),
                w.p[k + 1] + beta * (w.p[k + 1] - r[k + 1]),
                w.p[k + 2] + beta * (w.p[k + 2] - r[k + 2]),
            ];
            y[k..k + 3].copy_from_slice(&project_on_cone(&e, mu[c]));
        }
        r.copy_from_slice(&w.p);
        outer += 1;
        // The error of the triple the solve returns: r, v = M^-1 (q + H r), u = H^T v + b
        // (Newton's v balances p only to its tolerance).
        operator.global_velocity(q, r, &mut v_exact);
        let error = global_error_with(
            problem,
            ContactLaw::Coulomb,
            r,
            u_out,
            &v_exact,
            None,
            &mut error_work,
        );
        if error > last_error {
            // Adaptive restart of the extrapolation.
            momentum_t = 1.0;
            y.copy_from_slice(r);
        }
        last_error = error;
        observer(&IterationEvent {
            iteration: iterations,
            reaction: r,
            error,
        });
        let outcome = if error <= run.tolerance {
            Some(SolverOutcome::stopped(iterations, false))
        } else if refused || run.out_of_time() {
            Some(SolverOutcome::stopped(iterations, true))
        } else if iterations >= run.max_iter {
            Some(run.exhausted())
        } else if inner == 0 && law_sq == 0.0 && inner_tolerance <= inner_floor {
            // Nothing moved: the next outer iteration would repeat this one.
            Some(SolverOutcome::stopped(iterations, false))
        } else {
            None
        };
        if let Some(outcome) = outcome {
            v.copy_from_slice(&v_exact);
            return Ok(outcome.with_final_error(Some(error)));
        }
        let law = law_sq.sqrt() / rho;
        if outer > 1 && law > options.progress * last_law {
            rho = (rho * options.rho_growth).min(rho_max);
        }
        last_law = law;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_projection_jacobian_matches_finite_differences() {
        let points = [
            [1.0, 0.3, -0.2],
            [0.2, 1.5, 0.7],
            [-0.1, 0.8, -0.6],
            [-2.0, 0.1, 0.1],
            [0.5, -2.0, 3.0],
        ];
        for mu in [0.0, 0.3, 1.0, 2.5] {
            for x in points {
                let (p, d) = project_with_jacobian(&x, mu);
                let reference = project_on_cone(&x, mu);
                for i in 0..3 {
                    assert!((p[i] - reference[i]).abs() <= 1e-15 * (1.0 + reference[i].abs()));
                }
                for j in 0..3 {
                    let h = 1e-7;
                    let mut xp = x;
                    xp[j] += h;
                    let mut xm = x;
                    xm[j] -= h;
                    let (pp, pm) = (project_on_cone(&xp, mu), project_on_cone(&xm, mu));
                    for i in 0..3 {
                        let fd = (pp[i] - pm[i]) / (2.0 * h);
                        assert!(
                            (fd - d[i][j]).abs() < 1e-6,
                            "mu {mu} x {x:?}: d[{i}][{j}] = {} against {fd}",
                            d[i][j]
                        );
                    }
                }
                for i in 0..3 {
                    for j in 0..3 {
                        assert!((d[i][j] - d[j][i]).abs() < 1e-15);
                    }
                }
            }
        }
    }
}

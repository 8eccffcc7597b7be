//! Successive approximation by Tresca problems (TFP, Siconos id 503, Algorithm 11 of
//! Acary-Brémond-Huber): freeze the friction threshold `s_c = r_N,c` of the current iterate, solve
//! the Tresca problem on the cylinders `C_c = { r_N >= 0, ||r_T|| <= mu_c s_c }`,
//!
//! `-(W r + q) ∈ N_C(r)`,
//!
//! and repeat until the Coulomb (natural-map) error is below the tolerance. At a fixed point
//! `s = r_N` the Tresca conditions are the disjunctive form of Coulomb's law.
//!
//! The Tresca sub-problem solvers live here too, because the Panagiotopoulos solver (`pfp`) uses
//! them for its tangent problem (the same cylinder with the normal reaction frozen):
//! * [`TrescaInnerSolver::GaussSeidel`]: Gauss-Seidel over contacts with an exact one-contact
//!   Tresca solver (closed-form stick cases, a safeguarded Newton on the multiplier for sliding);
//! * [`TrescaInnerSolver::FixedPointViUpk`]: the projection fixed point on the cylinders with
//!   the self-adaptive rho of Algorithm 1 (nu = 2/3, L = 0.9, Lmin = 0.3);
//! * [`TrescaInnerSolver::ProjectedGradient`]: Algorithm 9 (Armijo backtracking on the quadratic
//!   `1/2 r.W r + r.q`).

use std::time::{Duration, Instant};

use crate::cone::{project_on_cylinder, project_on_disk};
use crate::error::Fc3dError;
use crate::linalg::{norm, norm2, Mat3, Vec3};
use crate::matrix::BlockRows;
use crate::measure::natural_map_error_of;
use crate::problem::FrictionProblem;
use crate::solver::{IterationEvent, SolverOutcome};

/// Solver of the Tresca sub-problems (Siconos internal solver id in brackets).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrescaInnerSolver {
    /// Gauss-Seidel over contacts with an exact one-contact Tresca solve [500, NSGS on the
    /// Tresca cylinder].
    GaussSeidel,
    /// Projection fixed point with self-adaptive rho (FP-VI-UPK) [566 VI_FPP_Cylinder].
    FixedPointViUpk,
    /// Projected gradient with Armijo line search, Algorithm 9 [567 CONVEXQP_PG_CYLINDER].
    ProjectedGradient,
}

impl TrescaInnerSolver {
    pub fn siconos_id(self) -> i32 {
        match self {
            TrescaInnerSolver::GaussSeidel => 500,
            TrescaInnerSolver::FixedPointViUpk => 566,
            TrescaInnerSolver::ProjectedGradient => 567,
        }
    }

    pub fn from_siconos_id(id: i32) -> Option<Self> {
        Some(match id {
            500 => TrescaInnerSolver::GaussSeidel,
            566 => TrescaInnerSolver::FixedPointViUpk,
            567 => TrescaInnerSolver::ProjectedGradient,
            _ => return None,
        })
    }
}

/// How the tolerance of an inner solve is chosen (Siconos iparam[2]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum InnerTolerance {
    /// `current outer error / ratio`, floored at `tolerance / ratio` (Siconos' adaptive strategy,
    /// default ratio 10 = dparam[2]).
    Adaptive { ratio: f64 },
    /// A fixed inner tolerance (the internal solver's dparam[0]).
    Given(f64),
}

impl InnerTolerance {
    pub(crate) fn value(self, outer_error: f64, tolerance: f64) -> f64 {
        match self {
            InnerTolerance::Adaptive { ratio } => {
                (outer_error / ratio).max(tolerance / ratio).min(1e-1)
            }
            InnerTolerance::Given(t) => t,
        }
    }

    pub(crate) fn validate(self) -> Result<(), Fc3dError> {
        match self {
            InnerTolerance::Adaptive { ratio } if !(ratio > 0.0 && ratio.is_finite()) => Err(
                Fc3dError::InvalidOption(format!("internal error ratio must be > 0, got {ratio}")),
            ),
            InnerTolerance::Given(t) if !(t >= 0.0 && t.is_finite()) => Err(
                Fc3dError::InvalidOption(format!("internal tolerance must be >= 0, got {t}")),
            ),
            _ => Ok(()),
        }
    }
}

/// Options of the Tresca successive approximation (TFP, Siconos id 503).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrescaOptions {
    /// Maximum outer (threshold update) iterations (default 1000, iparam[0]).
    pub max_iter: usize,
    /// Tolerance on the Coulomb natural-map error (default 1e-4, dparam[0]).
    pub tolerance: f64,
    /// Tresca sub-problem solver (default Gauss-Seidel = Siconos' internal NSGS, id 500).
    pub inner: TrescaInnerSolver,
    /// Maximum iterations of one inner solve (default 1000, the internal solver's iparam[0]).
    pub inner_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
    /// Wall-clock budget (default none): stop after the current outer iteration when spent.
    pub time_budget: Option<Duration>,
}

impl Default for TrescaOptions {
    fn default() -> Self {
        TrescaOptions {
            max_iter: 1000,
            tolerance: 1e-4,
            inner: TrescaInnerSolver::GaussSeidel,
            inner_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
            time_budget: None,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// One-contact solvers.

/// Solves the 2D problem `-(A x + b) ∈ N_D(x)` on the disk `D` of radius `radius`: the stick
/// point `-A^{-1} b` when it lies in the disk, otherwise the boundary point with
/// `(A + lambda I) x = -b`, `lambda >= 0`, found by a bisection-safeguarded Newton on
/// `1/||x(lambda)|| - 1/radius` (monotone when the symmetric part of A is positive definite).
/// A is not symmetrized.
pub fn solve_disk_problem(a: &[[f64; 2]; 2], b: [f64; 2], radius: f64) -> [f64; 2] {
    if radius.is_nan() || radius <= 0.0 || norm2(b[0], b[1]) == 0.0 {
        return [0.0, 0.0];
    }
    let solve = |lambda: f64| -> Option<[f64; 2]> {
        let (a00, a01, a10, a11) = (a[0][0] + lambda, a[0][1], a[1][0], a[1][1] + lambda);
        let det = a00 * a11 - a01 * a10;
        let scale = a00.abs().max(a11.abs()).max(a01.abs()).max(a10.abs());
        if !(det.abs() > 1e-300 && det.abs() > 1e-15 * scale * scale) {
            return None;
        }
        let x = [
            -(a11 * b[0] - a01 * b[1]) / det,
            -(-a10 * b[0] + a00 * b[1]) / det,
        ];
        x.iter().all(|v| v.is_finite()).then_some(x)
    };
    if let Some(x) = solve(0.0) {
        if norm2(x[0], x[1]) <= radius {
            return x;
        }
    }
    // ||x(lambda)|| <= ||b|| / (lambda - ||A||) <= radius beyond hi.
    let a_norm = (a[0][0].powi(2) + a[0][1].powi(2) + a[1][0].powi(2) + a[1][1].powi(2)).sqrt();
    let (mut lo, mut hi) = (0.0_f64, a_norm + norm2(b[0], b[1]) / radius);
    let inv_r = 1.0 / radius;
    // phi(lambda) = 1/||x|| - 1/radius: negative at lo (outside the disk), positive at hi.
    let phi_and_slope = |lambda: f64| -> Option<(f64, f64, [f64; 2])> {
        let x = solve(lambda)?;
        let nx = norm2(x[0], x[1]);
        if nx == 0.0 {
            return None;
        }
        // x' = -(A + lambda I)^{-1} x.
        let (a00, a01, a10, a11) = (a[0][0] + lambda, a[0][1], a[1][0], a[1][1] + lambda);
        let det = a00 * a11 - a01 * a10;
        let dx = [
            -(a11 * x[0] - a01 * x[1]) / det,
            -(-a10 * x[0] + a00 * x[1]) / det,
        ];
        let dot = x[0] * dx[0] + x[1] * dx[1];
        Some((1.0 / nx - inv_r, -dot / (nx * nx * nx), x))
    };
    let mut lambda = 0.5 * (lo + hi);
    let mut best = None;
    for _ in 0..100 {
        match phi_and_slope(lambda) {
            Some((phi, slope, x)) => {
                best = Some(x);
                if phi.abs() <= 1e-15 * inv_r {
                    break;
                }
                if phi < 0.0 {
                    lo = lambda;
                } else {
                    hi = lambda;
                }
                let newton = lambda - phi / slope;
                lambda = if slope > 0.0 && newton > lo && newton < hi {
                    newton
                } else {
                    0.5 * (lo + hi)
                };
            }
            None => {
                lo = lambda;
                lambda = 0.5 * (lo + hi);
            }
        }
        if hi - lo <= 1e-16 * hi {
            break;
        }
    }
    let x = best.unwrap_or([-b[0], -b[1]]);
    // On the boundary exactly.
    project_on_disk_boundary(x, radius)
}

fn project_on_disk_boundary(x: [f64; 2], radius: f64) -> [f64; 2] {
    let n = norm2(x[0], x[1]);
    if n > 0.0 {
        [x[0] * radius / n, x[1] * radius / n]
    } else {
        [0.0, 0.0]
    }
}

/// Solves the one-contact Tresca problem `-(W r + q) ∈ N_C(r)`, `C = R+ x D(radius)`, by its two
/// normal cases: contact (`u_N = 0`, the tangent problem on the Schur complement of W_NN) and
/// separation (`r_N = 0`, `u_N >= 0`). When neither case is consistent (W far from positive
/// definite), the separation candidate (feasible) is returned.
pub fn solve_local_tresca(w: &Mat3, q: &Vec3, radius: f64) -> Vec3 {
    let wtt = [[w[1][1], w[1][2]], [w[2][1], w[2][2]]];
    if w[0][0] > 0.0 {
        let inv = 1.0 / w[0][0];
        let schur = [
            [
                w[1][1] - w[1][0] * w[0][1] * inv,
                w[1][2] - w[1][0] * w[0][2] * inv,
            ],
            [
                w[2][1] - w[2][0] * w[0][1] * inv,
                w[2][2] - w[2][0] * w[0][2] * inv,
            ],
        ];
        let b = [q[1] - w[1][0] * q[0] * inv, q[2] - w[2][0] * q[0] * inv];
        let rt = solve_disk_problem(&schur, b, radius);
        let rn = -(q[0] + w[0][1] * rt[0] + w[0][2] * rt[1]) * inv;
        if rn > 0.0 {
            return [rn, rt[0], rt[1]];
        }
    }
    let rt = solve_disk_problem(&wtt, [q[1], q[2]], radius);
    [0.0, rt[0], rt[1]]
}

// ---------------------------------------------------------------------------------------------
// The Tresca sub-problem.

/// Which components a Tresca sub-problem moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TrescaMode {
    /// Normal and tangent reactions on the cylinders (TFP).
    Full,
    /// Tangent reactions on the disks, normal reactions frozen (the tangent problem of PFP).
    TangentOnly,
}

/// Work space of the Tresca sub-problem solvers, allocated once per solve.
pub(crate) struct TrescaWorkspace {
    pub rows: BlockRows,
    /// Cylinder radii `mu_c s_c`.
    pub radius: Vec<f64>,
    u: Vec<f64>,
    trial: Vec<f64>,
    u_trial: Vec<f64>,
    /// Self-adaptive step of the projection solvers, kept across calls (warm start).
    rho: f64,
    /// Initial step `1 / max_c max_i |W_cc,ii|`.
    rho0: f64,
}

/// Self-adaptive rho rule of FP-VI-UPK (Siconos' defaults).
const NU: f64 = 2.0 / 3.0;
const L_MAX: f64 = 0.9;
const L_MIN: f64 = 0.3;
/// Armijo parameter and backtracking cap of Algorithm 9.
const ARMIJO_SIGMA: f64 = 1e-4;
const MAX_LINE_SEARCH: usize = 60;

impl TrescaWorkspace {
    pub fn new(problem: &FrictionProblem<'_>) -> Result<Self, Fc3dError> {
        let rows = problem.w().block_rows()?;
        let n = problem.size();
        let max_diag = (0..rows.n_contacts())
            .map(|c| {
                let d = rows.diagonal(c);
                d[0][0].abs().max(d[1][1].abs()).max(d[2][2].abs())
            })
            .fold(0.0_f64, f64::max);
        Ok(TrescaWorkspace {
            radius: vec![0.0; rows.n_contacts()],
            rows,
            u: vec![0.0; n],
            trial: vec![0.0; n],
            u_trial: vec![0.0; n],
            rho: if max_diag > 0.0 { 1.0 / max_diag } else { 1.0 },
            rho0: if max_diag > 0.0 { 1.0 / max_diag } else { 1.0 },
        })
    }

    /// Solves the Tresca sub-problem with the current radii from `r`, to the relative tolerance
    /// `tol` or `max_iter` iterations; returns the iterations done. `r` stays finite.
    pub fn solve(
        &mut self,
        solver: TrescaInnerSolver,
        mode: TrescaMode,
        q: &[f64],
        tol: f64,
        max_iter: usize,
        r: &mut [f64],
    ) -> usize {
        match solver {
            TrescaInnerSolver::GaussSeidel => self.gauss_seidel(mode, q, tol, max_iter, r),
            TrescaInnerSolver::FixedPointViUpk | TrescaInnerSolver::ProjectedGradient => {
                self.projection(solver, mode, q, tol, max_iter, r)
            }
        }
    }

    fn gauss_seidel(
        &mut self,
        mode: TrescaMode,
        q: &[f64],
        tol: f64,
        max_iter: usize,
        r: &mut [f64],
    ) -> usize {
        for it in 1..=max_iter {
            let mut increment_sq = 0.0;
            for c in 0..self.rows.n_contacts() {
                let lq = self.rows.local_q(c, q, r);
                let w = self.rows.diagonal(c);
                let old = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
                let mut new = match mode {
                    TrescaMode::Full => solve_local_tresca(w, &lq, self.radius[c]),
                    TrescaMode::TangentOnly => {
                        let b = [lq[1] + w[1][0] * old[0], lq[2] + w[2][0] * old[0]];
                        let wtt = [[w[1][1], w[1][2]], [w[2][1], w[2][2]]];
                        let t = solve_disk_problem(&wtt, b, self.radius[c]);
                        [old[0], t[0], t[1]]
                    }
                };
                if !new.iter().all(|v| v.is_finite()) {
                    new = old;
                }
                increment_sq += (new[0] - old[0]).powi(2)
                    + (new[1] - old[1]).powi(2)
                    + (new[2] - old[2]).powi(2);
                r[3 * c..3 * c + 3].copy_from_slice(&new);
            }
            if crate::measure::cheap_error(increment_sq, r) <= tol {
                return it;
            }
        }
        max_iter
    }

    /// FP-VI-UPK and Algorithm 9: `r <- P_C(r - rho (W r + q))`, rho chosen by the self-adaptive
    /// rule (FP-VI-UPK) or by Armijo backtracking on `1/2 r.W r + r.q` (projected gradient).
    /// Stops when `||r - P_C(r - rho F(r))|| / rho`, relative to `max(||q||, ||r||, ||F||)`, is
    /// below `tol`.
    fn projection(
        &mut self,
        solver: TrescaInnerSolver,
        mode: TrescaMode,
        q: &[f64],
        tol: f64,
        max_iter: usize,
        r: &mut [f64],
    ) -> usize {
        let norm_q = norm(q);
        // The radii may have shrunk since r was computed: start from a feasible point, where
        // the projection step measures stationarity (and Armijo's slope is a descent slope).
        self.trial.copy_from_slice(r);
        project(&self.radius, mode, &mut self.trial, r);
        r.copy_from_slice(&self.trial);
        self.rows.velocity(q, r, &mut self.u);
        if solver == TrescaInnerSolver::ProjectedGradient {
            // Algorithm 9 starts every solve from rho0.
            self.rho = self.rho0;
        }
        for it in 1..=max_iter {
            let mut rho = self.rho;
            let mut accepted = false;
            let mut ratio = 0.0;
            for _ in 0..MAX_LINE_SEARCH {
                for ((t, ri), ui) in self.trial.iter_mut().zip(r.iter()).zip(&self.u) {
                    *t = ri - rho * ui;
                }
                project(&self.radius, mode, &mut self.trial, r);
                self.rows.velocity(q, &self.trial, &mut self.u_trial);
                let mut dr_sq = 0.0;
                let mut du_sq = 0.0;
                // slope = F(r).dr; curvature = dr.W dr = dr.(F(trial) - F(r)).
                let mut slope = 0.0;
                let mut curvature = 0.0;
                for (((t, ri), ut), ui) in self
                    .trial
                    .iter()
                    .zip(r.iter())
                    .zip(&self.u_trial)
                    .zip(&self.u)
                {
                    let dr = t - ri;
                    dr_sq += dr * dr;
                    let du = ut - ui;
                    du_sq += du * du;
                    slope += ui * dr;
                    curvature += du * dr;
                }
                if dr_sq == 0.0 {
                    accepted = true;
                    break;
                }
                match solver {
                    TrescaInnerSolver::ProjectedGradient => {
                        // theta(trial) - theta(r) = slope + curvature / 2, from differences only:
                        // the difference of the two values cancels to noise near the solution.
                        if (1.0 - ARMIJO_SIGMA) * slope + 0.5 * curvature <= 0.0 {
                            accepted = true;
                            break;
                        }
                    }
                    _ => {
                        ratio = rho * du_sq.sqrt() / dr_sq.sqrt();
                        if ratio <= L_MAX {
                            accepted = true;
                            break;
                        }
                    }
                }
                rho *= NU;
            }
            // Even a rejected smallest step is a projection step: it keeps r feasible and finite.
            let finite = self.trial.iter().all(|v| v.is_finite())
                && self.u_trial.iter().all(|v| v.is_finite());
            if !finite {
                return it;
            }
            let dr_sq: f64 = self
                .trial
                .iter()
                .zip(r.iter())
                .map(|(t, ri)| (t - ri).powi(2))
                .sum();
            r.copy_from_slice(&self.trial);
            std::mem::swap(&mut self.u, &mut self.u_trial);
            if solver == TrescaInnerSolver::ProjectedGradient {
                // Start the next backtracking from a larger step so rho can grow back; after a
                // failed backtracking keep the step it started from (rho must not collapse).
                self.rho = if accepted { rho / NU } else { self.rho };
            } else {
                self.rho = if accepted && ratio < L_MIN {
                    rho / NU
                } else {
                    rho
                };
            }
            let scale = norm_q.max(norm(r)).max(norm(&self.u));
            let scale = if scale > 0.0 { scale } else { 1.0 };
            if dr_sq == 0.0 && rho < 1e-6 * self.rho0 {
                // A step below the rounding of r proves nothing: restart from rho0.
                self.rho = self.rho0;
                continue;
            }
            if dr_sq.sqrt() / rho / scale <= tol {
                return it;
            }
        }
        max_iter
    }
}

/// Projects `x` on the cylinders (or, tangent only, on the disks with the normal part of `r`).
fn project(radius: &[f64], mode: TrescaMode, x: &mut [f64], r: &[f64]) {
    for (c, &rad) in radius.iter().enumerate() {
        let s = 3 * c;
        match mode {
            TrescaMode::Full => {
                let p = project_on_cylinder(&[x[s], x[s + 1], x[s + 2]], rad);
                x[s..s + 3].copy_from_slice(&p);
            }
            TrescaMode::TangentOnly => {
                let t = project_on_disk([x[s + 1], x[s + 2]], rad);
                x[s] = r[s];
                x[s + 1] = t[0];
                x[s + 2] = t[1];
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Shared outer-loop plumbing of the optimization-based families.

/// Deadline, finite-iterate guard and observer calls of an outer fixed-point loop.
pub(crate) struct OuterLoop {
    deadline: Option<Instant>,
    /// The last iterate known finite (allocated once).
    previous: Vec<f64>,
}

impl OuterLoop {
    pub fn new(time_budget: Option<Duration>, r: &[f64]) -> Self {
        OuterLoop {
            deadline: time_budget.map(|b| Instant::now() + b),
            previous: r.to_vec(),
        }
    }

    /// Restores the previous iterate if `r` is not finite (returns false then); otherwise
    /// records `r` as the new previous iterate.
    pub fn accept(&mut self, r: &mut [f64]) -> bool {
        if r.iter().all(|v| v.is_finite()) {
            self.previous.copy_from_slice(r);
            true
        } else {
            r.copy_from_slice(&self.previous);
            false
        }
    }

    pub fn out_of_time(&self) -> bool {
        self.deadline.is_some_and(|d| Instant::now() >= d)
    }

    /// Ends outer iteration `iteration`: guards `r` ([`OuterLoop::accept`]), measures the Coulomb
    /// error (returned), tells the observer, and gives the outcome when the loop must stop:
    /// converged, a non-finite step (r is back to the last finite iterate), or time spent.
    #[allow(clippy::too_many_arguments)]
    pub fn end_iteration(
        &mut self,
        iteration: usize,
        problem: &FrictionProblem<'_>,
        rows: &BlockRows,
        r: &mut [f64],
        u: &mut [f64],
        tol: f64,
        observer: &mut dyn FnMut(&IterationEvent<'_>),
    ) -> (f64, Option<SolverOutcome>) {
        let finite = self.accept(r);
        let error = coulomb_error(problem, rows, r, u);
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        let stop = if error <= tol || !finite {
            Some(false)
        } else if self.out_of_time() {
            Some(true)
        } else {
            None
        };
        let outcome = stop.map(|out_of_time| SolverOutcome {
            iterations: iteration,
            out_of_time,
            final_error: None,
        });
        (error, outcome)
    }

    /// The outcome of a loop that used all its iterations.
    pub fn iterations_exhausted(max_iter: usize) -> SolverOutcome {
        SolverOutcome {
            iterations: max_iter,
            out_of_time: false,
            final_error: None,
        }
    }
}

/// The Coulomb natural-map error of `r` with `u = W r + q` computed through the block rows.
pub(crate) fn coulomb_error(
    problem: &FrictionProblem<'_>,
    rows: &BlockRows,
    r: &[f64],
    u: &mut [f64],
) -> f64 {
    rows.velocity(problem.q(), r, u);
    natural_map_error_of(problem, r, u)
}

/// Runs TFP from the reaction in `r`. `u` is work space.
pub(crate) fn tfp(
    problem: &FrictionProblem<'_>,
    options: &TrescaOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolverOutcome, Fc3dError> {
    options.inner_tolerance.validate()?;
    let mut work = TrescaWorkspace::new(problem)?;
    let (q, mu) = (problem.q(), problem.mu());
    let tol = options.tolerance;
    let mut outer = OuterLoop::new(options.time_budget, r);
    let mut error = coulomb_error(problem, &work.rows, r, u);
    for iteration in 1..=options.max_iter {
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
        let (e, stop) = outer.end_iteration(iteration, problem, &work.rows, r, u, tol, observer);
        error = e;
        if let Some(outcome) = stop {
            return Ok(outcome);
        }
    }
    Ok(OuterLoop::iterations_exhausted(options.max_iter))
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn disk_stick_and_slide() {
        let a = [[2.0, 0.0], [0.0, 2.0]];
        // Stick: -A^{-1} b = (0.5, 0) inside radius 1.
        assert_eq!(solve_disk_problem(&a, [-1.0, 0.0], 1.0), [0.5, 0.0]);
        // Slide: x = -(A + lambda)^{-1} b on the boundary, opposite to b.
        let x = solve_disk_problem(&a, [-10.0, 0.0], 1.0);
        assert_relative_eq!(x[0], 1.0, epsilon = 1e-14);
        assert_relative_eq!(x[1], 0.0, epsilon = 1e-14);
        // Non-symmetric A: the solution satisfies A x + b = -lambda x with lambda >= 0.
        let a = [[2.0, 0.7], [-0.3, 1.0]];
        let b = [3.0, -4.0];
        let x = solve_disk_problem(&a, b, 0.5);
        assert_relative_eq!(norm2(x[0], x[1]), 0.5, epsilon = 1e-14);
        let g = [
            a[0][0] * x[0] + a[0][1] * x[1] + b[0],
            a[1][0] * x[0] + a[1][1] * x[1] + b[1],
        ];
        let cross = g[0] * x[1] - g[1] * x[0];
        assert!(cross.abs() <= 1e-12 * norm2(g[0], g[1]));
        assert!(g[0] * x[0] + g[1] * x[1] < 0.0);
    }

    #[test]
    fn local_tresca_cases() {
        let w = [[1.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.0]];
        // Take-off.
        assert_eq!(
            solve_local_tresca(&w, &[1.0, 0.0, 0.0], 1.0),
            [0.0, 0.0, 0.0]
        );
        // Stick: u = 0.
        let r = solve_local_tresca(&w, &[-1.0, -0.1, 0.05], 10.0);
        let u = crate::linalg::mat3_vec_add(&w, &r, &[-1.0, -0.1, 0.05]);
        for v in u {
            assert!(v.abs() < 1e-14);
        }
        // Slide: ||r_T|| = radius, u_N = 0, r_T opposite u_T.
        let q = [-1.0, 3.0, 0.0];
        let r = solve_local_tresca(&w, &q, 0.2);
        let u = crate::linalg::mat3_vec_add(&w, &r, &q);
        assert_relative_eq!(norm2(r[1], r[2]), 0.2, epsilon = 1e-14);
        assert!(u[0].abs() < 1e-14);
        assert!(r[1] < 0.0 && u[1] > 0.0);
    }
}

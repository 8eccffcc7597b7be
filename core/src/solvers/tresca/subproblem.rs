//! The Tresca sub-problem `-(W r + q) ∈ N_C(r)` on the cylinders `C_c = R+ x D(0, mu_c s_c)`
//! (TFP), or on the disks with the normal reactions frozen (PFP's tangent problem), solved by
//! Gauss-Seidel with exact one-contact solves, FP-VI-UPK or the projected gradient.

use std::time::Instant;

use super::local::{solve_disk_problem, solve_local_tresca};
use super::settings::TrescaInnerSolver;
use crate::contract::deadline_passed;
use crate::error::{try_vec, Fc3dError};
use crate::math::cone::{project_on_cylinder, project_on_disk};
use crate::math::linalg::norm;
use crate::math::step::{L as L_MAX, L_MIN, NU};
use crate::matrix::BlockRows;
use crate::problem::FrictionProblem;

/// Which components a Tresca sub-problem moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum TrescaMode {
    /// Normal and tangent reactions on the cylinders (TFP).
    Full,
    /// Tangent reactions on the disks, normal reactions frozen (the tangent problem of PFP).
    TangentOnly,
}

/// Work space of the Tresca sub-problem solvers, allocated once per solve.
pub(crate) struct TrescaWorkspace<'a> {
    pub rows: BlockRows<'a>,
    /// Cylinder radii `mu_c s_c`.
    pub radius: Vec<f64>,
    u: Vec<f64>,
    trial: Vec<f64>,
    u_trial: Vec<f64>,
    /// Self-adaptive step of the projection solvers, kept across calls (warm start).
    rho: f64,
    /// Initial step `1 / max_c max_i |W_cc,ii|`.
    rho0: f64,
    /// The run's deadline: an inner solve stops at it whatever its iteration limit.
    pub deadline: Option<Instant>,
}

/// Armijo parameter and backtracking cap of Algorithm 9.
const ARMIJO_SIGMA: f64 = 1e-4;
const MAX_LINE_SEARCH: usize = 60;

impl<'a> TrescaWorkspace<'a> {
    pub fn new(problem: &FrictionProblem<'a>) -> Result<Self, Fc3dError> {
        let rows = problem.w().block_rows()?;
        let n = problem.size();
        let max_diag = (0..rows.n_contacts())
            .map(|c| {
                let d = rows.diagonal(c);
                d[0][0].abs().max(d[1][1].abs()).max(d[2][2].abs())
            })
            .fold(0.0_f64, f64::max);
        Ok(TrescaWorkspace {
            radius: try_vec(rows.n_contacts(), 0.0, "the Tresca work arrays")?,
            rows,
            u: try_vec(n, 0.0, "the Tresca work arrays")?,
            trial: try_vec(n, 0.0, "the Tresca work arrays")?,
            u_trial: try_vec(n, 0.0, "the Tresca work arrays")?,
            rho: if max_diag > 0.0 { 1.0 / max_diag } else { 1.0 },
            rho0: if max_diag > 0.0 { 1.0 / max_diag } else { 1.0 },
            deadline: None,
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
            if deadline_passed(self.deadline) {
                return it - 1;
            }
            let mut increment_sq = 0.0;
            for c in 0..self.rows.n_contacts() {
                let lq = self.rows.local_q(c, q, r);
                let w = &self.rows.diagonal(c);
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
            if deadline_passed(self.deadline) {
                return it - 1;
            }
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

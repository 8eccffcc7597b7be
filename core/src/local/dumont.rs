//! Dumont's EBP (section 3.3): Newton on the bipotential fixed point of one contact,
//! `G(r) = r - P_K(r - rho ũ(W r + q))`, `ũ = (u_N + mu ||u_T||, u_T)`.
//!
//! Dumont's 6x6 system (29) in `(r, v)` with `v = W r + q` condenses to the 3x3 system (32),
//! `(A + B W) dr = -g + B f`; with `v` kept equal to `W r + q` the motion residual `f` is zero,
//! so Newton reads `(A + B W) dr = -G(r)` with
//! `A = dG/dr|_v = I - J_P(tau)`, `B = dG/dv = rho J_P(tau) D(u)`,
//! `D = dũ/du = I + mu e_N (0, u_T/||u_T||)^T` (the term is dropped at `u_T = 0`), and `J_P` the
//! Jacobian of the projection on the cone, re-derived here rather than taken from the paper's
//! component formulas: with `x = (x_N, x_T)`, `n = ||x_T||`, `e = x_T / n`, `c = 1 / (1 + mu^2)`
//! and `s = c (x_N + mu n)` on the boundary branch,
//! `dP_N = c [1, mu e^T]`, `dP_T = [c mu e, c mu^2 e e^T + (mu s / n)(I - e e^T)]`;
//! the identity inside the cone and zero in its polar.
//!
//! Dumont's SAL/EAL pair is the Alart-Curnier side: EAL's function (36) is the Alart-Curnier
//! function (60) with `rho_N = rho_T`, so EAL is 550's code with Dumont's rho rule; SBP is 552
//! and SAL is 557.
//!
//! Safeguard (not in the paper, where Newton takes full steps): the Newton step is damped by
//! backtracking until `||G||` decreases (Armijo, factor 1/2); when no damped step decreases it,
//! the plain SBP step `r - G(r)` is taken if it does, otherwise the solve stops. `||G||` thus
//! decreases at every accepted step: the solver cannot cycle, and `r` stays finite. Without it,
//! full steps fail on about 1.7 % of random SPD contacts with mu in [0, 2] (like 550). Damped
//! Newton can still stall at a local minimum of `||G||` (about 1.5 %, mu > 1, iterates outside
//! K); then, as 565 does for Alart-Curnier, projection iterations (553) restart Newton.

use super::{
    local_rho, LocalOutcome, LocalProblem, LocalSolver, ProjectionOnConeWithLocalIteration,
};
use crate::local::{LocalSolverOptions, RhoRule};
use std::time::Instant;

use crate::contract::past_deadline;
use crate::math::cone::{modified_velocity, project_on_cone};
use crate::math::linalg::{mat3_mul, norm2, norm3, solve3, Mat3, Vec3};

const DECREASE: f64 = 1e-4;
const MAX_BACKTRACKS: usize = 20;

/// Jacobian of the projection on the cone of coefficient `mu` at `x` (one element of the
/// generalized Jacobian on the branch boundaries).
pub fn cone_projection_jacobian(x: &Vec3, mu: f64) -> Mat3 {
    let nt = norm2(x[1], x[2]);
    if x[0] >= 0.0 && nt <= mu * x[0] {
        return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    }
    if mu * nt <= -x[0] || nt == 0.0 {
        return [[0.0; 3]; 3];
    }
    let c = 1.0 / (1.0 + mu * mu);
    let s = c * (x[0] + mu * nt);
    let e = [x[1] / nt, x[2] / nt];
    let k = mu * s / nt;
    let mut j = [[0.0; 3]; 3];
    j[0][0] = c;
    for i in 0..2 {
        j[0][1 + i] = c * mu * e[i];
        j[1 + i][0] = c * mu * e[i];
        for l in 0..2 {
            let id = if i == l { 1.0 } else { 0.0 };
            j[1 + i][1 + l] = c * mu * mu * e[i] * e[l] + k * (id - e[i] * e[l]);
        }
    }
    j
}

/// `G(r)` and the projected point `P_K(tau)` it comes from.
#[inline]
fn bipotential_residual(p: &LocalProblem<'_>, rho: f64, r: &Vec3) -> (Vec3, Vec3, Vec3) {
    let u = p.velocity(r);
    let ut = modified_velocity(&u, p.mu);
    let tau = [r[0] - rho * ut[0], r[1] - rho * ut[1], r[2] - rho * ut[2]];
    let proj = project_on_cone(&tau, p.mu);
    ([r[0] - proj[0], r[1] - proj[1], r[2] - proj[2]], tau, u)
}

/// The Newton matrix `A + B W` of (32) at a point with augmented reaction `tau` and velocity `u`.
pub fn bipotential_jacobian(p: &LocalProblem<'_>, rho: f64, tau: &Vec3, u: &Vec3) -> Mat3 {
    let jp = cone_projection_jacobian(tau, p.mu);
    let mut d = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let nut = norm2(u[1], u[2]);
    if nut > 0.0 {
        d[0][1] = p.mu * u[1] / nut;
        d[0][2] = p.mu * u[2] / nut;
    }
    let b = mat3_mul(&jp, &d);
    let bw = mat3_mul(&b, p.w);
    let mut j = [[0.0; 3]; 3];
    for i in 0..3 {
        for l in 0..3 {
            let id = if i == l { 1.0 } else { 0.0 };
            j[i][l] = id - jp[i][l] + rho * bw[i][l];
        }
    }
    j
}

/// [fc3d 571] Dumont's EBP local solver.
pub struct EnhancedBipotential {
    tolerance: f64,
    max_iter: usize,
    rule: RhoRule,
    projection: ProjectionOnConeWithLocalIteration,
    deadline: Option<Instant>,
}

impl EnhancedBipotential {
    pub fn new(options: &LocalSolverOptions) -> Self {
        let mut proj = *options;
        proj.max_iter = options.hybrid_max_iter;
        // EBP is fc3d's: its restart is fc3d's 553 iteration (from rho at every solve).
        proj.variant = crate::local::AlgorithmVariant::Fc3d;
        EnhancedBipotential {
            tolerance: options.tolerance,
            max_iter: options.max_iter,
            rule: options.rho_rule,
            projection: ProjectionOnConeWithLocalIteration::new(&proj),
            deadline: None,
        }
    }
}

impl LocalSolver for EnhancedBipotential {
    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
        self.projection.set_deadline(deadline);
    }

    fn rho(&self, w: &Mat3) -> (f64, f64) {
        // The cone projection takes one scalar rho; the normal one is Dumont's.
        let rho = local_rho(w, self.rule).0;
        (rho, rho)
    }

    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let start = *r;
        let first = self.newton(p, rho.0, r);
        if first.converged {
            return first;
        }
        // As 565 does for Alart-Curnier: projection iterations (553) from the better of the
        // start and the Newton point, then Newton again; the best point is kept.
        let mut iterations = first.iterations;
        let mut best = *r;
        let mut best_res = p.residual(r);
        let start_res = p.residual(&start);
        if start_res < best_res {
            best = start;
            best_res = start_res;
        }
        let mut x = best;
        let pr = self.projection.solve_with_rho(p, rho, &mut x);
        iterations += pr.iterations;
        let res = p.residual(&x);
        if res <= best_res {
            best = x;
            best_res = res;
        }
        let second = self.newton(p, rho.0, &mut x);
        iterations += second.iterations;
        let res = p.residual(&x);
        if second.converged || res <= best_res {
            best = x;
            best_res = res;
        }
        *r = best;
        LocalOutcome {
            converged: second.converged || best_res <= self.tolerance * p.scale(r),
            iterations,
        }
    }
}

impl EnhancedBipotential {
    /// Damped Newton on G from `r`.
    fn newton(&self, p: &LocalProblem<'_>, rho: f64, r: &mut Vec3) -> LocalOutcome {
        // G has the units of a reaction.
        let scale = norm3(r).max(rho * norm3(&p.q)).max(f64::MIN_POSITIVE);
        let (mut g, mut tau, mut u) = bipotential_residual(p, rho, r);
        let mut ng = norm3(&g);
        for it in 0..self.max_iter {
            if ng <= self.tolerance * scale {
                return LocalOutcome {
                    converged: true,
                    iterations: it,
                };
            }
            if past_deadline(self.deadline, it) {
                return LocalOutcome {
                    converged: false,
                    iterations: it,
                };
            }
            let jac = bipotential_jacobian(p, rho, &tau, &u);
            let mut accepted = None;
            if let Some(d) = solve3(&jac, &[-g[0], -g[1], -g[2]]) {
                let mut alpha = 1.0;
                for _ in 0..MAX_BACKTRACKS {
                    let x = [
                        r[0] + alpha * d[0],
                        r[1] + alpha * d[1],
                        r[2] + alpha * d[2],
                    ];
                    let (gx, tx, ux) = bipotential_residual(p, rho, &x);
                    let nx = norm3(&gx);
                    if nx.is_finite() && nx <= (1.0 - DECREASE * alpha) * ng {
                        accepted = Some((x, gx, tx, ux, nx));
                        break;
                    }
                    alpha *= 0.5;
                }
            }
            if accepted.is_none() {
                // The SBP step `r - G(r) = P_K(tau)`, taken only if it decreases ||G||.
                let x = [r[0] - g[0], r[1] - g[1], r[2] - g[2]];
                let (gx, tx, ux) = bipotential_residual(p, rho, &x);
                let nx = norm3(&gx);
                if nx < ng {
                    accepted = Some((x, gx, tx, ux, nx));
                }
            }
            let Some((x, gx, tx, ux, nx)) = accepted else {
                break;
            };
            *r = x;
            g = gx;
            tau = tx;
            u = ux;
            ng = nx;
        }
        LocalOutcome {
            converged: ng <= self.tolerance * scale,
            iterations: self.max_iter,
        }
    }
}

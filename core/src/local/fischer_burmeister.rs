//! Newton on the Fischer-Burmeister function of the second-order cone for one contact [561].
//!
//! De Saxcé's change of variable makes the contact a complementarity problem over a cone and its
//! dual, `K ∋ r ⟂ ũ ∈ K*`. With `x = (mu r_N, r_T)` and `y = rho (ũ_N, mu ũ_T)` both cones become
//! the self-dual Lorentz cone `L = {||z_T|| <= z_N}` and `x·y = rho mu r·ũ`, so (for mu > 0)
//! the contact law is `L ∋ x ⟂ y ∈ L`, i.e. `phi(x, y) = x + y - sqrt(x∘x + y∘y) = 0` in the
//! Jordan algebra of L (`a∘b = (a·b, a_N b_T + b_N a_T)`, `sqrt` by spectral decomposition).
//! `rho = 1 / W_NN` only balances the units of x and y. For mu = 0 the law is the scalar
//! complementarity `r_N ⟂ u_N` with `r_T = 0`, solved with the scalar FB function.
//!
//! `phi` is smooth away from `x = y = 0`; its Jacobian is taken by central differences (three
//! pairs of evaluations), and the Newton step is globalized by an Armijo backtracking on
//! `||phi||^2 / 2`. At a solution that is not strictly complementary (reaction on the cone's
//! boundary with zero velocity: the stick/slide transition) phi is not differentiable, Newton
//! slows down and the line search can fail; the solve then finishes with the Alart-Curnier
//! Newton with line search (551) from the FB iterate, whose function is piecewise smooth there.
//! Siconos' 561 applies Newton to Glocker's NCP reformulation with the FB
//! function; the FB-Newton idea is the same, the cone formulation is ours.

use super::{local_rho, AlartCurnierNewton, LocalOutcome, LocalProblem, LocalSolver};
use crate::local::{LocalSolverKind, LocalSolverOptions, RhoRule};
use std::time::Instant;

use crate::contract::past_deadline;
use crate::math::cone::modified_velocity;
use crate::math::linalg::{norm2, norm3, solve3, Mat3, Vec3};

const ARMIJO_SLOPE: f64 = 1e-4;
const MAX_BACKTRACKS: usize = 30;

/// Square root in the Jordan algebra of the Lorentz cone of a `w` in that cone.
#[inline]
fn soc_sqrt(w: &Vec3) -> Vec3 {
    let nw = norm2(w[1], w[2]);
    if nw == 0.0 {
        return [w[0].max(0.0).sqrt(), 0.0, 0.0];
    }
    let s1 = (w[0] - nw).max(0.0).sqrt();
    let s2 = (w[0] + nw).max(0.0).sqrt();
    let k = 0.5 * (s2 - s1) / nw;
    [0.5 * (s1 + s2), k * w[1], k * w[2]]
}

/// The FB function of the contact at `r` (see the module documentation).
#[inline]
pub fn fischer_burmeister_function(p: &LocalProblem<'_>, rho: f64, r: &Vec3) -> Vec3 {
    let u = p.velocity(r);
    let mu = p.mu;
    if mu == 0.0 {
        let (a, b) = (r[0], rho * u[0]);
        return [a + b - norm2(a, b), r[1], r[2]];
    }
    let ut = modified_velocity(&u, mu);
    let x = [mu * r[0], r[1], r[2]];
    let y = [rho * ut[0], rho * mu * ut[1], rho * mu * ut[2]];
    let w = [
        x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + y[0] * y[0] + y[1] * y[1] + y[2] * y[2],
        2.0 * (x[0] * x[1] + y[0] * y[1]),
        2.0 * (x[0] * x[2] + y[0] * y[2]),
    ];
    let s = soc_sqrt(&w);
    [x[0] + y[0] - s[0], x[1] + y[1] - s[1], x[2] + y[2] - s[2]]
}

pub struct FischerBurmeisterNewton {
    tolerance: f64,
    max_iter: usize,
    finish: AlartCurnierNewton,
    deadline: Option<Instant>,
}

impl FischerBurmeisterNewton {
    pub fn new(options: &LocalSolverOptions) -> Self {
        let mut finish = LocalSolverOptions::new(LocalSolverKind::NewtonAlartCurnierGp);
        finish.tolerance = options.tolerance;
        finish.max_iter = 20;
        // The finishing Newton stops on fc3d's residual test, the one 561 converges on.
        finish.variant = crate::local::AlgorithmVariant::Fc3d;
        FischerBurmeisterNewton {
            tolerance: options.tolerance,
            max_iter: options.max_iter,
            finish: AlartCurnierNewton::new(&finish),
            deadline: None,
        }
    }
}

impl LocalSolver for FischerBurmeisterNewton {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        let rho = local_rho(w, RhoRule::SplitSpectralNorm).0;
        (rho, rho)
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
        self.finish.set_deadline(deadline);
    }

    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let rho = rho.0;
        // Stop on the natural-map residual: at solutions that are not strictly complementary
        // (a reaction on the cone's boundary with a zero velocity) phi behaves like the square
        // of the distance to the solution, so a small phi alone does not mean an accurate r.
        let done = |r: &Vec3| p.residual(r) <= self.tolerance * p.scale(r);
        let mut f = fischer_burmeister_function(p, rho, r);
        let mut nf = norm3(&f);
        let mut iterations = self.max_iter;
        for it in 0..self.max_iter {
            if done(r) {
                return LocalOutcome {
                    converged: true,
                    iterations: it,
                };
            }
            if past_deadline(self.deadline, it) {
                iterations = it;
                break;
            }
            let mut jac = [[0.0; 3]; 3];
            for j in 0..3 {
                // Near a solution that is not strictly complementary phi bends on the scale of
                // the distance to it: the step follows ||phi|| down, but not below where
                // rounding in phi (about 1e-16 of the scale) would swamp the difference.
                let sc = p.scale(r);
                let h = (1e-7 * r[j].abs().max(1e-3 * sc)).min(nf.max(1e-12 * sc));
                let mut rp = *r;
                let mut rm = *r;
                rp[j] += h;
                rm[j] -= h;
                let fp = fischer_burmeister_function(p, rho, &rp);
                let fm = fischer_burmeister_function(p, rho, &rm);
                for i in 0..3 {
                    jac[i][j] = (fp[i] - fm[i]) / (2.0 * h);
                }
            }
            let Some(d) = solve3(&jac, &[-f[0], -f[1], -f[2]]) else {
                iterations = it;
                break;
            };
            let psi0 = 0.5 * nf * nf;
            let mut alpha = 1.0;
            let mut accepted = None;
            for _ in 0..MAX_BACKTRACKS {
                let x = [
                    r[0] + alpha * d[0],
                    r[1] + alpha * d[1],
                    r[2] + alpha * d[2],
                ];
                let fx = fischer_burmeister_function(p, rho, &x);
                let nx = norm3(&fx);
                if nx.is_finite() && 0.5 * nx * nx <= (1.0 - 2.0 * ARMIJO_SLOPE * alpha) * psi0 {
                    accepted = Some((x, fx, nx));
                    break;
                }
                alpha *= 0.5;
            }
            let Some((x, fx, nx)) = accepted else {
                iterations = it;
                break;
            };
            *r = x;
            f = fx;
            nf = nx;
        }
        if done(r) {
            return LocalOutcome {
                converged: true,
                iterations,
            };
        }
        let rho_ac = local_rho(p.w, RhoRule::SplitSpectralNorm);
        let out = self.finish.solve_with_rho(p, rho_ac, r);
        LocalOutcome {
            converged: out.converged || done(r),
            iterations: iterations + out.iterations,
        }
    }
}

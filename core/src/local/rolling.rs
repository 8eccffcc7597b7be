//! One-contact solvers of the rolling law (Siconos' 3001 / 3002 and their 2D twins 4001 / 4002),
//! written once for contacts of dimension `D` (5, or 3 in 2D): find `r` in the rolling cone `K`
//! with `u = W r + q` and `K* ∋ ũ ⟂ r` ([`crate::math::rolling`]).
//!
//! * [`rolling_projection_step`]: one projected step `r <- P_K(r - a ũ(W r + q))` with
//!   `a = min_i 1 / W_ii`, the step Siconos takes (not a contraction in general: its NSGS stalls
//!   on some problems, as Siconos' own suite expects);
//! * [`RollingProjectionIteration`]: projected steps with a self-adaptive step length `rho`
//!   (Armijo-like ratio test `rho ||ΔF|| <= L ||Δr||`, Siconos' constants), each contact keeping
//!   its `rho` from one sweep to the next, preceded by the closed-form branches that need no
//!   iteration: take-off (`q_N > 0`: `r = 0`) and, when asked, stick (`r = -W^{-1} q` in `K`:
//!   `u = 0`).

use std::time::Instant;

use crate::math::linalg::{block_vec_add, Block};
use crate::math::rolling::{in_rolling_cone, project_on_rolling_cone, rolling_modified_velocity};

/// Step-length constants of the self-adaptive iteration (Siconos' `tau`, `L`, `Lmin`): a trial
/// shrinks `rho` by `tau`, is accepted when `rho ||ΔF|| <= L ||Δr||`, and an easy step
/// (`rho ||ΔF|| < L_min ||Δr||` with a smaller residual) lets `rho` grow by `1 / tau`.
const TAU: f64 = 2.0 / 3.0;
const L: f64 = 0.9;
const L_MIN: f64 = 0.3;
/// Trials per step before the last one is taken anyway (Siconos' 100).
const MAX_TRIALS: usize = 100;

/// The one-contact rolling problem: block `W_cc`, local `q`, coefficients.
#[derive(Debug, Clone, Copy)]
pub struct RollingLocalProblem<'a, const D: usize> {
    pub w: &'a Block<D>,
    pub q: [f64; D],
    pub mu: f64,
    pub mu_r: f64,
}

impl<const D: usize> RollingLocalProblem<'_, D> {
    #[inline]
    fn modified_velocity(&self, r: &[f64; D]) -> ([f64; D], [f64; D]) {
        let u = block_vec_add(self.w, r, &self.q);
        (u, rolling_modified_velocity(&u, self.mu, self.mu_r))
    }
}

/// One projected step from `r` (Siconos 3001): `r <- P_K(r - a ũ)` with `a = min_i 1 / W_ii`
/// (Siconos' 3D step), or `a = 1` when `unit_step` is set (Siconos' 2D step).
#[inline]
pub fn rolling_projection_step<const D: usize>(
    p: &RollingLocalProblem<'_, D>,
    unit_step: bool,
    r: &mut [f64; D],
) {
    let mut a = if unit_step { 1.0 } else { f64::INFINITY };
    if !unit_step {
        for i in 0..D {
            a = a.min(1.0 / p.w[i][i]);
        }
    }
    let (_, ut) = p.modified_velocity(r);
    let mut x = *r;
    for (xk, uk) in x.iter_mut().zip(&ut) {
        *xk -= a * uk;
    }
    *r = project_on_rolling_cone(&x, p.mu, p.mu_r);
}

/// The closed-form branches: take-off when `q_N > 0` (`r = 0`), and, if `stick` is set, the
/// stick solution `r = -W^{-1} q` when it lies in the cone (then `u = 0`). `None` when neither
/// applies.
#[inline]
pub fn rolling_trivial_solution<const D: usize>(
    p: &RollingLocalProblem<'_, D>,
    stick: bool,
) -> Option<[f64; D]> {
    if p.q[0] > 0.0 {
        return Some([0.0; D]);
    }
    if !stick {
        return None;
    }
    let mut r = solve_block(p.w, &p.q)?;
    r.iter_mut().for_each(|v| *v = -*v);
    in_rolling_cone(&r, p.mu, p.mu_r).then_some(r)
}

/// `W x = b` by Gaussian elimination with partial pivoting; `None` when W is singular (a zero
/// pivot) or the solution is not finite.
fn solve_block<const D: usize>(w: &Block<D>, b: &[f64; D]) -> Option<[f64; D]> {
    let mut a = *w;
    let mut x = *b;
    for k in 0..D {
        let mut piv = k;
        for i in k + 1..D {
            if a[i][k].abs() > a[piv][k].abs() {
                piv = i;
            }
        }
        if a[piv][k] == 0.0 {
            return None;
        }
        a.swap(k, piv);
        x.swap(k, piv);
        for i in k + 1..D {
            let f = a[i][k] / a[k][k];
            for j in k..D {
                a[i][j] -= f * a[k][j];
            }
            x[i] -= f * x[k];
        }
    }
    for k in (0..D).rev() {
        let mut s = x[k];
        for j in k + 1..D {
            s -= a[k][j] * x[j];
        }
        x[k] = s / a[k][k];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Settings of the self-adaptive projection iteration (Siconos 3002 / 4002).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingProjectionIteration {
    /// Stop when the last step moved `r` by at most this (absolute; default 1e-12).
    pub tolerance: f64,
    /// Steps per solve (default 1000).
    pub max_iter: usize,
    /// Try the stick solution `-W^{-1} q` first (default true, Siconos'
    /// `USE_TRIVIAL_SOLUTION`); take-off is always tried.
    pub use_trivial_solution: bool,
}

impl Default for RollingProjectionIteration {
    fn default() -> Self {
        RollingProjectionIteration {
            tolerance: 1e-12,
            max_iter: 1000,
            use_trivial_solution: true,
        }
    }
}

impl RollingProjectionIteration {
    /// Solves `p` from `r`; `rho` is the contact's step length, carried from the previous solve
    /// (1 before the first) and updated. Returns the last step's length `||Δr||` (0 for a
    /// closed-form branch), Siconos' local error.
    pub fn solve<const D: usize>(
        &self,
        p: &RollingLocalProblem<'_, D>,
        rho: &mut f64,
        r: &mut [f64; D],
        deadline: Option<Instant>,
    ) -> f64 {
        if let Some(t) = rolling_trivial_solution(p, self.use_trivial_solution) {
            *r = t;
            return 0.0;
        }
        let mut error = 1.0;
        let mut step_rho = *rho;
        for _ in 0..self.max_iter {
            if error <= self.tolerance || deadline.is_some_and(|d| Instant::now() >= d) {
                break;
            }
            let previous_error = error;
            let r_k = *r;
            let (u_k, ut_k) = p.modified_velocity(&r_k);
            let mut trial = step_rho / TAU;
            let (mut du, mut dr) = (0.0, 0.0);
            for _ in 0..MAX_TRIALS {
                trial *= TAU;
                let mut x = r_k;
                for (xk, uk) in x.iter_mut().zip(&ut_k) {
                    *xk -= trial * uk;
                }
                *r = project_on_rolling_cone(&x, p.mu, p.mu_r);
                let u = block_vec_add(p.w, r, &p.q);
                du = 0.0;
                dr = 0.0;
                for k in 0..D {
                    du += (u_k[k] - u[k]) * (u_k[k] - u[k]);
                    dr += (r_k[k] - r[k]) * (r_k[k] - r[k]);
                }
                du = du.sqrt();
                dr = dr.sqrt();
                if trial * du <= L * dr {
                    break;
                }
            }
            error = dr;
            step_rho = if trial * du < L_MIN * dr && error < previous_error {
                trial / TAU
            } else {
                trial
            };
        }
        *rho = step_rho;
        error
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::rolling::rolling_residual_sq;

    fn identity<const D: usize>() -> Block<D> {
        let mut w = [[0.0; D]; D];
        for (i, row) in w.iter_mut().enumerate() {
            row[i] = 1.0;
        }
        w
    }

    fn residual<const D: usize>(p: &RollingLocalProblem<'_, D>, r: &[f64; D]) -> f64 {
        let u = block_vec_add(p.w, r, &p.q);
        rolling_residual_sq(r, &u, p.mu, p.mu_r).sqrt()
    }

    /// Sphere on a plane, W = I: take-off, rolling stick, rolling slip and full slip in closed
    /// form, reached by both solvers.
    #[test]
    fn single_contact_branches() {
        let w = identity::<5>();
        let cases: [([f64; 5], [f64; 5]); 4] = [
            // Take-off: q_N > 0.
            ([1.0, 0.3, 0.0, 0.2, 0.0], [0.0; 5]),
            // Stick and rolling stick: -q in K, r = -q, u = 0.
            ([-1.0, 0.2, 0.0, 0.0, 0.05], [1.0, -0.2, 0.0, 0.0, -0.05]),
            // Rolling slip, tangential stick: |q_R| = 0.5 > mu_r r_N = 0.1; r_N = 1, r_R on its
            // circle opposite to u_R = q_R + r_R = 0.4 e.
            ([-1.0, 0.2, 0.0, 0.5, 0.0], [1.0, -0.2, 0.0, -0.1, 0.0]),
            // Both slip: |q_T| = 2 > mu r_N, |q_R| = 0.5 > mu_r r_N.
            ([-1.0, 0.0, 2.0, 0.0, -0.5], [1.0, 0.0, -0.5, 0.0, 0.1]),
        ];
        for (q, expected) in cases {
            let p = RollingLocalProblem {
                w: &w,
                q,
                mu: 0.5,
                mu_r: 0.1,
            };
            assert!(residual(&p, &expected) < 1e-15, "{q:?}");
            let mut r = [0.0; 5];
            let mut rho = 1.0;
            RollingProjectionIteration::default().solve(&p, &mut rho, &mut r, None);
            for k in 0..5 {
                assert!((r[k] - expected[k]).abs() < 1e-10, "{q:?}: {r:?}");
            }
            // The projected step alone converges too (a fixed point of r = P_K(r - ũ), a = 1).
            let mut r = [0.3, 0.0, 0.0, 0.0, 0.0];
            for _ in 0..100 {
                rolling_projection_step(&p, false, &mut r);
            }
            assert!(residual(&p, &r) < 1e-12, "{q:?}: {r:?}");
        }
    }

    #[test]
    fn coupled_contact_converges_without_closed_form() {
        // A non-symmetric, well-conditioned 3x3 block (2D rolling): no trivial branch applies.
        let w: Block<3> = [[2.0, 0.3, -0.1], [0.1, 1.5, 0.2], [0.0, 0.4, 1.0]];
        let p = RollingLocalProblem {
            w: &w,
            q: [-1.0, 1.5, -0.8],
            mu: 0.3,
            mu_r: 0.05,
        };
        assert!(rolling_trivial_solution(&p, true).is_none());
        let mut r = [0.0; 3];
        let mut rho = 1.0;
        let it = RollingProjectionIteration {
            tolerance: 1e-14,
            max_iter: 10_000,
            use_trivial_solution: true,
        };
        it.solve(&p, &mut rho, &mut r, None);
        assert!(residual(&p, &r) < 1e-12, "{r:?}");
        assert!(rho > 0.0);
    }

    proptest::proptest! {
        /// On random well-conditioned blocks (`W = A Aᵀ + I`, not diagonal) the projection
        /// iteration reaches the exact rolling law, whatever branch the contact is on.
        #[test]
        fn projection_iteration_solves_random_contacts(
            a in proptest::array::uniform5(proptest::array::uniform5(-0.5f64..0.5)),
            q in proptest::array::uniform5(-2.0f64..2.0),
            mu in 0.0f64..1.0,
            mu_r in 0.0f64..0.5,
            stick in proptest::bool::ANY,
        ) {
            let mut w = identity::<5>();
            for i in 0..5 {
                for j in 0..5 {
                    for k in 0..5 {
                        w[i][j] += a[i][k] * a[j][k];
                    }
                }
            }
            let p = RollingLocalProblem { w: &w, q, mu, mu_r };
            let it = RollingProjectionIteration {
                tolerance: 1e-14,
                max_iter: 100_000,
                use_trivial_solution: stick,
            };
            let (mut r, mut rho) = ([0.0; 5], 1.0);
            it.solve(&p, &mut rho, &mut r, None);
            let scale = q.iter().fold(1.0f64, |m, v| m.max(v.abs()));
            proptest::prop_assert!(residual(&p, &r) <= 1e-9 * scale, "{:?} {}", r, residual(&p, &r));
        }
    }

    #[test]
    fn block_solve() {
        let w: Block<3> = [[0.0, 1.0, 0.0], [2.0, 0.0, 0.0], [0.0, 0.0, 4.0]];
        assert_eq!(solve_block(&w, &[1.0, 2.0, 8.0]), Some([1.0, 1.0, 2.0]));
        let singular: Block<3> = [[1.0, 1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
        assert_eq!(solve_block(&singular, &[1.0, 2.0, 8.0]), None);
    }
}

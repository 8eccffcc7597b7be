//! The convex relaxation of the frictional contact problem and the fixed point built on it
//! (section 7.3-7.4 of Acary-Brémond-Huber):
//!
//! * SOCLCP (Siconos id 517): `K* ∋ W r + q + s ⟂ r ∈ K` with `s = 0`, the problem without the
//!   De Saxcé term `mu ||u_T||` (an associated friction law: sliding lifts the contact). Its
//!   solution is a Coulomb solution only when every contact sticks or separates, so the solver
//!   reports `SolveStatus::RelaxationNotCoulomb` when the relaxed problem converged but the
//!   Coulomb error (the one reported) is above the tolerance.
//! * ACLMFP (Siconos id 516, Algorithm 12): the fixed point `s_c = (mu_c ||u_T,c||, 0, 0)` of the
//!   current velocity, then the SOCLCP with that `s`, until the Coulomb error is below the
//!   tolerance. At a fixed point `W r + q + s` is De Saxcé's modified velocity.
//!
//! Both solve the SOCLCP by Gauss-Seidel over contacts with an exact one-contact SOCLCP solver
//! ([`solve_local_soclcp`]).

use std::time::Duration;

use crate::cone::project_on_cone;
use crate::error::Fc3dError;
use crate::linalg::{dot3, mat3_vec, mat3_vec_add, norm, norm2, norm3, solve3, Mat3, Vec3};
use crate::matrix::BlockRows;
use crate::measure::cheap_error;
use crate::problem::FrictionProblem;
use crate::solver::{IterationEvent, SolverOutcome};
use crate::tresca::{coulomb_error, InnerTolerance, OuterLoop};

/// Options of the SOCLCP relaxation solved on its own (Siconos id 517).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoclcpOptions {
    /// Maximum Gauss-Seidel sweeps (default 1000, iparam[0]).
    pub max_iter: usize,
    /// Tolerance (default 1e-4, dparam[0]) on the SOCLCP natural-map error for the relaxed
    /// convergence test, and on the Coulomb error for `Converged`.
    pub tolerance: f64,
    /// Over-relaxation of the Gauss-Seidel update, in (0, 2) (default 1, dparam[8]).
    pub relaxation: f64,
    /// Wall-clock budget (default none): stop after the current sweep when spent.
    pub time_budget: Option<Duration>,
}

impl Default for SoclcpOptions {
    fn default() -> Self {
        SoclcpOptions {
            max_iter: 1000,
            tolerance: 1e-4,
            relaxation: 1.0,
            time_budget: None,
        }
    }
}

/// Options of the ACLM fixed point (Siconos id 516).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AclmOptions {
    /// Maximum outer (threshold update) iterations (default 1000, iparam[0]).
    pub max_iter: usize,
    /// Tolerance on the Coulomb natural-map error (default 1e-4, dparam[0]).
    pub tolerance: f64,
    /// Maximum Gauss-Seidel sweeps of each inner SOCLCP solve (default 1000).
    pub inner_max_iter: usize,
    /// Inner tolerance strategy (default adaptive with ratio 10, iparam[2] = 0, dparam[2] = 10).
    pub inner_tolerance: InnerTolerance,
    /// Wall-clock budget (default none): stop after the current outer iteration when spent.
    pub time_budget: Option<Duration>,
}

impl Default for AclmOptions {
    fn default() -> Self {
        AclmOptions {
            max_iter: 1000,
            tolerance: 1e-4,
            inner_max_iter: 1000,
            inner_tolerance: InnerTolerance::Adaptive { ratio: 10.0 },
            time_budget: None,
        }
    }
}

impl SoclcpOptions {
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        let w = self.relaxation;
        if w > 0.0 && w < 2.0 {
            Ok(())
        } else {
            Err(Fc3dError::InvalidOption(format!(
                "SOCLCP relaxation must be in (0, 2), got {w}"
            )))
        }
    }
}

// ---------------------------------------------------------------------------------------------
// One contact.

/// Samples of the boundary angle when looking for sign changes of the boundary equation.
const ANGLE_SAMPLES: usize = 48;

/// Solves the one-contact SOCLCP `K*_mu ∋ W r + q ⟂ r ∈ K_mu` exactly by its cases:
/// separation (`r = 0`, `q ∈ K*`), `u = 0` (`r = -W^{-1} q ∈ K`), and both on the boundaries,
/// `r = t (1, mu e)`, `u = lambda (mu, -e)` with `e = (cos a, sin a)`, `t, lambda > 0`: then
/// `q` lies in the span of `W (1, mu e)` and `(mu, -e)`, a trigonometric equation in `a`
/// solved by sampling and bisection. Returns `None` when no case is consistent (W far from
/// positive definite, or a double root that sampling missed).
///
/// `angle_hint`, the boundary angle of a previous solution (Gauss-Seidel sweeps), is tried first
/// by a few secant steps: for a positive definite W the solution is unique, so a consistent
/// candidate found there is the solution and the sampling is skipped.
pub fn solve_local_soclcp(w: &Mat3, q: &Vec3, mu: f64, angle_hint: Option<f64>) -> Option<Vec3> {
    let q_scale = norm3(q);
    if q[0] >= 0.0 && mu * norm2(q[1], q[2]) <= q[0] {
        return Some([0.0; 3]);
    }
    if mu == 0.0 {
        // K is the half-line r_T = 0: a scalar LCP in r_N.
        return (w[0][0] > 0.0).then(|| [(-q[0] / w[0][0]).max(0.0), 0.0, 0.0]);
    }
    if let Some(r) = solve3(w, &[-q[0], -q[1], -q[2]]) {
        if r[0] >= 0.0 && norm2(r[1], r[2]) <= mu * r[0] {
            return Some(r);
        }
    }
    let f = |a: f64| -> f64 {
        let (s, c) = a.sin_cos();
        let x = mat3_vec(w, &[1.0, mu * c, mu * s]);
        let b = [mu, -c, -s];
        let cross = [
            x[1] * b[2] - x[2] * b[1],
            x[2] * b[0] - x[0] * b[2],
            x[0] * b[1] - x[1] * b[0],
        ];
        dot3(&cross, q)
    };
    let candidate = |a: f64| -> Option<(Vec3, f64)> {
        let (s, c) = a.sin_cos();
        let dir = [1.0, mu * c, mu * s];
        let x = mat3_vec(w, &dir);
        let b = [mu, -c, -s];
        // Least squares for t x - lambda b = -q.
        let (xx, xb, bb) = (dot3(&x, &x), dot3(&x, &b), dot3(&b, &b));
        let det = xx * bb - xb * xb;
        if det.is_nan() || det <= 0.0 {
            return None;
        }
        let (rx, rb) = (-dot3(&x, q), dot3(&b, q));
        let t = (bb * rx + xb * rb) / det;
        let lambda = (xb * rx + xx * rb) / det;
        if !(t >= 0.0 && lambda >= 0.0) {
            return None;
        }
        let r = [t * dir[0], t * dir[1], t * dir[2]];
        let u = mat3_vec_add(w, &r, q);
        let res = norm3(&[
            u[0] - lambda * b[0],
            u[1] - lambda * b[1],
            u[2] - lambda * b[2],
        ]);
        Some((r, res))
    };
    let consistent = |res: f64| res <= 1e-8 * q_scale.max(f64::MIN_POSITIVE);
    if let Some(a_start) = angle_hint {
        let (mut a0, mut a1) = (a_start, a_start + 1e-4);
        let (mut f0, mut f1) = (f(a0), f(a1));
        for _ in 0..12 {
            if f1 == 0.0 || f1 == f0 {
                break;
            }
            let a2 = a1 - f1 * (a1 - a0) / (f1 - f0);
            if !a2.is_finite() {
                break;
            }
            (a0, f0) = (a1, f1);
            a1 = a2;
            f1 = f(a1);
            if (a1 - a0).abs() <= 1e-15 * (1.0 + a1.abs()) {
                break;
            }
        }
        if let Some((r, res)) = candidate(a1) {
            if consistent(res) {
                return Some(r);
            }
        }
    }
    let step = std::f64::consts::TAU / ANGLE_SAMPLES as f64;
    let mut best: Option<(Vec3, f64)> = None;
    let mut a0 = 0.0;
    let mut f0 = f(a0);
    for k in 1..=ANGLE_SAMPLES {
        let a1 = k as f64 * step;
        let f1 = f(a1);
        if f0 == 0.0 || f0.signum() != f1.signum() {
            // Bisection to the last bit: f is smooth, the bracket is short.
            let (mut lo, mut hi, mut flo) = (a0, a1, f0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let fm = f(mid);
                if fm == 0.0 {
                    lo = mid;
                    hi = mid;
                    break;
                }
                if fm.signum() == flo.signum() {
                    lo = mid;
                    flo = fm;
                } else {
                    hi = mid;
                }
            }
            if let Some((r, res)) = candidate(0.5 * (lo + hi)) {
                if best.as_ref().is_none_or(|b| res < b.1) {
                    best = Some((r, res));
                }
            }
        }
        a0 = a1;
        f0 = f1;
    }
    match best {
        Some((r, res)) if consistent(res) => Some(r),
        _ => None,
    }
}

/// Fallback local solve: projection iterations `r <- P_K(r - rho (W r + q))` with a step halved
/// while the fixed-point residual grows; returns a point of K.
fn local_soclcp_projection(w: &Mat3, q: &Vec3, mu: f64, r0: &Vec3) -> Vec3 {
    let scale = crate::linalg::mat3_max_abs(w);
    let mut rho = if scale > 0.0 { 0.5 / scale } else { 1.0 };
    let mut r = project_on_cone(r0, mu);
    let mut last = f64::INFINITY;
    for _ in 0..500 {
        let u = mat3_vec_add(w, &r, q);
        let next = project_on_cone(
            &[r[0] - rho * u[0], r[1] - rho * u[1], r[2] - rho * u[2]],
            mu,
        );
        let d = norm3(&[next[0] - r[0], next[1] - r[1], next[2] - r[2]]) / rho;
        if !next.iter().all(|v| v.is_finite()) {
            break;
        }
        if d > last {
            rho *= 0.5;
        }
        last = d;
        r = next;
        if d <= 1e-15 * (norm3(q) + scale * norm3(&r)) {
            break;
        }
    }
    r
}

// ---------------------------------------------------------------------------------------------
// Gauss-Seidel on the SOCLCP.

/// One Gauss-Seidel sweep of `K* ∋ W r + q + shift ⟂ r ∈ K`, where `shift_c` is added to the
/// normal component of contact c; returns `sum_c ||r_c^new - r_c^old||^2`.
fn soclcp_sweep(
    rows: &BlockRows,
    q: &[f64],
    mu: &[f64],
    shift: Option<&[f64]>,
    omega: f64,
    r: &mut [f64],
) -> f64 {
    let mut increment_sq = 0.0;
    for c in 0..rows.n_contacts() {
        let mut lq = rows.local_q(c, q, r);
        if let Some(s) = shift {
            lq[0] += s[c];
        }
        let w = rows.diagonal(c);
        let old = [r[3 * c], r[3 * c + 1], r[3 * c + 2]];
        let hint = (old[1] != 0.0 || old[2] != 0.0).then(|| old[2].atan2(old[1]));
        let mut new = solve_local_soclcp(w, &lq, mu[c], hint)
            .unwrap_or_else(|| local_soclcp_projection(w, &lq, mu[c], &old));
        if omega != 1.0 {
            new = project_on_cone(
                &[
                    omega * new[0] + (1.0 - omega) * old[0],
                    omega * new[1] + (1.0 - omega) * old[1],
                    omega * new[2] + (1.0 - omega) * old[2],
                ],
                mu[c],
            );
        }
        if !new.iter().all(|v| v.is_finite()) {
            new = old;
        }
        increment_sq +=
            (new[0] - old[0]).powi(2) + (new[1] - old[1]).powi(2) + (new[2] - old[2]).powi(2);
        r[3 * c..3 * c + 3].copy_from_slice(&new);
    }
    increment_sq
}

/// Relative natural-map error of the SOCLCP, `sqrt(sum_c ||r_c - P_K(r_c - u_c)||^2) /
/// max(||q||, ||r||, ||u||)` with `u = W r + q` (no De Saxcé term); `u` is overwritten.
pub(crate) fn soclcp_error(
    rows: &BlockRows,
    q: &[f64],
    mu: &[f64],
    r: &[f64],
    u: &mut [f64],
) -> f64 {
    rows.velocity(q, r, u);
    let mut sum = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        let s = 3 * c;
        let x = [r[s] - u[s], r[s + 1] - u[s + 1], r[s + 2] - u[s + 2]];
        let p = project_on_cone(&x, m);
        sum += (r[s] - p[0]).powi(2) + (r[s + 1] - p[1]).powi(2) + (r[s + 2] - p[2]).powi(2);
    }
    let scale = norm(q).max(norm(r)).max(norm(u));
    sum.sqrt() / if scale > 0.0 { scale } else { 1.0 }
}

/// Runs the SOCLCP solver from the reaction in `r`; `u` is work space. Returns the outcome and
/// whether the relaxed problem converged (its own error below the tolerance).
pub(crate) fn soclcp(
    problem: &FrictionProblem<'_>,
    options: &SoclcpOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<(SolverOutcome, bool), Fc3dError> {
    options.validate()?;
    let rows = problem.w().block_rows()?;
    let (q, mu) = (problem.q(), problem.mu());
    let tol = options.tolerance;
    let mut light_tol = tol;
    let outer = OuterLoop::new(options.time_budget, &[]);
    for iteration in 1..=options.max_iter {
        let increment_sq = soclcp_sweep(&rows, q, mu, None, options.relaxation, r);
        let light = cheap_error(increment_sq, r);
        let (error, relaxed_converged) = if light <= light_tol {
            let full = soclcp_error(&rows, q, mu, r, u);
            if full > tol {
                // As NSGS: ask the cheap error for what the full one still lacks.
                light_tol = light * tol / full;
            }
            (full, full <= tol)
        } else {
            (light, false)
        };
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error,
        });
        if relaxed_converged || outer.out_of_time() {
            return Ok((
                SolverOutcome {
                    iterations: iteration,
                    out_of_time: !relaxed_converged,
                    final_error: None,
                },
                relaxed_converged,
            ));
        }
    }
    Ok((
        SolverOutcome {
            iterations: options.max_iter,
            out_of_time: false,
            final_error: None,
        },
        false,
    ))
}

/// Runs ACLMFP from the reaction in `r`; `u` is work space.
pub(crate) fn aclmfp(
    problem: &FrictionProblem<'_>,
    options: &AclmOptions,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolverOutcome, Fc3dError> {
    options.inner_tolerance.validate()?;
    let rows = problem.w().block_rows()?;
    let (q, mu) = (problem.q(), problem.mu());
    let tol = options.tolerance;
    let mut shift = vec![0.0; rows.n_contacts()];
    let mut outer = OuterLoop::new(options.time_budget, r);
    let mut error = coulomb_error(problem, &rows, r, u);
    for iteration in 1..=options.max_iter {
        // u = W r + q is current here (coulomb_error computed it).
        for (c, s) in shift.iter_mut().enumerate() {
            *s = mu[c] * norm2(u[3 * c + 1], u[3 * c + 2]);
        }
        let inner_tol = options.inner_tolerance.value(error, tol);
        for _ in 0..options.inner_max_iter {
            let increment_sq = soclcp_sweep(&rows, q, mu, Some(&shift), 1.0, r);
            if cheap_error(increment_sq, r) <= inner_tol {
                break;
            }
        }
        let (e, stop) = outer.end_iteration(iteration, problem, &rows, r, u, tol, observer);
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
    use crate::linalg::mat3_vec_add;

    /// Checks `K* ∋ u ⟂ r ∈ K` for one contact.
    fn check(w: &Mat3, q: &Vec3, mu: f64, r: &Vec3) {
        let u = mat3_vec_add(w, r, q);
        let tol = 1e-10 * (1.0 + norm3(q));
        assert!(norm2(r[1], r[2]) <= mu * r[0] + tol, "r = {r:?}");
        assert!(mu * norm2(u[1], u[2]) <= u[0] + tol, "u = {u:?}");
        assert!(dot3(r, &u).abs() <= tol, "r.u = {}", dot3(r, &u));
    }

    #[test]
    fn local_cases() {
        let w = [[2.0, 0.3, -0.1], [0.2, 1.5, 0.1], [-0.1, 0.05, 1.2]];
        for q in [
            [1.0, 0.1, 0.0],   // separation
            [-1.0, 0.1, 0.05], // stick
            [-1.0, 3.0, -2.0], // slide
            [-0.2, -5.0, 1.0], // slide, strong
        ] {
            for mu in [0.1, 0.5, 1.0] {
                let r = solve_local_soclcp(&w, &q, mu, None).expect("solvable");
                check(&w, &q, mu, &r);
                // A warm start anywhere gives the same (unique) solution.
                for hint in [0.0, 2.0, -3.0] {
                    let h = solve_local_soclcp(&w, &q, mu, Some(hint)).expect("solvable");
                    for i in 0..3 {
                        assert!((h[i] - r[i]).abs() <= 1e-9 * (1.0 + norm3(&r)));
                    }
                }
                let p = local_soclcp_projection(&w, &q, mu, &[0.0; 3]);
                for i in 0..3 {
                    assert!((p[i] - r[i]).abs() <= 1e-9 * (1.0 + norm3(&r)));
                }
            }
        }
    }
}

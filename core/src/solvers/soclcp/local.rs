//! The one-contact SOCLCP `K*_mu ∋ W r + q ⟂ r ∈ K_mu`, solved exactly by its cases.

use crate::math::cone::project_on_cone;
use crate::math::linalg::{dot3, mat3_vec, mat3_vec_add, norm2, norm3, solve3, Mat3, Vec3};

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
pub(super) fn local_soclcp_projection(w: &Mat3, q: &Vec3, mu: f64, r0: &Vec3) -> Vec3 {
    let scale = crate::math::linalg::mat3_max_abs(w);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::linalg::mat3_vec_add;

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

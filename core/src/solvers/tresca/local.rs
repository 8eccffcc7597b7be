//! One-contact Tresca problems: the disk problem in the tangent plane and the cylinder problem.

use crate::math::linalg::{norm2, Mat3, Vec3};

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
        let u = crate::math::linalg::mat3_vec_add(&w, &r, &[-1.0, -0.1, 0.05]);
        for v in u {
            assert!(v.abs() < 1e-14);
        }
        // Slide: ||r_T|| = radius, u_N = 0, r_T opposite u_T.
        let q = [-1.0, 3.0, 0.0];
        let r = solve_local_tresca(&w, &q, 0.2);
        let u = crate::math::linalg::mat3_vec_add(&w, &r, &q);
        assert_relative_eq!(norm2(r[1], r[2]), 0.2, epsilon = 1e-14);
        assert!(u[0].abs() < 1e-14);
        assert!(r[1] < 0.0 && u[1] > 0.0);
    }
}

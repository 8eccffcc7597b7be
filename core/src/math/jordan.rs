//! The Jordan algebra of the second-order cone `L = { x ∈ R^3 : x_0 >= ||x̄|| }` (`x̄ = (x_1,
//! x_2)`), the algebra an interior-point method on Coulomb's cone works in (Alizadeh and
//! Goldfarb, "Second-order cone programming", 2003): the product `x ∘ y = (x·y, x_0 ȳ + y_0 x̄)`
//! with identity `e = (1, 0, 0)`, the spectral decomposition `x = λ_1 c_1 + λ_2 c_2` with
//! `λ_{1,2} = x_0 ∓ ||x̄||` and `c_{1,2} = (1, ∓x̄/||x̄||) / 2`, functions of `x` through it,
//! the arrow matrix `L_x` (`x ∘ y = L_x y`), the quadratic representation `Q_x = 2 x x^T -
//! det(x) R` (`R = diag(1, -1, -1)`), the Nesterov-Todd scaling point, and the longest step that
//! stays in `L`.
//!
//! `x̄ = 0` is an ordinary case (both spectral values equal `x_0`, any unit direction serves):
//! nothing here divides by `||x̄||` without testing it.

use crate::math::linalg::{dot3, mat3_vec, norm2, Mat3, Vec3};

/// The identity `e` of the algebra.
pub const IDENTITY: Vec3 = [1.0, 0.0, 0.0];

/// `det(x) = x_0^2 - ||x̄||^2 = λ_1 λ_2`.
#[inline]
pub fn det(x: &Vec3) -> f64 {
    let (low, high) = spectral_values(x);
    low * high
}

/// The spectral values `(x_0 - ||x̄||, x_0 + ||x̄||)`, smaller first.
#[inline]
pub fn spectral_values(x: &Vec3) -> (f64, f64) {
    let nt = norm2(x[1], x[2]);
    (x[0] - nt, x[0] + nt)
}

/// Whether `x` is in the interior of `L` (both spectral values positive).
#[inline]
pub fn is_interior(x: &Vec3) -> bool {
    x[0] > norm2(x[1], x[2])
}

/// `x ∘ y`.
#[inline]
pub fn product(x: &Vec3, y: &Vec3) -> Vec3 {
    [
        dot3(x, y),
        x[0] * y[1] + y[0] * x[1],
        x[0] * y[2] + y[0] * x[2],
    ]
}

/// The arrow matrix `L_x`: `x ∘ y = L_x y`.
#[inline]
pub fn arrow(x: &Vec3) -> Mat3 {
    [[x[0], x[1], x[2]], [x[1], x[0], 0.0], [x[2], 0.0, x[0]]]
}

/// `L_x^{-1}` (`x` interior): `(1/det x) [[x_0, -x̄^T], [-x̄, (det x / x_0) I + x̄ x̄^T / x_0]]`.
#[inline]
pub fn arrow_inverse(x: &Vec3) -> Mat3 {
    let d = det(x);
    let (x0, x1, x2) = (x[0], x[1], x[2]);
    [
        [x0 / d, -x1 / d, -x2 / d],
        [-x1 / d, 1.0 / x0 + x1 * x1 / (x0 * d), x1 * x2 / (x0 * d)],
        [-x2 / d, x1 * x2 / (x0 * d), 1.0 / x0 + x2 * x2 / (x0 * d)],
    ]
}

/// The quadratic representation `Q_x = 2 L_x^2 - L_{x∘x} = 2 x x^T - det(x) R`.
#[inline]
pub fn quadratic(x: &Vec3) -> Mat3 {
    let d = det(x);
    let mut q = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            q[i][j] = 2.0 * x[i] * x[j];
        }
    }
    q[0][0] -= d;
    q[1][1] += d;
    q[2][2] += d;
    q
}

/// `f(x) = f(λ_1) c_1 + f(λ_2) c_2`.
#[inline]
fn spectral_map(x: &Vec3, f: impl Fn(f64) -> f64) -> Vec3 {
    let nt = norm2(x[1], x[2]);
    let (f_low, f_high) = (f(x[0] - nt), f(x[0] + nt));
    let mean = 0.5 * (f_low + f_high);
    if nt > 0.0 {
        let s = 0.5 * (f_high - f_low) / nt;
        [mean, s * x[1], s * x[2]]
    } else {
        // λ_1 = λ_2: f(x) = f(x_0) e.
        [mean, 0.0, 0.0]
    }
}

/// `x^{1/2}` (`x ∈ L`; spectral values below zero by rounding are taken as zero).
#[inline]
pub fn sqrt(x: &Vec3) -> Vec3 {
    spectral_map(x, |l| l.max(0.0).sqrt())
}

/// `x^{-1/2}` (`x` interior).
#[inline]
pub fn inverse_sqrt(x: &Vec3) -> Vec3 {
    spectral_map(x, |l| 1.0 / l.sqrt())
}

/// `x^{-1} = (x_0, -x̄) / det(x)` (`x` interior).
#[inline]
pub fn inverse(x: &Vec3) -> Vec3 {
    spectral_map(x, |l| 1.0 / l)
}

/// The Nesterov-Todd scaling point of two interior points `u`, `r`: the `p` with
/// `Q_p u = Q_{p^{-1}} r` (equivalently `Q_p^2 u = r`), `p = w^{-1/2}` for
/// `w = Q_{u^{1/2}} (Q_{u^{1/2}} r)^{-1/2}`, the point with `Q_w r = u`.
#[inline]
pub fn nesterov_todd_point(u: &Vec3, r: &Vec3) -> Vec3 {
    let q_sqrt_u = quadratic(&sqrt(u));
    let w = mat3_vec(&q_sqrt_u, &inverse_sqrt(&mat3_vec(&q_sqrt_u, r)));
    inverse_sqrt(&w)
}

/// The largest `α >= 0` with `x + α dx ∈ L`, `f64::INFINITY` when every `α >= 0` keeps it there,
/// for `x ∈ L`. On the boundary the path leaves `L` where `det(x + α dx) = det(x) + 2 b α + a
/// α^2` (`b = x_0 dx_0 - x̄·dx̄`, `a = det(dx)`) first changes sign: its smallest positive root,
/// found with the cancellation-free form of the roots.
pub fn max_step(x: &Vec3, dx: &Vec3) -> f64 {
    let c = det(x).max(0.0);
    let b = x[0] * dx[0] - x[1] * dx[1] - x[2] * dx[2];
    let a = det(dx);
    if c == 0.0 {
        // On the boundary: det = α (2 b + a α).
        return if b > 0.0 && a < 0.0 {
            -2.0 * b / a
        } else if b > 0.0 || (b == 0.0 && a >= 0.0 && dx[0] >= 0.0) {
            f64::INFINITY
        } else {
            0.0
        };
    }
    // The roots are -b/a ± sqrt(b^2 - a c)/a: with s = -(b + sign(b) sqrt(b^2 - a c)), they are
    // s/a and c/s.
    let discriminant = b * b - a * c;
    if discriminant < 0.0 {
        // No real root: det keeps the sign of c > 0 (then a > 0) along the whole ray.
        return f64::INFINITY;
    }
    let s = -(b + b.signum() * discriminant.sqrt());
    let mut alpha = f64::INFINITY;
    for root in [s / a, c / s] {
        if root > 0.0 && root < alpha {
            alpha = root;
        }
    }
    alpha
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::linalg::mat3_mul;

    fn close(a: &Vec3, b: &Vec3, tol: f64) -> bool {
        (0..3).all(|k| (a[k] - b[k]).abs() <= tol * (1.0 + b[k].abs()))
    }

    #[test]
    fn functions_of_x_agree_with_the_product() {
        for x in [
            [2.0, 0.5, -1.2],
            [1.0, 0.0, 0.0],
            [3.0, 0.0, 2.9],
            [1e-3, 1e-4, 0.0],
        ] {
            let s = sqrt(&x);
            assert!(close(&product(&s, &s), &x, 1e-14), "{x:?}");
            let i = inverse(&x);
            assert!(close(&product(&i, &x), &IDENTITY, 1e-12), "{x:?}");
            let is = inverse_sqrt(&x);
            assert!(close(&product(&is, &is), &i, 1e-12), "{x:?}");
            assert!(close(&mat3_vec(&arrow(&x), &s), &product(&x, &s), 1e-15));
            let back = mat3_vec(&arrow_inverse(&x), &product(&x, &s));
            assert!(close(&back, &s, 1e-12), "{x:?}");
            // Q_x y = 2 x ∘ (x ∘ y) - (x ∘ x) ∘ y.
            let y = [0.3, -0.7, 0.2];
            let expected = {
                let a = product(&x, &product(&x, &y));
                let b = product(&product(&x, &x), &y);
                [2.0 * a[0] - b[0], 2.0 * a[1] - b[1], 2.0 * a[2] - b[2]]
            };
            assert!(close(&mat3_vec(&quadratic(&x), &y), &expected, 1e-14));
        }
    }

    #[test]
    fn the_nesterov_todd_point_maps_u_to_r() {
        let pairs = [
            ([2.0, 0.5, -1.2], [1.0, 0.1, 0.3]),
            ([1.0, 0.0, 0.0], [5.0, 4.0, 0.0]),
            ([1e-6, 0.0, 9e-7], [1e3, -1e2, 2e2]),
        ];
        for (u, r) in pairs {
            let p = nesterov_todd_point(&u, &r);
            assert!(is_interior(&p));
            let qp = quadratic(&p);
            let qp_inv = quadratic(&inverse(&p));
            let lhs = mat3_vec(&qp, &u);
            let rhs = mat3_vec(&qp_inv, &r);
            assert!(close(&lhs, &rhs, 1e-9), "{lhs:?} {rhs:?}");
            assert!(close(&mat3_vec(&mat3_mul(&qp, &qp), &u), &r, 1e-9));
        }
    }

    #[test]
    fn the_step_reaches_the_boundary_and_not_beyond() {
        let x = [1.0, 0.2, -0.3];
        for dx in [
            [-1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-0.5, 2.0, 1.0],
            [1.0, 0.5, 0.0],
            [-2.0, -0.4, 0.6],
            [0.0, 0.0, 0.0],
        ] {
            let alpha = max_step(&x, &dx);
            if alpha.is_finite() {
                let at = |t: f64| [x[0] + t * dx[0], x[1] + t * dx[1], x[2] + t * dx[2]];
                assert!(is_interior(&at(0.999 * alpha)), "{dx:?} {alpha}");
                assert!(!is_interior(&at(1.001 * alpha)), "{dx:?} {alpha}");
            } else {
                for t in [1.0, 1e3, 1e9] {
                    let y = [x[0] + t * dx[0], x[1] + t * dx[1], x[2] + t * dx[2]];
                    assert!(y[0] >= norm2(y[1], y[2]) - 1e-12 * t, "{dx:?}");
                }
            }
        }
        // From the boundary: inward is free, outward is 0.
        let edge = [1.0, 1.0, 0.0];
        assert_eq!(max_step(&edge, &[1.0, -1.0, 0.0]), f64::INFINITY);
        assert_eq!(max_step(&edge, &[-1.0, 0.0, 0.0]), 0.0);
    }
}

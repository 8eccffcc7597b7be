//! Euclidean projections of appendix A of Acary-Brémond-Huber: the Coulomb cone
//! `K_mu = { ||x_T|| <= mu x_N }`, its dual `K*_mu = K_{1/mu}`, the disk and the Tresca cylinder.
//! Components are ordered `(N, T1, T2)`.

use crate::math::linalg::{norm2, Vec3};

/// Projection on the Coulomb cone of coefficient `mu` (eq. (150), re-derived):
/// inside: unchanged; in the polar cone (`mu ||x_T|| <= -x_N`): 0; otherwise onto the boundary
/// ray along `x_T`, at height `(x_N + mu ||x_T||) / (1 + mu^2)`.
#[inline]
pub fn project_on_cone(x: &Vec3, mu: f64) -> Vec3 {
    let nt = norm2(x[1], x[2]);
    // `x[0] >= 0` matters for mu = 0 only: there `mu * x[0]` is -0.0 for x_N < 0, and
    // `0.0 <= -0.0` holds, which would return (x_N < 0, 0, 0) unchanged.
    if x[0] >= 0.0 && nt <= mu * x[0] {
        return *x;
    }
    if mu * nt <= -x[0] {
        return [0.0, 0.0, 0.0];
    }
    let n = (x[0] + mu * nt) / (1.0 + mu * mu);
    // nt > 0 here: nt = 0 falls in one of the two branches above for any mu >= 0.
    let s = mu * n / nt;
    [n, s * x[1], s * x[2]]
}

/// Projection on the dual cone `K*_mu = K_{1/mu}` (for mu = 0 the half-space `x_N >= 0`).
#[inline]
pub fn project_on_dual_cone(x: &Vec3, mu: f64) -> Vec3 {
    if mu == 0.0 {
        return [x[0].max(0.0), x[1], x[2]];
    }
    // K*_mu = { mu ||x_T|| <= x_N } is the Coulomb cone of coefficient 1/mu.
    let nt = norm2(x[1], x[2]);
    let inv = 1.0 / mu;
    if nt <= inv * x[0] {
        return *x;
    }
    if inv * nt <= -x[0] {
        return [0.0, 0.0, 0.0];
    }
    let n = (x[0] + inv * nt) / (1.0 + inv * inv);
    let s = inv * n / nt;
    [n, s * x[1], s * x[2]]
}

/// Projection of a 2-vector on the disk of radius `radius >= 0` (eq. (148) scaled).
#[inline]
pub fn project_on_disk(t: [f64; 2], radius: f64) -> [f64; 2] {
    let nt = norm2(t[0], t[1]);
    if nt <= radius {
        t
    } else if nt > 0.0 {
        let s = radius / nt;
        [s * t[0], s * t[1]]
    } else {
        [0.0, 0.0]
    }
}

/// Projection on the Tresca cylinder `{ x_N >= 0, ||x_T|| <= radius }`.
#[inline]
pub fn project_on_cylinder(x: &Vec3, radius: f64) -> Vec3 {
    let t = project_on_disk([x[1], x[2]], radius.max(0.0));
    [x[0].max(0.0), t[0], t[1]]
}

/// De Saxcé's modified velocity `(u_N + mu ||u_T||, u_T)`.
#[inline]
pub fn modified_velocity(u: &Vec3, mu: f64) -> Vec3 {
    [u[0] + mu * norm2(u[1], u[2]), u[1], u[2]]
}

/// Projection on the 2D Coulomb cone `{ |x_T| <= mu x_N }` of `x = (x_N, x_T)`: inside,
/// unchanged; in the polar cone (`mu |x_T| <= -x_N`), 0; otherwise onto the boundary ray on the
/// side of `x_T`, at height `(x_N + mu |x_T|) / (1 + mu^2)` (the formula of Siconos'
/// `fc2d_unitary_compute_and_add_error`).
#[inline]
pub fn project_on_cone_2d(x: &[f64; 2], mu: f64) -> [f64; 2] {
    let nt = x[1].abs();
    // As in 3D, `x[0] >= 0` keeps (x_N < 0, 0) out of the frictionless "cone" (0 <= -0.0).
    if x[0] >= 0.0 && nt <= mu * x[0] {
        return *x;
    }
    if mu * nt <= -x[0] {
        return [0.0, 0.0];
    }
    let n = (x[0] + mu * nt) / (1.0 + mu * mu);
    // nt > 0 here (nt = 0 falls in a branch above for any mu >= 0): the side is x_T's sign.
    [n, (mu * n).copysign(x[1])]
}

/// De Saxcé's modified velocity in 2D, `(u_N + mu |u_T|, u_T)`.
#[inline]
pub fn modified_velocity_2d(u: &[f64; 2], mu: f64) -> [f64; 2] {
    [u[0] + mu * u[1].abs(), u[1]]
}

/// [`project_on_cone`] or [`project_on_cone_2d`] for a contact of dimension `D` (2 or 3), chosen
/// at compile time.
#[inline(always)]
pub fn project_on_cone_d<const D: usize>(x: &[f64; D], mu: f64) -> [f64; D] {
    let mut out = [0.0; D];
    match D {
        3 => out.copy_from_slice(&project_on_cone(&[x[0], x[1], x[2]], mu)),
        2 => out.copy_from_slice(&project_on_cone_2d(&[x[0], x[1]], mu)),
        _ => unreachable!("contacts have dimension 2 or 3"),
    }
    out
}

/// [`modified_velocity`] or [`modified_velocity_2d`] for a contact of dimension `D`.
#[inline(always)]
pub fn modified_velocity_d<const D: usize>(u: &[f64; D], mu: f64) -> [f64; D] {
    let mut out = [0.0; D];
    match D {
        3 => out.copy_from_slice(&modified_velocity(&[u[0], u[1], u[2]], mu)),
        2 => out.copy_from_slice(&modified_velocity_2d(&[u[0], u[1]], mu)),
        _ => unreachable!("contacts have dimension 2 or 3"),
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::linalg::{dot3, norm3, sub3};
    use approx::assert_relative_eq;
    use proptest::prelude::*;

    fn in_cone(x: &Vec3, mu: f64, tol: f64) -> bool {
        norm2(x[1], x[2]) <= mu * x[0] + tol
    }

    #[test]
    fn cone_cases() {
        assert_eq!(project_on_cone(&[1.0, 0.1, 0.0], 0.5), [1.0, 0.1, 0.0]);
        assert_eq!(project_on_cone(&[-1.0, 0.1, 0.0], 0.5), [0.0, 0.0, 0.0]);
        // mu = 1, x = (0, 1, 0): the boundary point (1/2, 1/2, 0).
        let p = project_on_cone(&[0.0, 1.0, 0.0], 1.0);
        assert_relative_eq!(p[0], 0.5, epsilon = 1e-15);
        assert_relative_eq!(p[1], 0.5, epsilon = 1e-15);
        // mu = 0: the half-line x_T = 0, x_N >= 0.
        assert_eq!(project_on_cone(&[2.0, 1.0, -1.0], 0.0), [2.0, 0.0, 0.0]);
        assert_eq!(project_on_cone(&[0.0, 0.0, 0.0], 0.3), [0.0, 0.0, 0.0]);
    }

    #[test]
    fn frictionless_cone_of_negative_normal_axis_is_origin() {
        // Regression: with mu = 0, x = (x_N < 0, 0, 0) used to be returned unchanged
        // (`0 <= 0 * x_N` holds since 0 * x_N is -0.0), so the natural-map error of a separating
        // frictionless contact with r = 0, u = (u_N > 0, 0, 0) was u_N instead of 0.
        assert_eq!(project_on_cone(&[-1.0, 0.0, 0.0], 0.0), [0.0, 0.0, 0.0]);
        assert_eq!(project_on_cone(&[-1e-300, 0.0, 0.0], 0.0), [0.0, 0.0, 0.0]);
        assert_eq!(project_on_cone(&[2.0, 0.0, 0.0], 0.0), [2.0, 0.0, 0.0]);
    }

    #[test]
    fn cone_2d_cases() {
        assert_eq!(project_on_cone_2d(&[1.0, 0.3], 0.5), [1.0, 0.3]);
        assert_eq!(project_on_cone_2d(&[-1.0, 0.1], 0.5), [0.0, 0.0]);
        // mu = 1, x = (0, -1): the boundary point (1/2, -1/2).
        assert_eq!(project_on_cone_2d(&[0.0, -1.0], 1.0), [0.5, -0.5]);
        assert_eq!(project_on_cone_2d(&[2.0, 1.0], 0.0), [2.0, 0.0]);
        assert_eq!(project_on_cone_2d(&[-1.0, 0.0], 0.0), [0.0, 0.0]);
        // The 2D projection is the 3D one restricted to the plane x_T2 = 0.
        for x in [[0.3, 2.0], [1.0, -4.0], [-0.2, 0.1], [5.0, 1.0]] {
            let p3 = project_on_cone(&[x[0], x[1], 0.0], 0.7);
            let p2 = project_on_cone_2d(&x, 0.7);
            assert_relative_eq!(p2[0], p3[0], epsilon = 1e-15);
            assert_relative_eq!(p2[1], p3[1], epsilon = 1e-15);
            assert_eq!(p3[2], 0.0);
        }
    }

    proptest! {
        /// Moreau's characterisation in 2D: p in K, x - p in the polar cone, <p, x - p> = 0.
        #[test]
        fn cone_2d_projection_is_moreau(x in prop::array::uniform2(-10.0f64..10.0), mu in 0.0f64..5.0) {
            let p = project_on_cone_2d(&x, mu);
            let d = [x[0] - p[0], x[1] - p[1]];
            let scale = 1.0 + x[0].abs() + x[1].abs();
            prop_assert!(p[1].abs() <= mu * p[0] + 1e-12 * scale);
            prop_assert!(mu * d[1].abs() <= -d[0] + 1e-12 * scale);
            prop_assert!((p[0] * d[0] + p[1] * d[1]).abs() <= 1e-11 * scale * scale);
        }

        /// Characterisation of the projection on a closed convex cone (Moreau):
        /// p in K, x - p in polar cone (-K*), <p, x - p> = 0.
        #[test]
        fn cone_projection_is_moreau(x in prop::array::uniform3(-10.0f64..10.0), mu in 0.0f64..5.0) {
            let p = project_on_cone(&x, mu);
            let d = sub3(&x, &p);
            let scale = 1.0 + norm3(&x);
            prop_assert!(in_cone(&p, mu, 1e-12 * scale));
            // -d must be in the dual cone K_{1/mu}: mu ||d_T|| <= -d_N.
            prop_assert!(mu * norm2(d[1], d[2]) <= -d[0] + 1e-12 * scale);
            prop_assert!(dot3(&p, &d).abs() <= 1e-11 * scale * scale);
        }

        #[test]
        fn dual_projection_is_moreau(x in prop::array::uniform3(-10.0f64..10.0), mu in 0.01f64..5.0) {
            let p = project_on_dual_cone(&x, mu);
            let d = sub3(&x, &p);
            let scale = 1.0 + norm3(&x);
            prop_assert!(mu * norm2(p[1], p[2]) <= p[0] + 1e-12 * scale);
            prop_assert!(norm2(d[1], d[2]) <= mu * (-d[0]) + 1e-12 * scale);
            prop_assert!(dot3(&p, &d).abs() <= 1e-11 * scale * scale);
        }

        #[test]
        fn cylinder_projection_is_nearest(x in prop::array::uniform3(-10.0f64..10.0), rad in 0.0f64..5.0,
                                           y in prop::array::uniform3(-10.0f64..10.0)) {
            let p = project_on_cylinder(&x, rad);
            let y = project_on_cylinder(&y, rad);
            prop_assert!(norm3(&sub3(&x, &p)) <= norm3(&sub3(&x, &y)) + 1e-12);
        }
    }
}

//! Per-contact residuals `F_c(r_c, u_c)` of the four formulations and an element of their
//! generalized Jacobians (appendix B, re-derived): `A_c = dF_c/dr_c`, `B_c = dF_c/du_c`, so that
//! with `u = W r + q` the Jacobian of `F` is `J = A + B W` (A, B block diagonal).

use super::settings::NsnFormulation;
use crate::math::cone::{modified_velocity, project_on_cone};
use crate::math::linalg::{norm2, solve3, Mat3, Vec3};

const ZERO: Mat3 = [[0.0; 3]; 3];
const IDENTITY: Mat3 = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];

/// The data of one contact the residual depends on besides `(r_c, u_c)`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ContactData {
    pub mu: f64,
    pub rho_n: f64,
    pub rho_t: f64,
}

/// `F_c`, `A_c = dF_c/dr_c` and `B_c = dF_c/du_c` of one contact.
pub(crate) fn residual(
    formulation: NsnFormulation,
    r: &Vec3,
    u: &Vec3,
    d: &ContactData,
) -> (Vec3, Mat3, Mat3) {
    match formulation {
        NsnFormulation::AlartCurnier => alart_curnier(r, u, d, false),
        NsnFormulation::JeanMoreau => alart_curnier(r, u, d, true),
        NsnFormulation::NaturalMap => natural_map(r, u, d),
        NsnFormulation::FischerBurmeister => fischer_burmeister(r, u, d.mu),
    }
}

/// Alart-Curnier (60)-(61) or, with `jean_moreau`, (58)-(59):
/// `F_N = r_N - (r_N - rho_N u_N)_+`, `F_T = r_T - P_D(radius)(r_T - rho_T u_T)` with radius
/// `mu (r_N - rho_N u_N)_+` (AC) or `mu r_N` (JM, Christensen and Pang's form as Siconos'
/// `computeAlartCurnierJeanMoreau` writes it: not clamped at 0, so F stays linear in r_N where
/// an iterate has r_N < 0; clamping it stalls the global Newton, 607, on Spheres-i099-356-679:
/// 498 iterations to 1e-5 against 30). (The paper's (61) prints rho_N in the
/// tangential part; rho_T is meant.)
fn alart_curnier(r: &Vec3, u: &Vec3, d: &ContactData, jean_moreau: bool) -> (Vec3, Mat3, Mat3) {
    let (mu, rn, rt) = (d.mu, d.rho_n, d.rho_t);
    let mut f = [0.0; 3];
    let mut a = ZERO;
    let mut b = ZERO;
    let s_n = r[0] - rn * u[0];
    if s_n > 0.0 {
        f[0] = rn * u[0];
        b[0][0] = rn;
    } else {
        f[0] = r[0];
        a[0][0] = 1.0;
    }
    let (radius, radius_active) = if jean_moreau {
        (mu * r[0], true)
    } else {
        (mu * s_n.max(0.0), s_n > 0.0)
    };
    let v = [r[1] - rt * u[1], r[2] - rt * u[2]];
    let nv = norm2(v[0], v[1]);
    // Jean-Moreau's radius may be negative (r_N < 0 between iterates): a zero v_T then has no
    // direction, and Siconos takes the stick branch below 1e-20.
    if nv <= radius || (jean_moreau && nv < 1e-20) {
        // Stick: r_T - v_T = rho_T u_T.
        f[1] = rt * u[1];
        f[2] = rt * u[2];
        b[1][1] = rt;
        b[2][2] = rt;
    } else {
        // Slide: P = radius t with t = v_T / |v_T|; dP/dv_T = radius (I - t t^T) / |v_T|.
        let t = [v[0] / nv, v[1] / nv];
        f[1] = r[1] - radius * t[0];
        f[2] = r[2] - radius * t[1];
        for i in 0..2 {
            for j in 0..2 {
                let delta = if i == j { 1.0 } else { 0.0 };
                let g = radius * (delta - t[i] * t[j]) / nv;
                a[1 + i][1 + j] = delta - g;
                b[1 + i][1 + j] = rt * g;
            }
            if radius_active {
                a[1 + i][0] = -mu * t[i];
                if !jean_moreau {
                    b[1 + i][0] = mu * rn * t[i];
                }
            }
        }
    }
    (f, a, b)
}

/// `dũ/du` for `ũ = (u_N + mu |u_T|, u_T)`; at `u_T = 0` the element with a zero subgradient of
/// `|u_T|` is taken (it lies in Clarke's Jacobian).
fn modified_velocity_jacobian(u: &Vec3, mu: f64) -> Mat3 {
    let mut g = IDENTITY;
    let nt = norm2(u[1], u[2]);
    if nt > 0.0 {
        g[0][1] = mu * u[1] / nt;
        g[0][2] = mu * u[2] / nt;
    }
    g
}

/// An element of the generalized Jacobian of the projection on the Coulomb cone at `v`
/// (appendix A, re-derived from `P = a (1, mu t)`, `a = (v_N + mu |v_T|) / (1 + mu^2)`).
pub(crate) fn cone_projection_jacobian(v: &Vec3, mu: f64) -> Mat3 {
    let nt = norm2(v[1], v[2]);
    if v[0] >= 0.0 && nt <= mu * v[0] {
        return IDENTITY;
    }
    if mu * nt <= -v[0] {
        return ZERO;
    }
    // nt > 0 here (see project_on_cone).
    let t = [v[1] / nt, v[2] / nt];
    let den = 1.0 + mu * mu;
    let a = (v[0] + mu * nt) / den;
    let mut p = ZERO;
    p[0][0] = 1.0 / den;
    p[0][1] = mu * t[0] / den;
    p[0][2] = mu * t[1] / den;
    for i in 0..2 {
        p[1 + i][0] = mu * t[i] / den;
        for j in 0..2 {
            let delta = if i == j { 1.0 } else { 0.0 };
            p[1 + i][1 + j] = mu * mu * t[i] * t[j] / den + mu * a * (delta - t[i] * t[j]) / nt;
        }
    }
    p
}

/// Natural map (49): `F = r - P_K(r - rho ũ)`; `A = I - P'`, `B = rho P' dũ/du`.
fn natural_map(r: &Vec3, u: &Vec3, d: &ContactData) -> (Vec3, Mat3, Mat3) {
    let rho = d.rho_n;
    let ut = modified_velocity(u, d.mu);
    let v = [r[0] - rho * ut[0], r[1] - rho * ut[1], r[2] - rho * ut[2]];
    let p = project_on_cone(&v, d.mu);
    let f = [r[0] - p[0], r[1] - p[1], r[2] - p[2]];
    let dp = cone_projection_jacobian(&v, d.mu);
    let g = modified_velocity_jacobian(u, d.mu);
    let mut a = ZERO;
    let mut b = ZERO;
    for i in 0..3 {
        for j in 0..3 {
            a[i][j] = IDENTITY[i][j] - dp[i][j];
            b[i][j] = rho * (dp[i][0] * g[0][j] + dp[i][1] * g[1][j] + dp[i][2] * g[2][j]);
        }
    }
    (f, a, b)
}

/// Jordan-algebra arrow matrix `L_x` (`x ∘ y = L_x y`).
fn arrow(x: &Vec3) -> Mat3 {
    [[x[0], x[1], x[2]], [x[1], x[0], 0.0], [x[2], 0.0, x[0]]]
}

/// The square root of `w` in the second-order cone by its spectral decomposition (73);
/// spectral values below zero (rounding) are clamped.
fn soc_sqrt(w: &Vec3, min_spectral_value: f64) -> Vec3 {
    let nw = norm2(w[1], w[2]);
    let l1 = (w[0] - nw).max(min_spectral_value).max(0.0).sqrt();
    let l2 = (w[0] + nw).max(min_spectral_value).max(0.0).sqrt();
    if nw > 0.0 {
        let s = 0.5 * (l2 - l1) / nw;
        [0.5 * (l1 + l2), s * w[1], s * w[2]]
    } else {
        [0.5 * (l1 + l2), 0.0, 0.0]
    }
}

/// `1 - 1/sqrt(2)`: the diagonal of the Fischer-Burmeister Jacobian element chosen at `(0, 0)`.
const FB_ORIGIN_SLOPE: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;

/// Fischer-Burmeister (77) on the second-order cone with `x = (mu r_N, r_T)` and
/// `y = (ũ_N, mu u_T)` (the paper's `y` times mu, same zeros, no division by mu):
/// `F = x + y - (x∘x + y∘y)^(1/2)`. With `z = sqrt(w)`, `L_z dz = L_x dx + L_y dy`, so
/// `dF/dx = I - L_z^-1 L_x` and `dF/dy = I - L_z^-1 L_y`; where `L_z` is singular (w on the cone
/// boundary) z is taken from a slightly smoothed w for the Jacobian only. For mu = 0 the cone
/// degenerates and the scalar FB function on `(r_N, u_N)` with `F_T = r_T` is used.
fn fischer_burmeister(r: &Vec3, u: &Vec3, mu: f64) -> (Vec3, Mat3, Mat3) {
    let mut a = ZERO;
    let mut b = ZERO;
    if mu == 0.0 {
        let h = norm2(r[0], u[0]);
        let f = [r[0] + u[0] - h, r[1], r[2]];
        if h > 0.0 {
            a[0][0] = 1.0 - r[0] / h;
            b[0][0] = 1.0 - u[0] / h;
        } else {
            a[0][0] = FB_ORIGIN_SLOPE;
            b[0][0] = FB_ORIGIN_SLOPE;
        }
        a[1][1] = 1.0;
        a[2][2] = 1.0;
        return (f, a, b);
    }
    let ut = modified_velocity(u, mu);
    let x = [mu * r[0], r[1], r[2]];
    let y = [ut[0], mu * ut[1], mu * ut[2]];
    let w = [
        x[0] * x[0] + x[1] * x[1] + x[2] * x[2] + y[0] * y[0] + y[1] * y[1] + y[2] * y[2],
        2.0 * (x[0] * x[1] + y[0] * y[1]),
        2.0 * (x[0] * x[2] + y[0] * y[2]),
    ];
    let z = soc_sqrt(&w, 0.0);
    let f = [x[0] + y[0] - z[0], x[1] + y[1] - z[1], x[2] + y[2] - z[2]];
    // Smooth w just enough that L_z is safely invertible: the smaller spectral value of z is
    // kept above 1e-10 times the larger one.
    let zj = soc_sqrt(&w, 1e-20 * w[0]);
    let lz = arrow(&zj);
    let (lx, ly) = (arrow(&x), arrow(&y));
    // Columns of L_z^-1 L_x and L_z^-1 L_y.
    let mut dx = ZERO;
    let mut dy = ZERO;
    let mut ok = w[0] > 0.0;
    for j in 0..3 {
        if !ok {
            break;
        }
        match (
            solve3(&lz, &[lx[0][j], lx[1][j], lx[2][j]]),
            solve3(&lz, &[ly[0][j], ly[1][j], ly[2][j]]),
        ) {
            (Some(cx), Some(cy)) if cx.iter().chain(cy.iter()).all(|v| v.is_finite()) => {
                for i in 0..3 {
                    dx[i][j] = IDENTITY[i][j] - cx[i];
                    dy[i][j] = IDENTITY[i][j] - cy[i];
                }
            }
            _ => ok = false,
        }
    }
    if !ok {
        dx = ZERO;
        dy = ZERO;
        for i in 0..3 {
            dx[i][i] = FB_ORIGIN_SLOPE;
            dy[i][i] = FB_ORIGIN_SLOPE;
        }
    }
    // dx/dr = diag(mu, 1, 1); dy/du = diag(1, mu, mu) dũ/du.
    let g = modified_velocity_jacobian(u, mu);
    for i in 0..3 {
        a[i][0] = dx[i][0] * mu;
        a[i][1] = dx[i][1];
        a[i][2] = dx[i][2];
        for j in 0..3 {
            b[i][j] = dy[i][0] * g[0][j] + mu * (dy[i][1] * g[1][j] + dy[i][2] * g[2][j]);
        }
    }
    (f, a, b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    /// Central differences of F in r and u, compared with (A, B) at points away from kinks.
    fn check_against_differences(form: NsnFormulation, r: Vec3, u: Vec3, d: ContactData) {
        let (_, a, b) = residual(form, &r, &u, &d);
        let h = 1e-7;
        for j in 0..3 {
            let (mut rp, mut rm, mut up, mut um) = (r, r, u, u);
            rp[j] += h;
            rm[j] -= h;
            up[j] += h;
            um[j] -= h;
            let (fp, _, _) = residual(form, &rp, &u, &d);
            let (fm, _, _) = residual(form, &rm, &u, &d);
            let (gp, _, _) = residual(form, &r, &up, &d);
            let (gm, _, _) = residual(form, &r, &um, &d);
            for i in 0..3 {
                assert_relative_eq!(a[i][j], (fp[i] - fm[i]) / (2.0 * h), epsilon = 1e-6);
                assert_relative_eq!(b[i][j], (gp[i] - gm[i]) / (2.0 * h), epsilon = 1e-6);
            }
        }
    }

    #[test]
    fn jacobians_match_finite_differences_off_kinks() {
        let d = ContactData {
            mu: 0.6,
            rho_n: 0.8,
            rho_t: 1.3,
        };
        let points = [
            // stick, slide, take-off, mixed
            ([1.0, 0.1, -0.05], [-0.2, 0.01, 0.02]),
            ([1.0, 0.9, -0.7], [-0.1, 0.5, -0.3]),
            ([-0.3, 0.2, 0.1], [0.7, 0.4, -0.2]),
            ([0.4, -0.5, 0.3], [0.2, -0.8, 0.6]),
        ];
        for form in [
            NsnFormulation::AlartCurnier,
            NsnFormulation::JeanMoreau,
            NsnFormulation::NaturalMap,
            NsnFormulation::FischerBurmeister,
        ] {
            for (r, u) in points {
                check_against_differences(form, r, u, d);
            }
        }
    }

    #[test]
    fn residuals_vanish_at_solutions() {
        let d = ContactData {
            mu: 0.5,
            rho_n: 1.0,
            rho_t: 1.0,
        };
        // Stick: r inside the cone, u = 0. Slide: r on the boundary, u_T = -s r_T, u_N = 0.
        // Take-off: r = 0, u_N > 0.
        let cases = [
            ([1.0, 0.2, -0.1], [0.0, 0.0, 0.0]),
            ([2.0, 0.6, 0.8], [0.0, -0.6, -0.8]),
            ([0.0, 0.0, 0.0], [0.5, 0.3, -0.2]),
        ];
        for form in [
            NsnFormulation::AlartCurnier,
            NsnFormulation::JeanMoreau,
            NsnFormulation::NaturalMap,
            NsnFormulation::FischerBurmeister,
        ] {
            for (r, u) in cases {
                let (f, _, _) = residual(form, &r, &u, &d);
                for v in f {
                    assert!(v.abs() < 1e-12, "{form:?} at r={r:?} u={u:?}: F = {f:?}");
                }
            }
        }
    }

    #[test]
    fn frictionless_fischer_burmeister() {
        let (f, a, b) = fischer_burmeister(&[1.0, 0.3, 0.0], &[0.0, 5.0, 1.0], 0.0);
        assert_eq!(f, [0.0, 0.3, 0.0]);
        assert_relative_eq!(a[0][0], 0.0);
        assert_relative_eq!(b[0][0], 1.0);
        assert_eq!(a[1][1], 1.0);
    }
}

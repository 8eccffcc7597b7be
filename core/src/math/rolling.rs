//! The rolling-friction cone of Siconos' rolling problems, for contacts of dimension `D` = 5
//! (normal, two tangential, two rolling components) or 3 (normal, one tangential, one rolling):
//!
//! `K = { r : ||r_T|| <= mu r_N, ||r_R|| <= mu_r r_N }`,
//!
//! the intersection of a Coulomb cone on the tangential part and one on the rolling part. The
//! tangential part is `r[1..1 + m]`, the rolling part `r[1 + m..D]`, with `m = (D - 1) / 2`.
//!
//! Its dual is `K* = { y : y_N >= mu ||y_T|| + mu_r ||y_R|| }` (the support of `K` in the
//! direction `-y`: `min_{r in K} y·r = r_N (y_N - mu ||y_T|| - mu_r ||y_R||)`), so the De Saxcé
//! velocity of the rolling law is `ũ = (u_N + mu ||u_T|| + mu_r ||u_R||, u_T, u_R)`: `ũ ∈ K*` is
//! `u_N >= 0`.
//!
//! Projection. For a fixed normal component `t >= 0` the nearest point of `K` keeps the normal
//! component `t` and projects each part on its disk; what is left is the convex piecewise
//! quadratic `f(t) = (t - x_N)^2 + (||x_T|| - mu t)_+^2 + (||x_R|| - mu_r t)_+^2`. Its minimiser
//! solves a linear equation once the set of active parts (the parts with `||x_i|| > mu_i t`) is
//! known: the projection takes the candidate (both parts, tangential only, rolling only) whose
//! active set it confirms, and when rounding confirms none (a point on a breakpoint) the
//! candidate of least `f`, which is the minimiser of the convex `f` among them.

/// Number of tangential (and of rolling) components of a contact of dimension `D`.
#[inline]
pub const fn part_len(d: usize) -> usize {
    (d - 1) / 2
}

/// `(||x_T||, ||x_R||)`.
#[inline]
pub fn part_norms<const D: usize>(x: &[f64; D]) -> (f64, f64) {
    let m = part_len(D);
    if m == 1 {
        return (x[1].abs(), x[2].abs());
    }
    let mut t = 0.0;
    let mut r = 0.0;
    for k in 1..=m {
        t += x[k] * x[k];
        r += x[k + m] * x[k + m];
    }
    (t.sqrt(), r.sqrt())
}

/// Whether `x` is in the rolling cone.
#[inline]
pub fn in_rolling_cone<const D: usize>(x: &[f64; D], mu: f64, mu_r: f64) -> bool {
    let (nt, nr) = part_norms(x);
    nt <= mu * x[0] && nr <= mu_r * x[0]
}

/// Whether `x` is in the polar cone `-K*` (its projection on `K` is 0).
#[inline]
pub fn in_rolling_polar<const D: usize>(x: &[f64; D], mu: f64, mu_r: f64) -> bool {
    let (nt, nr) = part_norms(x);
    mu * nt + mu_r * nr <= -x[0]
}

/// The Euclidean projection of `x` on the rolling cone of coefficients `mu`, `mu_r` (both >= 0).
#[inline]
pub fn project_on_rolling_cone<const D: usize>(x: &[f64; D], mu: f64, mu_r: f64) -> [f64; D] {
    let (nt, nr) = part_norms(x);
    let x0 = x[0];
    if nt <= mu * x0 && nr <= mu_r * x0 {
        return *x;
    }
    if mu * nt + mu_r * nr <= -x0 {
        return [0.0; D];
    }
    let candidates = [
        (x0 + mu * nt + mu_r * nr) / (1.0 + mu * mu + mu_r * mu_r),
        (x0 + mu * nt) / (1.0 + mu * mu),
        (x0 + mu_r * nr) / (1.0 + mu_r * mu_r),
    ];
    // The candidate whose active set it confirms is the minimiser; when rounding leaves none
    // confirmed (a point on a breakpoint), the least value of f decides.
    let [both, tangential, rolling] = candidates;
    let t = if nt > mu * both && nr > mu_r * both {
        both
    } else if nt > mu * tangential && nr <= mu_r * tangential {
        tangential
    } else if nt <= mu * rolling && nr > mu_r * rolling {
        rolling
    } else {
        let f = |t: f64| {
            let a = (nt - mu * t).max(0.0);
            let b = (nr - mu_r * t).max(0.0);
            (t - x0) * (t - x0) + a * a + b * b
        };
        let mut t = 0.0;
        let mut best = f(0.0);
        for c in candidates {
            let c = c.max(0.0);
            let v = f(c);
            if v < best {
                best = v;
                t = c;
            }
        }
        t
    };
    let m = part_len(D);
    let mut p = *x;
    p[0] = t;
    // Each part scaled back on its disk of radius mu_i t when it lies outside.
    let st = if nt > mu * t { mu * t / nt } else { 1.0 };
    let sr = if nr > mu_r * t { mu_r * t / nr } else { 1.0 };
    for k in 1..=m {
        p[k] *= st;
        p[k + m] *= sr;
    }
    p
}

/// The projection of `x` on the dual cone `K*`, by Moreau's decomposition: `x = P_{K*}(x) -
/// P_K(-x)`.
#[inline]
pub fn project_on_rolling_dual<const D: usize>(x: &[f64; D], mu: f64, mu_r: f64) -> [f64; D] {
    let mut neg = *x;
    neg.iter_mut().for_each(|v| *v = -*v);
    let p = project_on_rolling_cone(&neg, mu, mu_r);
    let mut y = *x;
    for (yk, pk) in y.iter_mut().zip(&p) {
        *yk += pk;
    }
    y
}

/// The De Saxcé velocity of the rolling law, `(u_N + mu ||u_T|| + mu_r ||u_R||, u_T, u_R)`.
#[inline]
pub fn rolling_modified_velocity<const D: usize>(u: &[f64; D], mu: f64, mu_r: f64) -> [f64; D] {
    let (nt, nr) = part_norms(u);
    let mut v = *u;
    v[0] += mu * nt + mu_r * nr;
    v
}

/// Squared natural-map residual of one rolling contact, `||r - P_K(r - ũ)||^2` (the quantity
/// Siconos' `rolling_fc3d_unitary_compute_and_add_error` adds up).
#[inline]
pub fn rolling_residual_sq<const D: usize>(r: &[f64; D], u: &[f64; D], mu: f64, mu_r: f64) -> f64 {
    let ut = rolling_modified_velocity(u, mu, mu_r);
    let mut x = *r;
    for (xk, uk) in x.iter_mut().zip(&ut) {
        *xk -= uk;
    }
    let p = project_on_rolling_cone(&x, mu, mu_r);
    let mut s = 0.0;
    for k in 0..D {
        let d = r[k] - p[k];
        s += d * d;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn dot<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
        a.iter().zip(b).map(|(x, y)| x * y).sum()
    }

    fn dist<const D: usize>(a: &[f64; D], b: &[f64; D]) -> f64 {
        a.iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt()
    }

    fn scale(x: &[f64]) -> f64 {
        x.iter().fold(1.0f64, |a, v| a.max(v.abs()))
    }

    /// A point of K from a direction: normal |a|, parts scaled into their disks.
    fn in_cone<const D: usize>(x: &[f64; D], mu: f64, mu_r: f64) -> [f64; D] {
        let m = part_len(D);
        let mut k = *x;
        k[0] = x[0].abs();
        let (nt, nr) = part_norms(x);
        for j in 1..=m {
            if nt > 0.0 {
                k[j] = x[j] / nt.max(1.0) * mu * k[0] / (1.0 + nt);
            }
            if nr > 0.0 {
                k[j + m] = x[j + m] / nr.max(1.0) * mu_r * k[0] / (1.0 + nr);
            }
        }
        k
    }

    fn check_projection<const D: usize>(x: [f64; D], k: [f64; D], mu: f64, mu_r: f64) {
        let s = scale(&x);
        let tol = 1e-10 * s;
        let p = project_on_rolling_cone(&x, mu, mu_r);
        // In the cone (up to rounding).
        let (nt, nr) = part_norms(&p);
        assert!(
            p[0] >= -tol && nt <= mu * p[0] + tol && nr <= mu_r * p[0] + tol,
            "{p:?}"
        );
        // Idempotent.
        let pp = project_on_rolling_cone(&p, mu, mu_r);
        assert!(dist(&p, &pp) <= tol, "{p:?} {pp:?}");
        // Moreau: x - P_K(x) is in the polar cone and orthogonal to P_K(x).
        let mut y = x;
        for j in 0..D {
            y[j] -= p[j];
        }
        let (yt, yr) = part_norms(&y);
        assert!(mu * yt + mu_r * yr + y[0] <= tol, "{y:?}");
        assert!(dot(&y, &p).abs() <= tol * s, "{}", dot(&y, &p));
        // The dual projection completes the decomposition: x = P_K(x) - P_{K*}(-x).
        let mut neg = x;
        neg.iter_mut().for_each(|v| *v = -*v);
        let d = project_on_rolling_dual(&neg, mu, mu_r);
        let (dt, dr) = part_norms(&d);
        assert!(d[0] + tol >= mu * dt + mu_r * dr, "{d:?}");
        for j in 0..D {
            assert!((x[j] - (p[j] - d[j])).abs() <= tol, "{x:?} {p:?} {d:?}");
        }
        // Nearest point: the variational inequality against a point of K.
        let kk = in_cone(&k, mu, mu_r);
        let mut kp = kk;
        for j in 0..D {
            kp[j] -= p[j];
        }
        assert!(dot(&y, &kp) <= tol * scale(&kk).max(s), "{}", dot(&y, &kp));
        assert!(dist(&x, &p) <= dist(&x, &kk) + tol);
    }

    proptest! {
        #[test]
        fn projection_properties_5d(
            x in prop::array::uniform5(-10.0f64..10.0),
            k in prop::array::uniform5(-10.0f64..10.0),
            mu in 0.0f64..2.0,
            mu_r in 0.0f64..2.0,
        ) {
            check_projection(x, k, mu, mu_r);
        }

        #[test]
        fn projection_properties_3d(
            x in prop::array::uniform3(-10.0f64..10.0),
            k in prop::array::uniform3(-10.0f64..10.0),
            mu in 0.0f64..2.0,
            mu_r in 0.0f64..2.0,
        ) {
            check_projection(x, k, mu, mu_r);
        }
    }

    #[test]
    fn projection_cases_by_hand() {
        // Inside and polar.
        let x = [1.0, 0.1, 0.0, 0.0, 0.01];
        assert_eq!(project_on_rolling_cone(&x, 0.5, 0.1), x);
        assert_eq!(
            project_on_rolling_cone(&[-1.0, 0.1, 0.0, 0.1, 0.0], 0.5, 0.1),
            [0.0; 5]
        );
        // Only the tangential part outside: the Coulomb projection on (x_N, x_T), x_R kept.
        // (1, 2, 0) on ||t|| <= r_N: r_N = (1 + 2) / 2 = 1.5, t = 1.5.
        let p = project_on_rolling_cone(&[1.0, 2.0, 0.0, 0.1, 0.0], 1.0, 1.0);
        assert_eq!(p, [1.5, 1.5, 0.0, 0.1, 0.0]);
        // Both parts outside: t = (x_N + mu nt + mu_r nr) / (1 + mu^2 + mu_r^2) = (0 + 2 + 2) / 3.
        let p = project_on_rolling_cone(&[0.0, 2.0, 0.0, 0.0, 2.0], 1.0, 1.0);
        let t = 4.0 / 3.0;
        assert!(dist(&p, &[t, t, 0.0, 0.0, t]) < 1e-15);
        // 2D rolling: (x_N, x_T, x_R).
        let p = project_on_rolling_cone(&[1.0, 0.0, -3.0], 0.3, 1.0);
        assert!(dist(&p, &[2.0, 0.0, -2.0]) < 1e-15);
    }

    #[test]
    fn residual_vanishes_on_the_three_branches() {
        let (mu, mu_r) = (0.5, 0.1);
        // Take-off: r = 0, u_N > 0.
        assert_eq!(
            rolling_residual_sq(&[0.0; 5], &[1.0, 3.0, -1.0, 2.0, 0.5], mu, mu_r),
            0.0
        );
        // Stick (sliding and rolling both stopped): r inside, u = 0.
        assert_eq!(
            rolling_residual_sq(&[1.0, 0.2, 0.1, 0.05, 0.0], &[0.0; 5], mu, mu_r),
            0.0
        );
        // Sliding and rolling: each part at its boundary, opposite to its velocity, u_N = 0.
        let r = [2.0, -1.0, 0.0, 0.0, -0.2];
        let u = [0.0, 3.0, 0.0, 0.0, 7.0];
        assert!(rolling_residual_sq(&r, &u, mu, mu_r) < 1e-28);
        // A wrong direction is not a solution.
        let r = [2.0, 1.0, 0.0, 0.0, -0.2];
        assert!(rolling_residual_sq(&r, &u, mu, mu_r) > 1e-3);
    }
}

//! The exact solution of one contact by enumeration [562 QUARTIC] (the approach of
//! Bonnefon-Daviet): take-off, then stick, then slide, whose direction solves a quartic.
//!
//! * Take-off: `r = 0` solves the contact iff `q_N >= 0` (then `ũ = (q_N + mu||q_T||, q_T)`).
//! * Stick: `r = -W^{-1} q` if it lies in K (then `u = 0`).
//! * Slide: `r = r_N (1, -mu d)` with `|d| = 1`, `u_N = 0` and `u_T = s d`, `s > 0`.
//!   `u_N = 0` gives `r_N = -q_N / a(d)`, `a(d) = W_NN - mu W_NT·d`; `u_T ∥ d` is
//!   `cross(a u_T, d) = 0`, i.e. with `d = (c, s)`
//!   `A c^2 + B c s + C s^2 + D c + E s = 0`,
//!   * from `-q_N W_TN`: `D += q_N W_T2N`, `E -= q_N W_T1N`;
//!   * from `mu q_N W_TT d`: `A -= mu q_N W_21`, `B += mu q_N (W_11 - W_22)`, `C += mu q_N W_12`;
//!   * from `W_NN q_T`: `D -= W_NN q_T2`, `E += W_NN q_T1`;
//!   * from `-mu (W_NT·d) q_T`: `A += mu W_N1 q_T2`, `B -= mu (W_N1 q_T1 - W_N2 q_T2)`,
//!     `C -= mu W_N2 q_T1`.
//!
//!   `t = tan(theta/2)` turns it into the quartic
//!   `(A - D) t^4 + 2(E - B) t^3 + (4C - 2A) t^2 + 2(B + E) t + (A + D) = 0`,
//!   `d = (-1, 0)` (t = ∞) being checked directly. Real roots are found by Durand-Kerner
//!   iterations on the monic polynomial, polished by Newton on the trigonometric equation, and
//!   each admissible one (`r_N > 0`, `u_T·d > 0`) is a candidate; the one with the smallest
//!   natural-map residual wins.
//!
//! When no candidate solves the contact to the local tolerance (a degenerate W, or rounding
//! in a nearly double root), the best candidate is refined by the Alart-Curnier Newton with
//! line search, which also keeps the answer finite.

use super::{local_rho, AlartCurnierNewton, LocalOutcome, LocalProblem, LocalSolver};
use crate::local::{LocalSolverKind, LocalSolverOptions, RhoRule};
use crate::math::linalg::{norm2, solve3, Mat3, Vec3};

/// Durand-Kerner iterations at most, and the relative move below which it stops.
const DURAND_KERNER_MAX_ITER: usize = 100;
const DURAND_KERNER_STEP: f64 = 1e-10;

pub struct Quartic {
    tolerance: f64,
    fallback: AlartCurnierNewton,
}

impl Quartic {
    pub fn new(options: &LocalSolverOptions) -> Self {
        let mut newton = LocalSolverOptions::new(LocalSolverKind::NewtonAlartCurnierGp);
        newton.tolerance = options.tolerance.min(1e-14);
        newton.max_iter = 50;
        Quartic {
            tolerance: options.tolerance,
            fallback: AlartCurnierNewton::new(&newton),
        }
    }
}

/// Coefficients `(A, B, C, D, E)` of the slide equation (module documentation).
fn slide_equation(p: &LocalProblem<'_>) -> [f64; 5] {
    let w = p.w;
    let (qn, qt, mu) = (p.q[0], [p.q[1], p.q[2]], p.mu);
    let mut a = -mu * qn * w[2][1] + mu * w[0][1] * qt[1];
    let mut b = mu * qn * (w[1][1] - w[2][2]) - mu * (w[0][1] * qt[0] - w[0][2] * qt[1]);
    let mut c = mu * qn * w[1][2] - mu * w[0][2] * qt[0];
    let mut d = qn * w[2][0] - w[0][0] * qt[1];
    let mut e = -qn * w[1][0] + w[0][0] * qt[0];
    // Normalize: the equation is homogeneous in its coefficients.
    let m = a.abs().max(b.abs()).max(c.abs()).max(d.abs()).max(e.abs());
    if m > 0.0 && m.is_finite() {
        a /= m;
        b /= m;
        c /= m;
        d /= m;
        e /= m;
    }
    [a, b, c, d, e]
}

/// Value and derivative in theta of the slide equation at `d = (cos theta, sin theta)`.
#[inline]
fn slide_eq_theta(k: &[f64; 5], theta: f64) -> (f64, f64) {
    let (s, c) = theta.sin_cos();
    let f = k[0] * c * c + k[1] * c * s + k[2] * s * s + k[3] * c + k[4] * s;
    // d/dtheta: c' = -s, s' = c.
    let df =
        -2.0 * k[0] * c * s + k[1] * (c * c - s * s) + 2.0 * k[2] * s * c - k[3] * s + k[4] * c;
    (f, df)
}

#[derive(Clone, Copy)]
struct Complex {
    re: f64,
    im: f64,
}

impl Complex {
    fn mul(self, o: Complex) -> Complex {
        Complex {
            re: self.re * o.re - self.im * o.im,
            im: self.re * o.im + self.im * o.re,
        }
    }
    fn sub(self, o: Complex) -> Complex {
        Complex {
            re: self.re - o.re,
            im: self.im - o.im,
        }
    }
    fn div(self, o: Complex) -> Option<Complex> {
        let den = o.re * o.re + o.im * o.im;
        if den == 0.0 || !den.is_finite() {
            return None;
        }
        Some(Complex {
            re: (self.re * o.re + self.im * o.im) / den,
            im: (self.im * o.re - self.re * o.im) / den,
        })
    }
}

/// Real roots (at most 4) of `sum_i c[i] t^(4-i)`, leading zero coefficients dropped.
/// Returns them in a fixed array with a count.
fn real_roots(c: [f64; 5]) -> ([f64; 4], usize) {
    let scale = c.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut out = [0.0; 4];
    if scale == 0.0 || !scale.is_finite() {
        return (out, 0);
    }
    let mut start = 0;
    while start < 5 && c[start].abs() <= 1e-14 * scale {
        start += 1;
    }
    let degree = 4usize.saturating_sub(start);
    if start >= 4 {
        return (out, 0);
    }
    let lead = c[start];
    let mut monic = [0.0; 5];
    for i in 0..=degree {
        monic[i] = c[start + i] / lead;
    }
    let eval = |z: Complex| {
        let mut acc = Complex { re: 1.0, im: 0.0 };
        for coef in monic.iter().take(degree + 1).skip(1) {
            acc = acc.mul(z);
            acc.re += coef;
        }
        acc
    };
    // Durand-Kerner from the classical non-real starting points, inside a radius bound.
    let radius = 1.0 + monic[1..=degree].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let mut z = [Complex { re: 0.0, im: 0.0 }; 4];
    let seed = Complex { re: 0.4, im: 0.9 };
    let mut pw = Complex { re: 1.0, im: 0.0 };
    for zi in z.iter_mut().take(degree) {
        *zi = Complex {
            re: pw.re * radius.min(10.0),
            im: pw.im * radius.min(10.0),
        };
        pw = pw.mul(seed);
    }
    // The roots only seed the Newton polish on the trigonometric equation: a few digits
    // suffice, and clustered roots (where Durand-Kerner converges linearly) stop at the cap.
    for _ in 0..DURAND_KERNER_MAX_ITER {
        let mut moved = 0.0f64;
        for i in 0..degree {
            let mut den = Complex { re: 1.0, im: 0.0 };
            for j in 0..degree {
                if i != j {
                    den = den.mul(z[i].sub(z[j]));
                }
            }
            if let Some(step) = eval(z[i]).div(den) {
                if step.re.is_finite() && step.im.is_finite() {
                    z[i] = z[i].sub(step);
                    moved = moved.max(norm2(step.re, step.im) / (1.0 + norm2(z[i].re, z[i].im)));
                }
            }
        }
        if moved < DURAND_KERNER_STEP {
            break;
        }
    }
    let mut n = 0;
    for zi in z.iter().take(degree) {
        if zi.im.abs() <= 1e-6 * (1.0 + zi.re.abs()) && zi.re.is_finite() {
            out[n] = zi.re;
            n += 1;
        }
    }
    (out, n)
}

/// The slide candidate along `d` with its natural-map residual, if admissible.
fn slide_candidate(p: &LocalProblem<'_>, d: [f64; 2]) -> Option<Vec3> {
    let a = p.w[0][0] - p.mu * (p.w[0][1] * d[0] + p.w[0][2] * d[1]);
    let rn = -p.q[0] / a;
    if !(rn > 0.0 && rn.is_finite()) {
        return None;
    }
    let r = [rn, -p.mu * rn * d[0], -p.mu * rn * d[1]];
    let u = p.velocity(&r);
    // u_T must point along d (the reaction opposes the sliding velocity).
    if u[1] * d[0] + u[2] * d[1] < 0.0 {
        return None;
    }
    Some(r)
}

impl Quartic {
    /// The enumerated solution with the smallest residual (None if no case applies).
    fn enumerate(&self, p: &LocalProblem<'_>) -> Option<Vec3> {
        if p.q[0] >= 0.0 {
            return Some([0.0; 3]);
        }
        let mut best: Option<(f64, Vec3)> = None;
        let mut consider = |r: Vec3| {
            let res = p.residual(&r);
            if res.is_finite() && best.is_none_or(|b| res < b.0) {
                best = Some((res, r));
            }
        };
        if let Some(r) = solve3(p.w, &[-p.q[0], -p.q[1], -p.q[2]]) {
            if r[0] >= 0.0 && norm2(r[1], r[2]) <= p.mu * r[0] {
                consider(r);
            }
        }
        if p.mu == 0.0 {
            consider([(-p.q[0] / p.w[0][0]).max(0.0), 0.0, 0.0]);
            return best.map(|b| b.1);
        }
        let k = slide_equation(p);
        let poly = [
            k[0] - k[3],
            2.0 * (k[4] - k[1]),
            4.0 * k[2] - 2.0 * k[0],
            2.0 * (k[1] + k[4]),
            k[0] + k[3],
        ];
        let (roots, n) = real_roots(poly);
        let mut thetas = [std::f64::consts::PI; 5];
        for i in 0..n {
            thetas[i] = 2.0 * roots[i].atan();
        }
        for &theta0 in thetas.iter().take(n + 1) {
            let mut theta = theta0;
            for _ in 0..8 {
                let (f, df) = slide_eq_theta(&k, theta);
                if df == 0.0 || f == 0.0 {
                    break;
                }
                let next = theta - f / df;
                if !next.is_finite() || (next - theta).abs() > 0.5 {
                    break;
                }
                let converged = (next - theta).abs() <= 4.0 * f64::EPSILON * (1.0 + theta.abs());
                theta = next;
                if converged {
                    break;
                }
            }
            let (s, c) = theta.sin_cos();
            if let Some(r) = slide_candidate(p, [c, s]) {
                consider(r);
            }
        }
        best.map(|b| b.1)
    }
}

impl LocalSolver for Quartic {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        local_rho(w, RhoRule::SplitSpectralNorm)
    }

    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        if let Some(x) = self.enumerate(p) {
            if p.residual(&x) <= self.tolerance * p.scale(&x) {
                *r = x;
                return LocalOutcome {
                    converged: true,
                    iterations: 1,
                };
            }
            if p.residual(&x) < p.residual(r) {
                *r = x;
            }
        }
        let out = self.fallback.solve_with_rho(p, rho, r);
        LocalOutcome {
            converged: out.converged || p.residual(r) <= self.tolerance * p.scale(r),
            iterations: 1 + out.iterations,
        }
    }
}

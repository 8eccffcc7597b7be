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
//!   `d = (-1, 0)` (t = ∞) being checked directly. Real roots are isolated between the critical
//!   points of the quartic (the real roots of its derivative, recursively) and found by
//!   bracketed Newton steps, then polished by Newton on the trigonometric equation, and
//!   each admissible one (`r_N > 0`, `u_T·d > 0`) is a candidate; the one with the smallest
//!   natural-map residual wins.
//!
//! When no candidate solves the contact to the local tolerance (a degenerate W, or rounding
//! in a nearly double root), the best candidate is refined by the Alart-Curnier Newton with
//! line search, which also keeps the answer finite.

use super::{local_rho, AlartCurnierNewton, LocalOutcome, LocalProblem, LocalSolver};
use crate::local::{LocalSolverKind, LocalSolverOptions, RhoRule};
use crate::math::linalg::{norm2, solve3, Mat3, Vec3};
use crate::measure::contact_residual_sq;

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

/// Value and derivative in theta of the slide equation at the unit direction
/// `d = (c, s) = (cos theta, sin theta)`.
#[inline]
fn slide_eq_at(k: &[f64; 5], [c, s]: [f64; 2]) -> (f64, f64) {
    let f = k[0] * c * c + k[1] * c * s + k[2] * s * s + k[3] * c + k[4] * s;
    // d/dtheta: c' = -s, s' = c.
    let df =
        -2.0 * k[0] * c * s + k[1] * (c * c - s * s) + 2.0 * k[2] * s * c - k[3] * s + k[4] * c;
    (f, df)
}

/// Largest root `|t|` searched for (`t = tan(theta / 2)`).
const ROOT_CAP: f64 = 1e8;
/// Step (relative to `1 + |t|`) at which the root iteration stops.
const ROOT_STEP: f64 = 1e-14;

/// Real roots (at most 4) of `sum_i c[i] t^(4-i)`, leading zero coefficients dropped, in a
/// fixed array with a count. Between consecutive critical points (the real roots of the
/// derivative, found the same way) the polynomial is monotone: each interval whose ends differ
/// in sign holds one root, found by Newton steps kept inside the bracket (bisection when a step
/// leaves it); a critical point where the polynomial nearly vanishes is a double root.
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
    if start >= 4 {
        return (out, 0);
    }
    let degree = 4 - start;
    let mut monic = [0.0; 5];
    for i in 0..=degree {
        monic[i] = c[start + i] / c[start];
    }
    let n = monic_real_roots(&monic[..=degree], &mut out);
    (out, n)
}

/// Real roots of the monic polynomial `a[0] t^d + ... + a[d]` (`a[0] = 1`, `d <= 4`) into `out`;
/// returns their number, in increasing order.
fn monic_real_roots(a: &[f64], out: &mut [f64; 4]) -> usize {
    let d = a.len() - 1;
    match d {
        0 => return 0,
        1 => {
            out[0] = -a[1];
            return 1;
        }
        2 => {
            let (b, c) = (a[1], a[2]);
            let disc = b * b - 4.0 * c;
            if disc < 0.0 {
                return 0;
            }
            // The root away from cancellation first, the other from the product.
            let big = -0.5 * (b + b.signum() * disc.sqrt());
            if big == 0.0 {
                out[0] = 0.0;
                return 1;
            }
            let (x, y) = (big, c / big);
            out[0] = x.min(y);
            out[1] = x.max(y);
            return 2;
        }
        _ => {}
    }
    let eval = |t: f64| {
        let (mut p, mut dp) = (0.0, 0.0);
        for &k in a {
            dp = dp * t + p;
            p = p * t + k;
        }
        (p, dp)
    };
    // |p(t)| below this is rounding: the sum of the magnitudes of the terms.
    let noise = |t: f64| {
        let mut m = 0.0;
        for &k in a {
            m = m * t.abs() + k.abs();
        }
        1e-10 * m
    };
    // Critical points: roots of p' / d (monic).
    let mut derivative = [0.0; 4];
    for (i, k) in a[..d].iter().enumerate() {
        derivative[i] = k * (d - i) as f64 / d as f64;
    }
    let mut critical = [0.0; 4];
    let nc = monic_real_roots(&derivative[..d], &mut critical);
    // Every root lies inside Fujiwara's bound `2 max |a_k|^(1/k)` (`|a_d / 2|^(1/d)` for the
    // last), made strict. Roots beyond ROOT_CAP (slide angles within 2 / ROOT_CAP of pi) are
    // left to the polish from the candidate theta = pi.
    let mut fujiwara = 0.0f64;
    for (k, &ak) in a.iter().enumerate().skip(1) {
        let v = if k == d { 0.5 * ak.abs() } else { ak.abs() };
        // |v|^(1/k) by roots rather than powf (this runs for every slide enumeration).
        let root = match k {
            1 => v,
            2 => v.sqrt(),
            3 => v.cbrt(),
            _ => v.sqrt().sqrt(),
        };
        fujiwara = fujiwara.max(root);
    }
    let bound = (2.0 * fujiwara * (1.0 + 1e-12) + f64::MIN_POSITIVE).min(ROOT_CAP);
    let mut ends = [0.0; 5];
    ends[0] = -bound;
    ends[1..=nc].copy_from_slice(&critical[..nc]);
    ends[nc + 1] = bound;
    let mut n = 0;
    let mut push = |x: f64, n: &mut usize| {
        if *n < 4 && (*n == 0 || x > out[*n - 1]) {
            out[*n] = x;
            *n += 1;
        }
    };
    let mut left = eval(ends[0]).0;
    for k in 0..=nc {
        let (lo, hi) = (ends[k], ends[k + 1]);
        let right = eval(hi).0;
        let left_zero = k > 0 && left.abs() <= noise(lo);
        let right_zero = k < nc && right.abs() <= noise(hi);
        if left_zero {
            // A double root at the critical point (recorded once).
            push(lo, &mut n);
        } else if !right_zero && (left < 0.0) != (right < 0.0) {
            push(bracketed_root(&eval, lo, hi, left), &mut n);
        }
        left = right;
    }
    n
}

/// The root of `p` (value and derivative from `eval`) in `[lo, hi]`, where `p(lo) = p_lo` and
/// `p(hi)` differ in sign.
fn bracketed_root(eval: &dyn Fn(f64) -> (f64, f64), mut lo: f64, mut hi: f64, p_lo: f64) -> f64 {
    let lo_negative = p_lo < 0.0;
    let mut t = 0.5 * (lo + hi);
    for _ in 0..100 {
        let (p, dp) = eval(t);
        if p == 0.0 {
            return t;
        }
        if (p < 0.0) == lo_negative {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - p / dp;
        let next = if newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        // The polish on theta follows: t to 1e-14 (absolute near 0) is plenty, and rounding
        // keeps Newton from settling tighter near a root at 0.
        if (next - t).abs() <= ROOT_STEP * (1.0 + t.abs())
            || hi - lo <= ROOT_STEP * (1.0 + lo.abs().max(hi.abs()))
        {
            return next;
        }
        t = next;
    }
    t
}

/// The slide candidate along the unit direction `d` and its velocity, if admissible.
fn slide_candidate(p: &LocalProblem<'_>, d: [f64; 2]) -> Option<(Vec3, Vec3)> {
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
    Some((r, u))
}

/// The unit slide direction of `t = tan(theta / 2)`, without trigonometric functions.
#[inline]
fn direction_of_half_angle_tangent(t: f64) -> [f64; 2] {
    let t2 = t * t;
    let inv = 1.0 / (1.0 + t2);
    [(1.0 - t2) * inv, 2.0 * t * inv]
}

/// A candidate reaction with its squared natural-map residual.
#[derive(Clone, Copy)]
struct Candidate {
    r: Vec3,
    residual_sq: f64,
}

impl Quartic {
    /// Squared local tolerance relative to the scale of `p` at `r` (`p.scale(r)` squared, without
    /// its square roots).
    #[inline]
    fn tolerance_sq(&self, p: &LocalProblem<'_>, r: &Vec3) -> f64 {
        let norm_sq = |v: &Vec3| v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
        let scale_sq = norm_sq(r).max(norm_sq(&p.q));
        self.tolerance * self.tolerance * scale_sq
    }

    /// The enumerated solution with the smallest residual (None if no case applies). A
    /// candidate that solves the contact to the local tolerance ends the enumeration.
    fn enumerate(&self, p: &LocalProblem<'_>) -> Option<Candidate> {
        if p.q[0] >= 0.0 {
            // Take-off: `ũ = (q_N + mu ||q_T||, q_T)` lies in the dual cone, the residual is 0.
            return Some(Candidate {
                r: [0.0; 3],
                residual_sq: 0.0,
            });
        }
        let mut best: Option<Candidate> = None;
        let mut consider = |r: Vec3, u: &Vec3| {
            let residual_sq = contact_residual_sq(&r, u, p.mu);
            let candidate = Candidate { r, residual_sq };
            if residual_sq.is_finite() && best.is_none_or(|b| residual_sq < b.residual_sq) {
                best = Some(candidate);
            }
            candidate
        };
        if let Some(r) = solve3(p.w, &[-p.q[0], -p.q[1], -p.q[2]]) {
            if r[0] >= 0.0 && r[1] * r[1] + r[2] * r[2] <= p.mu * p.mu * r[0] * r[0] {
                // As in Siconos, a stick that solves the contact ends the enumeration. With r in
                // K, P_K(r) = r and P_K is 1-Lipschitz, so the residual is at most ||ũ||, and
                // ||ũ||^2 <= 2 u_N^2 + (1 + 2 mu^2) ||u_T||^2: a test without projection or root.
                let u = p.velocity(&r);
                let ut_sq = u[1] * u[1] + u[2] * u[2];
                let bound_sq = 2.0 * u[0] * u[0] + (1.0 + 2.0 * p.mu * p.mu) * ut_sq;
                let tolerance_sq = self.tolerance_sq(p, &r);
                if bound_sq <= tolerance_sq {
                    return Some(Candidate {
                        r,
                        residual_sq: bound_sq,
                    });
                }
                if consider(r, &u).residual_sq <= tolerance_sq {
                    return best;
                }
            }
        }
        if p.mu == 0.0 {
            let r = [(-p.q[0] / p.w[0][0]).max(0.0), 0.0, 0.0];
            consider(r, &p.velocity(&r));
            return best;
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
        // The roots, then t = infinity (d = (-1, 0)).
        for i in 0..=n {
            let d0 = if i < n {
                direction_of_half_angle_tangent(roots[i])
            } else {
                [-1.0, 0.0]
            };
            if let Some((r, u)) = slide_candidate(p, polish_slide_direction(&k, d0)) {
                consider(r, &u);
            }
        }
        best
    }

    /// Within a sweep a sliding contact usually slides on in nearly the same direction: the
    /// slide along the direction of `previous` (a reaction on the boundary of the cone), polished
    /// on the slide equation, when it solves the contact to the local tolerance. The
    /// enumeration gives the same point (a solution is verified, not assumed) in more time.
    fn warm_slide(&self, p: &LocalProblem<'_>, previous: &Vec3) -> Option<Vec3> {
        if p.q[0] >= 0.0 || p.mu == 0.0 || !(previous[0] > 0.0) {
            return None;
        }
        let norm_t = norm2(previous[1], previous[2]);
        let on_boundary = (norm_t - p.mu * previous[0]).abs() <= 1e-9 * norm_t;
        if !(norm_t > 0.0 && on_boundary) {
            return None;
        }
        let d0 = [-previous[1] / norm_t, -previous[2] / norm_t];
        let (r, u) = slide_candidate(p, polish_slide_direction(&slide_equation(p), d0))?;
        (contact_residual_sq(&r, &u, p.mu) <= self.tolerance_sq(p, &r)).then_some(r)
    }
}

/// Newton on the slide equation in theta from the unit direction `d`, at most 8 steps of at
/// most 0.5. A step `delta` moves `d` to `(d + delta d_perp) / sqrt(1 + delta^2)`, a turn by
/// `atan(delta)`: the same quadratic convergence as a turn by `delta`, without sine or cosine.
fn polish_slide_direction(k: &[f64; 5], mut d: [f64; 2]) -> [f64; 2] {
    for _ in 0..8 {
        let (f, df) = slide_eq_at(k, d);
        if df == 0.0 || f == 0.0 {
            break;
        }
        let delta = -f / df;
        if !delta.is_finite() || delta.abs() > 0.5 {
            break;
        }
        let inv = 1.0 / (1.0 + delta * delta).sqrt();
        d = [(d[0] - delta * d[1]) * inv, (d[1] + delta * d[0]) * inv];
        if delta.abs() <= 4.0 * f64::EPSILON {
            break;
        }
    }
    d
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
        if let Some(x) = self.warm_slide(p, r) {
            *r = x;
            return LocalOutcome {
                converged: true,
                iterations: 1,
            };
        }
        if let Some(best) = self.enumerate(p) {
            if best.residual_sq <= self.tolerance_sq(p, &best.r) {
                *r = best.r;
                return LocalOutcome {
                    converged: true,
                    iterations: 1,
                };
            }
            if best.residual_sq.sqrt() < p.residual(r) {
                *r = best.r;
            }
        }
        let out = self.fallback.solve_with_rho(p, rho, r);
        LocalOutcome {
            converged: out.converged || p.residual(r) <= self.tolerance * p.scale(r),
            iterations: 1 + out.iterations,
        }
    }
}

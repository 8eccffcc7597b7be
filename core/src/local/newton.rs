//! Alart-Curnier nonsmooth Newton for one contact (formulation (61), Jacobian of appendix B.2,
//! re-derived below), with an optional Goldstein-Price line search and the hybrid fallback to
//! projection steps that Siconos uses by default.
//!
//! With `u = w r + q`, `s_N = r_N - rho_N u_N`, `s_T = r_T - rho_T u_T` and `R = mu (s_N)_+`:
//!
//! `F_N = r_N - (s_N)_+`,  `F_T = r_T - P_{B(0,R)}(s_T)`.
//!
//! `F(r) = 0` is exactly the Coulomb law. An element of the generalized Jacobian is
//! `J = A + B w` with `A = dF/dr`, `B = dF/du` taken branch by branch:
//! * `s_N > 0`: `F_N = rho_N u_N` (A_N = 0, B_N = rho_N e_N); else `F_N = r_N` (A_N = e_N, B_N = 0);
//! * stick `||s_T|| <= R`: `F_T = rho_T u_T` (A_T = 0, B_T = rho_T [0 I]);
//! * slide: `F_T = r_T - R e`, `e = s_T/||s_T||`, `G = (I - e e^T)/||s_T||`:
//!   `A_T = [-mu [s_N>0] e, I - R G]`, `B_T = [mu rho_N [s_N>0] e, R rho_T G]`.
//!
//! Jean-Moreau (59) ("NSN-JM" of Table 3, Siconos formulation 1) only changes the radius to
//! `R = mu (r_N)_+`: in the slide branch `A_T[., 0] = -mu [r_N > 0] e` and `B_T[., 0] = 0`.
//!
//! Two variants ([`AlgorithmVariant`]). Siconos 4.4's (default): `q_N > -eps` is a take-off
//! (`r = 0`) without iterating; each Newton iteration steps first and then stops when
//! `||F||^2 / (2 ||q||) < tolerance`; a Goldstein-Price search that finds no acceptable step
//! in its trials takes its last bisection point; 565 runs Newton, then (while the local error
//! `||r - P_K(r - ũ)|| / ||q||` is at or above the tolerance, `hybrid_max_loop` times) 553's
//! iteration for `hybrid_max_iter` steps and Newton again, keeping a new point only when its
//! local error is within the tolerance or not larger than the kept one's. fc3d's: the stop
//! test `||F|| <= tolerance * max(||r||, rho_N ||q||)` comes before each step, a failed search
//! keeps its best decrease (or stops Newton), and 565 keeps the best point of every round.

use super::adaptive::siconos_cone_iteration;
use super::{
    local_rho_of_variant, LocalOutcome, LocalProblem, LocalSolver,
    ProjectionOnConeWithLocalIteration,
};
use crate::local::{AlgorithmVariant, LocalSolverKind, LocalSolverOptions, NewtonFormulation};
use std::time::Instant;

use crate::contract::{deadline_passed, past_deadline};
use crate::math::linalg::{mat3_mul, norm2, norm3, solve3, Mat3, Vec3};

/// The Alart-Curnier function and one element of its generalized Jacobian at `r`.
pub fn alart_curnier_function(
    p: &LocalProblem<'_>,
    rho_n: f64,
    rho_t: f64,
    r: &Vec3,
) -> (Vec3, Mat3) {
    ac_eval::<true, false>(p, rho_n, rho_t, r)
}

/// The Jean-Moreau function (59) and one element of its generalized Jacobian at `r`.
pub fn jean_moreau_function(
    p: &LocalProblem<'_>,
    rho_n: f64,
    rho_t: f64,
    r: &Vec3,
) -> (Vec3, Mat3) {
    ac_eval::<true, true>(p, rho_n, rho_t, r)
}

/// The Alart-Curnier function alone (the Jacobian is not formed): convergence tests and
/// line-search trials need only F.
#[inline]
fn alart_curnier_residual(p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Vec3 {
    ac_eval::<false, false>(p, rho_n, rho_t, r).0
}

/// F and, when `JAC`, the Jacobian `A + B w` (otherwise a zero matrix); one branch logic for both.
#[inline(always)]
fn ac_eval<const JAC: bool, const JEAN_MOREAU: bool>(
    p: &LocalProblem<'_>,
    rho_n: f64,
    rho_t: f64,
    r: &Vec3,
) -> (Vec3, Mat3) {
    let u = p.velocity(r);
    let mu = p.mu;
    let mut f = [0.0; 3];
    let mut a: Mat3 = [[0.0; 3]; 3];
    let mut b: Mat3 = [[0.0; 3]; 3];

    let s_n = r[0] - rho_n * u[0];
    let active = s_n > 0.0;
    if active {
        f[0] = rho_n * u[0];
        b[0][0] = rho_n;
    } else {
        f[0] = r[0];
        a[0][0] = 1.0;
    }

    // Jean-Moreau's disk follows r_N itself; Alart-Curnier's follows s_N.
    let radius_active = if JEAN_MOREAU { r[0] > 0.0 } else { active };
    let radius = match (JEAN_MOREAU, radius_active) {
        (_, false) => 0.0,
        (true, true) => mu * r[0],
        (false, true) => mu * s_n,
    };
    let s_t = [r[1] - rho_t * u[1], r[2] - rho_t * u[2]];
    let ns = norm2(s_t[0], s_t[1]);
    if ns <= radius {
        // Stick (includes s_T = 0 with R = 0).
        f[1] = rho_t * u[1];
        f[2] = rho_t * u[2];
        b[1][1] = rho_t;
        b[2][2] = rho_t;
    } else {
        let e = [s_t[0] / ns, s_t[1] / ns];
        f[1] = r[1] - radius * e[0];
        f[2] = r[2] - radius * e[1];
        if JAC {
            let k = radius / ns;
            let g = [
                [k * (1.0 - e[0] * e[0]), -k * e[0] * e[1]],
                [-k * e[1] * e[0], k * (1.0 - e[1] * e[1])],
            ];
            let dn = if radius_active { mu } else { 0.0 };
            for i in 0..2 {
                a[1 + i][0] = -dn * e[i];
                b[1 + i][0] = if JEAN_MOREAU { 0.0 } else { dn * rho_n * e[i] };
                for j in 0..2 {
                    a[1 + i][1 + j] = if i == j { 1.0 } else { 0.0 } - g[i][j];
                    b[1 + i][1 + j] = rho_t * g[i][j];
                }
            }
        }
    }
    if !JAC {
        return (f, [[0.0; 3]; 3]);
    }
    let bw = mat3_mul(&b, p.w);
    let mut jac = a;
    for i in 0..3 {
        for j in 0..3 {
            jac[i][j] += bw[i][j];
        }
    }
    (f, jac)
}

/// Gaussian elimination with partial pivoting as Siconos 4.4 solves its 3x3 Newton systems
/// (same pivots, same operation order, so the same bits): a pivot of magnitude at most
/// `f64::EPSILON` in the first two columns means singular (`None`); the last pivot is not
/// tested, and a non-finite solution is `None`.
fn solve3_partial_pivoting(m: &Mat3, b: &Vec3) -> Option<Vec3> {
    let col = [m[0][0].abs(), m[1][0].abs(), m[2][0].abs()];
    let (p, i, j) = if col[0] >= col[1] {
        if col[0] >= col[2] {
            (0, 1, 2)
        } else {
            (2, 0, 1)
        }
    } else if col[1] >= col[2] {
        (1, 0, 2)
    } else {
        (2, 0, 1)
    };
    let pivot = m[p][0];
    let (f1, f2) = (m[i][0] / pivot, m[j][0] / pivot);
    let (lp1, lp2) = (m[p][1], m[p][2]);
    let (lm1, lm2) = (m[i][1] - f1 * lp1, m[i][2] - f1 * lp2);
    let (ln1, ln2) = (m[j][1] - f2 * lp1, m[j][2] - f2 * lp2);
    let bl = b[p];
    let (bm, bn) = (b[i] - f1 * bl, b[j] - f2 * bl);
    if pivot.abs() <= f64::EPSILON {
        return None;
    }
    let (x1, x2) = if lm1.abs() >= ln1.abs() {
        if lm1.abs() < f64::EPSILON {
            return None;
        }
        let f = ln1 / lm1;
        let x2 = (bn - f * bm) / (ln2 - f * lm2);
        ((bm - lm2 * x2) / lm1, x2)
    } else {
        if ln1.abs() < f64::EPSILON {
            return None;
        }
        let f = lm1 / ln1;
        let x2 = (bm - f * bn) / (lm2 - f * ln2);
        ((bn - ln2 * x2) / ln1, x2)
    };
    let x0 = (bl - x1 * lp1 - x2 * lp2) / pivot;
    let x = [x0, x1, x2];
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The Alart-Curnier function at a point, with what its Jacobian needs, each value formed with
/// the operations, in the order, of Siconos 4.4's standard Alart-Curnier function, so that the
/// Siconos variant's iterates are Siconos' to the last bit (its local Newton, when it does not
/// converge, amplifies a difference of one ulp into visibly different sweeps). The same function
/// as [`alart_curnier_function`] otherwise. Newton evaluates F at a point once: the Jacobian of
/// the next step is formed from the point's branch and intermediates ([`SiconosAcPoint::jacobian`]),
/// and a line search's accepted trial is the next point.
#[derive(Debug, Clone, Copy)]
struct SiconosAcPoint {
    f: Vec3,
    /// `r_N - rho_N u_N > 0`.
    normal_active: bool,
    branch: TangentBranch,
    rvt: f64,
    rvs: f64,
    /// `1 / ||r_T - rho_T u_T||` (slide branch only).
    rv1: f64,
    radius: f64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum TangentBranch {
    Stick,
    Slide,
    /// Zero radius, outside the disk: `F_T = r_T`.
    Free,
}

impl SiconosAcPoint {
    #[inline]
    fn at(p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Self {
        let v = p.velocity(r);
        let mu = p.mu;
        let mut f = [0.0; 3];
        let rvn = r[0] - rho_n * v[0];
        let rvt = r[1] - rho_t * v[1];
        let rvs = r[2] - rho_t * v[2];
        let rv = (rvt * rvt + rvs * rvs).sqrt();
        let normal_active = rvn > 0.0;
        let radius = if normal_active {
            f[0] = rho_n * v[0];
            mu * rvn
        } else {
            f[0] = r[0];
            0.0
        };
        let (branch, rv1) = if rv <= radius {
            f[1] = rho_t * v[1];
            f[2] = rho_t * v[2];
            (TangentBranch::Stick, 0.0)
        } else if radius > 0.0 {
            let rv1 = 1.0 / rv;
            f[1] = r[1] - radius * rvt * rv1;
            f[2] = r[2] - radius * rvs * rv1;
            (TangentBranch::Slide, rv1)
        } else {
            f[1] = r[1];
            f[2] = r[2];
            (TangentBranch::Free, 0.0)
        };
        SiconosAcPoint {
            f,
            normal_active,
            branch,
            rvt,
            rvs,
            rv1,
            radius,
        }
    }

    /// The Jacobian `A W + B` at the point (A: derivative in u, Siconos' A; B: in r, its B).
    /// Each entry is Siconos' `(A_i0 W_0j + A_i1 W_1j) + A_i2 W_2j + B_ij`; a row of A with one
    /// non-zero entry `a` gives `a W_kj + 0.0` (W is finite: the zero products are signed
    /// zeros, which change nothing but a zero's sign, and the final `+ B_ij = + 0.0` makes
    /// that sign positive) and a zero row gives B's row, so only sliding rows are formed in
    /// full ([`SiconosAcPoint::jacobian_full`] is the reference of the tests).
    #[inline]
    fn jacobian(&self, p: &LocalProblem<'_>, rho_n: f64, rho_t: f64) -> Mat3 {
        let w = p.w;
        let scaled_row =
            |a: f64, k: usize| [a * w[k][0] + 0.0, a * w[k][1] + 0.0, a * w[k][2] + 0.0];
        let normal = if self.normal_active {
            scaled_row(rho_n, 0)
        } else {
            [1.0, 0.0, 0.0]
        };
        match self.branch {
            TangentBranch::Stick => [normal, scaled_row(rho_t, 1), scaled_row(rho_t, 2)],
            TangentBranch::Free => [normal, [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            TangentBranch::Slide => {
                let (a, b) = self.slide_rows(p.mu, rho_n, rho_t);
                let full_row = |i: usize| {
                    let row = |j: usize| {
                        a[i][0] * w[0][j] + a[i][1] * w[1][j] + a[i][2] * w[2][j] + b[i][j]
                    };
                    [row(0), row(1), row(2)]
                };
                [normal, full_row(0), full_row(1)]
            }
        }
    }

    /// Rows T and S of A and B in the slide branch.
    #[inline]
    fn slide_rows(&self, mu: f64, rho_n: f64, rho_t: f64) -> ([Vec3; 2], [Vec3; 2]) {
        let (rvt, rvs, rv1, radius) = (self.rvt, self.rvs, self.rv1, self.radius);
        let rv3 = rv1 * rv1 * rv1;
        let g_tt = rv1 - rvt * rvt * rv3;
        let g_ts = -rvt * rvs * rv3;
        let g_ss = rv1 - rvs * rvs * rv3;
        let a = [
            [
                mu * rho_n * rvt * rv1,
                g_tt * rho_t * radius,
                g_ts * rho_t * radius,
            ],
            [
                mu * rho_n * rvs * rv1,
                g_ts * rho_t * radius,
                g_ss * rho_t * radius,
            ],
        ];
        let b = [
            [-mu * rvt * rv1, 1.0 - g_tt * radius, -g_ts * radius],
            [-mu * rvs * rv1, -g_ts * radius, 1.0 - g_ss * radius],
        ];
        (a, b)
    }

    /// The Jacobian as Siconos forms it: A and B in full, `A W + B` by the full product.
    #[cfg(test)]
    fn jacobian_full(&self, p: &LocalProblem<'_>, rho_n: f64, rho_t: f64) -> Mat3 {
        let mut a: Mat3 = [[0.0; 3]; 3];
        let mut b: Mat3 = [[0.0; 3]; 3];
        if self.normal_active {
            a[0][0] = rho_n;
        } else {
            b[0][0] = 1.0;
        }
        match self.branch {
            TangentBranch::Stick => {
                a[1][1] = rho_t;
                a[2][2] = rho_t;
            }
            TangentBranch::Slide => {
                let (sa, sb) = self.slide_rows(p.mu, rho_n, rho_t);
                a[1] = sa[0];
                a[2] = sa[1];
                b[1] = sb[0];
                b[2] = sb[1];
            }
            TangentBranch::Free => {
                b[1][1] = 1.0;
                b[2][2] = 1.0;
            }
        }
        let mut jac = mat3_mul(&a, p.w);
        for (row, b_row) in jac.iter_mut().zip(&b) {
            for (x, y) in row.iter_mut().zip(b_row) {
                *x += y;
            }
        }
        jac
    }
}

/// [`SiconosAcPoint`]'s F and, when `JAC`, its Jacobian (the tests compare it with fc3d's
/// function).
#[cfg(test)]
fn alart_curnier_siconos<const JAC: bool>(
    p: &LocalProblem<'_>,
    rho_n: f64,
    rho_t: f64,
    r: &Vec3,
) -> (Vec3, Mat3) {
    let point = SiconosAcPoint::at(p, rho_n, rho_t, r);
    let jac = if JAC {
        point.jacobian(p, rho_n, rho_t)
    } else {
        [[0.0; 3]; 3]
    };
    (point.f, jac)
}

/// A Newton point of the Siconos variant: F at r, and how to form the Jacobian there. The
/// iterations are generic over it, so each formulation runs its own code.
trait SiconosPoint: Copy {
    fn at(p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Self;
    fn f(&self) -> Vec3;
    /// F and the Jacobian at `r`, the point's reaction.
    fn f_and_jacobian(
        &self,
        p: &LocalProblem<'_>,
        rho_n: f64,
        rho_t: f64,
        r: &Vec3,
    ) -> (Vec3, Mat3);
}

impl SiconosPoint for SiconosAcPoint {
    #[inline]
    fn at(p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Self {
        SiconosAcPoint::at(p, rho_n, rho_t, r)
    }
    #[inline]
    fn f(&self) -> Vec3 {
        self.f
    }
    /// The Jacobian from the point's branch and intermediates.
    #[inline]
    fn f_and_jacobian(
        &self,
        p: &LocalProblem<'_>,
        rho_n: f64,
        rho_t: f64,
        _r: &Vec3,
    ) -> (Vec3, Mat3) {
        (self.f, self.jacobian(p, rho_n, rho_t))
    }
}

/// Jean-Moreau's F; the Jacobian is formed anew (with F) at r.
#[derive(Debug, Clone, Copy)]
struct JeanMoreauPoint(Vec3);

impl SiconosPoint for JeanMoreauPoint {
    #[inline]
    fn at(p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Self {
        JeanMoreauPoint(ac_eval::<false, true>(p, rho_n, rho_t, r).0)
    }
    #[inline]
    fn f(&self) -> Vec3 {
        self.0
    }
    #[inline]
    fn f_and_jacobian(
        &self,
        p: &LocalProblem<'_>,
        rho_n: f64,
        rho_t: f64,
        r: &Vec3,
    ) -> (Vec3, Mat3) {
        jean_moreau_function(p, rho_n, rho_t, r)
    }
}

/// Whether `a` and `b` hold the same bits (so that any function of them gives the same value:
/// `-0.0 == 0.0` would not do).
#[inline]
fn same_bits(a: &Vec3, b: &Vec3) -> bool {
    a[0].to_bits() == b[0].to_bits()
        && a[1].to_bits() == b[1].to_bits()
        && a[2].to_bits() == b[2].to_bits()
}

/// Alart-Curnier Newton: plain (550), with Goldstein-Price line search (551), or hybrid (565).
pub struct AlartCurnierNewton {
    options: LocalSolverOptions,
    line_search: bool,
    hybrid: bool,
    jean_moreau: bool,
    variant: AlgorithmVariant,
    projection: ProjectionOnConeWithLocalIteration,
    deadline: Option<Instant>,
}

/// Goldstein-Price acceptance bounds on `(psi(r + a d) - psi(r)) / (a * slope)`.
const GP_M1: f64 = 0.1;
const GP_M2: f64 = 0.9;

impl AlartCurnierNewton {
    pub fn new(options: &LocalSolverOptions) -> Self {
        let line_search = matches!(
            options.kind,
            LocalSolverKind::NewtonAlartCurnierGp | LocalSolverKind::NewtonHybrid
        );
        let hybrid = options.kind == LocalSolverKind::NewtonHybrid;
        let mut proj = *options;
        proj.max_iter = options.hybrid_max_iter;
        AlartCurnierNewton {
            options: *options,
            line_search,
            hybrid,
            jean_moreau: options.formulation == NewtonFormulation::JeanMoreau,
            variant: options.variant,
            projection: ProjectionOnConeWithLocalIteration::new(&proj),
            deadline: None,
        }
    }

    #[inline]
    fn residual(&self, p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Vec3 {
        if self.jean_moreau {
            ac_eval::<false, true>(p, rho_n, rho_t, r).0
        } else {
            alart_curnier_residual(p, rho_n, rho_t, r)
        }
    }

    #[inline]
    fn jacobian(&self, p: &LocalProblem<'_>, rho_n: f64, rho_t: f64, r: &Vec3) -> Mat3 {
        if self.jean_moreau {
            jean_moreau_function(p, rho_n, rho_t, r).1
        } else {
            alart_curnier_function(p, rho_n, rho_t, r).1
        }
    }

    /// Newton iterations from `r`; returns (converged, iterations).
    fn newton(&self, p: &LocalProblem<'_>, rho: (f64, f64), r: &mut Vec3) -> (bool, usize) {
        let (rho_n, rho_t) = rho;
        let tol = self.options.tolerance;
        // F has the units of a reaction; compare it with the reaction scale.
        let scale = norm3(r).max(rho_n * norm3(&p.q)).max(f64::MIN_POSITIVE);
        // The Jacobian is formed only where a step is taken: the last F of a converging run
        // (most local solves late in NSGS) needs none.
        let mut f = self.residual(p, rho_n, rho_t, r);
        for it in 0..self.options.max_iter {
            let nf = norm3(&f);
            if nf <= tol * scale {
                return (true, it);
            }
            if past_deadline(self.deadline, it) {
                return (false, it);
            }
            let jac = self.jacobian(p, rho_n, rho_t, r);
            let Some(d) = solve3(&jac, &[-f[0], -f[1], -f[2]]) else {
                return (false, it);
            };
            let (r_new, f_new) = if self.line_search {
                match self.goldstein_price(p, rho, r, &d, nf * nf) {
                    Some(x) => x,
                    None => return (false, it),
                }
            } else {
                let rn = [r[0] + d[0], r[1] + d[1], r[2] + d[2]];
                (rn, self.residual(p, rho_n, rho_t, &rn))
            };
            if !r_new.iter().all(|v| v.is_finite()) {
                return (false, it);
            }
            *r = r_new;
            f = f_new;
        }
        (norm3(&f) <= tol * scale, self.options.max_iter)
    }

    /// Siconos 4.4's Newton iterations from `r` (module documentation); `inv_q` is
    /// `1 / ||q||` (1 for a tiny q). Returns (converged, iterations). F is evaluated once a
    /// point: the Jacobian of a step is formed from the point (Alart-Curnier), the point a
    /// line search accepted is the next one, and a step that leaves `r`'s bits unchanged keeps
    /// its point (near a solution the search's short trials round back to `r`: on
    /// Capsules-i101-404 three trials in four).
    fn newton_siconos(
        &self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        inv_q: f64,
        r: &mut Vec3,
    ) -> (bool, usize) {
        if self.jean_moreau {
            self.newton_siconos_with::<JeanMoreauPoint>(p, rho, inv_q, r)
        } else {
            self.newton_siconos_with::<SiconosAcPoint>(p, rho, inv_q, r)
        }
    }

    fn newton_siconos_with<P: SiconosPoint>(
        &self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        inv_q: f64,
        r: &mut Vec3,
    ) -> (bool, usize) {
        let (rho_n, rho_t) = rho;
        let tol = self.options.tolerance;
        let mut point = P::at(p, rho_n, rho_t, r);
        for it in 0..self.options.max_iter {
            if past_deadline(self.deadline, it) {
                return (false, it);
            }
            let (f, jac) = point.f_and_jacobian(p, rho_n, rho_t, r);
            // A singular Jacobian ends the iterations where they are.
            let Some(d) = solve3_partial_pivoting(&jac, &[-f[0], -f[1], -f[2]]) else {
                return (false, it);
            };
            let (t, accepted) = if self.line_search {
                // The slope F . J d (-||F||^2 up to rounding), formed as Siconos forms it.
                let jd = [
                    jac[0][0] * d[0] + jac[0][1] * d[1] + jac[0][2] * d[2],
                    jac[1][0] * d[0] + jac[1][1] * d[1] + jac[1][2] * d[2],
                    jac[2][0] * d[0] + jac[2][1] * d[1] + jac[2][2] * d[2],
                ];
                let slope = f[0] * jd[0] + f[1] * jd[1] + f[2] * jd[2];
                let f_sq = f[0] * f[0] + f[1] * f[1] + f[2] * f[2];
                self.goldstein_price_siconos(p, rho, r, &point, &d, f_sq, slope)
            } else {
                (1.0, None)
            };
            let next = [r[0] + t * d[0], r[1] + t * d[1], r[2] + t * d[2]];
            if !next.iter().all(|v| v.is_finite()) {
                return (false, it + 1);
            }
            // The accepted trial was evaluated at this very point (same operations); a step
            // that rounds back to r has r's point.
            point = match accepted {
                Some(trial) => trial,
                None if same_bits(&next, r) => point,
                None => P::at(p, rho_n, rho_t, &next),
            };
            *r = next;
            let f = point.f();
            if 0.5 * (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) * inv_q < tol {
                return (true, it + 1);
            }
        }
        (false, self.options.max_iter)
    }

    /// Siconos 4.4's Goldstein-Price search on `psi = ||F||^2 / 2` along `d` from `r`, whose
    /// point is `at_r` (slope `slope0`, `-||F||^2` up to rounding): bisection of `[lo, hi]`
    /// from `alpha = 1`, `hi` starting at 1e20; after the last trial the next bisection point
    /// is returned untested. Returns the step and, when a trial was accepted, the point it
    /// evaluated there. A trial point that rounds to `r` (same bits) has `at_r`'s F, so it is
    /// not evaluated again: its `psi` is `psi0`.
    #[allow(clippy::too_many_arguments)]
    fn goldstein_price_siconos<P: SiconosPoint>(
        &self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &Vec3,
        at_r: &P,
        d: &Vec3,
        f_sq: f64,
        slope0: f64,
    ) -> (f64, Option<P>) {
        const UNBOUNDED: f64 = 1e20;
        // Halvings that take any alpha below 2^70 (> 10 UNBOUNDED) to 0: 70 to 1, 1074 more
        // to the smallest subnormal, one to 0.
        const HALVINGS_TO_ZERO: usize = 1200;
        let psi0 = 0.5 * f_sq;
        let (mut lo, mut hi) = (0.0_f64, UNBOUNDED);
        let mut alpha = 1.0;
        for trial in 0..self.options.line_search_max_iter {
            if past_deadline(self.deadline, trial) {
                break;
            }
            let rt = [
                r[0] + alpha * d[0],
                r[1] + alpha * d[1],
                r[2] + alpha * d[2],
            ];
            // At r's bits, psi is psi0 (the same F, squared and summed in the same order).
            let trial_point = (!same_bits(&rt, r)).then(|| P::at(p, rho.0, rho.1, &rt));
            let psi = match &trial_point {
                Some(point) => {
                    let ft = point.f();
                    0.5 * (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2])
                }
                None => psi0,
            };
            let slope = (psi - psi0) / alpha;
            let long_enough = slope >= GP_M2 * slope0;
            let short_enough = slope <= GP_M1 * slope0;
            if long_enough && short_enough {
                return (alpha, Some(trial_point.unwrap_or(*at_r)));
            }
            if trial_point.is_none() && lo == 0.0 && long_enough {
                // Too long at a point that rounds to r: every later trial halves alpha, and
                // r + alpha d, monotone in alpha, rounds to r as well (psi = psi0, the same
                // verdict). Only the last bisection point remains to be formed: alpha halved
                // once a remaining trial, exactly as the trials would, but at most
                // HALVINGS_TO_ZERO times (alpha < 2^70 is 0 by then and stays 0), so that an
                // INT_MAX trial limit costs no more than that.
                let remaining = self.options.line_search_max_iter - trial;
                for _ in 0..remaining.min(HALVINGS_TO_ZERO) {
                    alpha *= 0.5;
                }
                return (alpha, None);
            }
            if !long_enough {
                lo = alpha;
            } else {
                hi = alpha;
            }
            alpha = if alpha < UNBOUNDED {
                0.5 * (lo + hi)
            } else {
                10.0 * alpha
            };
        }
        (alpha, None)
    }

    /// Siconos 4.4's 550 / 551 / 565 on one contact (module documentation); `step` is the
    /// contact's 553 step length kept between sweeps.
    fn solve_siconos(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        step: &mut f64,
        r: &mut Vec3,
    ) -> LocalOutcome {
        if p.q[0] > -f64::EPSILON {
            *r = [0.0; 3];
            return LocalOutcome {
                converged: true,
                iterations: 0,
            };
        }
        let norm_q = norm3(&p.q);
        let inv_q = if norm_q > f64::EPSILON {
            1.0 / norm_q
        } else {
            1.0
        };
        if !self.hybrid {
            let (converged, iterations) = self.newton_siconos(p, rho, inv_q, r);
            return LocalOutcome {
                converged,
                iterations,
            };
        }
        let tol = self.options.tolerance;
        let local_error = |x: &Vec3| p.residual(x) * inv_q;
        // A new point replaces the kept one when it is good enough or no worse. A point with
        // the kept one's bits has its error: it is not measured again.
        let keep_or_discard = |x: &mut Vec3, kept: &mut Vec3, kept_error: &mut f64| {
            if same_bits(x, kept) {
                return;
            }
            let e = local_error(x);
            if e <= tol || e <= *kept_error {
                *kept = *x;
                *kept_error = e;
            } else {
                *x = *kept;
            }
        };
        let start = *r;
        let (_, mut iterations) = self.newton_siconos(p, rho, inv_q, r);
        // The starting point's error is needed only when Newton's point is not within the
        // tolerance (or is the starting point itself).
        let mut kept = *r;
        let mut kept_error = local_error(r);
        let within_tolerance = kept_error <= tol;
        if !within_tolerance && !same_bits(r, &start) {
            let start_error = local_error(&start);
            let no_worse = kept_error <= start_error;
            if !no_worse {
                (kept, kept_error) = (start, start_error);
                *r = start;
            }
        }
        let mut round = 0;
        while kept_error > tol && round < self.options.hybrid_max_loop {
            // A round runs two iterations whose clocks tick every CLOCK_PERIOD steps: read the
            // clock at every round.
            if deadline_passed(self.deadline) {
                break;
            }
            round += 1;
            let pr = siconos_cone_iteration(
                p,
                step,
                tol,
                self.options.hybrid_max_iter,
                self.deadline,
                r,
            );
            iterations += pr.iterations;
            keep_or_discard(r, &mut kept, &mut kept_error);
            if kept_error < tol {
                break;
            }
            let (_, it) = self.newton_siconos(p, rho, inv_q, r);
            iterations += it;
            keep_or_discard(r, &mut kept, &mut kept_error);
        }
        LocalOutcome {
            converged: kept_error <= tol,
            iterations,
        }
    }

    /// Goldstein-Price search along the Newton direction `d` on `psi = ||F||^2 / 2`, whose slope
    /// along `d` is `-||F||^2`. Returns the accepted point with its F, or the best point that
    /// decreased psi, or `None` when no trial step decreased it.
    fn goldstein_price(
        &self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &Vec3,
        d: &Vec3,
        f_sq: f64,
    ) -> Option<(Vec3, Vec3)> {
        let psi0 = 0.5 * f_sq;
        let slope = -f_sq;
        let (mut lo, mut hi) = (0.0_f64, f64::INFINITY);
        let mut alpha = 1.0;
        let mut best: Option<(f64, Vec3, Vec3)> = None;
        for trial in 0..self.options.line_search_max_iter.max(1) {
            if past_deadline(self.deadline, trial) {
                break;
            }
            let rt = [
                r[0] + alpha * d[0],
                r[1] + alpha * d[1],
                r[2] + alpha * d[2],
            ];
            let ft = self.residual(p, rho.0, rho.1, &rt);
            let psi = 0.5 * (ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2]);
            if psi < best.as_ref().map_or(psi0, |b| b.0) {
                best = Some((psi, rt, ft));
            }
            let ratio = (psi - psi0) / (alpha * slope);
            if ratio < GP_M1 {
                hi = alpha; // too long: not enough decrease
            } else if ratio > GP_M2 {
                lo = alpha; // too short: decrease almost linear, try longer
            } else {
                return Some((rt, ft));
            }
            alpha = if hi.is_finite() {
                0.5 * (lo + hi)
            } else {
                2.0 * alpha
            };
        }
        best.map(|(_, rt, ft)| (rt, ft))
    }
}

impl LocalSolver for AlartCurnierNewton {
    fn rho(&self, w: &Mat3) -> (f64, f64) {
        local_rho_of_variant(w, self.options.rho_rule, self.variant)
    }

    fn set_deadline(&mut self, deadline: Option<Instant>) {
        self.deadline = deadline;
        self.projection.set_deadline(deadline);
    }

    fn solve_with_rho(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        r: &mut Vec3,
    ) -> LocalOutcome {
        let mut step = 1.0;
        self.solve_in_sweep(p, rho, &mut step, r)
    }

    fn solve_in_sweep(
        &mut self,
        p: &LocalProblem<'_>,
        rho: (f64, f64),
        step: &mut f64,
        r: &mut Vec3,
    ) -> LocalOutcome {
        if self.variant == AlgorithmVariant::Siconos {
            return self.solve_siconos(p, rho, step, r);
        }
        let start = *r;
        let (converged, mut iterations) = self.newton(p, rho, r);
        if converged || !self.hybrid {
            return LocalOutcome {
                converged,
                iterations,
            };
        }
        // Hybrid: keep the best of Newton and of (projection, Newton) rounds, judged by the
        // natural-map residual that the global error uses.
        let mut best = *r;
        let mut best_res = p.residual(r);
        let start_res = p.residual(&start);
        if start_res < best_res {
            best = start;
            best_res = start_res;
        }
        // Each round continues the projection iterations from where the previous round left
        // them (not from `best`, which would make every round after a failed one an exact
        // repeat), then tries Newton from the projected point. Both points are candidates.
        let mut projected = best;
        for round in 0..self.options.hybrid_max_loop {
            if past_deadline(self.deadline, round) {
                break;
            }
            let pr = self.projection.solve(p, &mut projected);
            iterations += pr.iterations;
            let res = p.residual(&projected);
            if res <= best_res {
                best = projected;
                best_res = res;
            }
            let mut x = projected;
            let (ok, it) = self.newton(p, rho, &mut x);
            iterations += it;
            let res = p.residual(&x);
            if res <= best_res {
                best = x;
                best_res = res;
            }
            if ok {
                *r = x;
                return LocalOutcome {
                    converged: true,
                    iterations,
                };
            }
            if pr.converged {
                // The projection itself reached the local tolerance.
                break;
            }
        }
        *r = best;
        let converged = best_res <= self.options.tolerance * p.scale(r);
        LocalOutcome {
            converged,
            iterations,
        }
    }
}

#[cfg(test)]
mod siconos_arithmetic_tests {
    use super::*;
    use proptest::prelude::*;

    fn close(a: f64, b: f64, scale: f64) -> bool {
        (a - b).abs() <= 1e-12 * scale.max(1.0)
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        /// Siconos' arithmetic computes the same function and Jacobian as fc3d's, in every
        /// branch (take-off, stick, slide, zero radius), up to rounding.
        #[test]
        fn siconos_alart_curnier_is_the_same_function(
            w in prop::array::uniform3(prop::array::uniform3(-3.0f64..3.0)),
            q in prop::array::uniform3(-5.0f64..5.0),
            r in prop::array::uniform3(-5.0f64..5.0),
            mu in 0.0f64..2.0,
            rho_n in 0.1f64..2.0,
            rho_t in 0.1f64..2.0,
        ) {
            let p = LocalProblem { w: &w, q, mu };
            let (f1, j1) = alart_curnier_function(&p, rho_n, rho_t, &r);
            let (f2, j2) = alart_curnier_siconos::<true>(&p, rho_n, rho_t, &r);
            let (f3, _) = alart_curnier_siconos::<false>(&p, rho_n, rho_t, &r);
            prop_assert_eq!(f2, f3);
            for i in 0..3 {
                prop_assert!(close(f1[i], f2[i], 10.0), "F {:?} {:?}", f1, f2);
                for j in 0..3 {
                    prop_assert!(close(j1[i][j], j2[i][j], 100.0), "J {:?} {:?}", j1, j2);
                }
            }
        }

        /// Siconos' elimination solves what fc3d's does on well-conditioned systems.
        #[test]
        fn siconos_elimination_solves_the_system(
            m in prop::array::uniform3(prop::array::uniform3(-3.0f64..3.0)),
            b in prop::array::uniform3(-3.0f64..3.0),
        ) {
            let mut m = m;
            for (i, row) in m.iter_mut().enumerate() {
                row[i] += 10.0;
            }
            let x = solve3_partial_pivoting(&m, &b).unwrap();
            let y = solve3(&m, &b).unwrap();
            for i in 0..3 {
                prop_assert!(close(x[i], y[i], 1.0), "{:?} {:?}", x, y);
            }
        }
    }

    /// A W entry: often an exact zero of either sign (so that products are signed zeros), else
    /// any value.
    fn w_entry() -> impl Strategy<Value = f64> {
        prop_oneof![Just(0.0), Just(-0.0), -3.0f64..3.0, -3.0f64..3.0]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(2048))]

        /// The Jacobian formed by branch has the bits of Siconos' full product `A W + B`.
        #[test]
        fn jacobian_by_branch_has_the_full_products_bits(
            w in prop::array::uniform3(prop::array::uniform3(w_entry())),
            q in prop::array::uniform3(-5.0f64..5.0),
            r in prop::array::uniform3(prop_oneof![Just(0.0), Just(-0.0), -5.0f64..5.0]),
            mu in prop_oneof![Just(0.0), 0.0f64..2.0],
            rho_n in 0.1f64..2.0,
            rho_t in 0.1f64..2.0,
        ) {
            let p = LocalProblem { w: &w, q, mu };
            let point = SiconosAcPoint::at(&p, rho_n, rho_t, &r);
            let lean = point.jacobian(&p, rho_n, rho_t).map(|row| row.map(f64::to_bits));
            let full = point.jacobian_full(&p, rho_n, rho_t).map(|row| row.map(f64::to_bits));
            prop_assert_eq!(lean, full, "{:?} at {:?}", point.branch, r);
        }
    }

    #[test]
    fn jacobian_by_branch_covers_every_branch() {
        let w = [[2.0, -0.0, 0.5], [0.0, 1.5, -0.25], [0.5, -0.25, 1.0]];
        let p = LocalProblem {
            w: &w,
            q: [-1.0, 0.2, -0.1],
            mu: 0.5,
        };
        let mut seen = Vec::new();
        // Stick at rest, slide with a large tangential reaction, free after take-off with a
        // tangential reaction, and take-off at zero.
        for r in [
            [0.5, 0.0, 0.0],
            [0.5, 3.0, -2.0],
            [0.0, 0.3, 3.0],
            [0.0, 0.0, 0.0],
        ] {
            let point = SiconosAcPoint::at(&p, 0.5, 0.5, &r);
            let bits = |m: Mat3| m.map(|row| row.map(f64::to_bits));
            assert_eq!(
                bits(point.jacobian(&p, 0.5, 0.5)),
                bits(point.jacobian_full(&p, 0.5, 0.5))
            );
            seen.push(point.branch);
        }
        for branch in [
            TangentBranch::Stick,
            TangentBranch::Slide,
            TangentBranch::Free,
        ] {
            assert!(seen.contains(&branch), "{branch:?} not reached: {seen:?}");
        }
    }

    /// Near a solution the Newton step is below half an ulp of r: every trial of Siconos'
    /// search rounds to r, the search takes its eleventh bisection point 2^-10 untested, and
    /// the step leaves r's bits unchanged (the point is reused, not evaluated again).
    #[test]
    fn a_search_whose_trials_round_to_r_ends_at_the_last_bisection_point() {
        let w = [[1.0, 0.1, 0.0], [0.1, 1.0, 0.0], [0.0, 0.0, 1.0]];
        let p = LocalProblem {
            w: &w,
            q: [-1.0, 0.0, 0.0],
            mu: 0.5,
        };
        let solver =
            AlartCurnierNewton::new(&LocalSolverOptions::new(LocalSolverKind::NewtonHybrid));
        let r = [1.0, -0.1, 0.0];
        let at_r = SiconosAcPoint::at(&p, 1.0, 1.0, &r);
        let d = [1e-17, -1e-18, 0.0];
        let f_sq = 1e-30;
        let (alpha, accepted) =
            solver.goldstein_price_siconos(&p, (1.0, 1.0), &r, &at_r, &d, f_sq, -f_sq);
        assert_eq!(alpha, 0.5f64.powi(10));
        assert!(accepted.is_none());
        // A step that does move r is searched as before: from a sticking point F is linear,
        // the full step is accepted and lands on the solution u = 0, r = (1, -0.1, 0) / 0.99.
        let mut x = [0.9, 0.0, 0.0];
        let (converged, iterations) = solver.newton_siconos(&p, (1.0, 1.0), 1.0, &mut x);
        assert!(converged, "{iterations} iterations to {x:?}");
        let exact = [1.0 / 0.99, -0.1 / 0.99, 0.0];
        for (x, e) in x.iter().zip(exact) {
            assert!((x - e).abs() < 1e-14, "{x} against {e}");
        }
    }

    #[test]
    fn siconos_elimination_refuses_a_zero_pivot() {
        let m = [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
        assert_eq!(solve3_partial_pivoting(&m, &[1.0, 1.0, 1.0]), None);
    }
}

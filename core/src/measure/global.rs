//! The error of a global result, Siconos' `gfc3d_compute_error`: with `u = H^T v + b`,
//!
//! `error = ||q + H r - M v|| / max(||q||, ||M v||, ||H r||)
//!        + sqrt(sum_c ||r_c - P_K(r_c - ũ_c)||^2) / max(||u||, ||r||)`
//!
//! (ũ the De Saxcé velocity; each division is skipped when its denominator is at most the
//! machine epsilon). The first term is the balance of momentum, the second the contact law.
//! `gfc3d_compute_error_convex` drops the De Saxcé term: the error of the convex relaxation
//! (the associated law, `u ∈ K*`), which Siconos' IPM and ADMM report with `UPDATE_S = NO`.

use super::contact_residual_sq_d;
use crate::math::cone::project_on_cone;
use crate::math::linalg::{contact_of, norm};
use crate::math::rolling::rolling_residual_sq;
use crate::matrix::transpose_mul_add;
use crate::problem::{GlobalProblem, GlobalRollingProblem};

/// The contact law a global error measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ContactLaw {
    /// Coulomb's law with De Saxcé's velocity (the problem's law).
    Coulomb,
    /// The convex relaxation: `K* ∋ u ⟂ r ∈ K` (no De Saxcé term).
    Convex,
}

/// Work space of the global error: `H r` and `M v`.
#[derive(Debug, Default)]
pub struct ErrorWork {
    hr: Vec<f64>,
    mv: Vec<f64>,
    shifted: Vec<f64>,
}

impl ErrorWork {
    /// Work space for problems with `ndof` unknowns (no allocation when measuring then).
    pub fn new(ndof: usize) -> Self {
        ErrorWork {
            hr: vec![0.0; ndof],
            mv: vec![0.0; ndof],
            shifted: Vec::new(),
        }
    }
}

/// The balance term `||q + H r - M v|| / max(norm_q, ||M v||, ||H r||)` (`norm_q` is `||q||`
/// but where a host passes its own, as to Siconos' `gfc3d_compute_error`).
fn balance<const D: usize>(
    problem: &GlobalProblem<'_, D>,
    r: &[f64],
    v: &[f64],
    norm_q: f64,
    work: &mut ErrorWork,
) -> f64 {
    let n = problem.ndof();
    let (hr, mv) = (&mut work.hr, &mut work.mv);
    hr.clear();
    hr.resize(n, 0.0);
    problem.h().mul_add(r, hr);
    mv.clear();
    mv.resize(n, 0.0);
    problem.m().mul_add(v, mv);
    let residual = problem
        .q()
        .iter()
        .zip(hr.iter())
        .zip(mv.iter())
        .map(|((q, h), m)| {
            let d = q + h - m;
            d * d
        })
        .sum::<f64>()
        .sqrt();
    let scale = norm_q.max(norm(mv)).max(norm(hr));
    if scale.abs() > f64::EPSILON {
        residual / scale
    } else {
        residual
    }
}

/// Sets `u = H^T v + b`.
fn local_velocity<const D: usize>(problem: &GlobalProblem<'_, D>, v: &[f64], u: &mut [f64]) {
    u.copy_from_slice(problem.b());
    transpose_mul_add(problem.h(), v, u);
}

/// `u + shift` into `out`, or u itself without a shift.
fn shifted<'x>(u: &'x [f64], shift: Option<&[f64]>, out: &'x mut Vec<f64>) -> &'x [f64] {
    match shift {
        None => u,
        Some(s) => {
            out.clear();
            out.extend(u.iter().zip(s).map(|(a, b)| a + b));
            out
        }
    }
}

/// The law's term: the absolute residual over `max(||u||, ||r||)`.
fn law_term(absolute: f64, r: &[f64], u: &[f64]) -> f64 {
    let scale = norm(u).max(norm(r));
    if scale > f64::EPSILON {
        absolute / scale
    } else {
        absolute
    }
}

/// Siconos' global error of `(r, v)`; writes `u = H^T v + b` into `u` (as Siconos does into the
/// caller's velocity).
pub fn global_error<const D: usize>(
    problem: &GlobalProblem<'_, D>,
    law: ContactLaw,
    r: &[f64],
    u: &mut [f64],
    v: &[f64],
) -> f64 {
    global_error_with(problem, law, r, u, v, None, &mut ErrorWork::default())
}

/// [`global_error`] in the given work space (allocates nothing once it has the problem's
/// size). With `shift`, the law is measured at `u + shift` (the problem with `b + shift`: the
/// inner problems of a fixed point on De Saxcé's term); `u` is still `H^T v + b`.
pub fn global_error_with<const D: usize>(
    problem: &GlobalProblem<'_, D>,
    law: ContactLaw,
    r: &[f64],
    u: &mut [f64],
    v: &[f64],
    shift: Option<&[f64]>,
    work: &mut ErrorWork,
) -> f64 {
    let norm_q = norm(problem.q());
    global_error_with_norm_q(problem, law, r, u, v, shift, norm_q, work)
}

/// [`global_error_with`] with the balance term scaled by `max(norm_q, ||M v||, ||H r||)` for a
/// given `norm_q` (Siconos' `gfc3d_compute_error` takes it from its caller; every caller passes
/// `||q||`, which [`global_error_with`] uses).
#[allow(clippy::too_many_arguments)]
pub fn global_error_with_norm_q<const D: usize>(
    problem: &GlobalProblem<'_, D>,
    law: ContactLaw,
    r: &[f64],
    u: &mut [f64],
    v: &[f64],
    shift: Option<&[f64]>,
    norm_q: f64,
    work: &mut ErrorWork,
) -> f64 {
    local_velocity(problem, v, u);
    let mut shifted_u = std::mem::take(&mut work.shifted);
    let u_law = shifted(u, shift, &mut shifted_u);
    let absolute = match law {
        ContactLaw::Coulomb => problem
            .mu()
            .iter()
            .enumerate()
            .map(|(c, &mu)| {
                contact_residual_sq_d::<D>(&contact_of(r, c), &contact_of(u_law, c), mu)
            })
            .sum::<f64>()
            .sqrt(),
        ContactLaw::Convex => convex_residual::<D>(problem.mu(), r, u_law),
    };
    let error = balance(problem, r, v, norm_q, work) + law_term(absolute, r, u_law);
    work.shifted = shifted_u;
    error
}

/// `sqrt(sum_c ||r_c - P_K(r_c - u_c)||^2)`: the residual of the associated law.
fn convex_residual<const D: usize>(mu: &[f64], r: &[f64], u: &[f64]) -> f64 {
    let mut s = 0.0;
    for (c, &m) in mu.iter().enumerate() {
        let (rc, uc) = (&r[D * c..D * (c + 1)], &u[D * c..D * (c + 1)]);
        if D == 3 {
            let p = project_on_cone(&[rc[0] - uc[0], rc[1] - uc[1], rc[2] - uc[2]], m);
            s += (0..3).map(|k| (rc[k] - p[k]).powi(2)).sum::<f64>();
        } else {
            let mut x = [0.0; D];
            for k in 0..D {
                x[k] = rc[k] - uc[k];
            }
            let p = crate::math::cone::project_on_cone_d(&x, m);
            s += (0..D).map(|k| (rc[k] - p[k]).powi(2)).sum::<f64>();
        }
    }
    s.sqrt()
}

/// The global error of a rolling result: the same balance term, and the rolling law's residual
/// (rolling cone and De Saxcé velocity) over `max(||u||, ||r||)`; writes `u = H^T v + b`.
pub fn global_rolling_error(
    problem: &GlobalRollingProblem<'_>,
    r: &[f64],
    u: &mut [f64],
    v: &[f64],
) -> f64 {
    let base = problem.base();
    local_velocity(base, v, u);
    let absolute = base
        .mu()
        .iter()
        .zip(problem.mu_r())
        .enumerate()
        .map(|(c, (&mu, &mu_r))| {
            rolling_residual_sq::<5>(&contact_of(r, c), &contact_of(u, c), mu, mu_r)
        })
        .sum::<f64>()
        .sqrt();
    balance(base, r, v, norm(base.q()), &mut ErrorWork::default()) + law_term(absolute, r, u)
}

//! Problem rescaling around any solver (Siconos' `iparam[3]`, SICONOS_FRICTION_3D_IPARAM_RESCALING);
//! `solve` runs the solver on the rescaled problem and maps the result back.
//!
//! FC(W, q, mu) is invariant under positive scalings: if `(r_s, u_s)` solves FC(s W, t q, mu)
//! then `r = (s / t) r_s`, `u = u_s / t` solves FC(W, q, mu) (cones are invariant under positive
//! scaling). [`Rescaling::Scalar`] picks `s` so that the diagonal of `s W` averages 1 and `t` so
//! that `||t q|| = 1`: a problem and any multiple `(alpha W, beta q)` of it become the same
//! problem, so a solver sees the same numbers, takes the same iterations and reaches the same
//! relative error whatever the units of the host. The error reported is always measured on the
//! host's problem.

use crate::math::linalg::norm;
use crate::problem::FrictionProblem;

/// Rescaling applied around a solver.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Rescaling {
    /// Solve the problem as given (default, Siconos' RESCALING_NO).
    #[default]
    None,
    /// Solve FC(s W, t q, mu) with `s = 1 / mean |W_ii|`, `t = 1 / ||q||` and map the solution
    /// back (Siconos' RESCALING_SCALAR).
    Scalar,
}

/// The scale factors `(s, t)` of [`Rescaling::Scalar`] for `problem` (1 where the problem gives no
/// scale: zero diagonal or zero q).
pub fn scalar_factors(problem: &FrictionProblem<'_>) -> (f64, f64) {
    let mut sum = 0.0;
    let mut count = 0usize;
    for c in 0..problem.n_contacts() {
        if let Some(b) = problem.w().diagonal_block(c) {
            for (i, row) in b.iter().enumerate() {
                if row[i] != 0.0 {
                    sum += row[i].abs();
                    count += 1;
                }
            }
        }
    }
    let fix = |x: f64| if x > 0.0 && x.is_finite() { x } else { 1.0 };
    let s = fix(count as f64 / sum);
    let t = fix(1.0 / norm(problem.q()));
    (s, t)
}

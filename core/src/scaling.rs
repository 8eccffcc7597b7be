//! Problem rescaling around any solver (Siconos' `iparam[3]`, SICONOS_FRICTION_3D_IPARAM_RESCALING).
//!
//! FC(W, q, mu) is invariant under positive scalings: if `(r_s, u_s)` solves FC(s W, t q, mu)
//! then `r = (s / t) r_s`, `u = u_s / t` solves FC(W, q, mu) (cones are invariant under positive
//! scaling). [`Rescaling::Scalar`] picks `s` so that the diagonal of `s W` averages 1 and `t` so
//! that `||t q|| = 1`: a problem and any multiple `(alpha W, beta q)` of it become the same
//! problem, so a solver sees the same numbers, takes the same iterations and reaches the same
//! relative error whatever the units of the host. The error reported is always measured on the
//! host's problem.

use crate::error::{check_finite, Fc3dError};
use crate::linalg::norm;
use crate::measure::natural_map_error;
use crate::problem::FrictionProblem;
use crate::report::{SolveReport, SolveStatus};
use crate::solver::{solve_with_observer, IterationEvent, SolverConfig};

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

/// [`solve_with_observer`] with a rescaling: the solver runs on the rescaled problem, the observer
/// sees iterates mapped back to the host's units, and the report's error is the natural-map error
/// of the returned `(r, u)` on the host's problem (the status follows from it).
///
/// On `Err`, `r` and `u` are left untouched.
pub fn solve_rescaled(
    problem: &FrictionProblem<'_>,
    config: &SolverConfig,
    rescaling: Rescaling,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut dyn FnMut(&IterationEvent<'_>),
) -> Result<SolveReport, Fc3dError> {
    if rescaling == Rescaling::None {
        return solve_with_observer(problem, config, r, u, observer);
    }
    let n = problem.size();
    if r.len() != n {
        return Err(Fc3dError::dims("reaction", n, r.len()));
    }
    if u.len() != n {
        return Err(Fc3dError::dims("velocity", n, u.len()));
    }
    check_finite("initial reaction", r)?;
    let (s, t) = scalar_factors(problem);
    let scaled_q: Vec<f64> = problem.q().iter().map(|v| t * v).collect();
    let scaled = FrictionProblem::new(problem.w().scaled(s), scaled_q, problem.mu().to_vec())?;
    let to_host = s / t;
    let mut r_s: Vec<f64> = r.iter().map(|v| v / to_host).collect();
    let mut u_s = vec![0.0; n];
    let mut host_r = vec![0.0; n];
    let mut mapped = |ev: &IterationEvent<'_>| {
        for (h, v) in host_r.iter_mut().zip(ev.reaction) {
            *h = to_host * v;
        }
        observer(&IterationEvent {
            iteration: ev.iteration,
            reaction: &host_r,
            error: ev.error,
        });
    };
    let inner = solve_with_observer(&scaled, config, &mut r_s, &mut u_s, &mut mapped)?;

    for (h, v) in r.iter_mut().zip(&r_s) {
        *h = to_host * v;
    }
    let mut error = natural_map_error(problem, r, u);
    if !error.is_finite() || !r.iter().chain(u.iter()).all(|v| v.is_finite()) {
        // Mapping back overflowed: r = 0, u = q is the finite answer (see solve_with_observer).
        r.iter_mut().for_each(|v| *v = 0.0);
        error = natural_map_error(problem, r, u);
    }
    let status = if error <= config.tolerance() {
        SolveStatus::Converged
    } else if inner.status == SolveStatus::TimeBudgetExhausted {
        SolveStatus::TimeBudgetExhausted
    } else {
        SolveStatus::MaxIterationsReached
    };
    Ok(SolveReport {
        status,
        iterations: inner.iterations,
        error,
        // Dumont's criterion is absolute: in the rescaled units, where the run measured it.
        dumont_criterion: inner.dumont_criterion,
    })
}

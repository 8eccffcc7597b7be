//! The hyperplane projection (HP 508) as Siconos 4.4 runs it: a prediction
//! `r̄ = P_K(r - rho F(r))`, a search along the segment `[r, r̄]` for a point w whose velocity
//! `v = W w + q` satisfies `v·(r - r̄) >= sigma / rho ||r - r̄||^2`, and the projection step
//! `P_K(r - (v·(r - r̄) / ||v||^2) v)` (see [`super::HyperplaneSearch`]).

use super::{evaluate, project_step, stopping_error, StepSize, ViOptions};
use crate::contract::{ErrorSchedule, IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::{bounded, distance_sq, dot, norm};
use crate::problem::FrictionProblem;

/// Runs HP from the reaction in `r`; on return `u = W r + q`.
pub(super) fn run(
    problem: &FrictionProblem<'_>,
    options: &ViOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let StepSize::Fixed(rho) = options.step else {
        // `validate` rejects a self-adaptive rho for HP.
        return Err(Fc3dError::InvalidOption(
            "HP (508) projects its prediction with a fixed rho".into(),
        ));
    };
    let search = options.hyperplane;
    let n = problem.size();
    let mu = problem.mu();
    let norm_q = norm(problem.q());
    let lineage = options.solver.lineage();
    let run = limits.start();
    let mut schedule = ErrorSchedule::new(options.error_evaluation, run.tolerance, 1, run.max_iter);

    // Work vectors, allocated once: F(r), the prediction r̄ and its velocity, r - r̄, the velocity
    // v at the accepted search point and the next iterate.
    let mut f = try_vec(n, 0.0, "the VI work arrays")?;
    let mut prediction = try_vec(n, 0.0, "the VI work arrays")?;
    let mut prediction_u = try_vec(n, 0.0, "the VI work arrays")?;
    let mut direction = try_vec(n, 0.0, "the VI work arrays")?;
    let mut v = try_vec(n, 0.0, "the VI work arrays")?;
    let mut next = try_vec(n, 0.0, "the VI work arrays")?;

    evaluate(problem, r, u, &mut f);
    for iteration in 1..=run.max_iter {
        project_step(mu, r, &f, rho, &mut prediction);
        for ((d, &a), &b) in direction.iter_mut().zip(r.iter()).zip(&prediction) {
            *d = a - b;
        }
        let threshold = search.sigma / rho * dot(&direction, &direction);

        // The search points w = t r̄ + (1 - t) r, t = 2^-m, m = 0, 1, ...: the first with
        // v·(r - r̄) >= threshold (the last one tried when none passes). v = W w + q is affine in
        // t, v = t u(r̄) + (1 - t) u(r), so one product with W per iteration serves the whole
        // search (Siconos forms W w + q for every trial: same points, same test).
        problem.velocity(&prediction, &mut prediction_u);
        let along_prediction = dot(&prediction_u, &direction);
        let along_iterate = dot(u, &direction);
        // O(1) per trial, and at most ~1075 trials whatever `max_halvings` (t underflows to 0,
        // after which every trial is w = r): no time check needed inside.
        let mut weight = 1.0;
        for m in 0..=search.max_halvings {
            if m > 0 {
                weight *= 0.5;
            }
            let lhs = weight * along_prediction + (1.0 - weight) * along_iterate;
            if lhs >= threshold || weight == 0.0 {
                break;
            }
        }
        for ((vi, &a), &b) in v.iter_mut().zip(&prediction_u).zip(u.iter()) {
            *vi = weight * a + (1.0 - weight) * b;
        }
        let lhs = dot(&v, &direction);
        let v_sq = dot(&v, &v);
        if v_sq == 0.0 {
            // v = 0: the velocity at w vanishes and w is in K (a convex combination of points
            // of K), so w is a solution.
            for ((x, &a), &b) in next.iter_mut().zip(&prediction).zip(r.iter()) {
                *x = weight * a + (1.0 - weight) * b;
            }
        } else {
            project_step(mu, r, &v, lhs / v_sq, &mut next);
        }
        if !bounded(&next) {
            return Ok(SolverOutcome::diverged(iteration));
        }
        let increment_sq = distance_sq(r, &next);
        r.copy_from_slice(&next);
        evaluate(problem, r, u, &mut f);
        if !bounded(&f) {
            return Ok(SolverOutcome::diverged(iteration));
        }

        let test = schedule.test(iteration, increment_sq, r, |_| {
            stopping_error(lineage, problem, r, u, norm_q)
        });
        observer(&IterationEvent {
            iteration,
            reaction: r,
            error: test.error,
        });
        if let Some(outcome) = run.end_of_iteration(iteration, test.converged) {
            return Ok(outcome);
        }
    }
    Ok(run.exhausted())
}

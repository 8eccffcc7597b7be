//! The hyperplane projection (HP 508) as Siconos 4.4 runs it: a prediction
//! `r̄ = P_K(r - rho F(r))`, a search along the segment `[r, r̄]` for a point w whose velocity
//! `v = W w + q` satisfies `v·(r - r̄) >= sigma / rho ||r - r̄||^2`, and the projection step
//! `P_K(r - (v·(r - r̄) / ||v||^2) v)` (see [`super::HyperplaneSearch`]).

use super::{evaluate, project_step, stopping_error, StepSize, ViOptions};
use crate::contract::{ErrorSchedule, IterationEvent, Limits, Observer, SolverOutcome};
use crate::error::Fc3dError;
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

    // Work vectors, allocated once: F(r), the prediction, r - r̄, the search point w, its
    // velocity v and the next iterate.
    let mut f = vec![0.0; n];
    let mut prediction = vec![0.0; n];
    let mut direction = vec![0.0; n];
    let mut point = vec![0.0; n];
    let mut point_u = vec![0.0; n];
    let mut next = vec![0.0; n];

    evaluate(problem, r, u, &mut f);
    for iteration in 1..=run.max_iter {
        project_step(mu, r, &f, rho, &mut prediction);
        for ((d, &a), &b) in direction.iter_mut().zip(r.iter()).zip(&prediction) {
            *d = a - b;
        }
        let threshold = search.sigma / rho * dot(&direction, &direction);

        // w = 2^-m r̄ + (1 - 2^-m) r, m = 0, 1, ...: the first w with v·(r - r̄) >= threshold
        // (the last one tried when none passes).
        let mut lhs = f64::NAN;
        let mut weight = 1.0;
        for m in 0..=search.max_halvings {
            if m > 0 {
                if run.out_of_time() {
                    break;
                }
                weight *= 0.5;
            }
            for ((w, &a), &b) in point.iter_mut().zip(r.iter()).zip(&prediction) {
                *w = weight * b + (1.0 - weight) * a;
            }
            problem.velocity(&point, &mut point_u);
            lhs = dot(&point_u, &direction);
            if lhs >= threshold {
                break;
            }
        }
        let v_sq = dot(&point_u, &point_u);
        if v_sq == 0.0 {
            // v = 0: the velocity at w vanishes and w is in K (a convex combination of points
            // of K), so w is a solution.
            next.copy_from_slice(&point);
        } else {
            project_step(mu, r, &point_u, lhs / v_sq, &mut next);
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

//! The fixed point (95) and the extragradient, with a fixed rho or Algorithm 3.

use super::settings::Lineage;
use super::{
    ExtraGradientCorrection, StepRatio, StepSize, TrialStart, ViIteration, ViMap, ViOptions,
    ViSolver,
};
use crate::contract::{
    ErrorEvaluation, ErrorSchedule, IterationEvent, Limits, Observer, SolverOutcome,
};
use crate::error::{try_vec, Fc3dError};
use crate::math::linalg::{bounded, distance_sq, norm};
use crate::measure::cheap_error;

/// The two quantities Algorithm 3 compares for a trial `r̄` from `r` (F values `f`, `f̄`):
/// Khobotov's `(||F(r̄) - F(r)||, ||r̄ - r||)` or Solodov-Tseng's
/// `((r̄ - r)·(F(r̄) - F(r)), ||r̄ - r||)`.
fn trial_measures(kind: StepRatio, r: &[f64], rbar: &[f64], f: &[f64], fbar: &[f64]) -> (f64, f64) {
    let dr = distance_sq(r, rbar).sqrt();
    let a1 = match kind {
        StepRatio::Khobotov => distance_sq(f, fbar).sqrt(),
        StepRatio::SolodovTseng => r
            .iter()
            .zip(rbar)
            .zip(f.iter().zip(fbar))
            .map(|((a, b), (fa, fb))| (b - a) * (fb - fa))
            .sum(),
    };
    (a1, dr)
}

/// The ratio (98) or (99) of a trial with step `rho` from its measures: 0 when `r̄ = r` (a fixed
/// point: nothing to reject), +inf when not measurable.
fn ratio_of(kind: StepRatio, rho: f64, a1: f64, a2: f64) -> f64 {
    if a2 == 0.0 {
        return 0.0;
    }
    let r = match kind {
        StepRatio::Khobotov => rho * a1 / a2,
        StepRatio::SolodovTseng => rho * a1 / (a2 * a2),
    };
    if r.is_nan() {
        f64::INFINITY
    } else {
        r
    }
}

/// Runs the fixed point or the extragradient of `options` on `map` from `r` (the unknowns x:
/// the reaction, or the global `(v, r)`); on return `u` is the velocity computed with `F(r)`.
pub(crate) fn run(
    map: &impl ViMap,
    options: &ViOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
) -> Result<SolverOutcome, Fc3dError> {
    let n = map.size();
    let run = limits.start();
    let lineage = options.solver.lineage();
    let iteration_kind = options.solver.iteration();
    // Siconos' VI solvers test the full error at every iteration when rho is fixed.
    let evaluation = match (lineage, options.step) {
        (Lineage::Vi, StepSize::Fixed(_)) => ErrorEvaluation::Full,
        _ => options.error_evaluation,
    };
    let mut schedule = ErrorSchedule::new(evaluation, run.tolerance, 1, run.max_iter);

    // Work vectors, allocated once: F at the current iterate, the trial (prediction) and its
    // velocity and F, and the extragradient's corrected iterate.
    let mut f = try_vec(n, 0.0, "the VI work arrays")?;
    let mut trial = try_vec(n, 0.0, "the VI work arrays")?;
    let mut trial_u = try_vec(map.velocity_size(), 0.0, "the VI work arrays")?;
    let mut trial_f = try_vec(n, 0.0, "the VI work arrays")?;
    let mut corrected = match iteration_kind {
        ViIteration::ExtraGradient => try_vec(n, 0.0, "the VI work arrays")?,
        _ => Vec::new(),
    };

    map.evaluate(r, u, &mut f);
    let mut rho = match options.step {
        StepSize::Fixed(rho) => rho,
        StepSize::SelfAdaptive(s) => s.initial_rho,
    };
    // Siconos' friction-lineage solvers start from error_k = 1 for their increase rule.
    let mut previous_error = 1.0;

    for iteration in 1..=run.max_iter {
        // Prediction, with Algorithm 3 when rho is self-adaptive.
        let mut rho_k = rho;
        let (mut a1, mut ratio) = (0.0, 0.0);
        match options.step {
            StepSize::Fixed(rho) => {
                map.project_step(r, &f, rho, &mut trial);
                map.evaluate(&trial, &mut trial_u, &mut trial_f);
            }
            StepSize::SelfAdaptive(s) => {
                // The VI solvers build the trial steps as (rho / nu) nu^(m+1), the friction
                // ones as rho nu^m (same values up to rounding, which long runs amplify).
                if lineage == Lineage::Vi {
                    rho_k = rho / s.nu;
                }
                for m in 0..s.max_trials {
                    if m > 0 && run.out_of_time() {
                        // The iteration ends with the last trial; the loop stops after it.
                        break;
                    }
                    rho_k = match lineage {
                        Lineage::Vi => rho_k * s.nu,
                        Lineage::Friction => rho * s.nu.powf(m as f64),
                    };
                    match (m, s.trial_start) {
                        (0, _) | (_, TrialStart::Iterate) => {
                            map.project_step(r, &f, rho_k, &mut trial)
                        }
                        (_, TrialStart::PreviousTrial) => {
                            map.project_step_in_place(&mut trial, &f, rho_k)
                        }
                    }
                    map.evaluate(&trial, &mut trial_u, &mut trial_f);
                    let a2;
                    (a1, a2) = trial_measures(s.ratio, r, &trial, &f, &trial_f);
                    ratio = if bounded(&trial_f) {
                        ratio_of(s.ratio, rho_k, a1, a2)
                    } else {
                        f64::INFINITY
                    };
                    // Siconos' FPP 511 accepts a ratio equal to L; the others need it below.
                    let accepted = if options.solver == ViSolver::FixedPointProjection {
                        ratio <= s.l
                    } else {
                        ratio < s.l
                    };
                    if accepted {
                        break;
                    }
                }
            }
        }

        // The new iterate: the prediction itself (fixed point) or the correction step.
        let (new_r, new_u, new_f) = match iteration_kind {
            ViIteration::ExtraGradient => {
                let base: &[f64] = match options.correction {
                    ExtraGradientCorrection::FromPrediction => &trial,
                    ExtraGradientCorrection::FromIterate => r,
                };
                map.project_step(base, &trial_f, rho_k, &mut corrected);
                map.evaluate(&corrected, &mut trial_u, &mut trial_f);
                (&mut corrected, &mut trial_u, &mut trial_f)
            }
            _ => (&mut trial, &mut trial_u, &mut trial_f),
        };
        if !bounded(new_r) || !bounded(new_f) {
            // Diverged (rho far too large for W): keep the last bounded iterate and stop.
            return Ok(SolverOutcome::diverged(iteration).with_final_rho(handed_back(options, rho)));
        }
        // The cheap error: the increment (134), or for the VI extragradient Siconos' quantity
        // (the last trial's a1 over ||r_{k+1}||).
        let light = match (lineage, iteration_kind, options.step) {
            (Lineage::Vi, ViIteration::ExtraGradient, StepSize::SelfAdaptive(_)) => {
                let nr = norm(new_r);
                if nr > f64::EPSILON {
                    a1 / nr
                } else {
                    a1
                }
            }
            _ => cheap_error(distance_sq(r, new_r), new_r),
        };
        r.copy_from_slice(new_r);
        u.copy_from_slice(new_u);
        f.copy_from_slice(new_f);

        // u = W r + q holds exactly here, so the full error costs O(n) on top of the step.
        let test = schedule.test_light(iteration, light, |_| map.stopping_error(lineage, r, u, &f));
        if let StepSize::SelfAdaptive(s) = options.step {
            let easy = ratio < s.l_min && (lineage == Lineage::Vi || test.error < previous_error);
            rho = if easy { rho_k * s.increase } else { rho_k };
        }
        previous_error = test.error;
        observer(&IterationEvent {
            iteration,
            reaction: map.reaction(r),
            error: test.error,
        });
        if let Some(outcome) = run.end_of_iteration(iteration, test.converged) {
            return Ok(outcome.with_final_rho(handed_back(options, rho)));
        }
    }
    Ok(run.exhausted().with_final_rho(handed_back(options, rho)))
}

/// The rho Siconos' generic VI solvers (506/507) hand back to the host when it is self-adaptive.
fn handed_back(options: &ViOptions, rho: f64) -> Option<f64> {
    match (options.solver.lineage(), options.step) {
        (Lineage::Vi, StepSize::SelfAdaptive(_)) => Some(rho),
        _ => None,
    }
}

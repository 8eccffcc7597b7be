//! The stage loop: runs a plan's stages in chunks from the best iterate, watches their
//! progress and the limits, and hands the time over from stage to stage.

use std::time::{Duration, Instant};

use crate::contract::{
    BestIterate, ErrorEvaluation, Family, Fill, IterationEvent, Limits, Observer, SolverOutcome,
    Stage, StageEnd, StageKind, StageLog, MAX_STAGES,
};
use crate::error::Fc3dError;
use crate::measure::natural_map_error;
use crate::problem::FrictionProblem;
use crate::solvers::admm::AdmmOptions;
use crate::solvers::nsgs::{run_sweeps, NsgsOptions, PreparedSweep, SweepSchedule, Sweeper};
use crate::solvers::nsn::{NewtonSolver, NsnFormulation, NsnOptions};
use crate::solvers::prox::{ProxOptions, ProxState};
use crate::solvers::tresca::{TrescaInnerSolver, TrescaOptions};
use crate::solvers::vi::{ViOptions, ViSolver};

use super::features::ProblemFeatures;
use super::plan::{next_probe, next_stage, probe_runs_on, Handover, ProbeProgress};
use super::rules::{
    choose, stall_rule, sweep_local_solver, StallRule, SweepTuning, PROBE, PROBE_PRODUCTS,
    SHORT_BUDGET, TO_THE_LIMITS,
};
use super::{AutoCarry, AutoChoice, AutoOptions, ROUND_OFF};

use StageKind::{Admm, ExtraGradient, Newton, Nsgs, Prox, Tresca, TrescaApgd};

/// The remaining budget as limits for a stage of at most `max_iter` iterations.
fn stage_limits(tolerance: f64, max_iter: usize, deadline: Option<Instant>) -> Limits {
    Limits {
        tolerance,
        max_iter,
        // An exhausted budget still allows one iteration (the caller stops right after).
        time_budget: deadline.map(|d| {
            d.saturating_duration_since(Instant::now())
                .max(Duration::from_nanos(1))
        }),
    }
}

/// Runs AUTO; a workspace hands in what it kept and gets it back in `carry` (see [`AutoCarry`]).
pub(crate) fn auto_with<'a>(
    problem: &FrictionProblem<'a>,
    options: &AutoOptions,
    limits: &Limits,
    r: &mut [f64],
    u: &mut [f64],
    observer: &mut Observer<'_>,
    carry: &mut AutoCarry<'a>,
) -> Result<SolverOutcome, Fc3dError> {
    options.validate()?;
    let run = limits.start();
    // An anytime solve (a budget and a tolerance below round-off) stops at round-off: the
    // stages after it gain nothing and their steps overran the budget on the small shared
    // problems (docs/auto.md, "AUTO against Siconos at equal budget").
    let tolerance = if run.deadline().is_some() {
        run.tolerance.max(ROUND_OFF)
    } else {
        run.tolerance
    };
    let requested = run.tolerance;
    let budget = limits.time_budget;
    let resume = carry.resume.take().filter(|c| {
        options.plan.is_none()
            && c.tolerance == requested
            && c.budget == budget
            && c.stage < c.plan.len()
    });
    // On W's block pattern of the kept choice, the features are not measured again. On another
    // one (a contact appeared or vanished) they are, and the solve resumes only if they give
    // the same rule: the choice follows the scene, not the exact contact set.
    let (rule, plan, first, resumed) = match (options.plan, resume) {
        (Some(plan), _) => (usize::MAX, plan, 0, false),
        (None, Some(c)) if carry.same_pattern => (c.rule, c.plan, c.stage, true),
        (None, kept) => {
            let (rule, plan) = choose(&ProblemFeatures::try_of(problem)?, requested, budget);
            match kept.filter(|c| c.rule == rule) {
                Some(c) => (rule, plan, c.stage, true),
                None => (rule, plan, 0, false),
            }
        }
    };
    carry.resumed = resumed;
    let mut last_stage = first;
    // A colouring kept for another run is handed back as it came.
    let (kept_rows, kept_colouring) = match carry.sweep.take() {
        Some(p) => (Some(p.rows), p.colouring),
        None => (None, None),
    };
    let mut kept_rows = kept_rows;
    let mut kept_newton = carry.newton.take();
    let mut log = StageLog::new(rule);
    // The initial error is not measured (a product with W, as much as a whole solve of a small
    // problem): the first stage starts from r as given.
    let mut error = f64::INFINITY;
    let mut best = BestIterate::try_new(r, error)?;
    let mut best_error = error;
    let mut total = 0usize;
    let mut out_of_time = false;
    // A plan has at most one NSGS stage; its sweep options are the sweeper's.
    let tuning = plan
        .iter()
        .find(|s| s.kind == Nsgs)
        .map_or(SweepTuning::PLAIN, |s| s.sweep);
    let nsgs_options = NsgsOptions {
        relaxation: tuning.relaxation,
        freezing: tuning.freezing,
        ..NsgsOptions::with_local(sweep_local_solver(rule))
    };
    // The sweeps run without a test of their own (Siconos' increment test passes hundreds of
    // sweeps after the error on the Capsules): AUTO measures the full error after each run of
    // sweeps, whose length it predicts from the rate seen (see `next_probe`).
    let schedule = SweepSchedule {
        error_evaluation: ErrorEvaluation::Light,
        evaluation_frequency: 1,
        local_tolerance: nsgs_options.local_tolerance,
        stop_when_stalled: false,
        acceleration: Default::default(),
    };
    let mut sweeper: Option<Sweeper> = None;
    // At most 50 Newton steps per proximal step, not NSN's 200: on the settling pile's
    // hyperstatic steps the shift rule cycles (a shift too small for the Newton solve, then ten
    // and a hundred times it), and each failed solve ran its 200 steps (0.3 s) where the ones
    // that converge take at most 82, mostly under 30. On the 30 shared problems AUTO takes the
    // same iterations with 50 as with 200 except on BoxesStack1 at 1e-8 (7 PROX steps instead
    // of 6, 0.72x the time).
    let prox_options = ProxOptions {
        internal_max_iter: Some(50),
        ..ProxOptions::default()
    };
    let admm_options = AdmmOptions::default();
    let tresca_options = TrescaOptions::default();
    let tresca_apgd_options = TrescaOptions {
        inner: TrescaInnerSolver::apgd(),
        ..TrescaOptions::default()
    };
    let eg_options = ViOptions::new(ViSolver::ExtraGradient);
    let newton_options = NsnOptions::new(NsnFormulation::AlartCurnier);
    let mut newton: Option<NewtonSolver> = None;
    let mut prox: Option<ProxState> = None;
    // The largest factorization of the stages that factorize (PROX and ADMM build their own).
    let mut fill = None;

    // Under a time budget, a plan whose stages all ended (stalled) before the deadline starts
    // over from the best iterate, and a stage stopped short of the deadline hands the time left
    // to the plan's first stage that does not factorize (see `next_stage`). The log's capacity
    // ends the solve at the latest.
    let mut previous: Option<(usize, Handover)> = None;
    'plan: loop {
        if error <= tolerance || total >= run.max_iter || out_of_time || log.is_full() {
            break;
        }
        let time = run
            .deadline()
            .zip(limits.time_budget)
            .map(|(d, b)| (d.saturating_duration_since(Instant::now()), b));
        let Some(next) = next_stage(plan, first, previous, time) else {
            break;
        };
        let index = next.index;
        let planned = &plan[index];
        last_stage = index;
        // Every stage starts from the best iterate seen.
        if best.restore_if_better(r, error) {
            error = best_error;
        }
        let watch = match (planned.kind, planned.sweep.stall) {
            (Nsgs, Some((chunk, factor))) => StallRule {
                kind: Nsgs,
                chunk,
                factor,
            },
            _ => stall_rule(planned.kind),
        };
        // NSGS measures its error at least every this many sweeps, whatever its stall window.
        let longest_probe = stall_rule(planned.kind).chunk;
        let probe = planned.allowance == PROBE && !next.to_the_limits;
        let allowance = match planned.allowance {
            _ if probe => usize::MAX,
            a => a.unwrap_or(usize::MAX),
        };
        let to_the_limits = next.to_the_limits || planned.allowance == TO_THE_LIMITS;
        // Under a budget above SHORT_BUDGET, a stage of a plan with several gets at most half of
        // the time left, so that a method that is slow on this problem (PROX on BoxesStack and
        // RockPile) leaves time to the next one while a fast one (PROX on the Capsules) still
        // converges; the plan then starts over (docs/auto.md, AUTO against Siconos at equal budget).
        // The last stage the log can hold gets all the time left: halving would end the solve
        // before the deadline with the budget unspent.
        // So does a stage run to the limits (large piles).
        let last_possible = log.len() + 1 == MAX_STAGES;
        let whole_remainder = last_possible || to_the_limits;
        let stage_deadline = match run.deadline() {
            Some(d)
                if plan.len() > 1
                    && !whole_remainder
                    && limits.time_budget.is_some_and(|b| b > SHORT_BUDGET) =>
            {
                let now = Instant::now();
                Some(now + d.saturating_duration_since(now) / 2)
            }
            other => other,
        };
        let stage_over = || stage_deadline.is_some_and(|d| Instant::now() >= d);
        let mut done = 0usize;
        let end;
        let mut handover = Handover::Ended;
        // The sweeper and the Newton matrix are built once per solve, at their first stage.
        // A workspace's structures (built for this W's pattern) are taken over.
        let built = match planned.kind {
            Newton if newton.is_none() => {
                NewtonSolver::reusing(problem, &newton_options, kept_newton.take())
                    .map(|(s, _)| newton = Some(s))
                    .is_ok()
            }
            // PROX's Newton matrix is the Newton stage's with a shift: a kept one serves it.
            Prox if prox.is_none() => {
                ProxState::reusing(problem, &prox_options, kept_newton.take())
                    .map(|(s, _)| prox = Some(s))
                    .is_ok()
            }
            Nsgs if sweeper.is_none() => match kept_rows.take() {
                Some(rows) => Sweeper::with_rows(rows, &nsgs_options, tolerance, None),
                None => Sweeper::with_options(problem, &nsgs_options, tolerance),
            }
            .map(|s| sweeper = Some(s))
            .is_ok(),
            _ => true,
        };
        if !built {
            log.push(Stage {
                kind: planned.kind,
                iterations: 0,
                error,
                end: StageEnd::Failed,
            });
            previous = Some((index, Handover::Ended));
            continue 'plan;
        }
        // A PROX stage goes on from chunk to chunk; a new one starts its shift rule over.
        if let (Prox, Some(state)) = (planned.kind, prox.as_mut()) {
            state.restart();
        }
        // The stall test looks at windows of `watch.chunk` iterations; NSGS measures inside a
        // window as often as its predicted convergence asks.
        let mut window_start = error;
        let mut window = 0usize;
        let mut probe_sweeps = 1usize;
        // A probe's products with W: those of its first iteration set its cap; its error after
        // that iteration and its best one since decide whether it runs on past the cap.
        let (mut products, mut first_products) = (0usize, None);
        let (mut first_error, mut stage_best) = (None, f64::INFINITY);
        let mut caps = 1usize;
        loop {
            let left = (run.max_iter - total).min(allowance - done);
            if left == 0 {
                end = if done >= allowance {
                    StageEnd::Allowance
                } else {
                    StageEnd::Limits
                };
                break;
            }
            let chunk = match planned.kind {
                Nsgs => probe_sweeps.min(watch.chunk - window).min(longest_probe),
                // A probe checks its cap after each iteration.
                _ if probe => 1,
                _ => watch.chunk,
            }
            .min(left);
            let before = error;
            let offset = total;
            let mut shifted = |ev: &IterationEvent<'_>| {
                observer(&IterationEvent {
                    iteration: offset + ev.iteration,
                    reaction: ev.reaction,
                    error: ev.error,
                })
            };
            // The families report the natural-map error of (r, u = W r + q) when their last
            // step measured it (the contract of `SolverOutcome::final_error`): then it is not
            // measured again.
            let (iterations, measured, stopped_for_time, chunk_products) = match planned.kind {
                Nsgs => {
                    let sweeper = sweeper.as_mut().expect("built above");
                    // Tolerance 0: the sweeps run the whole probe (or stop on a fixed point).
                    let l = stage_limits(0.0, chunk, stage_deadline);
                    let o = run_sweeps(problem, sweeper, &schedule, &l, r, u, &mut shifted)?;
                    (o.iterations, o.final_error, o.out_of_time, o.products)
                }
                Newton => {
                    let solver = newton.as_mut().expect("built above");
                    let inner = stage_limits(tolerance, chunk, stage_deadline).start();
                    let o = solver.run(problem.q(), problem.mu(), 0.0, &inner, r, u, &mut shifted);
                    (o.iterations, None, o.out_of_time, None)
                }
                Prox => {
                    let state = prox.as_mut().expect("built above");
                    let l = stage_limits(tolerance, chunk, stage_deadline);
                    let o = state.run(problem, &l.start(), r, u, &mut shifted)?;
                    fill = Fill::largest(fill, o.fill);
                    (o.iterations, o.final_error, o.out_of_time, o.products)
                }
                Admm | Tresca | TrescaApgd | ExtraGradient => {
                    let family: &dyn Family = match planned.kind {
                        Admm => &admm_options,
                        ExtraGradient => &eg_options,
                        TrescaApgd => &tresca_apgd_options,
                        _ => &tresca_options,
                    };
                    let l = stage_limits(tolerance, chunk, stage_deadline);
                    let o = family.run(problem, &l, r, u, &mut shifted)?;
                    fill = Fill::largest(fill, o.fill);
                    (o.iterations, o.final_error, o.out_of_time, o.products)
                }
            };
            // A stage that did nothing (converged at entry, or cut at once) still counts one
            // iteration so that the loop ends.
            let iterations = iterations.max(1);
            done += iterations;
            total += iterations;
            error = measured.unwrap_or_else(|| natural_map_error(problem, r, u));
            best.offer(r, error);
            best_error = best_error.min(error);
            if error <= tolerance {
                end = StageEnd::Converged;
                break;
            }
            if run.out_of_time() {
                out_of_time = true;
                end = StageEnd::Limits;
                break;
            }
            // A stage under the whole budget that stopped for time before the deadline (its
            // next Newton step or factorization expected to end past it) leaves the time left to
            // a stage whose iterations are short.
            if stopped_for_time && stage_deadline == run.deadline() {
                handover = Handover::ShortOfDeadline;
                end = StageEnd::Limits;
                break;
            }
            if stage_over() {
                end = StageEnd::Limits;
                break;
            }
            if probe {
                // A family that does not count its products counts one per iteration.
                let last_products = chunk_products.unwrap_or(iterations);
                products += last_products;
                let first = *first_error.get_or_insert(error);
                stage_best = stage_best.min(error);
                let cap = PROBE_PRODUCTS * *first_products.get_or_insert(products);
                if products > caps * cap {
                    let progress = ProbeProgress {
                        first_error: first,
                        best_error: stage_best,
                        steps: done,
                        products,
                        last_products,
                    };
                    if caps == 1 && probe_runs_on(&progress, tolerance, cap) {
                        caps = 2;
                    } else {
                        end = StageEnd::Allowance;
                        break;
                    }
                }
            }
            // A stage run to the limits is not ended by a stall (large piles: every method's
            // error falls slowly).
            // So is the last stage of a budgeted solve: the host gave the time left.
            // Neither is a probe running on past its cap (bounded by it, and its error is not
            // monotone: a window can end on a bad step of a fast-falling sequence).
            let patient =
                (to_the_limits || caps > 1 || (last_possible && run.deadline().is_some()))
                    && error.is_finite();
            window += iterations;
            if window >= watch.chunk {
                // NaN compares false: a non-finite error is a stall.
                if !patient && !(error <= watch.factor * window_start) {
                    end = StageEnd::Stalled;
                    break;
                }
                window_start = error;
                window = 0;
            }
            probe_sweeps = next_probe(
                probe_sweeps,
                before,
                error,
                iterations,
                tolerance,
                longest_probe,
            );
        }
        log.push(Stage {
            kind: planned.kind,
            iterations: done,
            error,
            end,
        });
        previous = Some((index, handover));
    }
    // The last error was measured on (r, u = W r + q) by `natural_map_error` (here or by the
    // family's last step): it is the final error unless an earlier iterate was better.
    let restored = best.restore_if_better(r, error);
    let fill = Fill::largest(fill, newton.as_ref().and_then(NewtonSolver::fill));
    // Only a stage that reached the tolerance (or, in an anytime solve, the one the budget ended
    // in) is worth starting from: after a solve that ran out of stages or iterations, the next
    // one chooses afresh.
    let finished = error <= tolerance || (requested == 0.0 && out_of_time);
    carry.choice = finished.then_some(AutoChoice {
        rule,
        plan,
        stage: last_stage,
        tolerance: requested,
        budget,
    });
    carry.sweep = sweeper
        .map(|s| s.into_prepared().0)
        .or(kept_rows)
        .map(|rows| PreparedSweep {
            rows,
            colouring: kept_colouring,
        });
    carry.newton = newton
        .or_else(|| prox.and_then(ProxState::into_newton))
        .or(kept_newton);
    Ok(SolverOutcome {
        stages: Some(log),
        fill,
        ..SolverOutcome::stopped(total.min(run.max_iter), out_of_time)
            .with_final_error((!restored && error.is_finite()).then_some(error))
    })
}

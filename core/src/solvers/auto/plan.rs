//! The order of a solve's stages: which stage of the plan runs next ([`next_stage`]) and how
//! often an NSGS stage measures its error ([`next_probe`]), apart from the clock so that they
//! are tested without it.

use std::time::Duration;

use crate::contract::StageKind;

use super::rules::{PlannedStage, PROBE};

use StageKind::{Admm, Newton, Prox};

/// Whether a stage of this kind factorizes a matrix of W's size in its first step (5-10 ms on
/// the Capsules, more than 20 ms from 400 contacts on): such a step cannot be interrupted.
pub fn factorizes(kind: StageKind) -> bool {
    matches!(kind, Prox | Admm | Newton)
}

/// How a stage ended, as far as the choice of the next one goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Handover {
    /// It stalled, used its allowance or its share of the budget, or could not be set up.
    Ended,
    /// It stopped for time before the deadline: its next step (a Newton step, a
    /// factorization) was expected to end past it.
    ShortOfDeadline,
}

/// The stage to run next: its index in the plan, and whether it runs to the limits whatever its
/// progress.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NextStage {
    pub index: usize,
    pub to_the_limits: bool,
}

/// The plan's stage that fills the time a stage stopped short of the deadline left: its first
/// stage that does not factorize (NSGS, TFP or EG, whose iterations are short and end at the
/// deadline), a probe excepted.
fn filler(plan: &[PlannedStage]) -> Option<usize> {
    plan.iter()
        .position(|s| !factorizes(s.kind) && s.allowance != PROBE)
}

/// The next stage of a solve: `first` to begin with (`previous` is `None`), then the stage after
/// `previous`. Without a budget (`time` is `None`) the plan ends after its last stage. Under a
/// budget (`time`: the time left and the budget) the time is used up to the deadline:
/// - the plan starts over after its last stage (a plan whose stages all stalled early), without
///   its probe (a probe runs once);
/// - a factorizing stage is not started after the first one when less than a quarter of the
///   budget is left (its first step overran the deadline on the Capsules), the next stage of the
///   plan is taken instead;
/// - after a stage that stopped short of the deadline, the plan's first non-factorizing stage
///   runs to the limits from the best iterate (it was PROX's next step, expected past the
///   deadline, that ended the solve with the budget unspent); after that filler itself stopped
///   short, nothing is left to try.
pub fn next_stage(
    plan: &[PlannedStage],
    first: usize,
    previous: Option<(usize, Handover)>,
    time: Option<(Duration, Duration)>,
) -> Option<NextStage> {
    let Some((last, handover)) = previous else {
        return (first < plan.len()).then_some(NextStage {
            index: first,
            to_the_limits: false,
        });
    };
    let fill = || {
        filler(plan)
            .filter(|&i| i != last || handover == Handover::Ended)
            .map(|index| NextStage {
                index,
                to_the_limits: true,
            })
    };
    let Some((left, budget)) = time else {
        return (last + 1 < plan.len()).then_some(NextStage {
            index: last + 1,
            to_the_limits: false,
        });
    };
    if handover == Handover::ShortOfDeadline {
        return fill();
    }
    (1..=plan.len())
        .map(|k| (last + k) % plan.len())
        .find(|&i| {
            !(factorizes(plan[i].kind) && left < budget / 4)
                && !(plan[i].allowance == PROBE && i <= last)
        })
        .map(|index| NextStage {
            index,
            to_the_limits: false,
        })
        .or_else(fill)
}

/// The sweeps to run before the next measurement of the error: those the contraction seen over
/// the last `iterations` sweeps (from `before` to `error`) needs to reach `tolerance`, between 1
/// and `max`; twice the last probe while no contraction is known yet. Measured this way, a
/// Gauss-Seidel stage stops within a sweep or two of the first one below the tolerance, with
/// a few measurements of the error (each costs about one product with W, less than a sweep).
pub(crate) fn next_probe(
    last: usize,
    before: f64,
    error: f64,
    iterations: usize,
    tolerance: f64,
    max: usize,
) -> usize {
    let rate = (error / before).powf(1.0 / iterations.max(1) as f64);
    let sweeps = if rate.is_finite() && rate > 0.0 && rate < 1.0 && error > tolerance {
        ((tolerance / error).ln() / rate.ln()).ceil()
    } else {
        (2 * last) as f64
    };
    // Tolerance 0 (an anytime solve) asks for infinitely many: the longest probe.
    if sweeps >= 1.0 {
        (sweeps.min(max as f64) as usize).max(1)
    } else {
        1
    }
}

/// A probe's progress when its products with W pass its cap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ProbeProgress {
    /// Its error after its first iteration and its best error since.
    pub first_error: f64,
    pub best_error: f64,
    /// Iterations done.
    pub steps: usize,
    /// Products with W spent, and those of its last iteration.
    pub products: usize,
    pub last_products: usize,
}

/// The most iterations a probe past its cap may be short of the tolerance, at its mean rate, to
/// run on.
pub(crate) const PROBE_RUN_ON_STEPS: f64 = 2.0;

/// Whether a probe that passed its cap of `cap` products runs on, once, up to twice the cap:
/// when it is nearly there, at most [`PROBE_RUN_ON_STEPS`] iterations short of `tolerance` at
/// its mean rate (from its first iteration to its best error), and these, each costing what its
/// last one cost, fit in that. The mean rate flatters a probe whose fall slows down (the
/// generated 40-contact pile at 1e-4: 0.28 after the first step, 2.0e-3 after the seventh, a
/// mean rate of 0.44 that asks for 4 more; five more reached 1.8e-4): such a probe hands over,
/// as one that crawls. The error of a Tresca
/// fixed point is not monotone (LMGC_100_PR_PerioBox: 3.0e-8 at the seventh outer step of
/// TFP-APGD, 2.0e-3 at the eighth), hence the best error. Its later iterations cost more as its
/// inner tolerance follows the outer error (BoxesStack1: 206 products for the fourth, 1165 for
/// the fifth), hence the cost of the last one, not the mean: a probe that falls fast but whose
/// iterations grow (BoxesStack1, the Capsules) hands over, as one that crawls.
pub(crate) fn probe_runs_on(progress: &ProbeProgress, tolerance: f64, cap: usize) -> bool {
    let ProbeProgress {
        first_error,
        best_error,
        steps,
        products,
        last_products,
    } = *progress;
    if steps < 2 || !(best_error > tolerance) || !(tolerance > 0.0) || !(first_error > best_error) {
        return false;
    }
    let rate = (best_error / first_error).powf(1.0 / (steps - 1) as f64);
    let needed = ((tolerance / best_error).ln() / rate.ln()).ceil();
    needed <= PROBE_RUN_ON_STEPS
        && products as f64 + needed * last_products as f64 <= (2 * cap) as f64
}

#[cfg(test)]
mod tests {
    use super::super::rules::{stage, PlannedStage, TO_THE_LIMITS};
    use super::{next_probe, next_stage, probe_runs_on, Handover, NextStage, ProbeProgress};
    use crate::contract::StageKind::{Admm, ExtraGradient, Nsgs, Prox};
    use std::time::Duration;

    const ADMM_PROX_NSGS: &[PlannedStage] =
        &[stage(Admm, None), stage(Prox, None), stage(Nsgs, None)];
    const MS: Duration = Duration::from_millis(1);

    fn at(index: usize) -> Option<NextStage> {
        Some(NextStage {
            index,
            to_the_limits: false,
        })
    }

    fn filling(index: usize) -> Option<NextStage> {
        Some(NextStage {
            index,
            to_the_limits: true,
        })
    }

    #[test]
    fn without_a_budget_the_plan_runs_once_from_its_first_stage() {
        let plan = ADMM_PROX_NSGS;
        assert_eq!(next_stage(plan, 0, None, None), at(0));
        assert_eq!(next_stage(plan, 1, None, None), at(1));
        assert_eq!(next_stage(plan, 0, Some((0, Handover::Ended)), None), at(1));
        assert_eq!(next_stage(plan, 0, Some((2, Handover::Ended)), None), None);
    }

    #[test]
    fn under_a_budget_the_plan_starts_over_and_late_factorizations_are_skipped() {
        let plan = ADMM_PROX_NSGS;
        // The first stage starts whatever the time left (it is the rule's choice).
        assert_eq!(next_stage(plan, 0, None, Some((MS, 10 * MS))), at(0));
        // Half the budget left: the next stage, then the plan starts over after its last one.
        let half = Some((5 * MS, 10 * MS));
        assert_eq!(next_stage(plan, 0, Some((0, Handover::Ended)), half), at(1));
        assert_eq!(next_stage(plan, 0, Some((2, Handover::Ended)), half), at(0));
        // Less than a quarter left: PROX and ADMM are skipped, NSGS runs (again).
        let late = Some((2 * MS, 10 * MS));
        assert_eq!(next_stage(plan, 0, Some((0, Handover::Ended)), late), at(2));
        assert_eq!(next_stage(plan, 0, Some((2, Handover::Ended)), late), at(2));
        // A plan of factorizing stages only, late: nothing to run.
        let factorizing = &[stage(Prox, None), stage(Admm, None)];
        assert_eq!(
            next_stage(factorizing, 0, Some((0, Handover::Ended)), late),
            None
        );
    }

    #[test]
    fn a_stage_stopped_short_of_the_deadline_leaves_the_time_to_a_non_factorizing_one() {
        // PROX stopped with 4 of 10 ms left (its next step expected past the deadline): the
        // plan's first stage that does not factorize runs to the limits, not ADMM.
        let plan = ADMM_PROX_NSGS;
        let left = Some((4 * MS, 10 * MS));
        assert_eq!(
            next_stage(plan, 0, Some((1, Handover::ShortOfDeadline)), left),
            filling(2)
        );
        // The first non-factorizing stage of the plan is the filler (EG here).
        let eg_first = &[
            stage(ExtraGradient, None),
            stage(Admm, None),
            stage(Prox, None),
            stage(Nsgs, None),
        ];
        assert_eq!(
            next_stage(eg_first, 0, Some((2, Handover::ShortOfDeadline)), left),
            filling(0)
        );
        // A filler that stopped short itself ends the solve; one that ended otherwise (a stage
        // run to the limits only ends at the limits) hands over as any stage.
        assert_eq!(
            next_stage(plan, 0, Some((2, Handover::ShortOfDeadline)), left),
            None
        );
        let sweeps = &[stage(Nsgs, TO_THE_LIMITS)];
        assert_eq!(
            next_stage(sweeps, 0, Some((0, Handover::Ended)), left),
            at(0)
        );
    }

    #[test]
    fn a_probe_runs_once_and_never_fills() {
        use super::super::rules::PROBE;
        use crate::contract::StageKind::TrescaApgd;
        let plan = &[
            stage(TrescaApgd, PROBE),
            stage(Admm, None),
            stage(Nsgs, None),
        ];
        let half = Some((5 * MS, 10 * MS));
        assert_eq!(next_stage(plan, 0, None, half), at(0));
        assert_eq!(next_stage(plan, 0, Some((0, Handover::Ended)), half), at(1));
        // The plan starts over after its last stage without the probe.
        assert_eq!(next_stage(plan, 0, Some((2, Handover::Ended)), half), at(1));
        // The filler is the first non-factorizing stage that is not a probe.
        assert_eq!(
            next_stage(plan, 0, Some((1, Handover::ShortOfDeadline)), half),
            filling(2)
        );
    }

    #[test]
    fn probes_double_until_a_rate_is_known_then_aim_at_the_tolerance() {
        // No rate yet (first measurement): twice the last probe, at most `max`.
        assert_eq!(next_probe(1, f64::INFINITY, 1e-2, 1, 1e-4, 10), 2);
        assert_eq!(next_probe(8, f64::INFINITY, 1e-2, 8, 1e-4, 10), 10);
        // Error divided by 10 per sweep, 1e-2 -> 1e-4: two more sweeps.
        assert_eq!(next_probe(2, 1e-0, 1e-2, 2, 1e-4, 10), 2);
        // A slow rate asks for the longest probe; no progress: doubling.
        assert_eq!(next_probe(2, 1.0, 0.99, 1, 1e-4, 10), 10);
        assert_eq!(next_probe(2, 1.0, 1.5, 1, 1e-4, 10), 4);
        // An anytime solve (tolerance 0) measures at the longest probe.
        assert_eq!(next_probe(2, 1.0, 0.5, 1, 0.0, 10), 10);
        // NaN errors: doubling too (the stall window ends the stage).
        assert_eq!(next_probe(2, f64::NAN, f64::NAN, 1, 1e-4, 10), 4);
    }

    #[test]
    fn a_probe_runs_on_when_two_steps_short_within_twice_its_cap() {
        let at = |first_error, best_error, steps, products, last_products| ProbeProgress {
            first_error,
            best_error,
            steps,
            products,
            last_products,
        };
        // LMGC_100_PR_PerioBox at 1e-8, TFP-APGD past its cap (140) after its seventh step:
        // 9.7e-5 -> 3.0e-8, mean rate 0.26, one more step of 13 products: runs on (to 280).
        assert!(probe_runs_on(&at(9.73e-5, 3.0e-8, 7, 151, 13), 1e-8, 140));
        // BoxesStack1 after its fourth (cap 230): rate 0.094, to 1e-8 four more steps of 206
        // products, to 1e-6 two: hands over either way.
        assert!(!probe_runs_on(
            &at(7.25e-2, 6.08e-5, 4, 394, 206),
            1e-8,
            230
        ));
        assert!(!probe_runs_on(
            &at(7.25e-2, 6.08e-5, 4, 394, 206),
            1e-6,
            230
        ));
        // Capsules-i100-889 after its sixth (cap 210): 5 more steps of 43 to 1e-8.
        assert!(!probe_runs_on(&at(2.09e-3, 4.42e-6, 6, 215, 43), 1e-8, 210));
        // The generated 40-contact pile at 1e-4 after its seventh (cap 270): 4 more steps.
        assert!(!probe_runs_on(&at(0.281, 1.99e-3, 7, 278, 45), 1e-4, 270));
        // Two steps short within twice the cap runs on; three, or past twice the cap, not.
        assert!(probe_runs_on(&at(1e-2, 1e-6, 5, 150, 10), 1e-8, 140));
        assert!(!probe_runs_on(&at(1e-2, 1e-6, 5, 150, 10), 1e-9, 140));
        assert!(!probe_runs_on(&at(1e-2, 1e-6, 5, 150, 70), 1e-8, 140));
        // A crawl, no fall, one step only, an anytime solve (tolerance 0), NaN: hands over.
        assert!(!probe_runs_on(&at(1e-3, 5e-4, 7, 150, 10), 1e-8, 140));
        assert!(!probe_runs_on(&at(1e-4, 1e-4, 7, 150, 10), 1e-8, 140));
        assert!(!probe_runs_on(&at(1e-4, 1e-6, 1, 150, 150), 1e-8, 140));
        assert!(!probe_runs_on(&at(1e-4, 1e-6, 7, 150, 10), 0.0, 140));
        assert!(!probe_runs_on(&at(f64::NAN, 1e-6, 7, 150, 10), 1e-8, 140));
        assert!(!probe_runs_on(&at(1e-4, f64::NAN, 7, 150, 10), 1e-8, 140));
    }
}

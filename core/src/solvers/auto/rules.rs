//! AUTO's rule table ([`RULES`]), its thresholds, and how each kind of stage is watched
//! ([`STALL`]): data, each row with the measurement behind it.

use std::time::Duration;

use crate::contract::StageKind;
use crate::local::LocalSolverKind;

use super::features::ProblemFeatures;

use StageKind::{Admm, ExtraGradient, Newton, Nsgs, Prox, Tresca, TrescaApgd};

/// A time budget this short favours methods whose first iterations are cheap.
pub const SHORT_BUDGET: Duration = Duration::from_millis(20);
/// From this budget on (up to [`SHORT_BUDGET`]) ADMM's first steps fit on the strongly coupled
/// problems of 40 to 300 contacts: its set-up (a factorization) takes 5-10 ms on the Capsules.
pub const ADMM_BUDGET: Duration = Duration::from_millis(7);

/// The most contacts on which ADMM's set-up fits a short budget (1.6 ms for its first step on
/// the 276-contact Capsules, 22-170 ms on RockPile's 463 contacts and generated piles of 400
/// and 1000): rule 2 (ADMM first from 7 ms) up to it, NSGS alone under a short budget above.
pub const ADMM_MAX_CONTACTS: usize = 300;

/// Contacts from which AUTO leaves out the methods that factorize a matrix of W's size (ADMM,
/// PROX, Newton) on strongly coupled problems: between the 1k-contact pile, where ADMM and PROX
/// still reach 1e-4 within 2 s, and the 10k-contact one, where one ADMM iteration costs 75x more.
pub const LARGE_PROBLEM: usize = 5000;

/// Contacts from which AUTO runs the Tresca fixed point to the limits on strongly coupled
/// problems, without Gauss-Seidel and extragradient stages: between the 10k-contact pile (EG best
/// after 10 s, TFP 2-3.5x behind it) and the 100k one (TFP best after 1 s, EG 9x behind NSGS
/// after 10 s).
pub const HUGE_PROBLEM: usize = 30_000;

/// `mu_max` below which PROX beats ADMM on strongly coupled problems at tight tolerances: the
/// shared and generated problems of that class have mu <= 0.42 or mu >= 0.7.
pub const MODERATE_MU: f64 = 0.5;

/// How an NSGS stage sweeps beyond Gauss-Seidel's default (ignored by the other kinds).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SweepTuning {
    /// Over-relaxation (PSOR) factor omega in (0, 2), `None`: plain Gauss-Seidel
    /// ([`NsgsOptions::relaxation`](crate::NsgsOptions)).
    pub relaxation: Option<f64>,
    /// Sweeps a contact that stopped moving (relative to the tolerance) is skipped, `None`:
    /// never ([`NsgsOptions::freezing`](crate::NsgsOptions)).
    pub freezing: Option<usize>,
    /// The stall window of the stage (sweeps, and the factor by which the error must fall over
    /// them), `None`: NSGS's row of [`STALL`].
    pub stall: Option<(usize, f64)>,
}

impl SweepTuning {
    /// Plain Gauss-Seidel sweeps.
    pub const PLAIN: SweepTuning = SweepTuning {
        relaxation: None,
        freezing: None,
        stall: None,
    };
}

/// One stage of a plan: a method, the iterations the rule allows it (`None`: until it stalls
/// or the limits stop it; [`TO_THE_LIMITS`]: not stopped by a stall either) and, for an NSGS
/// stage, its sweep options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedStage {
    pub kind: StageKind,
    pub allowance: Option<usize>,
    pub sweep: SweepTuning,
}

/// A stage with plain sweeps (where it sweeps at all).
pub const fn stage(kind: StageKind, allowance: Option<usize>) -> PlannedStage {
    PlannedStage {
        kind,
        allowance,
        sweep: SweepTuning::PLAIN,
    }
}

/// Over-relaxation factor of the tight-tolerance NSGS stage on the strongly coupled problems
/// with `mu >= 0.5` ([`PSOR_FREEZING`]).
pub const PSOR_OMEGA: f64 = 1.3;

/// Freezing (sweeps) of that stage.
pub const PSOR_FREEZE_SWEEPS: usize = 5;

/// NSGS with over-relaxation and freezing: on the Capsules at 1e-6 the fastest of the
/// library's solvers (docs/auto.md, "NSGS with PSOR and freezing"). Its error has plateaus
/// that end when the active set changes (Capsules-i100-1090: 1.1e-5 after 50 sweeps, 8.1e-6
/// after 79, 3.1e-6 after 81, 1e-6 after 110), which NSGS's stall window (10 sweeps, 0.7) took
/// for a stall: the stage is ended when its error does not halve over 100 sweeps.
pub const PSOR_FREEZING: SweepTuning = SweepTuning {
    relaxation: Some(PSOR_OMEGA),
    freezing: Some(PSOR_FREEZE_SWEEPS),
    stall: Some((100, 0.5)),
};

const fn tuned_sweeps(allowance: Option<usize>, sweep: SweepTuning) -> PlannedStage {
    PlannedStage {
        kind: Nsgs,
        allowance,
        sweep,
    }
}

/// The allowance of a stage that runs until the tolerance or the limits, whatever its progress:
/// on large hyperstatic piles every method's error falls slowly but steadily (docs/scale.md),
/// and a stall test would end the solve with most of the budget unspent.
pub const TO_THE_LIMITS: Option<usize> = Some(usize::MAX);

/// The allowance of a probe: a stage that ends, whatever its progress, once its products with
/// W pass [`PROBE_PRODUCTS`] times those of its first iteration. A probe tries a method that is
/// far ahead on some problems of a class and behind on others at a bounded cost: the TFP-APGD
/// probe in front of ADMM (LMGC_100_PR_PerioBox: TFP-APGD at 1e-6 in 5 outer steps, 0.3 ms,
/// where ADMM first took 170 ms).
pub const PROBE: Option<usize> = Some(usize::MAX - 1);

/// How many times the products with W of its first iteration a probe may spend. The first
/// outer step of TFP-APGD (a frictionless solve from r = 0) takes 0.1-0.45 ms on the strongly
/// coupled shared problems (1.1-1.4 ms on RockPile); its later steps cost more as the inner
/// tolerance follows the outer error (BoxesStack1: 0.1 ms, then 9 ms for its fifth step). Ten
/// first steps is the 10x margin AUTO may lose to the best fixed solver, spent once.
pub const PROBE_PRODUCTS: usize = 10;

/// When a rule applies: every condition given must hold (`None`: any value).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Condition {
    /// Some contact has a singular one-contact problem (`W_NN <= 0`).
    pub singular_contacts: Option<bool>,
    /// At most this many contacts.
    pub max_contacts: Option<usize>,
    /// The tolerance is at least this (a loose solve).
    pub min_tolerance: Option<f64>,
    /// At least this many contacts.
    pub min_contacts: Option<usize>,
    /// Strong frictional coupling: `mu_max >= STRONG_MU` and a normal row far from diagonal
    /// dominance (`diagonal_dominance < WEAK_DOMINANCE`), the case where Gauss-Seidel and the
    /// Tresca fixed point crawl.
    pub strongly_coupled: Option<bool>,
    /// The solve has a time budget of at most this (a short anytime solve).
    pub max_budget: Option<Duration>,
    /// The solve has a time budget of at least this.
    pub min_budget: Option<Duration>,
    /// The largest friction coefficient is below this.
    pub max_mu: Option<f64>,
    /// The tolerance is below this (a tight solve).
    pub max_tolerance: Option<f64>,
}

impl Condition {
    const ANY: Condition = Condition {
        singular_contacts: None,
        max_contacts: None,
        min_tolerance: None,
        min_contacts: None,
        strongly_coupled: None,
        max_budget: None,
        min_budget: None,
        max_mu: None,
        max_tolerance: None,
    };

    fn holds(&self, f: &ProblemFeatures, tolerance: f64, budget: Option<Duration>) -> bool {
        self.singular_contacts
            .is_none_or(|s| s == (f.singular_contacts > 0))
            && self.max_contacts.is_none_or(|m| f.n_contacts <= m)
            && self.min_tolerance.is_none_or(|t| tolerance >= t)
            && self.min_contacts.is_none_or(|m| f.n_contacts >= m)
            && self
                .strongly_coupled
                .is_none_or(|s| s == f.strongly_coupled())
            && self
                .max_budget
                .is_none_or(|m| budget.is_some_and(|b| b <= m))
            && self
                .min_budget
                .is_none_or(|m| budget.is_some_and(|b| b >= m))
            && self.max_mu.is_none_or(|m| f.mu_max < m)
            && self.max_tolerance.is_none_or(|t| tolerance < t)
    }
}

/// A row of the rule table: when it applies, the plan, and why (the measurement behind it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rule {
    pub when: Condition,
    pub plan: &'static [PlannedStage],
    pub why: &'static str,
}

/// AUTO's rule table: the first row whose condition holds gives the plan. The last row holds
/// always. docs/auto.md has the bench runs behind each row.
pub const RULES: &[Rule] = &[
    Rule {
        when: Condition {
            singular_contacts: Some(true),
            ..Condition::ANY
        },
        plan: &[stage(Prox, None), stage(Nsgs, None)],
        why: "a contact with W_NN <= 0 has no well-posed one-contact problem: Gauss-Seidel's \
              local solves and an unshifted Newton matrix break down, the proximal shift does not",
    },
    Rule {
        when: Condition {
            max_contacts: Some(1),
            ..Condition::ANY
        },
        plan: &[stage(Nsgs, None), stage(Prox, None)],
        why: "one contact: one Gauss-Seidel sweep is the one-contact solver itself, which solves \
              it to the tolerance",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_contacts: Some(40),
            max_contacts: Some(ADMM_MAX_CONTACTS),
            min_budget: Some(ADMM_BUDGET),
            max_budget: Some(SHORT_BUDGET),
            ..Condition::ANY
        },
        plan: &[stage(Admm, None), stage(Prox, None), stage(Nsgs, None)],
        why: "strongly coupled problems of 40-300 contacts (BoxesStack, Capsules) under a budget \
              of 7-20 ms: within 10 ms ADMM reaches about 1e-6 where NSGS is at 1e-5 and a PROX \
              step is not done (5-10 ms a step on the Capsules); smaller ones (OneObject: PROX \
              after a few sweeps) and larger ones (RockPile: ADMM still at 0.4 after 20 ms) keep \
              the next row",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_contacts: Some(ADMM_MAX_CONTACTS + 1),
            max_budget: Some(SHORT_BUDGET),
            ..Condition::ANY
        },
        plan: &[stage(Nsgs, TO_THE_LIMITS)],
        why: "strongly coupled problems above 300 contacts under a budget of 20 ms or less \
              (RockPile, 463 contacts; generated piles of 400 and 1000): the first step of PROX \
              or ADMM (a factorization) takes 22-240 ms there and overran the budget, while \
              Gauss-Seidel's error falls steadily sweep after sweep",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            max_budget: Some(SHORT_BUDGET),
            ..Condition::ANY
        },
        plan: &[stage(Nsgs, None), stage(Prox, None), stage(Admm, None)],
        why: "strongly coupled problems under a budget of 20 ms or less: within 1 ms NSGS (local \
              solver 551) is the closest to the solution on the Capsules (1e-5, where one PROX \
              step is not done yet); PROX takes over where it stalls",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_contacts: Some(HUGE_PROBLEM),
            ..Condition::ANY
        },
        plan: &[stage(Tresca, TO_THE_LIMITS)],
        why: "hyperstatic piles of 10^5 contacts: the Tresca fixed point to the limits, the best \
              fixed choice after 1 s in three runs (1.6e-2-5.3e-2, NSGS 1.6-2x behind) and within \
              1.25x of the best after 10 s; EG falls behind there (3.0e-2 after 10 s against \
              NSGS's 3.5e-3)",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_contacts: Some(LARGE_PROBLEM),
            ..Condition::ANY
        },
        plan: &[stage(Nsgs, None), stage(ExtraGradient, TO_THE_LIMITS)],
        why: "large hyperstatic piles (generated, 10^4-10^5 contacts): no method reaches 1e-4 \
              within a minute, the factorizing ones (ADMM, PROX, Newton) cost 75-245x more per \
              iteration at 10x the contacts and overrun a 1 s budget in their set-up (ADMM: over \
              9 GB at 10^5); Gauss-Seidel gains most in the first second, EG (one product with \
              W per iteration) in the next ones, to the limits since every error falls slowly",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_tolerance: Some(1e-5),
            min_contacts: Some(100),
            ..Condition::ANY
        },
        plan: &[
            stage(ExtraGradient, None),
            stage(Admm, None),
            stage(Prox, None),
            stage(Nsgs, None),
        ],
        why: "large strongly coupled problems to 1e-4 (Capsules, RockPile): EG's iterations (one \
              product with W) are the cheapest, EG is the fastest on the Capsules (3-10x ADMM); \
              where it stalls (RockPile) ADMM, then PROX take over",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            max_mu: Some(MODERATE_MU),
            max_tolerance: Some(1e-5),
            ..Condition::ANY
        },
        plan: &[stage(Prox, None), stage(Admm, None), stage(Nsgs, None)],
        why: "strongly coupled problems with mu < 0.5 to 1e-6 or tighter (OneObject, mu 0.3; \
              generated piles of 40 and 60 contacts, mu 0.38-0.42): PROX is the fastest or within \
              1.7x of it at 1e-6 where ADMM first is 2.8-54x behind; with mu = 0.7 (BoxesStack, \
              Capsules) it is the other way round (PROX 10-30x behind ADMM on two of them)",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_contacts: Some(100),
            min_tolerance: Some(1e-6),
            ..Condition::ANY
        },
        plan: &[
            tuned_sweeps(None, PSOR_FREEZING),
            stage(Admm, None),
            stage(Prox, None),
        ],
        why: "strongly coupled problems of 100 contacts or more with mu >= 0.5 to 1e-6 (the \
              Capsules, RockPile): NSGS with over-relaxation 1.3 and freezing for 5 sweeps \
              reaches 1e-6 on the four Capsules in 81-340 sweeps, 3-4x faster than ADMM and \
              than AUTO's former plan (TFP-APGD probe, ADMM); where it stalls (RockPile) ADMM \
              and PROX take over. Smaller ones (BoxesStack1, 52 contacts: 57-100k sweeps; \
              LMGC_100_PR_PerioBox) keep the next row, tighter tolerances too (at 1e-8 PROX \
              after the probe is 5-20x ahead of any NSGS)",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            min_tolerance: Some(1e-6),
            ..Condition::ANY
        },
        plan: &[
            stage(TrescaApgd, PROBE),
            stage(Admm, None),
            stage(Prox, None),
            stage(Nsgs, None),
        ],
        why: "strongly coupled problems (BoxesStack, Capsules, RockPile) to 1e-4 or 1e-6: ADMM is \
              the fastest on most, NSGS and TFP crawl; PROX takes over where ADMM stalls. The \
              TFP-APGD probe first: on LMGC_100_PR_PerioBox its first outer step (a frictionless \
              solve) is at 9.7e-5 and it reaches 1e-6 in 5 (0.1 and 0.5 ms) where ADMM first \
              took 100-170 ms (2300-3300x the best fixed solver); elsewhere its cap costs ten \
              first steps (0.1-0.45 ms on BoxesStack1, the Capsules, OneObject)",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            ..Condition::ANY
        },
        plan: &[
            stage(TrescaApgd, PROBE),
            stage(Prox, None),
            stage(Admm, None),
            stage(Nsgs, None),
        ],
        why: "strongly coupled problems (OneObject, Capsules at 1e-8): the proximal Newton \
              converges in a few steps where NSGS does not converge at all. The TFP-APGD probe \
              first: from its iterate PROX needs 1-3 steps, at 1e-8 AUTO's instruction count \
              falls from 763M to 60M on LMGC_100_PR_PerioBox, 391M to 60M on BoxesStack1, 178M \
              to 130M and 76M to 71M on Capsules-i100-889 and -i101-404; a probe two steps \
              short of the tolerance runs on (LMGC_100_PR_PerioBox: 11 steps, 14M)",
    },
    Rule {
        when: Condition::ANY,
        plan: &[
            stage(Nsgs, None),
            stage(TrescaApgd, None),
            stage(Prox, None),
            stage(Newton, None),
        ],
        why: "small or weakly coupled problems (Rover, Confeti, NESpheres, FC3D_Example1): NSGS \
              with the Newton local solver 551 is the fastest or within 1.5x of it (TFP, PFP); \
              TFP-APGD, PROX and Newton go on where it stalls (a generated tower of 142 boxes, \
              568 contacts: TFP-APGD converges in 4-8 outer steps after the sweeps where TFP \
              with Gauss-Seidel sub-problems stalled and PROX ended the solve 5.7-15x behind)",
    },
];

/// How each stage kind is watched: iterations per chunk, and the factor by which the error must
/// fall over a chunk for the stage to go on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StallRule {
    pub kind: StageKind,
    pub chunk: usize,
    pub factor: f64,
}

/// The stall rules (one per kind).
pub const STALL: [StallRule; 7] = [
    StallRule {
        kind: Nsgs,
        chunk: 10,
        factor: 0.7,
    },
    StallRule {
        kind: Newton,
        chunk: 5,
        factor: 0.5,
    },
    // A PROX stage goes on from chunk to chunk (its state is kept); a stricter window (10 steps
    // at 0.87) ended it on six of the settling pile's hyperstatic steps where it converges
    // slowly (docs/time-stepping.md).
    StallRule {
        kind: Prox,
        chunk: 50,
        factor: 0.5,
    },
    // ADMM builds its matrix at each call: long chunks.
    StallRule {
        kind: Admm,
        chunk: 1000,
        factor: 0.5,
    },
    StallRule {
        kind: Tresca,
        chunk: 5,
        factor: 0.5,
    },
    StallRule {
        kind: ExtraGradient,
        chunk: 100,
        factor: 0.5,
    },
    // As TFP (its error is not monotone: on LMGC_100_PR_PerioBox 1.1e-6 at the third outer
    // step, 2.5e-3 at the fourth, 2.9e-7 at the fifth).
    StallRule {
        kind: TrescaApgd,
        chunk: 5,
        factor: 0.5,
    },
];

pub(crate) fn stall_rule(kind: StageKind) -> StallRule {
    STALL
        .into_iter()
        .find(|s| s.kind == kind)
        .expect("one stall rule per kind")
}

/// The index of the rule that applies and its plan.
pub fn choose(
    features: &ProblemFeatures,
    tolerance: f64,
    budget: Option<Duration>,
) -> (usize, &'static [PlannedStage]) {
    RULES
        .iter()
        .enumerate()
        .find(|(_, r)| r.when.holds(features, tolerance, budget))
        .map(|(i, r)| (i, r.plan))
        .expect("the last rule always holds")
}

/// The local solver of the NSGS stages of rule `rule`'s plan: QUARTIC (562, the exact
/// one-contact solution by enumeration) on strongly coupled problems, where its sweeps are
/// 1.3-1.8x as many as 551's in the same time with the same progress per sweep (`fc3d bench` on
/// BoxesStack1, the Capsules, OneObject and RockPile at 1 ms, 10 ms and 100 ms, and on the
/// generated 10^4-contact pile at 1 s: docs/auto.md); the Newton with Goldstein-Price line
/// search (551) otherwise (the fastest NSGS on the small weakly coupled problems) and for a plan
/// given in [`AutoOptions`].
pub fn sweep_local_solver(rule: usize) -> LocalSolverKind {
    match RULES.get(rule) {
        Some(r) if r.when.strongly_coupled == Some(true) => LocalSolverKind::Quartic,
        _ => LocalSolverKind::NewtonAlartCurnierGp,
    }
}

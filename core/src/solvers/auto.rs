//! AUTO (fc3d id 590, `FC3D_AUTO`): the solver that chooses. From cheap features of the
//! problem ([`ProblemFeatures`], one pass over W's stored entries), the tolerance and the
//! budget, the first matching row of [`RULES`] gives a plan: a sequence of stages (Gauss-Seidel
//! sweeps, a nonsmooth Newton with line search, the proximal point method). Each stage starts
//! from the best iterate so far and runs in chunks; after each chunk the natural-map error is
//! measured, and a stage whose error does not fall by its stall factor over a chunk hands over to
//! the next one. The iteration limit counts the iterations of all stages together and the time
//! budget is one deadline for the whole solve. With a tolerance of 0 the solve is an anytime
//! one: it runs until the limits and returns the best iterate it measured.
//!
//! The rules and the stall factors are data ([`RULES`], [`STALL`]); README.md "AUTO" gives the
//! `fc3d bench` runs on the shared problems that justify them.

use std::time::{Duration, Instant};

use crate::contract::{
    BestIterate, ErrorEvaluation, Family, Fill, IterationEvent, Limits, Observer, SolverOutcome,
    Stage, StageEnd, StageKind, StageLog, MAX_STAGES,
};
use crate::error::Fc3dError;
use crate::local::LocalSolverKind;
use crate::matrix::Delassus;
use crate::measure::natural_map_error;
use crate::problem::FrictionProblem;
use crate::solvers::admm::AdmmOptions;
use crate::solvers::nsgs::{run_sweeps, NsgsOptions, PreparedSweep, SweepSchedule, Sweeper};
use crate::solvers::nsn::{NewtonSolver, NsnFormulation, NsnOptions};
use crate::solvers::prox::ProxOptions;
use crate::solvers::tresca::TrescaOptions;
use crate::solvers::vi::{ViOptions, ViSolver};

/// Cheap features of a problem, computed in one pass over W's stored entries (O(nnz)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProblemFeatures {
    pub n_contacts: usize,
    /// Stored 3x3 blocks of W (nonzero entries / 9 for an entry-wise storage) over `nc^2`: 1 for
    /// a fully coupled W.
    pub block_density: f64,
    pub mu_min: f64,
    pub mu_max: f64,
    /// Contacts with mu = 0 (frictionless).
    pub frictionless: usize,
    /// min over contacts of `W_NN / sum |W_Nj|` over the entries j of the normal row outside
    /// the contact's block (infinite for an uncoupled contact): > 1 is a diagonally dominant
    /// normal row, the case where Gauss-Seidel converges fast.
    pub diagonal_dominance: f64,
    /// max over the diagonal blocks of `max |B - B^T| / max |B|`.
    pub block_asymmetry: f64,
    /// Conditioning estimate: `max W_NN / min W_NN` over the contacts (infinite when some
    /// `W_NN <= 0`).
    pub diagonal_spread: f64,
    /// Contacts whose normal diagonal entry is not positive relative to the largest one
    /// (`W_NN <= 1e-12 max W_NN`): their one-contact problems are singular.
    pub singular_contacts: usize,
}

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

/// `mu_max` from which friction couples the contacts strongly (see [`Condition`]).
pub const STRONG_MU: f64 = 0.25;
/// Normal-row diagonal dominance below which a coupled problem is hard for Gauss-Seidel.
pub const WEAK_DOMINANCE: f64 = 0.16;
/// `mu_max` below which PROX beats ADMM on strongly coupled problems at tight tolerances: the
/// shared and generated problems of that class have mu <= 0.42 or mu >= 0.7.
pub const MODERATE_MU: f64 = 0.5;

impl ProblemFeatures {
    /// Strong frictional coupling (see [`Condition::strongly_coupled`]).
    pub fn strongly_coupled(&self) -> bool {
        self.mu_max >= STRONG_MU && self.diagonal_dominance < WEAK_DOMINANCE
    }

    pub fn of(problem: &FrictionProblem<'_>) -> ProblemFeatures {
        let nc = problem.n_contacts();
        let mu = problem.mu();
        let mut rows = NormalRows::new(nc);
        let stored_blocks = rows.read(problem.w(), nc);
        let NormalRows {
            w_nn,
            largest,
            smallest,
            diagonal_dominance,
            block_asymmetry,
        } = rows;
        let singular_contacts = w_nn.iter().filter(|&&v| v <= 1e-12 * largest).count();
        let diagonal_spread = if smallest > 0.0 {
            largest / smallest
        } else {
            f64::INFINITY
        };
        let (mut mu_min, mut mu_max, mut frictionless) = (f64::INFINITY, 0.0_f64, 0);
        for &m in mu {
            mu_min = mu_min.min(m);
            mu_max = mu_max.max(m);
            frictionless += usize::from(m == 0.0);
        }
        ProblemFeatures {
            n_contacts: nc,
            block_density: if nc > 0 {
                stored_blocks / (nc as f64 * nc as f64)
            } else {
                0.0
            },
            mu_min,
            mu_max,
            frictionless,
            diagonal_dominance,
            block_asymmetry,
            diagonal_spread,
            singular_contacts,
        }
    }
}

/// What one pass over W's normal rows (and the diagonal blocks they cross) gathers: each
/// contact's `W_NN` (kept for the singular count, which needs the largest first) and running
/// extremes, so that nothing else of size `nc` is allocated.
struct NormalRows {
    w_nn: Vec<f64>,
    largest: f64,
    smallest: f64,
    diagonal_dominance: f64,
    block_asymmetry: f64,
}

impl NormalRows {
    fn new(nc: usize) -> Self {
        NormalRows {
            w_nn: Vec::with_capacity(nc),
            largest: 0.0,
            smallest: f64::INFINITY,
            diagonal_dominance: f64::INFINITY,
            block_asymmetry: 0.0,
        }
    }

    /// Contact `c`'s normal row: its diagonal block (row-major) and the sum of `|W_Nj|` outside
    /// that block.
    fn push(&mut self, block: &[[f64; 3]; 3], off: f64) {
        let d = block[0][0];
        self.w_nn.push(d);
        self.largest = self.largest.max(d);
        self.smallest = self.smallest.min(d);
        if off > 0.0 {
            self.diagonal_dominance = self.diagonal_dominance.min(d / off);
        }
        let scale = block.iter().flatten().fold(0.0_f64, |m, v| m.max(v.abs()));
        let mut skew = 0.0_f64;
        for i in 0..3 {
            for j in 0..i {
                skew = skew.max((block[i][j] - block[j][i]).abs());
            }
        }
        if scale > 0.0 {
            self.block_asymmetry = self.block_asymmetry.max(skew / scale);
        }
    }

    /// Reads every contact's normal row and diagonal block, in contact order; returns the
    /// number of stored 3x3 blocks (a third of a dense W is read).
    fn read(&mut self, w: &Delassus<'_>, nc: usize) -> f64 {
        match w {
            Delassus::Dense(d) => {
                let n = 3 * nc;
                let values = d.values();
                for c in 0..nc {
                    let i = 3 * c;
                    let mut off = 0.0;
                    for j in (0..i).chain(i + 3..n) {
                        off += values[i + j * n].abs();
                    }
                    let block = std::array::from_fn(|a| {
                        std::array::from_fn(|b| values[(i + a) + (i + b) * n])
                    });
                    self.push(&block, off);
                }
                (nc * nc) as f64
            }
            Delassus::SparseBlock(b) => {
                let (row_ptr, cols) = (b.row_ptr(), b.col_idx());
                for c in 0..nc {
                    let mut diag = [[0.0; 3]; 3];
                    let mut off = 0.0;
                    for k in row_ptr[c]..row_ptr[c + 1] {
                        // Column-major: the normal row is entries 0, 3, 6.
                        let block = b.block(k);
                        if cols[k] == c {
                            for (a, row) in diag.iter_mut().enumerate() {
                                for (b, v) in row.iter_mut().enumerate() {
                                    *v += block[a + 3 * b];
                                }
                            }
                        } else {
                            off += block[0].abs() + block[3].abs() + block[6].abs();
                        }
                    }
                    self.push(&diag, off);
                }
                b.n_blocks() as f64
            }
            Delassus::Sparse(m) => {
                let (ptr, cols, values) = (m.row_ptr(), m.col_idx(), m.values());
                for c in 0..nc {
                    let i = 3 * c;
                    let mut off = 0.0;
                    for k in ptr[i]..ptr[i + 1] {
                        if cols[k] / 3 != c {
                            off += values[k].abs();
                        }
                    }
                    let block = w.diagonal_block(c).unwrap_or([[0.0; 3]; 3]);
                    self.push(&block, off);
                }
                m.nnz() as f64 / 9.0
            }
        }
    }
}

/// One stage of a plan: a method and the iterations the rule allows it (`None`: until it stalls
/// or the limits stop it; [`TO_THE_LIMITS`]: not stopped by a stall either).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlannedStage {
    pub kind: StageKind,
    pub allowance: Option<usize>,
}

const fn stage(kind: StageKind, allowance: Option<usize>) -> PlannedStage {
    PlannedStage { kind, allowance }
}

/// The allowance of a stage that runs until the tolerance or the limits, whatever its progress:
/// on large hyperstatic piles every method's error falls slowly but steadily (README "Scale"),
/// and a stall test would end the solve with most of the budget unspent.
pub const TO_THE_LIMITS: Option<usize> = Some(usize::MAX);

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

use StageKind::{Admm, ExtraGradient, Newton, Nsgs, Prox, Tresca};

/// AUTO's rule table: the first row whose condition holds gives the plan. The last row holds
/// always. README.md "AUTO" has the bench runs behind each row.
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
            min_tolerance: Some(1e-6),
            ..Condition::ANY
        },
        plan: &[stage(Admm, None), stage(Prox, None), stage(Nsgs, None)],
        why: "strongly coupled problems (BoxesStack, Capsules, RockPile) to 1e-4 or 1e-6: ADMM is \
              the fastest on most, NSGS and TFP crawl; PROX takes over where ADMM stalls",
    },
    Rule {
        when: Condition {
            strongly_coupled: Some(true),
            ..Condition::ANY
        },
        plan: &[stage(Prox, None), stage(Admm, None), stage(Nsgs, None)],
        why: "strongly coupled problems (OneObject, Capsules at 1e-8): the proximal Newton \
              converges in a few steps where NSGS does not converge at all",
    },
    Rule {
        when: Condition::ANY,
        plan: &[
            stage(Nsgs, None),
            stage(Tresca, None),
            stage(Prox, None),
            stage(Newton, None),
        ],
        why: "small or weakly coupled problems (Rover, Confeti, NESpheres, FC3D_Example1): NSGS \
              with the Newton local solver 551 is the fastest or within 1.5x of it (TFP, PFP); \
              TFP, PROX and Newton go on where it stalls",
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
pub const STALL: [StallRule; 6] = [
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
    // PROX and ADMM build their matrices at each call: long chunks.
    StallRule {
        kind: Prox,
        chunk: 50,
        factor: 0.5,
    },
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
];

fn stall_rule(kind: StageKind) -> StallRule {
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
/// generated 10^4-contact pile at 1 s: README "AUTO"); the Newton with Goldstein-Price line
/// search (551) otherwise (the fastest NSGS on the small weakly coupled problems) and for a plan
/// given in [`AutoOptions`].
pub fn sweep_local_solver(rule: usize) -> LocalSolverKind {
    match RULES.get(rule) {
        Some(r) if r.when.strongly_coupled == Some(true) => LocalSolverKind::Quartic,
        _ => LocalSolverKind::NewtonAlartCurnierGp,
    }
}

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
/// deadline).
fn filler(plan: &[PlannedStage]) -> Option<usize> {
    plan.iter().position(|s| !factorizes(s.kind))
}

/// The next stage of a solve: `first` to begin with (`previous` is `None`), then the stage after
/// `previous`. Without a budget (`time` is `None`) the plan ends after its last stage. Under a
/// budget (`time`: the time left and the budget) the time is used up to the deadline:
/// - the plan starts over after its last stage (a plan whose stages all stalled early);
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
        .find(|&i| !(factorizes(plan[i].kind) && left < budget / 4))
        .map(|index| NextStage {
            index,
            to_the_limits: false,
        })
        .or_else(fill)
}

/// Settings of AUTO. Its limits default to a tolerance of 1e-4 (Siconos' NSGS default) and
/// 10000 iterations over all stages.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AutoOptions {
    /// Run this plan instead of the rule table's (tests, experiments).
    pub plan: Option<&'static [PlannedStage]>,
}

impl Family for AutoOptions {
    fn name(&self) -> &'static str {
        "AUTO"
    }

    fn label(&self) -> String {
        "AUTO".into()
    }

    fn siconos_id(&self) -> i32 {
        AUTO_ID
    }

    fn default_limits(&self) -> (f64, usize) {
        (1e-4, 10_000)
    }

    fn validate(&self) -> Result<(), Fc3dError> {
        if let Some(plan) = self.plan {
            if plan.is_empty() {
                return Err(Fc3dError::InvalidOption(
                    "AUTO: a plan needs at least one stage".into(),
                ));
            }
        }
        Ok(())
    }

    fn run(
        &self,
        problem: &FrictionProblem<'_>,
        limits: &Limits,
        r: &mut [f64],
        u: &mut [f64],
        observer: &mut Observer<'_>,
    ) -> Result<SolverOutcome, Fc3dError> {
        auto_with(
            problem,
            self,
            limits,
            r,
            u,
            observer,
            &mut AutoCarry::default(),
        )
    }
}

/// Where AUTO ended a solve: the rule and plan it followed and the stage of that plan that
/// reached the tolerance (in an anytime solve, the one the budget ended in). A workspace keeps it so that the next step with the same W pattern, tolerance
/// and budget skips the feature pass and the stages that came before.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AutoChoice {
    /// Index of the rule in [`RULES`] (`usize::MAX` for a plan given in [`AutoOptions`]).
    pub rule: usize,
    pub plan: &'static [PlannedStage],
    /// Index in `plan` of the stage that reached the tolerance.
    pub stage: usize,
    pub tolerance: f64,
    pub budget: Option<Duration>,
}

impl AutoChoice {
    /// The kind of the stage that reached the tolerance.
    pub fn kind(&self) -> StageKind {
        self.plan[self.stage].kind
    }
}

/// What a workspace hands AUTO and gets back: structures built from W's block pattern (valid
/// for the problem solved) and the choice to resume from (only when the pattern is unchanged).
/// After the solve, `choice` is where this solve ended and the structures are handed back.
#[derive(Default)]
pub(crate) struct AutoCarry<'a> {
    pub sweep: Option<PreparedSweep<'a>>,
    pub newton: Option<NewtonSolver>,
    pub resume: Option<AutoChoice>,
    pub choice: Option<AutoChoice>,
    /// The solve resumed from `resume` (same tolerance and budget).
    pub resumed: bool,
}

/// The sweeps to run before the next measurement of the error: those the contraction seen over
/// the last `iterations` sweeps (from `before` to `error`) needs to reach `tolerance`, between 1
/// and `max`; twice the last probe while no contraction is known yet. Measured this way, a
/// Gauss-Seidel stage stops within a sweep or two of the first one below the tolerance, with
/// a few measurements of the error (each costs about one product with W, less than a sweep).
fn next_probe(
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

/// The error at which an anytime solve stops: errors this small are round-off (the shared
/// problems' solutions score 1e-17 to 1e-16 when exact).
pub const ROUND_OFF: f64 = 1e-15;

/// AUTO's id: fc3d's own, in the range 568..=599 Siconos 4.4 leaves free.
pub const AUTO_ID: i32 = 590;

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
    // problems (README "AUTO against Siconos at equal budget").
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
    let (rule, plan, first) = match (options.plan, resume) {
        (Some(plan), _) => (usize::MAX, plan, 0),
        (None, Some(c)) => (c.rule, c.plan, c.stage),
        (None, None) => {
            let (rule, plan) = choose(&ProblemFeatures::of(problem), requested, budget);
            (rule, plan, 0)
        }
    };
    carry.resumed = resume.is_some() && options.plan.is_none();
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
    let mut best = BestIterate::new(r, error);
    let mut best_error = error;
    let mut total = 0usize;
    let mut out_of_time = false;
    let nsgs_options = NsgsOptions::with_local(sweep_local_solver(rule));
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
    let prox_options = ProxOptions::default();
    let admm_options = AdmmOptions::default();
    let tresca_options = TrescaOptions::default();
    let eg_options = ViOptions::new(ViSolver::ExtraGradient);
    let newton_options = NsnOptions::new(NsnFormulation::AlartCurnier);
    let mut newton: Option<NewtonSolver> = None;
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
        let watch = stall_rule(planned.kind);
        let allowance = planned.allowance.unwrap_or(usize::MAX);
        let to_the_limits = next.to_the_limits || planned.allowance == TO_THE_LIMITS;
        // Under a budget above SHORT_BUDGET, a stage of a plan with several gets at most half of
        // the time left, so that a method that is slow on this problem (PROX on BoxesStack and
        // RockPile) leaves time to the next one while a fast one (PROX on the Capsules) still
        // converges; the plan then starts over (README "AUTO against Siconos at equal budget").
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
        // The stall test looks at windows of `watch.chunk` iterations; NSGS measures inside a
        // window as often as its predicted convergence asks.
        let mut window_start = error;
        let mut window = 0usize;
        let mut probe = 1usize;
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
                Nsgs => probe.min(watch.chunk - window),
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
            let (iterations, measured, stopped_for_time) = match planned.kind {
                Nsgs => {
                    let sweeper = sweeper.as_mut().expect("built above");
                    // Tolerance 0: the sweeps run the whole probe (or stop on a fixed point).
                    let l = stage_limits(0.0, chunk, stage_deadline);
                    let o = run_sweeps(problem, sweeper, &schedule, &l, r, u, &mut shifted)?;
                    (o.iterations, o.final_error, o.out_of_time)
                }
                Newton => {
                    let solver = newton.as_mut().expect("built above");
                    let inner = stage_limits(tolerance, chunk, stage_deadline).start();
                    let o = solver.run(problem.q(), problem.mu(), 0.0, &inner, r, u, &mut shifted);
                    (o.iterations, None, o.out_of_time)
                }
                Prox | Admm | Tresca | ExtraGradient => {
                    let family: &dyn Family = match planned.kind {
                        Prox => &prox_options,
                        Admm => &admm_options,
                        ExtraGradient => &eg_options,
                        _ => &tresca_options,
                    };
                    let l = stage_limits(tolerance, chunk, stage_deadline);
                    let o = family.run(problem, &l, r, u, &mut shifted)?;
                    fill = Fill::largest(fill, o.fill);
                    (o.iterations, o.final_error, o.out_of_time)
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
            // A stage run to the limits is not ended by a stall (large piles: every method's
            // error falls slowly).
            // So is the last stage of a budgeted solve: the host gave the time left.
            let patient =
                (to_the_limits || (last_possible && run.deadline().is_some())) && error.is_finite();
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
            probe = next_probe(probe, before, error, iterations, tolerance, watch.chunk);
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
    carry.newton = newton.or(kept_newton);
    Ok(SolverOutcome {
        stages: Some(log),
        fill,
        ..SolverOutcome::stopped(total.min(run.max_iter), out_of_time)
            .with_final_error((!restored && error.is_finite()).then_some(error))
    })
}

#[cfg(test)]
mod tests {
    use super::{next_probe, next_stage, stage, Handover, NextStage, PlannedStage, TO_THE_LIMITS};
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
}

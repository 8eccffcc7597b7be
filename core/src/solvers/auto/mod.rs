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
//! The rules and the stall factors are data ([`RULES`], [`STALL`]); docs/auto.md gives the
//! `fc3d bench` runs on the shared problems that justify them.

mod features;
mod plan;
mod rules;
mod run;

use std::time::Duration;

use crate::contract::{Family, Limits, Observer, SolverOutcome, StageKind};
use crate::error::Fc3dError;
use crate::problem::FrictionProblem;
use crate::solvers::nsgs::PreparedSweep;
use crate::solvers::nsn::NewtonSolver;

pub use features::{ProblemFeatures, STRONG_MU, WEAK_DOMINANCE};
pub use plan::{factorizes, next_stage, Handover, NextStage};
pub use rules::{
    choose, stage, sweep_local_solver, Condition, PlannedStage, Rule, StallRule, SweepTuning,
    ADMM_BUDGET, ADMM_MAX_CONTACTS, HUGE_PROBLEM, LARGE_PROBLEM, MODERATE_MU, PROBE,
    PROBE_PRODUCTS, PSOR_FREEZE_SWEEPS, PSOR_FREEZING, PSOR_OMEGA, RULES, SHORT_BUDGET, STALL,
    TO_THE_LIMITS,
};
pub(crate) use run::auto_with;

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
/// reached the tolerance (in an anytime solve, the one the budget ended in). A workspace keeps
/// it so that the next step with the same tolerance and budget skips the stages that came
/// before: at once on the same W block pattern, after the feature pass gave the same rule on
/// another one.
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
/// for the problem solved) and the choice to resume from. After the solve, `choice` is where
/// this solve ended and the structures are handed back.
#[derive(Default)]
pub(crate) struct AutoCarry<'a> {
    pub sweep: Option<PreparedSweep<'a>>,
    pub newton: Option<NewtonSolver>,
    pub resume: Option<AutoChoice>,
    /// W's block pattern is the one `resume` was chosen on: the rule is taken as it is. On
    /// another pattern the features are measured again and the solve resumes only if they
    /// give the same rule.
    pub same_pattern: bool,
    pub choice: Option<AutoChoice>,
    /// The solve resumed from `resume` (same tolerance, budget and rule).
    pub resumed: bool,
}

/// The error at which an anytime solve stops: errors this small are round-off (the shared
/// problems' solutions score 1e-17 to 1e-16 when exact).
pub const ROUND_OFF: f64 = 1e-15;

/// AUTO's id: fc3d's own, in the range 568..=599 Siconos 4.4 leaves free.
pub const AUTO_ID: i32 = 590;

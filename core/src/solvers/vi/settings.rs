//! Settings of the VI / projection family with Siconos 4.4's defaults.

use crate::contract::ErrorEvaluation;
use crate::error::{require_setting, Fc3dError};
use crate::math::step;

/// The Siconos solver a [`ViOptions`] stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ViSolver {
    /// De Saxcé's fixed point with a fixed rho, "FP-DS" [505 DSFP].
    DeSaxceFixedPoint,
    /// Fixed-point projection through Siconos' generic VI solvers [506 VI_FPP].
    ViFixedPointProjection,
    /// Extragradient through Siconos' generic VI solvers [507 VI_EG].
    ViExtraGradient,
    /// Hyperplane projection [508 HP].
    HyperplaneProjection,
    /// Fixed-point projection written on the friction problem [511 FPP].
    FixedPointProjection,
    /// Extragradient written on the friction problem [512 EG].
    ExtraGradient,
}

/// The iterations of the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViIteration {
    /// Rule (95): one projection per iteration.
    FixedPoint,
    /// A prediction and a correction per iteration (see [`ExtraGradientCorrection`]).
    ExtraGradient,
    /// A prediction, a search along the segment to it, and a projection through the separating
    /// hyperplane (see [`HyperplaneSearch`]).
    HyperplaneProjection,
}

/// Which of Siconos' two code bases an id follows. Siconos wrote 506/507 on its generic VI
/// solvers and 505/508/511/512 directly on the friction problem; the two differ in details that
/// change iteration counts, and each id follows its own:
///
/// * stopping error: the VI solvers test `||r - P_K(r - F(r))|| / ||q||`; the others Siconos'
///   friction error (133) normalised by `max(||q||, ||r||, ||u||)` (never larger than the VI
///   one, so a VI stop is also a stop for the friction error);
/// * cheap error of the extragradient (`iparam[7]` = 1 or 2): the VI solver uses the last
///   trial's `||F(r̄) - F(r_k)||` (its Solodov-Tseng product for UPTS) over `||r_{k+1}||`; the
///   fixed points use the increment (134);
/// * trial steps: the VI solvers form them as `(rho / nu) nu^m`, the friction ones as
///   `rho nu^m`, and the friction ones let rho grow only when the error decreased.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Lineage {
    Vi,
    Friction,
}

impl ViSolver {
    pub const ALL: [ViSolver; 6] = [
        ViSolver::DeSaxceFixedPoint,
        ViSolver::ViFixedPointProjection,
        ViSolver::ViExtraGradient,
        ViSolver::HyperplaneProjection,
        ViSolver::FixedPointProjection,
        ViSolver::ExtraGradient,
    ];

    pub fn siconos_id(self) -> i32 {
        match self {
            ViSolver::DeSaxceFixedPoint => 505,
            ViSolver::ViFixedPointProjection => 506,
            ViSolver::ViExtraGradient => 507,
            ViSolver::HyperplaneProjection => 508,
            ViSolver::FixedPointProjection => 511,
            ViSolver::ExtraGradient => 512,
        }
    }

    pub fn from_siconos_id(id: i32) -> Option<Self> {
        ViSolver::ALL.into_iter().find(|s| s.siconos_id() == id)
    }

    /// Short name used in labels and by `fc3d bench` (`DSFP`, `VI-FPP`, `VI-EG`, `HP`, `FPP`,
    /// `EG`).
    pub fn short_name(self) -> &'static str {
        match self {
            ViSolver::DeSaxceFixedPoint => "DSFP",
            ViSolver::ViFixedPointProjection => "VI-FPP",
            ViSolver::ViExtraGradient => "VI-EG",
            ViSolver::HyperplaneProjection => "HP",
            ViSolver::FixedPointProjection => "FPP",
            ViSolver::ExtraGradient => "EG",
        }
    }

    pub fn iteration(self) -> ViIteration {
        match self {
            ViSolver::DeSaxceFixedPoint
            | ViSolver::ViFixedPointProjection
            | ViSolver::FixedPointProjection => ViIteration::FixedPoint,
            ViSolver::ViExtraGradient | ViSolver::ExtraGradient => ViIteration::ExtraGradient,
            ViSolver::HyperplaneProjection => ViIteration::HyperplaneProjection,
        }
    }

    pub(crate) fn lineage(self) -> Lineage {
        match self {
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient => Lineage::Vi,
            _ => Lineage::Friction,
        }
    }

    /// Siconos' default limits: (tolerance, iterations).
    pub(crate) fn default_limits(self) -> (f64, usize) {
        match self {
            ViSolver::HyperplaneProjection => (1e-3, 2_000_000),
            _ => (1e-3, 20000),
        }
    }
}

/// The ratio Algorithm 3 compares with `L` to accept a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepRatio {
    /// (98), Khobotov: `rho ||F(r) - F(r̄)|| / ||r - r̄||` (UPK, Siconos' default).
    Khobotov,
    /// (99), Solodov-Tseng: `rho (r - r̄)·(F(r) - F(r̄)) / ||r - r̄||^2` (UPTS).
    SolodovTseng,
}

/// Where the trials of one iteration's line search start (Siconos' `iparam[10]`,
/// `SICONOS_VI_IPARAM_ACTIVATE_UPDATE`, for 506/507).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrialStart {
    /// Every trial projects from the iterate: `r̄ = P_K(r_k - rho_m F(r_k))` (Algorithm 3 as
    /// written; 506/507's default, `iparam[10]` = 0).
    Iterate,
    /// Every trial projects from the previous trial: `r̄_m = P_K(r̄_{m-1} - rho_m F(r_k))`, with
    /// `r̄_{-1} = r_k` (the "update within the self-adaptive loop" of section 4.2; 506/507 with
    /// `iparam[10]` = 1, and always in Siconos' 511/512).
    PreviousTrial,
}

/// Algorithm 3's parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAdaptiveStep {
    /// rho of the first iteration (default 1).
    pub initial_rho: f64,
    pub ratio: StepRatio,
    /// Reduction factor of a rejected trial, in (0, 1) (default 2/3; 0.6 for 511/512).
    pub nu: f64,
    /// Increase factor applied after an easily accepted step, >= 1 (default 3/2; 1/0.7 for
    /// 511/512).
    pub increase: f64,
    /// Acceptance threshold on the ratio, in (0, 1) (default 0.9).
    pub l: f64,
    /// Below this ratio the next rho is increased, in [0, L) (default 0.3).
    pub l_min: f64,
    /// Trials per iteration; the last one is taken when none is accepted (default 10).
    pub max_trials: usize,
    /// Default [`TrialStart::Iterate`] for 506/507, [`TrialStart::PreviousTrial`] for 511/512.
    pub trial_start: TrialStart,
}

impl Default for SelfAdaptiveStep {
    /// Siconos' VI solvers' constants (506/507).
    fn default() -> Self {
        SelfAdaptiveStep {
            initial_rho: 1.0,
            ratio: StepRatio::Khobotov,
            nu: step::NU,
            increase: 1.5,
            l: step::L,
            l_min: step::L_MIN,
            max_trials: 10,
            trial_start: TrialStart::Iterate,
        }
    }
}

impl SelfAdaptiveStep {
    /// The constants Siconos' FPP 511 and EG 512 hard-code: nu = 0.6, increase 1/0.7, trials
    /// from the previous trial.
    pub fn friction_defaults() -> Self {
        SelfAdaptiveStep {
            nu: 0.6,
            increase: 1.0 / 0.7,
            trial_start: TrialStart::PreviousTrial,
            ..SelfAdaptiveStep::default()
        }
    }
}

/// How rho is chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepSize {
    /// The same rho at every iteration.
    Fixed(f64),
    /// Algorithm 3.
    SelfAdaptive(SelfAdaptiveStep),
}

/// The point the extragradient's correction projects from, with the prediction
/// `r̄ = P_K(r_k - rho F(r_k))`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExtraGradientCorrection {
    /// `r_{k+1} = P_K(r̄ - rho F(r̄))`: Siconos 4.4's VI_EG 507 and EG 512 with a self-adaptive
    /// rho (two projection steps per iteration, each with the accepted rho). Default.
    FromPrediction,
    /// `r_{k+1} = P_K(r_k - rho F(r̄))`: Korpelevich's rule (96) of the paper, as Siconos' EG 512
    /// does with a fixed rho. 4-6 times the iterations of `FromPrediction` on the shared
    /// problems (EG at 1e-8: NESpheres_10_1 261 against 50, Confeti-ex03 421 against 100), at
    /// the same cost per iteration.
    FromIterate,
}

/// The hyperplane projection's parameters (HP 508), Siconos 4.4's algorithm: with the
/// prediction `r̄ = P_K(r - rho F(r))`, the search tries `w = 2^-m r̄ + (1 - 2^-m) r`,
/// m = 0, 1, ..., and stops at the first with `v·(r - r̄) >= sigma / rho ||r - r̄||^2` where
/// `v = W w + q` (the velocity at w, without the De Saxcé term); then
/// `r <- P_K(r - (v·(r - r̄) / ||v||^2) v)`. Its fixed points include the friction solutions
/// but, with the De Saxcé term left out of v, it stalls on problems with sliding contacts
/// (as Siconos' does; its own suite marks HP on Confeti-ex13 as expected to fail).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HyperplaneSearch {
    /// In (0, 1) (default 0.99, Siconos' `dparam[4]`).
    pub sigma: f64,
    /// Halvings after the full step (default 50, Siconos' `iparam[12]`): the search tries
    /// `max_halvings + 1` points.
    pub max_halvings: usize,
}

impl Default for HyperplaneSearch {
    fn default() -> Self {
        HyperplaneSearch {
            sigma: 0.99,
            max_halvings: 50,
        }
    }
}

/// Settings of the VI / projection family (Siconos ids 505, 506, 507, 508, 511, 512). Its
/// limits default to a tolerance of 1e-3 and 20000 iterations (2000000 for HP).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViOptions {
    pub solver: ViSolver,
    /// Default: `Fixed(1.0)` for 505 and 508; `SelfAdaptive` with Siconos' VI constants for
    /// 506 and 507, with [`SelfAdaptiveStep::friction_defaults`] for 511 and 512.
    pub step: StepSize,
    /// Default: `LightWithFullFinal` for 506 and 507 (Siconos' iparam[7] = 1), `Full` for the
    /// others. The light error is the cheap error (134) `||r_{k+1} - r_k|| / ||r_{k+1}||` (for
    /// 507, see [`Lineage`]). With a fixed rho, 506/507 test the full error at every iteration,
    /// as Siconos does.
    pub error_evaluation: ErrorEvaluation,
    /// The extragradient's correction (507, 512); default [`ExtraGradientCorrection::FromPrediction`].
    pub correction: ExtraGradientCorrection,
    /// The hyperplane projection's search (508).
    pub hyperplane: HyperplaneSearch,
}

impl ViOptions {
    /// Siconos 4.4's defaults for `solver`.
    pub fn new(solver: ViSolver) -> Self {
        let (step, error_evaluation) = match solver {
            ViSolver::DeSaxceFixedPoint | ViSolver::HyperplaneProjection => {
                (StepSize::Fixed(1.0), ErrorEvaluation::Full)
            }
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient => (
                StepSize::SelfAdaptive(SelfAdaptiveStep::default()),
                ErrorEvaluation::LightWithFullFinal,
            ),
            ViSolver::FixedPointProjection | ViSolver::ExtraGradient => (
                StepSize::SelfAdaptive(SelfAdaptiveStep::friction_defaults()),
                ErrorEvaluation::Full,
            ),
        };
        ViOptions {
            solver,
            step,
            error_evaluation,
            correction: ExtraGradientCorrection::FromPrediction,
            hyperplane: HyperplaneSearch::default(),
        }
    }

    /// Checks the step parameters (the tolerance is checked by the caller).
    pub(crate) fn validate(&self) -> Result<(), Fc3dError> {
        if self.error_evaluation == ErrorEvaluation::DumontCriterion {
            return Err(Fc3dError::InvalidOption(format!(
                "{}: Dumont's criterion is a stopping test of NSGS sweeps (it needs the velocities \
                 contacts were solved with); use Full, Light or LightWithFullFinal",
                self.solver.short_name()
            )));
        }
        if self.solver == ViSolver::HyperplaneProjection {
            let h = self.hyperplane;
            require_setting(
                h.sigma > 0.0 && h.sigma < 1.0,
                "vi.sigma",
                h.sigma,
                "in (0, 1)",
            )?;
            if let StepSize::SelfAdaptive(_) = self.step {
                return Err(Fc3dError::InvalidOption(
                    "HP (508) projects its prediction with a fixed rho: use StepSize::Fixed".into(),
                ));
            }
        }
        match self.step {
            StepSize::Fixed(rho) => require_setting(
                rho > 0.0 && rho.is_finite(),
                "vi.rho",
                rho,
                "finite and > 0",
            ),
            StepSize::SelfAdaptive(s) => {
                if self.solver == ViSolver::DeSaxceFixedPoint {
                    return Err(Fc3dError::InvalidOption(
                        "DSFP (505) is the fixed-rho fixed point: use StepSize::Fixed".into(),
                    ));
                }
                let rho = s.initial_rho;
                require_setting(
                    rho > 0.0 && rho.is_finite(),
                    "vi.rho",
                    rho,
                    "finite and > 0",
                )?;
                require_setting(s.nu > 0.0 && s.nu < 1.0, "vi.nu", s.nu, "in (0, 1)")?;
                require_setting(
                    s.increase >= 1.0 && s.increase.is_finite(),
                    "vi.increase",
                    s.increase,
                    "finite and >= 1",
                )?;
                require_setting(s.l > 0.0 && s.l < 1.0, "vi.l", s.l, "in (0, 1)")?;
                require_setting(
                    s.l_min >= 0.0 && s.l_min < s.l,
                    "vi.l_min",
                    s.l_min,
                    "in [0, L)",
                )?;
                require_setting(
                    s.max_trials > 0,
                    "vi.max_trials",
                    s.max_trials,
                    ">= 1 (the line search needs a trial)",
                )
            }
        }
    }
}

impl Default for ViOptions {
    /// VI_FPP (506) with Siconos' defaults.
    fn default() -> Self {
        ViOptions::new(ViSolver::ViFixedPointProjection)
    }
}

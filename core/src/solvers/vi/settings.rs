//! Settings of the VI / fixed-point family with Siconos 4.4's defaults.

use crate::contract::ErrorEvaluation;
use crate::error::{require_setting, Fc3dError};
use crate::math::step;

/// The Siconos solver a [`ViOptions`] stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ViSolver {
    /// De Saxcé's fixed point with a fixed rho, "FP-DS" [505 DSFP].
    DeSaxceFixedPoint,
    /// Fixed-point projection through the VI solvers [506 VI_FPP].
    ViFixedPointProjection,
    /// Extragradient through the VI solvers [507 VI_EG].
    ViExtraGradient,
    /// Fixed-point projection on the friction problem [511 FPP].
    FixedPointProjection,
    /// Extragradient on the friction problem [512 EG].
    ExtraGradient,
}

/// The two iterations of the family.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViIteration {
    /// Rule (95): one projection per iteration.
    FixedPoint,
    /// Rule (96): a prediction and a correction per iteration.
    ExtraGradient,
}

impl ViSolver {
    pub const ALL: [ViSolver; 5] = [
        ViSolver::DeSaxceFixedPoint,
        ViSolver::ViFixedPointProjection,
        ViSolver::ViExtraGradient,
        ViSolver::FixedPointProjection,
        ViSolver::ExtraGradient,
    ];

    pub fn siconos_id(self) -> i32 {
        match self {
            ViSolver::DeSaxceFixedPoint => 505,
            ViSolver::ViFixedPointProjection => 506,
            ViSolver::ViExtraGradient => 507,
            ViSolver::FixedPointProjection => 511,
            ViSolver::ExtraGradient => 512,
        }
    }

    pub fn from_siconos_id(id: i32) -> Option<Self> {
        ViSolver::ALL.into_iter().find(|s| s.siconos_id() == id)
    }

    /// Short name used in labels and by `fc3d bench` (`DSFP`, `VI-FPP`, `VI-EG`, `FPP`, `EG`).
    pub fn short_name(self) -> &'static str {
        match self {
            ViSolver::DeSaxceFixedPoint => "DSFP",
            ViSolver::ViFixedPointProjection => "VI-FPP",
            ViSolver::ViExtraGradient => "VI-EG",
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

/// Algorithm 3's parameters (Siconos' constants by default).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SelfAdaptiveStep {
    /// rho of the first iteration (default 1).
    pub initial_rho: f64,
    pub ratio: StepRatio,
    /// Reduction factor of a rejected trial, in (0, 1) (default 2/3).
    pub nu: f64,
    /// Increase factor applied after an easily accepted step, > 1 (default 3/2 = 1/nu).
    pub increase: f64,
    /// Acceptance threshold on the ratio, in (0, 1) (default 0.9).
    pub l: f64,
    /// Below this ratio the next rho is increased, in (0, L) (default 0.3).
    pub l_min: f64,
    /// Trials per iteration; the last one is taken when none is accepted (default 10).
    pub max_trials: usize,
}

impl Default for SelfAdaptiveStep {
    fn default() -> Self {
        SelfAdaptiveStep {
            initial_rho: 1.0,
            ratio: StepRatio::Khobotov,
            nu: step::NU,
            increase: 1.5,
            l: step::L,
            l_min: step::L_MIN,
            max_trials: 10,
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

/// Settings of the VI / fixed-point family (Siconos ids 505, 506, 507, 511, 512). Its limits
/// default to 20000 iterations and a tolerance of 1e-3 for every id.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ViOptions {
    pub solver: ViSolver,
    /// Default: `Fixed(1.0)` for 505 and 511, `SelfAdaptive` with Siconos' constants for 506,
    /// 507 and 512.
    pub step: StepSize,
    /// Default: `LightWithFullFinal` for 506 and 507 (Siconos' iparam[7] = 1), `Full` for the
    /// others. The light error is the cheap error (134) `||r_{k+1} - r_k|| / ||r_{k+1}||`.
    pub error_evaluation: ErrorEvaluation,
}

impl ViOptions {
    /// Siconos 4.4's defaults for `solver`.
    pub fn new(solver: ViSolver) -> Self {
        let (step, error_evaluation) = match solver {
            ViSolver::DeSaxceFixedPoint | ViSolver::FixedPointProjection => {
                (StepSize::Fixed(1.0), ErrorEvaluation::Full)
            }
            ViSolver::ViFixedPointProjection | ViSolver::ViExtraGradient => (
                StepSize::SelfAdaptive(SelfAdaptiveStep::default()),
                ErrorEvaluation::LightWithFullFinal,
            ),
            ViSolver::ExtraGradient => (
                StepSize::SelfAdaptive(SelfAdaptiveStep::default()),
                ErrorEvaluation::Full,
            ),
        };
        ViOptions {
            solver,
            step,
            error_evaluation,
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
